/* INI scene files: reading, validation against the schema, overrides, typed getters
 * and the effective-scene writer (see include/tiptap/config/scene.h). */
#include "tiptap/config/scene.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tiptap/config/ini.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

typedef struct {
    char *section; /* schema section name, "material" */
    char *name;    /* NULL or the section's name, "glass" */
    char *key;
    char *value;
    char *origin;  /* file that set it, or "--set" */
    unsigned load; /* which tt_scene_load set it (0: --set), to refuse a key given twice */
} entry;

typedef struct {
    char *section;
    char *name;
    char *origin;
} section_use;

/* The names of one named section in order of appearance (indices into uses), so that
 * listing 50,000 materials is linear. */
typedef struct {
    size_t *use;
    size_t n, cap;
} name_list;

/* Open-addressing hash index: slot holds an array index + 1, 0 when empty. */
typedef struct {
    size_t *slot;
    size_t cap; /* a power of two, at least twice the number of items */
} hash_index;

struct tt_scene {
    entry *entries;
    size_t n, cap;
    section_use *uses; /* sections in order of appearance (named ones once per name) */
    size_t nuses, capuses;
    char *origin;
    hash_index by_key;     /* (section, name, key) -> entries */
    hash_index by_section; /* (section, name) -> uses */
    name_list *names;      /* per schema section */
    unsigned loads;        /* files read so far */
};

static int streq(const char *a, const char *b)
{
    if (!a || !b)
        return a == b;
    return strcmp(a, b) == 0;
}

/* FNV-1a over section, name and key; a NULL name hashes apart from "". */
static size_t hash_of(const char *section, const char *name, const char *key)
{
    const char *part[3] = {section, name ? name : "\x01", key ? key : ""};
    size_t h = 1469598103934665603u;
    for (int i = 0; i < 3; i++) {
        for (const unsigned char *p = (const unsigned char *)part[i]; *p; p++)
            h = (h ^ *p) * 1099511628211u;
        h = (h ^ 0xff) * 1099511628211u;
    }
    return h;
}

static size_t entry_hash(const entry *e) { return hash_of(e->section, e->name, e->key); }
static size_t use_hash(const section_use *u) { return hash_of(u->section, u->name, NULL); }

/* Make room for one more of n items, rehashing all n when the table grows. */
static int index_reserve(hash_index *h, size_t n, const void *items, size_t size,
                         size_t (*hash)(const void *))
{
    if (2 * (n + 1) <= h->cap)
        return TT_OK;
    size_t cap = h->cap ? 2 * h->cap : 64;
    while (cap < 2 * (n + 1))
        cap *= 2;
    size_t *slot = calloc(cap, sizeof *slot);
    if (!slot)
        return tt_error(TT_ENOMEM, "out of memory reading the scene");
    for (size_t i = 0; i < n; i++) {
        size_t j = hash((const char *)items + i * size) & (cap - 1);
        while (slot[j])
            j = (j + 1) & (cap - 1);
        slot[j] = i + 1;
    }
    free(h->slot);
    h->slot = slot;
    h->cap = cap;
    return TT_OK;
}

static void index_add(hash_index *h, size_t hash, size_t i)
{
    size_t j = hash & (h->cap - 1);
    while (h->slot[j])
        j = (j + 1) & (h->cap - 1);
    h->slot[j] = i + 1;
}

static size_t entry_hash_v(const void *e) { return entry_hash(e); }
static size_t use_hash_v(const void *u) { return use_hash(u); }

static entry *find_entry(const tt_scene *s, const char *section, const char *name,
                         const char *key)
{
    if (!s->by_key.cap)
        return NULL;
    for (size_t j = hash_of(section, name, key) & (s->by_key.cap - 1); s->by_key.slot[j];
         j = (j + 1) & (s->by_key.cap - 1)) {
        entry *e = &s->entries[s->by_key.slot[j] - 1];
        if (strcmp(e->section, section) == 0 && streq(e->name, name) && strcmp(e->key, key) == 0)
            return e;
    }
    return NULL;
}

