/* Reading a scene back: the typed getters (a quantity in SI units, a whole number, yes or
 * no, a string, a path relative to the file that named it), each falling back on the
 * schema's default, and the error messages that name the file a bad value came from
 * (tt_scene_fail, tt_scene_locate; see include/tiptap/config/scene.h). */
#include "scene_private.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

static const char *origin_of(const tt_scene *s, const char *section, const char *name,
                             const char *key)
{
    const entry *e = key ? scene_find_entry(s, section, name, key) : NULL;
    if (e)
        return e->origin;
    const section_use *u = scene_find_use(s, section, name);
    return u ? u->origin : tt_scene_origin(s);
}

int tt_scene_fail(const tt_scene *s, const char *section, const char *name, const char *key,
                  const char *fmt, ...)
{
    char label[256], msg[700];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    scene_section_label(label, sizeof label, section, name);
    if (!s && key)
        return tt_error(TT_EINVAL, "[%s] %s: %s", label, key, msg);
    if (!s)
        return tt_error(TT_EINVAL, "[%s]: %s", label, msg);
    if (key)
        return tt_error(TT_EINVAL, "%s: [%s] %s: %s", origin_of(s, section, name, key), label, key,
                        msg);
    return tt_error(TT_EINVAL, "%s: [%s]: %s", origin_of(s, section, name, key), label, msg);
}

/* "section.key" into its parts; 0 when it has no dot. */
static int split_dotted(const char *dotted, char *section, size_t slen, char *key, size_t klen)
{
    const char *dot = strchr(dotted, '.');
    if (!dot)
        return 0;
    snprintf(section, slen, "%.*s", (int)(dot - dotted), dotted);
    snprintf(key, klen, "%s", dot + 1);
    return 1;
}

int tt_scene_fail_set(const tt_scene *s, const char *const *keys, const char *fmt, ...)
{
    char msg[700], section[64], key[64];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    size_t pick = 0;
    for (size_t i = 0; keys[i]; i++)
        if (s && split_dotted(keys[i], section, sizeof section, key, sizeof key) &&
            tt_scene_has(s, section, NULL, key)) {
            pick = i;
            break;
        }
    if (!split_dotted(keys[pick], section, sizeof section, key, sizeof key))
        return tt_error(TT_EINVAL, "%s", msg);
    return tt_scene_fail(s, section, NULL, key, "%s", msg);
}

int tt_scene_locate(const tt_scene *s, int rc)
{
    const char *m = tt_error_message();
    const char *close = m[0] == '[' ? strchr(m, ']') : NULL;
    if (rc == TT_OK || !close)
        return rc;
    char section[128], name[128] = "", key[128] = "", msg[1024];
    snprintf(section, sizeof section, "%.*s", (int)(close - m - 1), m + 1);
    char *space = strchr(section, ' ');
    if (space) {
        snprintf(name, sizeof name, "%s", space + 1);
        *space = '\0';
    }
    const char *colon = strchr(close, ':');
    if (close[1] == ' ' && colon)
        snprintf(key, sizeof key, "%.*s", (int)(colon - close - 2), close + 2);
    snprintf(msg, sizeof msg, "%s", m);
    return tt_error(rc, "%s: %s", origin_of(s, section, name[0] ? name : NULL, key[0] ? key : NULL),
                    msg);
}

/* The value text and key description of section.key, or an error. */
static int lookup(const tt_scene *s, const char *section, const char *name, const char *key,
                  const char **text, const tt_scene_key **kd)
{
    const tt_scene_section *sec = scene_find_section(section);
    const tt_scene_key *k = sec ? scene_find_key(sec, key) : NULL;
    if (!k)
        return tt_error(TT_EINVAL, "internal: [%s] %s is not in the schema", section, key);
    const entry *e = scene_find_entry(s, section, name, key);
    *kd = k;
    *text = e ? e->value : k->def;
    if (!*text)
        return tt_scene_fail(s, section, name, key, "missing; expected %s",
                             k->kind == TT_KEY_QUANTITY ? tt_scene_key_describe(k) : "a value");
    return TT_OK;
}

