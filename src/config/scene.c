/* INI scene files: reading, validation against the schema, overrides, typed getters
 * and the effective-scene writer (see include/tiptap/config/scene.h). */
#include "tiptap/config/scene.h"

#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

typedef struct {
    char *section; /* schema section name, "material" */
    char *name;    /* NULL or the section's name, "glass" */
    char *key;
    char *value;
    char *origin;  /* file that set it, or "--set" */
} entry;

typedef struct {
    char *section;
    char *name;
    char *origin;
} section_use;

struct tt_scene {
    entry *entries;
    size_t n, cap;
    section_use *uses; /* sections in order of appearance (named ones once per name) */
    size_t nuses, capuses;
    char *origin;
};

static char *dupstr(const char *s)
{
    if (!s)
        return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

static int streq(const char *a, const char *b)
{
    if (!a || !b)
        return a == b;
    return strcmp(a, b) == 0;
}

tt_scene *tt_scene_alloc(void) { return calloc(1, sizeof(tt_scene)); }

void tt_scene_free(tt_scene *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->n; i++) {
        free(s->entries[i].section);
        free(s->entries[i].name);
        free(s->entries[i].key);
        free(s->entries[i].value);
        free(s->entries[i].origin);
    }
    for (size_t i = 0; i < s->nuses; i++) {
        free(s->uses[i].section);
        free(s->uses[i].name);
        free(s->uses[i].origin);
    }
    free(s->entries);
    free(s->uses);
    free(s->origin);
    free(s);
}

tt_scene *tt_scene_copy(const tt_scene *s)
{
    tt_scene *c = tt_scene_alloc();
    if (!c)
        return NULL;
    c->entries = calloc(s->n ? s->n : 1, sizeof *c->entries);
    c->uses = calloc(s->nuses ? s->nuses : 1, sizeof *c->uses);
    c->origin = dupstr(s->origin);
    if (!c->entries || !c->uses || (s->origin && !c->origin)) {
        tt_scene_free(c);
        return NULL;
    }
    c->cap = s->n ? s->n : 1;
    c->capuses = s->nuses ? s->nuses : 1;
    /* Counts grow one at a time so that tt_scene_free releases exactly what was copied. */
    for (size_t i = 0; i < s->n; i++, c->n++) {
        const entry *e = &s->entries[i];
        entry *d = &c->entries[i];
        d->section = dupstr(e->section);
        d->name = dupstr(e->name);
        d->key = dupstr(e->key);
        d->value = dupstr(e->value);
        d->origin = dupstr(e->origin);
        if (!d->section || (e->name && !d->name) || !d->key || !d->value || !d->origin) {
            c->n++;
            tt_scene_free(c);
            return NULL;
        }
    }
    for (size_t i = 0; i < s->nuses; i++, c->nuses++) {
        const section_use *u = &s->uses[i];
        section_use *d = &c->uses[i];
        d->section = dupstr(u->section);
        d->name = dupstr(u->name);
        d->origin = dupstr(u->origin);
        if (!d->section || (u->name && !d->name) || !d->origin) {
            c->nuses++;
            tt_scene_free(c);
            return NULL;
        }
    }
    return c;
}

const char *tt_scene_origin(const tt_scene *s) { return s->origin ? s->origin : "scene"; }

static const tt_scene_section *find_section(const char *name)
{
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    for (size_t i = 0; i < n; i++)
        if (strcmp(sec[i].name, name) == 0)
            return &sec[i];
    return NULL;
}

static const tt_scene_key *find_key(const tt_scene_section *sec, const char *key)
{
    for (size_t i = 0; i < sec->nkeys; i++)
        if (strcmp(sec->keys[i].key, key) == 0)
            return &sec->keys[i];
    return NULL;
}

/* "[material glass]" -> "material glass" in messages; "[cantilever]" -> "cantilever". */
static void section_label(char *buf, size_t len, const char *section, const char *name)
{
    if (name)
        snprintf(buf, len, "%s %s", section, name);
    else
        snprintf(buf, len, "%s", section);
}

static const char *list_keys(const tt_scene_section *sec, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < sec->nkeys && used + 2 < len; i++) {
        int w = snprintf(buf + used, len - used, "%s%s", i ? ", " : "", sec->keys[i].key);
        if (w < 0 || (size_t)w >= len - used)
            break;
        used += (size_t)w;
    }
    return buf;
}

static int parse_bool(const char *v, int *out)
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

