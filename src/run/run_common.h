/* Shared by the run layer's files (src/run/): a table's columns made from a list. */
#ifndef TIPTAP_RUN_COMMON_H
#define TIPTAP_RUN_COMMON_H

#include "tiptap/config/setup.h"
#include "tiptap/util/table.h"

typedef struct {
    const char *name, *unit;
    int text;
} run_column;

/* A new table with the n columns of cols; NULL with the message when out of memory. */
tt_table *run_table(const run_column *cols, size_t n);

/* The number %.17g (reads back to the same double) as the metadata key's value. */
int run_meta_number(tt_table *t, const char *key, double value);

/* A setup made from a copy of the scene (*copy: the caller frees it after the setup),
 * since the setup may change its scene (tt_setup_apply: a trace's ramp). */
int run_setup(const tt_scene *s, tt_scene **copy, tt_setup **st);

/* Append src's rows to dst, which has the same columns. */
int run_table_append(tt_table *dst, const tt_table *src);

/* The SI unit of a scene key written "section.key" or "section.NAME.key" ("m", "J/m^2";
 * "" for plain numbers, fractions, texts and unknown keys). */
const char *run_key_unit(const char *key);

#endif