static const section_use *find_use(const tt_scene *s, const char *section, const char *name)
{
    if (!s->by_section.cap)
        return NULL;
    for (size_t j = hash_of(section, name, NULL) & (s->by_section.cap - 1); s->by_section.slot[j];
         j = (j + 1) & (s->by_section.cap - 1)) {
        const section_use *u = &s->uses[s->by_section.slot[j] - 1];
        if (strcmp(u->section, section) == 0 && streq(u->name, name))
            return u;
    }
    return NULL;
}

static const tt_scene_section *find_section(const char *name);

/* The list of names of a named schema section, NULL for an unknown one. */
static name_list *names_of(const tt_scene *s, const char *section)
{
    size_t n;
    const tt_scene_section *all = tt_scene_schema(&n);
    const tt_scene_section *sec = find_section(section);
    if (!sec || !s->names)
        return NULL;
    return &s->names[sec - all];
}

static int names_add(tt_scene *s, const char *section, size_t use)
{
    if (!s->names) {
        size_t n;
        tt_scene_schema(&n);
        s->names = calloc(n, sizeof *s->names);
        if (!s->names)
            return tt_error(TT_ENOMEM, "out of memory reading the scene");
    }
    name_list *l = names_of(s, section);
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 8;
        size_t *u = realloc(l->use, cap * sizeof *u);
        if (!u)
            return tt_error(TT_ENOMEM, "out of memory reading the scene");
        l->use = u;
        l->cap = cap;
    }
    l->use[l->n++] = use;
    return TT_OK;
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
    if (s->names) {
        size_t n;
        tt_scene_schema(&n);
        for (size_t i = 0; i < n; i++)
            free(s->names[i].use);
    }
    free(s->names);
    free(s->by_key.slot);
    free(s->by_section.slot);
    free(s->entries);
    free(s->uses);
    free(s->origin);
    free(s);
}

static int note_section(tt_scene *s, const char *section, const char *name, const char *origin);
static int store(tt_scene *s, const char *origin, unsigned load, const char *section,
                 const char *name, const char *key, const char *value);