static int enum_has(const char *choices, const char *v)
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
static int check_value(const tt_scene_key *k, const char *v, char *why, size_t len)
{
    double x;
    switch (k->kind) {
    case TT_KEY_QUANTITY: {
        tt_dim dim;
        if (tt_units_parse(v, k->dims, &x, &dim, why, len) != 0)
            return -1;
        break;
    }
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
        if (!enum_has(k->choices, v)) {
            snprintf(why, len, "'%s' is not one of %s", v, k->choices);
            return -1;
        }
        return 0;
    case TT_KEY_BOOL: {
        int b;
        if (parse_bool(v, &b) != 0) {
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
        /* the space goes with the unit, so that a plain number ends the message */
        const char *sp = *sym ? " " : "";
        if (!lo_ok && isfinite(k->max) && k->max < 1e300)
            snprintf(why, len, "%s is out of range; expected %s %g%s%s and %s %g%s%s", v,
                     (k->flags & TT_KEY_MIN_EXCL) ? "above" : "at least", k->min, sp, sym,
                     (k->flags & TT_KEY_MAX_EXCL) ? "below" : "at most", k->max, sp, sym);
        else if (!lo_ok)
            snprintf(why, len, "%s is out of range; expected %s %g%s%s", v,
                     (k->flags & TT_KEY_MIN_EXCL) ? "above" : "at least", k->min, sp, sym);
        else
            snprintf(why, len, "%s is out of range; expected %s %g%s%s", v,
                     (k->flags & TT_KEY_MAX_EXCL) ? "below" : "at most", k->max, sp, sym);
        return -1;
    }
    return 0;
}

static entry *find_entry(const tt_scene *s, const char *section, const char *name,
                         const char *key)
{
    for (size_t i = 0; i < s->n; i++)
        if (strcmp(s->entries[i].section, section) == 0 && streq(s->entries[i].name, name) &&
            strcmp(s->entries[i].key, key) == 0)
            return &s->entries[i];
    return NULL;
}

static int note_section(tt_scene *s, const char *section, const char *name, const char *origin)
{
    for (size_t i = 0; i < s->nuses; i++)
        if (strcmp(s->uses[i].section, section) == 0 && streq(s->uses[i].name, name))
            return TT_OK;
    if (s->nuses == s->capuses) {
        size_t cap = s->capuses ? 2 * s->capuses : 8;
        section_use *u = realloc(s->uses, cap * sizeof *u);
        if (!u)
            return tt_error(TT_ENOMEM, "out of memory reading the scene");
        s->uses = u;
        s->capuses = cap;
    }
    section_use *u = &s->uses[s->nuses];
    u->section = dupstr(section);
    u->name = dupstr(name);
    u->origin = dupstr(origin);
    if (!u->section || (name && !u->name) || !u->origin)
        return tt_error(TT_ENOMEM, "out of memory reading the scene");
    s->nuses++;
    return TT_OK;
}

/* Validate and store one key; origin names the file for messages. */
static int put(tt_scene *s, const char *origin, const char *section, const char *name,
               const char *key, const char *value)
{
    char label[256], why[512];
    const tt_scene_section *sec = find_section(section);
    section_label(label, sizeof label, section, name);
    if (!sec) {
        size_t n;
        const tt_scene_section *all = tt_scene_schema(&n);
        char known[512];
        size_t used = 0;
        known[0] = '\0';
        for (size_t i = 0; i < n && used + 2 < sizeof known; i++) {
            int w = snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "", all[i].name);
            if (w < 0 || (size_t)w >= sizeof known - used)
                break;
            used += (size_t)w;
        }
        return tt_error(TT_EINVAL, "%s: [%s]: unknown section; known sections: %s", origin, label,
                        known);
    }
    if (sec->named && !name)
        return tt_error(TT_EINVAL, "%s: [%s]: this section needs a name, as in [%s NAME]", origin,
                        label, section);
    if (!sec->named && name)
        return tt_error(TT_EINVAL, "%s: [%s]: this section takes no name; write [%s]", origin, label,
                        section);
    const tt_scene_key *k = find_key(sec, key);
    if (!k) {
        char keys[768];
        return tt_error(TT_EINVAL, "%s: [%s] %s: unknown key; [%s] takes %s", origin, label, key,
                        section, list_keys(sec, keys, sizeof keys));
    }
    if (check_value(k, value, why, sizeof why) != 0)
        return tt_error(TT_EINVAL, "%s: [%s] %s: %s", origin, label, key, why);
    int rc = note_section(s, section, name, origin);
    if (rc)
        return rc;
    entry *e = find_entry(s, section, name, key);
    if (e) {
        char *v = dupstr(value), *o = dupstr(origin);
        if (!v || !o) {
            free(v);
            free(o);
            return tt_error(TT_ENOMEM, "out of memory reading the scene");
        }
        free(e->value);
        free(e->origin);
        e->value = v;
        e->origin = o;
        return TT_OK;
    }
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 32;
        entry *ne = realloc(s->entries, cap * sizeof *ne);
        if (!ne)
            return tt_error(TT_ENOMEM, "out of memory reading the scene");
        s->entries = ne;
        s->cap = cap;
    }
    e = &s->entries[s->n];
    e->section = dupstr(section);
    e->name = dupstr(name);
    e->key = dupstr(key);
    e->value = dupstr(value);
    e->origin = dupstr(origin);
    if (!e->section || (name && !e->name) || !e->key || !e->value || !e->origin)
        return tt_error(TT_ENOMEM, "out of memory reading the scene");
    s->n++;
    return TT_OK;
}

