/* tiptap: tables of results, column by column: what a run gives a caller that is not
 * the command line (the Python package's dicts of arrays, HDF5 datasets).
 *
 * A table has named columns, each with its SI unit ("m", "deg", "J"; "" for counts and
 * fractions) and of numbers or of texts, and rows appended one at a time: a new row
 * holds NaN and "" until set. A number column is one contiguous array of the rows'
 * values. Metadata pairs (texts) say what the table is of.
 *
 * Ownership: tt_table_alloc makes a table the caller frees with tt_table_free; names,
 * texts and metadata are copied in; pointers the accessors return belong to the table
 * and live until the next tt_table_row (a column's array may move) or the free.
 */
#ifndef TIPTAP_TABLE_H
#define TIPTAP_TABLE_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct tt_table tt_table;

int tt_table_alloc(tt_table **out);
void tt_table_free(tt_table *t);

/* Add a column before the first row: text 0 for numbers, 1 for texts. */
int tt_table_add(tt_table *t, const char *name, const char *unit, int text);
/* Append a row (NaN and ""), which the setters fill. */
int tt_table_row(tt_table *t);
/* Set column col of the last row. */
void tt_table_set(tt_table *t, size_t col, double value);
int tt_table_set_text(tt_table *t, size_t col, const char *text);
/* Add a metadata pair (copied). */
int tt_table_meta(tt_table *t, const char *key, const char *value);

size_t tt_table_columns(const tt_table *t);
size_t tt_table_rows(const tt_table *t);
const char *tt_table_name(const tt_table *t, size_t col);
const char *tt_table_unit(const tt_table *t, size_t col);
int tt_table_is_text(const tt_table *t, size_t col);
/* A number column's values (rows of them); NULL for a text column. */
const double *tt_table_numbers(const tt_table *t, size_t col);
/* A text column's value in row row ("" for a number column). */
const char *tt_table_text(const tt_table *t, size_t col, size_t row);
/* The column named name, or -1. */
long tt_table_find(const tt_table *t, const char *name);
size_t tt_table_metas(const tt_table *t);
const char *tt_table_meta_key(const tt_table *t, size_t i);
const char *tt_table_meta_value(const tt_table *t, size_t i);

TT_END_DECLS
#endif