tt_scene *tt_scene_copy(const tt_scene *s)
{
    tt_scene *c = tt_scene_alloc();
    if (!c)
        return NULL;
    c->origin = tt_strdup(s->origin);
    c->loads = s->loads;
    int rc = (s->origin && !c->origin) ? TT_ENOMEM : TT_OK;
    /* sections first, so that their order and origins are kept */
    for (size_t i = 0; i < s->nuses && !rc; i++)
        rc = note_section(c, s->uses[i].section, s->uses[i].name, s->uses[i].origin);
    for (size_t i = 0; i < s->n && !rc; i++) {
        const entry *e = &s->entries[i];
        rc = store(c, e->origin, e->load, e->section, e->name, e->key, e->value);
    }
    if (rc) {
        tt_scene_free(c);
        return NULL;
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

static int note_section(tt_scene *s, const char *section, const char *name, const char *origin)
{
    if (find_use(s, section, name))
        return TT_OK;
    if (s->nuses == s->capuses) {
        size_t cap = s->capuses ? 2 * s->capuses : 8;
        section_use *u = realloc(s->uses, cap * sizeof *u);
        if (!u)
            return tt_error(TT_ENOMEM, "out of memory reading the scene");
        s->uses = u;
        s->capuses = cap;
    }
    int rc = index_reserve(&s->by_section, s->nuses, s->uses, sizeof *s->uses, use_hash_v);
    if (rc)
        return rc;
    section_use *u = &s->uses[s->nuses];
    u->section = tt_strdup(section);
    u->name = tt_strdup(name);
    u->origin = tt_strdup(origin);
    if (!u->section || (name && !u->name) || !u->origin) {
        free(u->section);
        free(u->name);
        free(u->origin);
        return tt_error(TT_ENOMEM, "out of memory reading the scene");
    }
    if (name && (rc = names_add(s, section, s->nuses)))
        return rc;
    index_add(&s->by_section, use_hash(u), s->nuses);
    s->nuses++;
    return TT_OK;
}

/* Store one checked key (a new one, or a new value for a key already there). */
static int store(tt_scene *s, const char *origin, unsigned load, const char *section,
                 const char *name, const char *key, const char *value)
{
    entry *e = find_entry(s, section, name, key);
    char *v = tt_strdup(value), *o = tt_strdup(origin);
    if (!v || !o) {
        free(v);
        free(o);
        return tt_error(TT_ENOMEM, "out of memory reading the scene");
    }
    if (e) {
        free(e->value);
        free(e->origin);
        e->value = v;
        e->origin = o;
        e->load = load;
        return TT_OK;
    }
    int rc = TT_OK;
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 32;
        entry *ne = realloc(s->entries, cap * sizeof *ne);
        if (!ne)
            rc = tt_error(TT_ENOMEM, "out of memory reading the scene");
        else {
            s->entries = ne;
            s->cap = cap;
        }
    }
    if (!rc)
        rc = index_reserve(&s->by_key, s->n, s->entries, sizeof *s->entries, entry_hash_v);
    if (!rc) {
        e = &s->entries[s->n];
        *e = (entry){tt_strdup(section), tt_strdup(name), tt_strdup(key), v, o, load};
        if (!e->section || (name && !e->name) || !e->key) {
            free(e->section);
            free(e->name);
            free(e->key);
            rc = tt_error(TT_ENOMEM, "out of memory reading the scene");
        }
    }
    if (rc) {
        free(v);
        free(o);
        return rc;
    }
    index_add(&s->by_key, entry_hash(e), s->n);
    s->n++;
    return TT_OK;
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
static int check_section(const char *origin, const char *section, const char *name)
{
    char label[256], shown[160];
    const tt_scene_section *sec = find_section(section);
    section_label(label, sizeof label, section, name);
    tt_ini_escape(label, shown, sizeof shown);
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
static int put(tt_scene *s, const char *origin, unsigned load, const char *section,
               const char *name, const char *key, const char *value)
{
    char label[256], why[512], shown[160];
    int rc = check_section(origin, section, name);
    if (rc)
        return rc;
    const tt_scene_section *sec = find_section(section);
    section_label(label, sizeof label, section, name);
    const tt_scene_key *k = find_key(sec, key);
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
    if (check_value(k, value, why, sizeof why) != 0)
        return tt_error(TT_EINVAL, "%s: [%s] %s: %s", origin, label, key, why);
    const entry *e = find_entry(s, section, name, key);
    if (e && load && e->load == load)
        return tt_error(TT_EINVAL, "%s: [%s] %s: given twice in this file", origin, label, key);
    if ((rc = note_section(s, section, name, origin)))
        return rc;
    return store(s, origin, load, section, name, key, value);
}

/* Split an INI section header "material glass" into schema section and name (NULL when
 * there is none); both are allocated together in *buf, which the caller frees. */
static int split_header(const char *header, char **buf, const char **section, const char **name)
{
    size_t n = strlen(header);
    char *b = malloc(n + 1);
    if (!b)
        return tt_error(TT_ENOMEM, "out of memory reading the scene");
    memcpy(b, header, n + 1);
    char *p = b;
    while (*p && !isspace((unsigned char)*p))
        p++;
    char *rest = p;
    while (isspace((unsigned char)*rest))
        rest++;
    *p = '\0';
    *buf = b;
    *section = b;
    *name = *rest ? rest : NULL;
    return TT_OK;
}

typedef struct {
    tt_scene *s;
    const char *origin;
    unsigned load;
} load_ctx;

static int on_item(void *user, const tt_ini_item *it)
{
    load_ctx *c = user;
    char *buf = NULL;
    const char *section = NULL, *name = NULL;
    char shown[160];
    if (!it->key && !it->section[0])
        return tt_error(TT_EINVAL, "%s: line %ld: empty section header '[]'", c->origin, it->line);
    if (!it->section[0])
        return tt_error(TT_EINVAL, "%s: %s: key outside any section; put it under a [section]",
                        c->origin, tt_ini_escape(it->key, shown, sizeof shown));
    int rc = split_header(it->section, &buf, &section, &name);
    if (rc)
        return rc;
    if (!it->key) {
        /* a section without keys still exists: [material glass] with all defaults */
        rc = check_section(c->origin, section, name);
        if (!rc)
            rc = note_section(c->s, section, name, c->origin);
    } else {
        rc = put(c->s, c->origin, c->load, section, name, it->key, it->value);
    }
    free(buf);
    return rc;
}

static int load_text(tt_scene *s, const char *text, size_t len, const char *origin)
{
    load_ctx c = {s, origin, ++s->loads};
    int rc = tt_ini_parse(text, len, origin, on_item, &c);
    if (rc)
        return rc;
    if (!s->origin && !(s->origin = tt_strdup(origin)))
        return tt_error(TT_ENOMEM, "out of memory reading the scene");
    return TT_OK;
}

/* The largest scene file read: far above any real scene (50,000 materials take 5 MB). */
#define TT_SCENE_MAX_BYTES (256L << 20)

int tt_scene_load(tt_scene *s, const char *path)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return tt_error(TT_EIO, "%s: cannot open scene file: %s", path, strerror(errno));
    struct stat st;
    int rc = TT_OK;
    char *text = NULL;
    size_t len = 0;
    /* a folder reads as empty and /dev/zero never ends: only regular files are scenes */
    if (fstat(fd, &st) != 0)
        rc = tt_error(TT_EIO, "%s: cannot read scene file: %s", path, strerror(errno));
    else if (S_ISDIR(st.st_mode))
        rc = tt_error(TT_EINVAL, "%s: is a folder, not a scene file", path);
    else if (!S_ISREG(st.st_mode))
        rc = tt_error(TT_EINVAL, "%s: not a regular file (a device, pipe or socket); a scene is "
                      "a file", path);
    else if (st.st_size > TT_SCENE_MAX_BYTES)
        rc = tt_error(TT_EINVAL, "%s: %lld bytes is too large for a scene file (at most %ld)", path,
                      (long long)st.st_size, TT_SCENE_MAX_BYTES);
    else if (!(text = malloc((size_t)st.st_size + 1)))
        rc = tt_error(TT_ENOMEM, "%s: out of memory reading the scene", path);
    while (!rc && len <= (size_t)st.st_size) {
        ssize_t got = read(fd, text + len, (size_t)st.st_size + 1 - len);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0)
            rc = tt_error(TT_EIO, "%s: cannot read scene file: %s", path, strerror(errno));
        else if (got == 0)
            break;
        else
            len += (size_t)got;
    }
    close(fd);
    if (!rc && len > (size_t)st.st_size)
        rc = tt_error(TT_EIO, "%s: the file grew while it was read", path);
    if (!rc)
        rc = load_text(s, text, len, path);
    free(text);
    return rc;
}

int tt_scene_load_string(tt_scene *s, const char *text, const char *origin)
{
    return load_text(s, text, strlen(text), origin);
}

/* A --set into a named section the scene lacks would make a new one that nothing uses
 * (material.silicone.KEY when the scene has [material silicon]): refused with the names
 * it has. A scene without any has the default material, "sample". Unnamed sections
 * ([approach], [trace], ...) are made by a --set as by a file. */
static int check_set_names(const tt_scene *s, const char *shown, const char *section,
                           const char *name)
{
    const tt_scene_section *sec = find_section(section);
    if (!sec || !sec->named || !name || find_use(s, section, name))
        return TT_OK;
    size_t n = tt_scene_count_named(s, section);
    if (n == 0 && strcmp(section, "material") == 0 && strcmp(name, "sample") == 0)
        return TT_OK;
    char have[512] = "", nm[160];
    size_t used = 0;
    for (size_t i = 0; i < n && used + 8 < sizeof have; i++) {
        tt_ini_escape(tt_scene_named(s, section, i), nm, sizeof nm);
        int w = snprintf(have + used, sizeof have - used, "%s%s", i ? ", " : "", nm);
        if (w < 0 || (size_t)w >= sizeof have - used) {
            snprintf(have + used, sizeof have - used, ", ...");
            break;
        }
        used += (size_t)w;
    }
    tt_ini_escape(name, nm, sizeof nm);
    return tt_error(TT_EINVAL, "--set %s: no [%s %s] in the scene; it has: %s", shown, section, nm,
                    n ? have : strcmp(section, "material") == 0 ? "none but the default, sample"
                                                                : "none");
}

int tt_scene_set(tt_scene *s, const char *assignment)
{
    char shown[160];
    const char *eq = strchr(assignment, '=');
    tt_ini_escape(assignment, shown, sizeof shown);
    if (!eq)
        return tt_error(TT_EINVAL, "--set %s: expected section.key=value", shown);
    size_t n = (size_t)(eq - assignment);
    char *lhs = malloc(n + 1);
    if (!lhs)
        return tt_error(TT_ENOMEM, "out of memory reading --set");
    memcpy(lhs, assignment, n);
    lhs[n] = '\0';
    while (n > 0 && isspace((unsigned char)lhs[n - 1]))
        lhs[--n] = '\0';
    const char *value = eq + 1;
    while (isspace((unsigned char)*value) && *value != '\n' && *value != '\r')
        value++;
    size_t vl = strlen(value);
    while (vl > 0 && (value[vl - 1] == ' ' || value[vl - 1] == '\t'))
        vl--;
    char *val = malloc(vl + 1);
    char *d1 = strchr(lhs, '.');
    int rc = TT_OK;
    if (!val)
        rc = tt_error(TT_ENOMEM, "out of memory reading --set");
    else if (!d1)
        rc = tt_error(TT_EINVAL, "--set %s: expected section.key=value", shown);
    if (!rc) {
        memcpy(val, value, vl);
        val[vl] = '\0';
        *d1 = '\0';
        const char *section = lhs, *name = NULL, *key = d1 + 1;
        /* "material.glass.youngs_modulus": the last dot separates the key. */
        char *d2 = strrchr(d1 + 1, '.');
        if (d2) {
            *d2 = '\0';
            name = d1 + 1;
            key = d2 + 1;
        }
        if (!section[0] || !key[0] || (name && !name[0]))
            rc = tt_error(TT_EINVAL, "--set %s: empty %s; expected section.key=value or "
                          "section.name.key=value", shown,
                          !section[0] ? "section" : !key[0] ? "key" : "name");
        else if (!(rc = check_set_names(s, shown, section, name)))
            rc = put(s, "--set", 0, section, name, key, val);
    }
    free(val);
    free(lhs);
    return rc;
}

int tt_scene_has(const tt_scene *s, const char *section, const char *name, const char *key)
{
    return find_entry(s, section, name, key) != NULL;
}

int tt_scene_has_section(const tt_scene *s, const char *section, const char *name)
{
    if (name)
        return find_use(s, section, name) != NULL;
    return find_use(s, section, NULL) != NULL || tt_scene_count_named(s, section) > 0;
}

size_t tt_scene_count_named(const tt_scene *s, const char *section)
{
    const name_list *l = names_of(s, section);
    return l ? l->n : 0;
}

const char *tt_scene_named(const tt_scene *s, const char *section, size_t idx)
{
    const name_list *l = names_of(s, section);
    return l && idx < l->n ? s->uses[l->use[idx]].name : NULL;
}

static const char *origin_of(const tt_scene *s, const char *section, const char *name,
                             const char *key)
{
    const entry *e = key ? find_entry(s, section, name, key) : NULL;
    if (e)
        return e->origin;
    const section_use *u = find_use(s, section, name);
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
