/* Tables made from column lists (see src/run/run_common.h). */
#include "run_common.h"

#include <stdio.h>
#include <string.h>

#include "tiptap/config/scene.h"
#include "tiptap/config/units.h"

#include "tiptap/util/error.h"

tt_table *run_table(const run_column *cols, size_t n)
{
    tt_table *t;
    if (tt_table_alloc(&t))
        return NULL;
    for (size_t i = 0; i < n; i++)
        if (tt_table_add(t, cols[i].name, cols[i].unit, cols[i].text)) {
            tt_table_free(t);
            return NULL;
        }
    return t;
}

int run_meta_number(tt_table *t, const char *key, double value)
{
    char v[40];
    snprintf(v, sizeof v, "%.17g", value);
    return tt_table_meta(t, key, v);
}

const char *run_key_unit(const char *key)
{
    const char *dot = strchr(key, '.'), *last = strrchr(key, '.');
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    for (size_t i = 0; dot && i < n; i++) {
        if (strlen(sec[i].name) != (size_t)(dot - key) || strncmp(sec[i].name, key, (size_t)(dot - key)))
            continue;
        for (size_t k = 0; k < sec[i].nkeys; k++) {
            unsigned d = sec[i].keys[k].dims;
            if (strcmp(sec[i].keys[k].key, last + 1) == 0 && sec[i].keys[k].kind == TT_KEY_QUANTITY &&
                d != TT_DIM_NONE && d != TT_DIM_FRACTION && (d & (d - 1)) == 0)
                return tt_units_symbol((tt_dim)d);
        }
    }
    return "";
}

int run_table_append(tt_table *dst, const tt_table *src)
{
    int rc = TT_OK;
    for (size_t r = 0; r < tt_table_rows(src) && !rc; r++) {
        rc = tt_table_row(dst);
        for (size_t c = 0; c < tt_table_columns(src) && !rc; c++) {
            if (tt_table_is_text(src, c))
                rc = tt_table_set_text(dst, c, tt_table_text(src, c, r));
            else
                tt_table_set(dst, c, tt_table_numbers(src, c)[r]);
        }
    }
    return rc;
}

int run_setup(const tt_scene *s, tt_scene **copy, tt_setup **st)
{
    *st = NULL;
    *copy = tt_scene_copy(s);
    if (!*copy)
        return tt_error_nomem("a copy of the scene %s", tt_scene_origin(s));
    return tt_setup_alloc(st, *copy);
}
