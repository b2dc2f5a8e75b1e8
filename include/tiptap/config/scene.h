/* tiptap: scene files.
 *
 * A scene is an INI file (or several, read in order, later ones overriding earlier
 * ones) plus command-line overrides "--set section.key=value". Every key is described
 * by a schema (section, key, kind, unit, default, range); the scene refuses unknown
 * sections and keys, values without or with wrong units, and values out of range, with
 * a one-line message "file: [section] key: what is wrong".
 *
 * Named sections such as "[material glass]" may appear several times with different
 * names; on the command line they are written "material.glass.key=value".
 *
 * Ownership: tt_scene_alloc returns a scene the caller frees with tt_scene_free.
 * Strings returned by the getters belong to the scene and live as long as it does.
 */
#ifndef TIPTAP_SCENE_H
#define TIPTAP_SCENE_H

#include <stddef.h>
#include <stdio.h>

#include "tiptap/export.h"
#include "tiptap/config/units.h"

TT_BEGIN_DECLS

typedef enum {
    TT_KEY_QUANTITY, /* a number with a unit (dims says which) */
    TT_KEY_INT,      /* a whole number */
    TT_KEY_ENUM,     /* one of choices, "a|b|c" */
    TT_KEY_STRING,   /* free text: a name, a path, a list */
    TT_KEY_BOOL      /* yes/no, true/false, on/off, 1/0 */
} tt_key_kind;

enum {
    TT_KEY_MIN_EXCL = 1 << 0, /* value must be > min, not >= */
    TT_KEY_MAX_EXCL = 1 << 1, /* value must be < max, not <= */
    TT_KEY_PATH = 1 << 2      /* a string that is a path relative to the scene file */
};

typedef struct {
    const char *key;
    tt_key_kind kind;
    unsigned dims;       /* TT_KEY_QUANTITY: accepted dimensions (tt_dim mask) */
    const char *def;     /* default as written in a scene; NULL: absent unless given */
    double min, max;     /* allowed range in SI units (QUANTITY, INT) */
    unsigned flags;
    const char *choices; /* TT_KEY_ENUM: "maugis|hertz|dmt|jkr" */
    const char *doc;     /* one line for --help and docs */
} tt_scene_key;

typedef struct {
    const char *name;
    int named; /* 1: written [name NAME], may repeat with different names */
    const tt_scene_key *keys;
    size_t nkeys;
    const char *doc;
} tt_scene_section;

/* The schema: all sections tiptap knows, in documentation order. */
const tt_scene_section *tt_scene_schema(size_t *count);

/* What a key's value looks like, for listings and messages (static text): the choices,
 * "integer", "yes|no", "text", or the quantity with an example, for a key without a unit
 * an example of its own ("a number, no unit, such as '0.3'" for poisson_ratio). */
const char *tt_scene_key_describe(const tt_scene_key *k);

typedef struct tt_scene tt_scene;

tt_scene *tt_scene_alloc(void);
void tt_scene_free(tt_scene *s);

/* A deep copy (keys, their origins, sections in use), for a caller that varies some
 * keys without changing the scene it was given; NULL when out of memory. The caller
 * frees it with tt_scene_free. */
tt_scene *tt_scene_copy(const tt_scene *s);

/* Read an INI file into the scene; keys already present are overridden.
 * Fails (TT_EINVAL or TT_EIO) with "file: [section] key: ..." on the first problem. */
int tt_scene_load(tt_scene *s, const char *path);

/* Read INI text (for tests and built-in scenes); origin names it in messages. */
int tt_scene_load_string(tt_scene *s, const char *text, const char *origin);

/* Apply "section.key=value" or "section.name.key=value" from the command line. */
int tt_scene_set(tt_scene *s, const char *assignment);

/* The origin (file name) used in messages: the first file loaded, or "scene". */
const char *tt_scene_origin(const tt_scene *s);

/* Whether a key was given (in a file or with --set), not just defaulted. */
int tt_scene_has(const tt_scene *s, const char *section, const char *name, const char *key);

/* Whether a section (named: with that name) appears at all. */
int tt_scene_has_section(const tt_scene *s, const char *section, const char *name);

/* Number of distinct names of a named section, and the i-th in order of appearance. */
size_t tt_scene_count_named(const tt_scene *s, const char *section);
const char *tt_scene_named(const tt_scene *s, const char *section, size_t i);

/* Typed getters: the given value, else the schema default. name is NULL for unnamed
 * sections. They fail with TT_EINVAL when the key has no value and no default. */
int tt_scene_get_double(const tt_scene *s, const char *section, const char *name,
                        const char *key, double *out);
/* As tt_scene_get_double, also telling which dimension the text had
 * (a setpoint in nm is TT_DIM_LENGTH, in % TT_DIM_FRACTION). */
int tt_scene_get_quantity(const tt_scene *s, const char *section, const char *name,
                          const char *key, double *out, tt_dim *dim);
int tt_scene_get_int(const tt_scene *s, const char *section, const char *name,
                     const char *key, long *out);
int tt_scene_get_bool(const tt_scene *s, const char *section, const char *name,
                      const char *key, int *out);
/* The text of the value (enum choice, string); NULL if absent with no default. */
const char *tt_scene_get_string(const tt_scene *s, const char *section, const char *name,
                                const char *key);
/* A path key resolved against the folder of the file that set it. The result is
 * written into buf; returns TT_EINVAL if absent. */
int tt_scene_get_path(const tt_scene *s, const char *section, const char *name,
                      const char *key, char *buf, size_t len);

/* Parse text as a value of section.key (used for ramps of another key). */
int tt_scene_parse_value(const tt_scene *s, const char *section, const char *key,
                         const char *text, double *out);

/* Report a problem with a key the way the loader does, with the file that set the
 * key (or the scene's origin if it was defaulted), and return TT_EINVAL. s NULL: no
 * file, "[section] key: what" (for tt_scene_locate to complete). */
int tt_scene_fail(const tt_scene *s, const char *section, const char *name, const char *key,
                  const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* tt_scene_fail for a rule between keys of unnamed sections: named on the first of
 * keys ("section.key", NULL-ended, in order of preference) that the scene set, else on
 * the first, so that a refusal never names a key the scene left at its default while
 * it set another that the rule involves. */
int tt_scene_fail_set(const tt_scene *s, const char *const *keys, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* A module's error "[section] key: what" (or "[section NAME]: what"), the last one
 * reported (error.h), told again with the file that set that key in front, as
 * tt_scene_fail would have written it; rc is returned. Other messages stay as they are. */
int tt_scene_locate(const tt_scene *s, int rc);

/* Write the effective scene (every key of every section in use, defaults included)
 * as INI that tiptap reads back to the same scene. sections: NULL for all, or a
 * "|"-separated list such as "cantilever|tip|material|scan". */
int tt_scene_write(const tt_scene *s, FILE *out, const char *sections);
/* tt_scene_write into a string the caller frees with tt_free (or free); NULL when out
 * of memory (with the message). */
char *tt_scene_write_string(const tt_scene *s, const char *sections);

TT_END_DECLS
#endif