/* Split an INI section header "material glass" into schema section and name. */
static int split_header(const char *header, char *section, size_t slen, char *name, size_t nlen)
{
    const char *p = header;
    while (isspace((unsigned char)*p))
        p++;
    size_t i = 0;
    while (*p && !isspace((unsigned char)*p) && i + 1 < slen)
        section[i++] = *p++;
    section[i] = '\0';
    while (isspace((unsigned char)*p))
        p++;
    i = 0;
    while (*p && i + 1 < nlen)
        name[i++] = *p++;
    while (i > 0 && isspace((unsigned char)name[i - 1]))
        i--;
    name[i] = '\0';
    return 0;
}

typedef struct {
    tt_scene *s;
    const char *origin;
    int status;
    /* keys seen in this file, to refuse a key written twice in one section */
    char **seen;
    size_t nseen, capseen;
} load_ctx;

static int seen_before(load_ctx *c, const char *header, const char *key)
{
    size_t need = strlen(header) + strlen(key) + 2;
    char *id = malloc(need);
    if (!id)
        return 0;
    snprintf(id, need, "%s\n%s", header, key);
    for (size_t i = 0; i < c->nseen; i++)
        if (strcmp(c->seen[i], id) == 0) {
            free(id);
            return 1;
        }
    if (c->nseen == c->capseen) {
        size_t cap = c->capseen ? 2 * c->capseen : 32;
        char **n = realloc(c->seen, cap * sizeof *n);
        if (!n) {
            free(id);
            return 0;
        }
        c->seen = n;
        c->capseen = cap;
    }
    c->seen[c->nseen++] = id;
    return 0;
}

static int on_key(void *user, const char *header, const char *key, const char *value)
{
    load_ctx *c = user;
    char section[128], name[128];
    if (c->status != TT_OK)
        return 0;
    split_header(header, section, sizeof section, name, sizeof name);
    if (section[0] == '\0') {
        c->status = tt_error(TT_EINVAL, "%s: %s: key outside any section; put it under a [section]",
                             c->origin, key);
        return 0;
    }
    if (seen_before(c, header, key)) {
        char label[256];
        section_label(label, sizeof label, section, name[0] ? name : NULL);
        c->status = tt_error(TT_EINVAL, "%s: [%s] %s: given twice in this file", c->origin, label, key);
        return 0;
    }
    c->status = put(c->s, c->origin, section, name[0] ? name : NULL, key, value);
    return c->status == TT_OK;
}

static int finish_load(tt_scene *s, load_ctx *c, int rc, const char *origin)
{
    for (size_t i = 0; i < c->nseen; i++)
        free(c->seen[i]);
    free(c->seen);
    if (c->status != TT_OK)
        return c->status;
    if (rc > 0)
        return tt_error(TT_EINVAL, "%s: line %d: not a section header or key = value line", origin, rc);
    if (rc < 0)
        return tt_error(TT_ENOMEM, "%s: could not be parsed (out of memory)", origin);
    if (!s->origin) {
        s->origin = dupstr(origin);
        if (!s->origin)
            return tt_error(TT_ENOMEM, "out of memory reading the scene");
    }
    return TT_OK;
}