int tt_scene_get_quantity(const tt_scene *s, const char *section, const char *name,
                          const char *key, double *out, tt_dim *dim)
{
    /* lookup sets both whenever it returns TT_OK; gcc cannot see that across files */
    const char *text = NULL;
    const tt_scene_key *k = NULL;
    char why[512];
    int rc = lookup(s, section, name, key, &text, &k);
    if (rc)
        return rc;
    if (k->kind == TT_KEY_INT) {
        long l = 0;
        rc = tt_scene_get_int(s, section, name, key, &l);
        *out = (double)l;
        if (dim)
            *dim = TT_DIM_NONE;
        return rc;
    }
    tt_dim found;
    if (tt_units_parse(text, k->dims, out, &found, why, sizeof why) != 0)
        return tt_scene_fail(s, section, name, key, "%s", why);
    if (dim)
        *dim = found;
    return TT_OK;
}

int tt_scene_get_double(const tt_scene *s, const char *section, const char *name,
                        const char *key, double *out)
{
    return tt_scene_get_quantity(s, section, name, key, out, NULL);
}

int tt_scene_get_int(const tt_scene *s, const char *section, const char *name, const char *key,
                     long *out)
{
    const char *text;
    const tt_scene_key *k;
    int rc = lookup(s, section, name, key, &text, &k);
    if (rc)
        return rc;
    char *end;
    *out = strtol(text, &end, 10);
    if (end == text)
        return tt_scene_fail(s, section, name, key, "'%s' is not a whole number", text);
    return TT_OK;
}

int tt_scene_get_bool(const tt_scene *s, const char *section, const char *name, const char *key,
                      int *out)
{
    const char *text;
    const tt_scene_key *k;
    int rc = lookup(s, section, name, key, &text, &k);
    if (rc)
        return rc;
    if (scene_parse_bool(text, out) != 0)
        return tt_scene_fail(s, section, name, key, "'%s' is not yes or no", text);
    return TT_OK;
}

const char *tt_scene_get_string(const tt_scene *s, const char *section, const char *name,
                                const char *key)
{
    const entry *e = scene_find_entry(s, section, name, key);
    if (e)
        return e->value;
    const tt_scene_section *sec = scene_find_section(section);
    const tt_scene_key *k = sec ? scene_find_key(sec, key) : NULL;
    return k ? k->def : NULL;
}

int tt_scene_get_path(const tt_scene *s, const char *section, const char *name, const char *key,
                      char *buf, size_t len)
{
    const entry *e = scene_find_entry(s, section, name, key);
    const char *v = e ? e->value : tt_scene_get_string(s, section, name, key);
    if (!v)
        return tt_scene_fail(s, section, name, key, "missing; expected a file path");
    /* Relative paths are relative to the folder of the scene file that named them. */
    if (v[0] != '/' && e && strcmp(e->origin, "--set") != 0) {
        const char *slash = strrchr(e->origin, '/');
        if (slash) {
            int w = snprintf(buf, len, "%.*s/%s", (int)(slash - e->origin), e->origin, v);
            if (w < 0 || (size_t)w >= len)
                return tt_scene_fail(s, section, name, key, "path too long");
            return TT_OK;
        }
    }
    int w = snprintf(buf, len, "%s", v);
    if (w < 0 || (size_t)w >= len)
        return tt_scene_fail(s, section, name, key, "path too long");
    return TT_OK;
}

int tt_scene_parse_value(const tt_scene *s, const char *section, const char *key,
                         const char *text, double *out)
{
    (void)s;
    const tt_scene_section *sec = scene_find_section(section);
    const tt_scene_key *k = sec ? scene_find_key(sec, key) : NULL;
    char why[512];
    if (!k)
        return tt_error(TT_EINVAL, "[%s] %s: unknown key", section, key);
    if (scene_check_value(k, text, why, sizeof why) != 0)
        return tt_error(TT_EINVAL, "[%s] %s: %s", section, key, why);
    if (k->kind == TT_KEY_QUANTITY)
        return tt_units_parse(text, k->dims, out, NULL, why, sizeof why) == 0 ? TT_OK : TT_EINVAL;
    if (k->kind == TT_KEY_INT) {
        *out = (double)strtol(text, NULL, 10);
        return TT_OK;
    }
    return tt_error(TT_EINVAL, "[%s] %s: not a number-valued key", section, key);
}
