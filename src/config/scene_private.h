/* tiptap: the scene's insides (internal to the config layer), shared by the five files
 * that implement tiptap/config/scene.h: the key store and its hash indexes
 * (scene_store.c), the checks against the schema (scene_check.c), loading files and
 * --set (scene_load.c), the typed getters (scene_get.c) and the effective scene
 * (scene_write.c). Nothing outside src/config/ includes it.
 *
 * Ownership: the scene owns every string in it; the pointers returned below point into
 * the scene (or the schema) and live as long as it does.
 */
#ifndef TIPTAP_SCENE_PRIVATE_H
#define TIPTAP_SCENE_PRIVATE_H

#include <stddef.h>

#include "tiptap/config/scene.h"

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
    char **files;          /* the files read (tt_scene_load), as named: inputs of its runs */
    size_t nfiles;
};

/* scene_store.c */

/* The entry of section.key ([section name] when name is not NULL), NULL when not given. */
entry *scene_find_entry(const tt_scene *s, const char *section, const char *name,
                        const char *key);
/* The section's first appearance, NULL when the scene has no such section. */
const section_use *scene_find_use(const tt_scene *s, const char *section, const char *name);
/* Record that a section appears (a no-op when it already did), keeping the origin of its
 * first appearance. */
int scene_note_section(tt_scene *s, const char *section, const char *name, const char *origin);
/* Remember a file the scene was read from. */
int scene_note_file(tt_scene *s, const char *path);
/* Store one checked key (a new one, or a new value for a key already there). */
int scene_store(tt_scene *s, const char *origin, unsigned load, const char *section,
                const char *name, const char *key, const char *value);

/* scene_check.c */

/* The schema's section and key by name, NULL when unknown. */
const tt_scene_section *scene_find_section(const char *name);
const tt_scene_key *scene_find_key(const tt_scene_section *sec, const char *key);
/* "[material glass]" -> "material glass" in messages; "[cantilever]" -> "cantilever". */
void scene_section_label(char *buf, size_t len, const char *section, const char *name);
/* yes/true/on/1 and no/false/off/0, any case: 0 and *out set, or -1. */
int scene_parse_bool(const char *v, int *out);
/* Append item to the comma-separated list in buf (len bytes; *used of them so far) for a
 * message: 0, or -1 when it does not fit (buf then holds the items before it). */
int scene_list_add(char *buf, size_t len, size_t *used, const char *item);
/* Whether v is one of choices, "a|b|c". */
int scene_enum_has(const char *choices, const char *v);
/* Whether the scene's surface type reads KEY of [surface] (read_surface.c). */
int scene_surface_key_applies(const tt_scene *s, const char *key);
/* Check one value against its key description; on failure (-1) write why. */
int scene_check_value(const tt_scene_key *k, const char *v, char *why, size_t len);
/* Check a section header: a known section, with a name exactly when it takes one. */
int scene_check_section(const char *origin, const char *section, const char *name);
/* Validate and store one key; origin names the file for messages, load the file read
 * (0: --set) to refuse a key given twice in one file. */
int scene_put(tt_scene *s, const char *origin, unsigned load, const char *section,
              const char *name, const char *key, const char *value);

#endif
