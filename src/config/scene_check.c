/* Checks of a scene against the schema: section headers (known, named exactly when they
 * take a name), keys (known to their section) and values (unit, whole number, choice,
 * yes or no, range), each refused with one line "file: [section] key: what is wrong";
 * scene_put stores a key only once it passed (see src/config/scene_private.h). */
#include "scene_private.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/config/ini.h"
#include "tiptap/util/error.h"

const tt_scene_section *scene_find_section(const char *name)
{
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    for (size_t i = 0; i < n; i++)
        if (strcmp(sec[i].name, name) == 0)
            return &sec[i];
    return NULL;
}

const tt_scene_key *scene_find_key(const tt_scene_section *sec, const char *key)
{
    for (size_t i = 0; i < sec->nkeys; i++)
        if (strcmp(sec->keys[i].key, key) == 0)
            return &sec->keys[i];
    return NULL;
}

/* "[material glass]" -> "material glass" in messages; "[cantilever]" -> "cantilever". */
void scene_section_label(char *buf, size_t len, const char *section, const char *name)
{
    if (name)
        snprintf(buf, len, "%s %s", section, name);
    else
        snprintf(buf, len, "%s", section);
}

int scene_list_add(char *buf, size_t len, size_t *used, const char *item)
{
    int w = snprintf(buf + *used, len - *used, "%s%s", *used ? ", " : "", item);
    if (w < 0 || (size_t)w >= len - *used) {
        buf[*used] = '\0';
        return -1;
    }
    *used += (size_t)w;
    return 0;
}

static const char *list_keys(const tt_scene_section *sec, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < sec->nkeys; i++)
        if (scene_list_add(buf, len, &used, sec->keys[i].key))
            break;
    return buf;
}

int scene_parse_bool(const char *v, int *out)
{
    static const char *yes[] = {"yes", "true", "on", "1"};
    static const char *no[] = {"no", "false", "off", "0"};
    for (size_t i = 0; i < 4; i++) {
        if (strcasecmp(v, yes[i]) == 0) {
            *out = 1;
            return 0;
        }
        if (strcasecmp(v, no[i]) == 0) {
            *out = 0;
            return 0;
        }
    }
    return -1;
}

int scene_enum_has(const char *choices, const char *v)
{
    size_t n = strlen(v);
    const char *p = choices;
    while (p && *p) {
        const char *bar = strchr(p, '|');
        size_t len = bar ? (size_t)(bar - p) : strlen(p);
        if (len == n && strncmp(p, v, n) == 0)
            return 1;
        p = bar ? bar + 1 : NULL;
    }
    return 0;
}

/* Check one value against its key description; on failure write why. */
int scene_check_value(const tt_scene_key *k, const char *v, char *why, size_t len)
{
    double x;
    tt_dim dim = TT_DIM_NONE;
    switch (k->kind) {
    case TT_KEY_QUANTITY:
        if (tt_units_parse(v, k->dims, &x, &dim, why, len) != 0)
            return -1;
        break;
    case TT_KEY_INT: {
        char *end;
        errno = 0;
        long l = strtol(v, &end, 10);
        while (isspace((unsigned char)*end))
            end++;
        if (end == v || *end != '\0' || errno) {
            snprintf(why, len, "'%s' is not a whole number", v);
            return -1;
        }
        x = (double)l;
        break;
    }
    case TT_KEY_ENUM:
        if (!scene_enum_has(k->choices, v)) {
            snprintf(why, len, "'%s' is not one of %s", v, k->choices);
            return -1;
        }
        return 0;
    case TT_KEY_BOOL: {
        int b;
        if (scene_parse_bool(v, &b) != 0) {
            snprintf(why, len, "'%s' is not yes or no", v);
            return -1;
        }
        return 0;
    }
    case TT_KEY_STRING:
        if (v[0] == '\0') {
            snprintf(why, len, "empty value");
            return -1;
        }
        return 0;
    default:
        return 0;
    }
    int lo_ok = (k->flags & TT_KEY_MIN_EXCL) ? x > k->min : x >= k->min;
    int hi_ok = (k->flags & TT_KEY_MAX_EXCL) ? x < k->max : x <= k->max;
    if (!lo_ok || !hi_ok) {
        const char *sym = "";
        if (k->kind == TT_KEY_QUANTITY && !(k->dims & (TT_DIM_NONE | TT_DIM_FRACTION)))
            for (unsigned d = 1; d <= TT_DIM_FRACTION; d <<= 1)
                if (k->dims & d) {
                    sym = tt_units_symbol((tt_dim)d);
                    break;
                }
        /* angles are written in degrees (0 deg: "above 0 deg and below 90 deg", not rad) */
        double f = 1;
        if (k->kind == TT_KEY_QUANTITY && (k->dims & TT_DIM_ANGLE)) {
            sym = "deg";
            f = 180 / M_PI;
        }
        /* a value given in % hears its bounds in % (the setpoint's 0 %, not 0 of a fraction) */
        if (k->kind == TT_KEY_QUANTITY && dim == TT_DIM_FRACTION) {
            sym = "%";
            f = 100;
        }
        /* the space goes with the unit, so that a plain number ends the message */
        const char *sp = *sym ? " " : "";
        if (!lo_ok && isfinite(k->max) && k->max < 1e300)
            snprintf(why, len, "%s is out of range; expected %s %g%s%s and %s %g%s%s", v,
                     (k->flags & TT_KEY_MIN_EXCL) ? "above" : "at least", k->min * f, sp, sym,
                     (k->flags & TT_KEY_MAX_EXCL) ? "below" : "at most", k->max * f, sp, sym);
        else if (!lo_ok)
            snprintf(why, len, "%s is out of range; expected %s %g%s%s", v,
                     (k->flags & TT_KEY_MIN_EXCL) ? "above" : "at least", k->min * f, sp, sym);
        else
            snprintf(why, len, "%s is out of range; expected %s %g%s%s", v,
                     (k->flags & TT_KEY_MAX_EXCL) ? "below" : "at most", k->max * f, sp, sym);
        return -1;
    }
    return 0;
}