int tt_scene_load(tt_scene *s, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return tt_error(TT_EIO, "%s: cannot open scene file: %s", path, strerror(errno));
    load_ctx c = {s, path, TT_OK, NULL, 0, 0};
    int rc = ini_parse_file(f, on_key, &c);
    fclose(f);
    return finish_load(s, &c, rc, path);
}

int tt_scene_load_string(tt_scene *s, const char *text, const char *origin)
{
    load_ctx c = {s, origin, TT_OK, NULL, 0, 0};
    int rc = ini_parse_string(text, on_key, &c);
    return finish_load(s, &c, rc, origin);
}

int tt_scene_set(tt_scene *s, const char *assignment)
{
    const char *eq = strchr(assignment, '=');
    if (!eq)
        return tt_error(TT_EINVAL, "--set %s: expected section.key=value", assignment);
    char lhs[256];
    size_t n = (size_t)(eq - assignment);
    if (n >= sizeof lhs)
        return tt_error(TT_EINVAL, "--set %s: key too long", assignment);
    memcpy(lhs, assignment, n);
    lhs[n] = '\0';
    while (n > 0 && isspace((unsigned char)lhs[n - 1]))
        lhs[--n] = '\0';
    const char *value = eq + 1;
    while (isspace((unsigned char)*value))
        value++;
    char *d1 = strchr(lhs, '.');
    if (!d1)
        return tt_error(TT_EINVAL, "--set %s: expected section.key=value", assignment);
    *d1 = '\0';
    const char *section = lhs, *name = NULL, *key = d1 + 1;
    /* "material.glass.youngs_modulus": the last dot separates the key. */
    char *d2 = strrchr(d1 + 1, '.');
    if (d2) {
        *d2 = '\0';
        name = d1 + 1;
        key = d2 + 1;
    }
    char valbuf[512];
    snprintf(valbuf, sizeof valbuf, "%s", value);
    size_t vl = strlen(valbuf);
    while (vl > 0 && isspace((unsigned char)valbuf[vl - 1]))
        valbuf[--vl] = '\0';
    return put(s, "--set", section, name, key, valbuf);
}

int tt_scene_has(const tt_scene *s, const char *section, const char *name, const char *key)
{
    return find_entry(s, section, name, key) != NULL;
}

int tt_scene_has_section(const tt_scene *s, const char *section, const char *name)
{
    for (size_t i = 0; i < s->nuses; i++)
        if (strcmp(s->uses[i].section, section) == 0 && (name == NULL || streq(s->uses[i].name, name)))
            return 1;
    return 0;
}

size_t tt_scene_count_named(const tt_scene *s, const char *section)
{
    size_t n = 0;
    for (size_t i = 0; i < s->nuses; i++)
        if (strcmp(s->uses[i].section, section) == 0 && s->uses[i].name)
            n++;
    return n;
}

const char *tt_scene_named(const tt_scene *s, const char *section, size_t idx)
{
    size_t n = 0;
    for (size_t i = 0; i < s->nuses; i++)
        if (strcmp(s->uses[i].section, section) == 0 && s->uses[i].name) {
            if (n == idx)
                return s->uses[i].name;
            n++;
        }
    return NULL;
}

static const char *origin_of(const tt_scene *s, const char *section, const char *name,
                             const char *key)
{
    const entry *e = key ? find_entry(s, section, name, key) : NULL;
    if (e)
        return e->origin;
    for (size_t i = 0; i < s->nuses; i++)
        if (strcmp(s->uses[i].section, section) == 0 && streq(s->uses[i].name, name))
            return s->uses[i].origin;
    return tt_scene_origin(s);
}

int tt_scene_fail(const tt_scene *s, const char *section, const char *name, const char *key,
                  const char *fmt, ...)
{
    char label[256], msg[700];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    section_label(label, sizeof label, section, name);
    if (!s && key)
        return tt_error(TT_EINVAL, "[%s] %s: %s", label, key, msg);
    if (!s)
        return tt_error(TT_EINVAL, "[%s]: %s", label, msg);
    if (key)
        return tt_error(TT_EINVAL, "%s: [%s] %s: %s", origin_of(s, section, name, key), label, key,
                        msg);
    return tt_error(TT_EINVAL, "%s: [%s]: %s", origin_of(s, section, name, key), label, msg);
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
    const tt_scene_section *sec = find_section(section);
    const tt_scene_key *k = sec ? find_key(sec, key) : NULL;
    if (!k)
        return tt_error(TT_EINVAL, "internal: [%s] %s is not in the schema", section, key);
    const entry *e = find_entry(s, section, name, key);
    *kd = k;
    *text = e ? e->value : k->def;
    if (!*text)
        return tt_scene_fail(s, section, name, key, "missing; expected %s",
                             k->kind == TT_KEY_QUANTITY ? tt_units_describe(k->dims) : "a value");
    return TT_OK;
}

