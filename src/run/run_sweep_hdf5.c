/* A sweep's table as HDF5 over its grid (see include/tiptap/run/sweep.h, docs/hdf5.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/config/meta.h"
#include "tiptap/version.h"
#include "tiptap/io/hdf5.h"
#include "tiptap/run/sweep.h"
#include "tiptap/util/error.h"

#define CHANNEL "/Measurement_000/Channel_000"
/* The pyNSID release whose reader (pyNSID.io.hdf_utils.check_if_main) the numeric
 * columns satisfy as main datasets, as a scan's images do (scan_hdf5.c). */
#define NSID_VERSION "0.0.7.2"

/* The grid's shape: a dimension per varied key, and one of rows when a combination
 * has several (approach curves, scans per material); *rows: that count (1: none). */
static int grid_shape(const tt_sweep *g, const tt_table *t, size_t *dims, size_t *rows)
{
    size_t nk = tt_sweep_keys(g), n = tt_sweep_count(g), most = 0;
    size_t *per = calloc(n ? n : 1, sizeof *per);
    if (!per)
        return tt_error_nomem("the HDF5 file's grid of %zu combinations", n);
    const double *comb = tt_table_numbers(t, 0);
    for (size_t r = 0; r < tt_table_rows(t); r++) {
        size_t i = (size_t)comb[r] - 1;
        if (i < n && ++per[i] > most)
            most = per[i];
    }
    free(per);
    for (size_t k = 0; k < nk; k++)
        dims[k] = tt_sweep_levels(g, k);
    *rows = most > 1 ? most : 1;
    return TT_OK;
}

/* A scale's NSID attributes. */
static int scale_attrs(tt_h5 *f, const char *path, const char *name, const char *unit)
{
    int rc;
    if ((rc = tt_h5_attr_text(f, path, "name", name)) ||
        (rc = tt_h5_attr_text(f, path, "units", unit)) || /* "1": a fraction, as the table's */
        (rc = tt_h5_attr_text(f, path, "quantity", name)))
        return rc;
    return tt_h5_attr_text(f, path, "dimension_type", "UNKNOWN");
}

/* A text key's levels as numbers, 0 .. n - 1, a second scale of its dimension: sidpy
 * holds numbers only, and pyNSID's reader takes a dimension's last scale. */
static int level_scale(tt_h5 *f, const char *key, size_t n)
{
    char path[512], name[512];
    snprintf(path, sizeof path, CHANNEL "/%s.level", key);
    snprintf(name, sizeof name, "%s.level", key);
    double *v = malloc(n * sizeof *v);
    if (!v)
        return tt_error_nomem("the HDF5 file's levels of %s", key);
    for (size_t i = 0; i < n; i++)
        v[i] = (double)i;
    int rc = tt_h5_doubles(f, path, 1, &n, v);
    free(v);
    if (!rc && !(rc = tt_h5_scale(f, path, name)))
        rc = scale_attrs(f, path, key, "1"); /* sidpy refuses a dimension without a unit */
    return rc;
}

/* Key k's values, in level order, as a dimension scale of the channel. */
static int key_scale(tt_h5 *f, const tt_sweep *g, size_t k)
{
    char path[512];
    size_t n = tt_sweep_levels(g, k), i = 0, stride = 1;
    for (size_t j = k + 1; j < tt_sweep_keys(g); j++)
        stride *= tt_sweep_levels(g, j);
    const char *unit = tt_sweep_unit(g, k);
    snprintf(path, sizeof path, CHANNEL "/%s", tt_sweep_key(g, k));
    double *v = malloc(n * sizeof *v);
    const char **s = malloc(n * sizeof *s);
    int rc = v && s ? TT_OK : tt_error_nomem("the HDF5 file's values of %s", tt_sweep_key(g, k));
    /* combination l * stride has level l of key k and level 0 of the keys after it */
    for (i = 0; i < n && !rc; i++) {
        v[i] = tt_sweep_value(g, i * stride, k);
        s[i] = tt_sweep_text(g, i * stride, k);
    }
    if (!rc)
        rc = unit[0] ? tt_h5_doubles(f, path, 1, &n, v) : tt_h5_texts(f, path, 1, &n, s);
    if (!rc && !(rc = tt_h5_scale(f, path, tt_sweep_key(g, k))))
        rc = scale_attrs(f, path, tt_sweep_key(g, k), unit);
    if (!rc && !unit[0])
        rc = level_scale(f, tt_sweep_key(g, k), n);
    free(v);
    free(s);
    return rc;
}