/* Whether text holds a byte that must not reach a terminal or a line of scene.ini. */
static int has_control(const char *text)
{
    for (const unsigned char *p = (const unsigned char *)text; *p; p++)
        if ((*p < 0x20 && *p != '\t') || *p == 0x7f)
            return 1;
    return 0;
}

/* Check a section header: a known section, with a name exactly when it takes one. */
int scene_check_section(const char *origin, const char *section, const char *name)
{
    char label[256], shown[160];
    const tt_scene_section *sec = scene_find_section(section);
    scene_section_label(label, sizeof label, section, name);
    tt_ini_escape(label, shown, sizeof shown);
    if (!sec) {
        size_t n;
        const tt_scene_section *all = tt_scene_schema(&n);
        char known[512];
        size_t used = 0;
        known[0] = '\0';
        for (size_t i = 0; i < n; i++)
            if (scene_list_add(known, sizeof known, &used, all[i].name))
                break;
        return tt_error(TT_EINVAL, "%s: [%s]: unknown section; known sections: %s", origin, shown,
                        known);
    }
    if (sec->named && (!name || !name[0]))
        return tt_error(TT_EINVAL, "%s: [%s]: this section needs a name, as in [%s NAME]", origin,
                        shown, section);
    if (!sec->named && name)
        return tt_error(TT_EINVAL, "%s: [%s]: this section takes no name; write [%s]", origin, shown,
                        section);
    /* the effective scene writes "[section name]": a name must read back the same */
    if (name && (strpbrk(name, "[]") || isspace((unsigned char)name[0]) ||
                 isspace((unsigned char)name[strlen(name) - 1]) || has_control(name)))
        return tt_error(TT_EINVAL, "%s: [%s]: a name must not hold '[', ']', control characters "
                        "or blanks at its ends", origin, shown);
    return TT_OK;
}

/* Validate and store one key; origin names the file for messages. */
int scene_put(tt_scene *s, const char *origin, unsigned load, const char *section,
              const char *name, const char *key, const char *value)
{
    char label[256], why[512], shown[160];
    int rc = scene_check_section(origin, section, name);
    if (rc)
        return rc;
    const tt_scene_section *sec = scene_find_section(section);
    scene_section_label(label, sizeof label, section, name);
    const tt_scene_key *k = scene_find_key(sec, key);
    if (!k) {
        char keys[768];
        return tt_error(TT_EINVAL, "%s: [%s] %s: unknown key; [%s] takes %s", origin, label,
                        tt_ini_escape(key, shown, sizeof shown), section,
                        list_keys(sec, keys, sizeof keys));
    }
    /* scene.ini holds one key per line, and " ;" there starts a comment */
    if (has_control(value))
        return tt_error(TT_EINVAL, "%s: [%s] %s: '%s' holds a control character; a value is one "
                        "line of text", origin, label, key, tt_ini_escape(value, shown, sizeof shown));
    for (const char *c = strchr(value, ';'); c; c = strchr(c + 1, ';'))
        if (c > value && (c[-1] == ' ' || c[-1] == '\t'))
            return tt_error(TT_EINVAL, "%s: [%s] %s: '%s': a ';' after a blank starts a comment in "
                            "a scene file", origin, label, key, value);
    if (scene_check_value(k, value, why, sizeof why) != 0)
        return tt_error(TT_EINVAL, "%s: [%s] %s: %s", origin, label, key, why);
    const entry *e = scene_find_entry(s, section, name, key);
    if (e && load && e->load == load)
        return tt_error(TT_EINVAL, "%s: [%s] %s: given twice in this file", origin, label, key);
    if ((rc = scene_note_section(s, section, name, origin)))
        return rc;
    return scene_store(s, origin, load, section, name, key, value);
}
