/* Tables of results, column by column (see include/tiptap/util/table.h). */
#include "tiptap/util/table.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

typedef struct {
    char *name, *unit;
    int text;
    double *numbers; /* rows values (number columns) */
    char **texts;    /* rows strings, NULL for "" (text columns) */
} column;

struct tt_table {
    column *cols;
    size_t ncols, nrows, cap;
    char **meta; /* key, value, key, value, ... */
    size_t nmeta;
};

int tt_table_alloc(tt_table **out)
{
    *out = calloc(1, sizeof **out);
    return *out ? TT_OK : tt_error_nomem("a table of results");
}

void tt_table_free(tt_table *t)
{
    if (!t)
        return;
    for (size_t c = 0; c < t->ncols; c++) {
        for (size_t r = 0; t->cols[c].texts && r < t->nrows; r++)
            free(t->cols[c].texts[r]);
        free(t->cols[c].name);
        free(t->cols[c].unit);
        free(t->cols[c].numbers);
        free(t->cols[c].texts);
    }
    for (size_t i = 0; i < 2 * t->nmeta; i++)
        free(t->meta[i]);
    free(t->meta);
    free(t->cols);
    free(t);
}

int tt_table_add(tt_table *t, const char *name, const char *unit, int text)
{
    if (t->nrows > 0)
        return tt_error(TT_EINVAL, "table: column %s added after the first row", name);
    column *c = realloc(t->cols, (t->ncols + 1) * sizeof *c);
    if (!c)
        return tt_error_nomem("a table's column %s", name);
    t->cols = c;
    c += t->ncols;
    memset(c, 0, sizeof *c);
    c->name = tt_strdup(name);
    c->unit = tt_strdup(unit ? unit : "");
    c->text = text;
    if (!c->name || !c->unit) {
        free(c->name);
        free(c->unit);
        return tt_error_nomem("a table's column %s", name);
    }
    t->ncols++;
    return TT_OK;
}

/* Room for one more row in every column (doubling). */
static int grow(tt_table *t)
{
    size_t cap = t->cap ? 2 * t->cap : 64;
    for (size_t i = 0; i < t->ncols; i++) {
        column *c = &t->cols[i];
        if (c->text) {
            char **p = realloc(c->texts, cap * sizeof *p);
            if (!p)
                return tt_error_nomem("a table of %zu rows", cap);
            c->texts = p;
        } else {
            double *p = realloc(c->numbers, cap * sizeof *p);
            if (!p)
                return tt_error_nomem("a table of %zu rows", cap);
            c->numbers = p;
        }
    }
    t->cap = cap;
    return TT_OK;
}

int tt_table_row(tt_table *t)
{
    int rc = t->nrows == t->cap ? grow(t) : TT_OK;
    if (rc)
        return rc;
    for (size_t i = 0; i < t->ncols; i++) {
        if (t->cols[i].text)
            t->cols[i].texts[t->nrows] = NULL;
        else
            t->cols[i].numbers[t->nrows] = NAN;
    }
    t->nrows++;
    return TT_OK;
}

void tt_table_set(tt_table *t, size_t col, double value)
{
    if (col < t->ncols && t->nrows > 0 && !t->cols[col].text)
        t->cols[col].numbers[t->nrows - 1] = value;
}

int tt_table_set_text(tt_table *t, size_t col, const char *text)
{
    if (col >= t->ncols || t->nrows == 0 || !t->cols[col].text)
        return tt_error(TT_EINVAL, "table: no text column %zu in a row", col);
    char *s = tt_strdup(text);
    if (!s)
        return tt_error_nomem("a table's text");
    free(t->cols[col].texts[t->nrows - 1]);
    t->cols[col].texts[t->nrows - 1] = s;
    return TT_OK;
}

int tt_table_meta(tt_table *t, const char *key, const char *value)
{
    char **m = realloc(t->meta, 2 * (t->nmeta + 1) * sizeof *m);
    if (!m)
        return tt_error_nomem("a table's metadata");
    t->meta = m;
    m[2 * t->nmeta] = tt_strdup(key);
    m[2 * t->nmeta + 1] = tt_strdup(value);
    if (!m[2 * t->nmeta] || !m[2 * t->nmeta + 1]) {
        free(m[2 * t->nmeta]);
        free(m[2 * t->nmeta + 1]);
        return tt_error_nomem("a table's metadata");
    }
    t->nmeta++;
    return TT_OK;
}

size_t tt_table_columns(const tt_table *t) { return t->ncols; }
size_t tt_table_rows(const tt_table *t) { return t->nrows; }
const char *tt_table_name(const tt_table *t, size_t col) { return col < t->ncols ? t->cols[col].name : ""; }
const char *tt_table_unit(const tt_table *t, size_t col) { return col < t->ncols ? t->cols[col].unit : ""; }
int tt_table_is_text(const tt_table *t, size_t col) { return col < t->ncols && t->cols[col].text; }

const double *tt_table_numbers(const tt_table *t, size_t col)
{
    return col < t->ncols && !t->cols[col].text ? t->cols[col].numbers : NULL;
}

const char *tt_table_text(const tt_table *t, size_t col, size_t row)
{
    if (col >= t->ncols || row >= t->nrows || !t->cols[col].text || !t->cols[col].texts[row])
        return "";
    return t->cols[col].texts[row];
}

long tt_table_find(const tt_table *t, const char *name)
{
    for (size_t c = 0; c < t->ncols; c++)
        if (strcmp(t->cols[c].name, name) == 0)
            return (long)c;
    return -1;
}

size_t tt_table_metas(const tt_table *t) { return t->nmeta; }
const char *tt_table_meta_key(const tt_table *t, size_t i) { return i < t->nmeta ? t->meta[2 * i] : ""; }
const char *tt_table_meta_value(const tt_table *t, size_t i) { return i < t->nmeta ? t->meta[2 * i + 1] : ""; }
