/* The scene's key store: every key given, and every section that appeared, in order of
 * appearance, with the file that set it; hash indexes by (section, name, key) and by
 * (section, name), and the names of each named section, so that a scene of 50,000
 * materials reads and lists in linear time. Values arrive here already checked
 * (scene_check.c); this file only keeps them (see src/config/scene_private.h). */
#include "scene_private.h"

#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

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
        return tt_error_nomem("the scene's key index (%zu slots)", cap);
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

entry *scene_find_entry(const tt_scene *s, const char *section, const char *name,
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

const section_use *scene_find_use(const tt_scene *s, const char *section, const char *name)
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

/* The list of names of a named schema section, NULL for an unknown one. */
static name_list *names_of(const tt_scene *s, const char *section)
{
    size_t n;
    const tt_scene_section *all = tt_scene_schema(&n);
    const tt_scene_section *sec = scene_find_section(section);
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
            return tt_error_nomem("the scene's section names");
    }
    name_list *l = names_of(s, section);
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 8;
        size_t *u = realloc(l->use, cap * sizeof *u);
        if (!u)
            return tt_error_nomem("the names of the scene's [%s] sections", section);
        l->use = u;
        l->cap = cap;
    }
    l->use[l->n++] = use;
    return TT_OK;
}

tt_scene *tt_scene_alloc(void) { return calloc(1, sizeof(tt_scene)); }

int scene_note_file(tt_scene *s, const char *path)
{
    char **grown = realloc(s->files, (s->nfiles + 1) * sizeof *grown);
    if (!grown)
        return tt_error_nomem("the list of the scene's files (%s)", path);
    s->files = grown;
    if (!(s->files[s->nfiles] = tt_strdup(path)))
        return tt_error_nomem("the list of the scene's files (%s)", path);
    s->nfiles++;
    return TT_OK;
}

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
    for (size_t i = 0; i < s->nfiles; i++)
        free(s->files[i]);
    free(s->files);
    free(s);
}

int scene_note_section(tt_scene *s, const char *section, const char *name, const char *origin)
{
    if (scene_find_use(s, section, name))
        return TT_OK;
    if (s->nuses == s->capuses) {
        size_t cap = s->capuses ? 2 * s->capuses : 8;
        section_use *u = realloc(s->uses, cap * sizeof *u);
        if (!u)
            return tt_error_nomem("the sections of the scene (at [%s%s%s] from %s)", section, name ? " " : "", name ? name : "", origin);
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
        return tt_error_nomem("the sections of the scene (at [%s%s%s] from %s)", section, name ? " " : "", name ? name : "", origin);
    }
    if (name && (rc = names_add(s, section, s->nuses))) {
        free(u->section);
        free(u->name);
        free(u->origin);
        return rc;
    }
    index_add(&s->by_section, use_hash(u), s->nuses);
    s->nuses++;
    return TT_OK;
}

/* Store one checked key (a new one, or a new value for a key already there). */
int scene_store(tt_scene *s, const char *origin, unsigned load, const char *section,
                const char *name, const char *key, const char *value)
{
    entry *e = scene_find_entry(s, section, name, key);
    char *v = tt_strdup(value), *o = tt_strdup(origin);
    if (!v || !o) {
        free(v);
        free(o);
        return tt_error_nomem("[%s%s%s] %s from %s (a value of %zu bytes)", section, name ? " " : "",
                              name ? name : "", key, origin, strlen(value));
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
            rc = tt_error_nomem("[%s%s%s] %s from %s", section, name ? " " : "", name ? name : "", key, origin);
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
            rc = tt_error_nomem("[%s%s%s] %s from %s", section, name ? " " : "", name ? name : "", key, origin);
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
        rc = scene_note_section(c, s->uses[i].section, s->uses[i].name, s->uses[i].origin);
    for (size_t i = 0; i < s->n && !rc; i++) {
        const entry *e = &s->entries[i];
        rc = scene_store(c, e->origin, e->load, e->section, e->name, e->key, e->value);
    }
    for (size_t i = 0; i < s->nfiles && !rc; i++)
        rc = scene_note_file(c, s->files[i]);
    if (rc) {
        tt_scene_free(c);
        return NULL;
    }
    return c;
}

const char *tt_scene_origin(const tt_scene *s) { return s->origin ? s->origin : "scene"; }

int tt_scene_has(const tt_scene *s, const char *section, const char *name, const char *key)
{
    return scene_find_entry(s, section, name, key) != NULL;
}

int tt_scene_has_section(const tt_scene *s, const char *section, const char *name)
{
    if (name)
        return scene_find_use(s, section, name) != NULL;
    return scene_find_use(s, section, NULL) != NULL || tt_scene_count_named(s, section) > 0;
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