/* Column c over the grid (and rows), NaN and "" where a combination has fewer rows. */
static int column(tt_h5 *f, const tt_sweep *g, const tt_table *t, size_t c, const size_t *dims,
                  int rank, size_t rows)
{
    char path[512], scale[512];
    size_t cells = tt_sweep_count(g) * rows, n = tt_sweep_count(g), nk = tt_sweep_keys(g);
    int text = tt_table_is_text(t, c);
    double *v = text ? NULL : malloc(cells * sizeof *v);
    const char **s = text ? malloc(cells * sizeof *s) : NULL;
    size_t *next = calloc(n ? n : 1, sizeof *next);
    int rc = (text ? s != NULL : v != NULL) && next ? TT_OK : tt_error_nomem("the HDF5 file's column %s", tt_table_name(t, c));
    for (size_t k = 0; k < cells && !rc; k++) {
        if (text)
            s[k] = "";
        else
            v[k] = NAN;
    }
    const double *comb = tt_table_numbers(t, 0);
    for (size_t r = 0; r < tt_table_rows(t) && !rc; r++) {
        size_t i = (size_t)comb[r] - 1, k = i * rows + next[i];
        if (i >= n || next[i]++ >= rows)
            continue;
        if (text)
            s[k] = tt_table_text(t, c, r);
        else
            v[k] = tt_table_numbers(t, c)[r];
    }
    snprintf(path, sizeof path, CHANNEL "/%s", tt_table_name(t, c));
    if (!rc)
        rc = text ? tt_h5_texts(f, path, rank, dims, s) : tt_h5_doubles(f, path, rank, dims, v);
    for (size_t k = 0; k < nk && !rc; k++) {
        snprintf(scale, sizeof scale, CHANNEL "/%s", tt_sweep_key(g, k));
        rc = tt_h5_attach(f, path, scale, (unsigned)k, tt_sweep_key(g, k));
        snprintf(scale, sizeof scale, CHANNEL "/%s.level", tt_sweep_key(g, k));
        if (!rc && !tt_sweep_unit(g, k)[0])
            rc = tt_h5_attach(f, path, scale, (unsigned)k, tt_sweep_key(g, k));
    }
    if (!rc && rows > 1)
        rc = tt_h5_attach(f, path, CHANNEL "/row", (unsigned)nk, "row");
    if (!rc && !(rc = tt_h5_attr_text(f, path, "quantity", tt_table_name(t, c))) &&
        !(rc = tt_h5_attr_text(f, path, "units", tt_table_unit(t, c))) &&
        !(rc = tt_h5_attr_text(f, path, "data_type", "UNKNOWN")))
        rc = tt_h5_attr_text(f, path, "source", "tiptap sweep");
    /* a number column is an NSID main dataset; a text one (regime, found) stays plain,
     * as sidpy holds numbers only */
    if (!rc && !text && !(rc = tt_h5_attr_text(f, path, "title", tt_table_name(t, c))) &&
        !(rc = tt_h5_attr_text(f, path, "main_data_name", tt_table_name(t, c))) &&
        !(rc = tt_h5_attr_text(f, path, "modality", "tapping-mode AFM (simulated)")))
        rc = tt_h5_attr_text(f, path, "pyNSID_version", NSID_VERSION);
    free(v);
    free(s);
    free(next);
    return rc;
}