int tt_scene_get_quantity(const tt_scene *s, const char *section, const char *name,
                          const char *key, double *out, tt_dim *dim)
{
    const char *text;
    const tt_scene_key *k;
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
    if (parse_bool(text, out) != 0)
        return tt_scene_fail(s, section, name, key, "'%s' is not yes or no", text);
    return TT_OK;
}

const char *tt_scene_get_string(const tt_scene *s, const char *section, const char *name,
                                const char *key)
{
    const entry *e = find_entry(s, section, name, key);
    if (e)
        return e->value;
    const tt_scene_section *sec = find_section(section);
    const tt_scene_key *k = sec ? find_key(sec, key) : NULL;
    return k ? k->def : NULL;
}

int tt_scene_get_path(const tt_scene *s, const char *section, const char *name, const char *key,
                      char *buf, size_t len)
{
    const entry *e = find_entry(s, section, name, key);
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
    const tt_scene_section *sec = find_section(section);
    const tt_scene_key *k = sec ? find_key(sec, key) : NULL;
    char why[512];
    if (!k)
        return tt_error(TT_EINVAL, "[%s] %s: unknown key", section, key);
    if (check_value(k, text, why, sizeof why) != 0)
        return tt_error(TT_EINVAL, "[%s] %s: %s", section, key, why);
    if (k->kind == TT_KEY_QUANTITY)
        return tt_units_parse(text, k->dims, out, NULL, why, sizeof why) == 0 ? TT_OK : TT_EINVAL;
    if (k->kind == TT_KEY_INT) {
        *out = (double)strtol(text, NULL, 10);
        return TT_OK;
    }
    return tt_error(TT_EINVAL, "[%s] %s: not a number-valued key", section, key);
}

static int wanted(const char *sections, const char *name)
{
    if (!sections)
        return 1;
    return enum_has(sections, name);
}

/* Defaults that do not apply when another key of the same section is given: writing
 * them out would make the effective scene contradict itself. */
static const struct {
    const char *section, *key, *given;
} yields[] = {
    {"material", "youngs_modulus", "reduced_modulus"},
    {"material", "poisson_ratio", "reduced_modulus"},
};

static int default_yields(const tt_scene *s, const char *section, const char *name,
                          const char *key)
{
    for (size_t i = 0; i < sizeof yields / sizeof yields[0]; i++)
        if (strcmp(yields[i].section, section) == 0 && strcmp(yields[i].key, key) == 0 &&
            tt_scene_has(s, section, name, yields[i].given))
            return 1;
    return 0;
}

int tt_scene_write(const tt_scene *s, FILE *out, const char *sections)
{
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    fprintf(out, "; effective scene written by tiptap: every key, defaults included\n");
    for (size_t i = 0; i < n; i++) {
        if (!wanted(sections, sec[i].name))
            continue;
        size_t names = sec[i].named ? tt_scene_count_named(s, sec[i].name) : 1;
        for (size_t j = 0; j < names; j++) {
            const char *name = sec[i].named ? tt_scene_named(s, sec[i].name, j) : NULL;
            if (name)
                fprintf(out, "\n[%s %s]\n", sec[i].name, name);
            else
                fprintf(out, "\n[%s]\n", sec[i].name);
            for (size_t k = 0; k < sec[i].nkeys; k++) {
                const entry *e = find_entry(s, sec[i].name, name, sec[i].keys[k].key);
                const char *v = e ? e->value : sec[i].keys[k].def;
                if (!e && default_yields(s, sec[i].name, name, sec[i].keys[k].key))
                    continue;
                char path[4096], abs[4096];
                if (e && (sec[i].keys[k].flags & TT_KEY_PATH) &&
                    tt_scene_get_path(s, sec[i].name, name, sec[i].keys[k].key, path, sizeof path) ==
                        TT_OK) {
                    /* the written scene lives elsewhere: name files absolutely */
                    v = realpath(path, abs) ? abs : path;
                }
                if (v)
                    fprintf(out, "%s = %s\n", sec[i].keys[k].key, v);
            }
        }
    }
    return ferror(out) ? tt_error(TT_EIO, "could not write the scene") : TT_OK;
}
