/* A plot's points held to a budget (see include/tiptap/io/decimate.h). */
#include "tiptap/io/decimate.h"

#include <math.h>
#include <stdlib.h>

#include "tiptap/util/error.h"

struct tt_decimate {
    size_t lines, n, cap, budget;
    double **v;        /* lines arrays of cap points */
    size_t stride;     /* input samples a bucket (1: every sample kept) */
    size_t in_bucket;
    double *lo, *hi;   /* the bucket's extremes; lo[0], hi[0]: its first and last abscissa */
};

int tt_decimate_alloc(tt_decimate **out, size_t lines, double total, size_t budget)
{
    *out = NULL;
    tt_decimate *d = calloc(1, sizeof *d);
    if (!d || lines < 1 || budget < 2 || !(d->v = calloc(lines, sizeof *d->v)) ||
        !(d->lo = calloc(lines, sizeof *d->lo)) || !(d->hi = calloc(lines, sizeof *d->hi))) {
        tt_decimate_free(d);
        if (lines < 1 || budget < 2)
            return tt_error(TT_EINVAL, "decimate: needs a line and a budget of 2");
        return tt_error_nomem("a plot's %zu lines", lines);
    }
    d->lines = lines;
    d->budget = budget;
    /* two points a bucket; a longer input than expected still ends within twice it */
    d->stride = total > (double)budget ? (size_t)ceil(2 * total / (double)budget) : 1;
    *out = d;
    return TT_OK;
}

void tt_decimate_free(tt_decimate *d)
{
    if (!d)
        return;
    for (size_t i = 0; d->v && i < d->lines; i++)
        free(d->v[i]);
    free(d->v);
    free(d->lo);
    free(d->hi);
    free(d);
}

static int append(tt_decimate *d, const double *v)
{
    if (d->n == d->cap) {
        size_t cap = d->cap ? 2 * d->cap : 1024;
        for (size_t i = 0; i < d->lines; i++) {
            double *nw = realloc(d->v[i], cap * sizeof *nw);
            if (!nw)
                return tt_error_nomem("a plot's points");
            d->v[i] = nw;
        }
        d->cap = cap;
    }
    for (size_t i = 0; i < d->lines; i++)
        d->v[i][d->n] = v[i];
    d->n++;
    return TT_OK;
}

int tt_decimate_finish(tt_decimate *d)
{
    int rc = TT_OK;
    if (d->in_bucket > 0 && !(rc = append(d, d->lo)))
        rc = append(d, d->hi);
    d->in_bucket = 0;
    return rc;
}

int tt_decimate_push(tt_decimate *d, const double *v)
{
    if (d->stride == 1)
        return append(d, v);
    for (size_t i = 1; i < d->lines; i++) {
        if (d->in_bucket == 0 || v[i] < d->lo[i])
            d->lo[i] = v[i];
        if (d->in_bucket == 0 || v[i] > d->hi[i])
            d->hi[i] = v[i];
    }
    if (d->in_bucket == 0)
        d->lo[0] = v[0];
    d->hi[0] = v[0];
    if (++d->in_bucket < d->stride)
        return TT_OK;
    return tt_decimate_finish(d);
}

size_t tt_decimate_count(const tt_decimate *d) { return d->n; }
const double *tt_decimate_line(const tt_decimate *d, size_t line)
{
    return line < d->lines ? d->v[line] : NULL;
}