/* The rows dimension: 0 .. rows - 1. */
static int row_scale(tt_h5 *f, size_t rows)
{
    double *v = malloc(rows * sizeof *v);
    if (!v)
        return tt_error_nomem("the HDF5 file's rows");
    for (size_t r = 0; r < rows; r++)
        v[r] = (double)r;
    int rc = tt_h5_doubles(f, CHANNEL "/row", 1, &rows, v);
    free(v);
    if (!rc && !(rc = tt_h5_scale(f, CHANNEL "/row", "row")))
        rc = scale_attrs(f, CHANNEL "/row", "row", "1");
    return rc;
}

/* The base scene's keys and the sweep's own as the measurement's attributes, and the
 * effective base scene; the same pairs as the channel's original_metadata and the
 * sweep's own as its metadata, the groups pyNSID's reader hands to sidpy. */
static int about(tt_h5 *f, const tt_sweep *g, tt_sweep_kind kind, const tt_scene *base)
{
    char count[32], varied[4096] = "";
    snprintf(count, sizeof count, "%zu", tt_sweep_count(g));
    for (size_t k = 0; k < tt_sweep_keys(g); k++) {
        size_t used = strlen(varied);
        snprintf(varied + used, sizeof varied - used, "%s%s", k ? ", " : "", tt_sweep_key(g, k));
    }
    const char *keys[] = {"tiptap_version", "sweep.run", "sweep.combinations", "sweep.varied"};
    const char *vals[] = {tt_version(), tt_sweep_kind_name(kind), count, varied};
    tt_meta m;
    int rc = tt_meta_scene(&m, base, keys, vals, 4);
    if (rc)
        return rc;
    for (size_t i = 0; i < m.n && !rc; i++)
        rc = tt_h5_attr_text(f, "/Measurement_000", m.keys[i], m.values[i]);
    if (!rc)
        rc = tt_h5_group(f, CHANNEL "/original_metadata");
    for (size_t i = 0; i < m.n && !rc; i++)
        rc = tt_h5_attr_text(f, CHANNEL "/original_metadata", m.keys[i], m.values[i]);
    if (!rc)
        rc = tt_h5_group(f, CHANNEL "/metadata");
    for (size_t i = 0; i < 4 && !rc; i++)
        rc = tt_h5_attr_text(f, CHANNEL "/metadata", keys[i], vals[i]);
    tt_meta_free(&m);
    char *text = rc ? NULL : tt_scene_write_string(base, NULL);
    if (!rc && !text)
        rc = TT_ENOMEM;
    if (!rc)
        rc = tt_h5_text(f, "/Measurement_000/scene", text);
    free(text);
    return rc;
}

int tt_run_sweep_hdf5(const char *path, const tt_sweep *grid, tt_sweep_kind kind,
                      const tt_scene *base, const tt_table *t)
{
    size_t nk = tt_sweep_keys(grid), dims[33], rows = 1;
    if (nk > 31)
        return tt_error(TT_EINVAL, "%s: a sweep of %zu keys has more dimensions than HDF5's 32", path, nk);
    int rc = grid_shape(grid, t, dims, &rows);
    if (rc)
        return rc;
    int rank = (int)nk + (rows > 1);
    dims[nk] = rows;
    tt_h5 *f;
    tt_config_note_inputs(base); /* no table written over the scene it ran */
    if ((rc = tt_h5_create(&f, path)))
        return rc;
    if (!(rc = tt_h5_attr_text(f, "/", "file_kind", "tiptap sweep")) &&
        !(rc = tt_h5_attr_text(f, "/", "layout", "tiptap HDF5 1 (docs/hdf5.md), after pycroscopy's NSID")) &&
        !(rc = tt_h5_group(f, CHANNEL)) && !(rc = about(f, grid, kind, base)) && rows > 1)
        rc = row_scale(f, rows);
    for (size_t k = 0; k < nk && !rc; k++)
        rc = key_scale(f, grid, k);
    /* every column but the combination and the varied keys, which are the dimensions */
    for (size_t c = 1 + nk; c < tt_table_columns(t) && !rc; c++)
        rc = column(f, grid, t, c, dims, rank, rows);
    int crc = tt_h5_close(f, rc == TT_OK);
    return rc ? rc : crc;
}
