/* The full-rate record of a scan line: one point per lock-in block, trace and retrace
 * (see include/tiptap/instrument/scan_scope.h). */
#include "tiptap/instrument/scan_scope.h"
#include "scan_private.h"

#include <math.h>
#include <stdlib.h>

#include "tiptap/util/error.h"

struct tt_scan_scope {
    long line;
    long n[2];    /* points of trace and retrace */
    long cap;     /* points each series holds */
    double rate;  /* blocks per second */
    double *v[2][TT_SCOPE_COUNT];
};

static const struct {
    const char *name, *unit;
} info[TT_SCOPE_COUNT] = {
    {"time", "s"}, {"position", "m"}, {"z", "m"},         {"error", "m"},
    {"amplitude", "m"}, {"phase", "deg"}, {"surface", "m"}, {"pixel", ""}, {"material", ""},
    {"followed", "m"},
};

const char *tt_scan_scope_name(int q) { return q >= 0 && q < TT_SCOPE_COUNT ? info[q].name : "?"; }
const char *tt_scan_scope_unit(int q) { return q >= 0 && q < TT_SCOPE_COUNT ? info[q].unit : "?"; }

int tt_scan_scope_alloc(tt_scan_scope **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return tt_error_nomem("a scan's scope");
    (*out)->line = -1;
    return TT_OK;
}

void tt_scan_scope_free(tt_scan_scope *sc)
{
    if (!sc)
        return;
    for (int r = 0; r < 2; r++)
        for (int q = 0; q < TT_SCOPE_COUNT; q++)
            free(sc->v[r][q]);
    free(sc);
}

long tt_scan_scope_line(const tt_scan_scope *sc) { return sc->line; }
double tt_scan_scope_rate(const tt_scan_scope *sc) { return sc->rate; }

long tt_scan_scope_points(const tt_scan_scope *sc, int retrace)
{
    return retrace == 0 || retrace == 1 ? sc->n[retrace] : 0;
}

const double *tt_scan_scope_series(const tt_scan_scope *sc, int retrace, int q)
{
    if (retrace < 0 || retrace > 1 || q < 0 || q >= TT_SCOPE_COUNT || !sc->n[retrace])
        return NULL;
    return sc->v[retrace][q];
}

void tt_scan_scope_attach(tt_scan *S, long line, tt_scan_scope *sc)
{
    S->watch_line = sc ? line : -1;
    S->watch = sc;
}

int tt_scan_scope_begin(tt_scan_scope *sc, const tt_scan *S, long line)
{
    const long P = S->lockin.periods_per_block;
    const long nc = tt_raster_cycles_per_direction(&S->raster, S->cantilever.T);
    const long nb = (nc + P - 1) / P;
    if (nb > sc->cap) {
        for (int r = 0; r < 2; r++)
            for (int q = 0; q < TT_SCOPE_COUNT; q++) {
                double *v = realloc(sc->v[r][q], (size_t)nb * sizeof *v);
                if (!v)
                    return tt_error_nomem("a scope of %ld points", nb);
                sc->v[r][q] = v;
            }
        sc->cap = nb;
    }
    sc->line = line;
    sc->rate = S->cantilever.fd / (double)P;
    sc->n[0] = nb;
    /* continuous lines run the retrace, recorded in the images or not */
    sc->n[1] = S->raster.retrace || S->continuous ? nb : 0;
    for (int r = 0; r < 2; r++)
        for (int q = 0; q < TT_SCOPE_COUNT; q++)
            for (long i = 0; i < sc->n[r]; i++)
                sc->v[r][q][i] = NAN;
    return TT_OK;
}

void tt_scan_scope_end(tt_scan_scope *sc, int ok)
{
    if (ok)
        return;
    sc->line = -1;
    sc->n[0] = sc->n[1] = 0;
}

void tt_scan_scope_put(const line_ctx *L, const line_state *st, long b, double A, double ph)
{
    const tt_scan *S = L->S;
    tt_scan_scope *sc = L->W->scope;
    if (b < 0 || b >= sc->n[L->dir])
        return;
    /* the block's end: the start of the cycle after its last (the line's end for the
     * last, shorter block) */
    long k = (b + 1) * L->P;
    if (k > L->nc)
        k = L->nc;
    double **v = sc->v[L->dir];
    v[TT_SCOPE_TIME][b] = tt_scan_clock_at(S, L->line, L->phase, L->nc, k);
    v[TT_SCOPE_POSITION][b] = tt_raster_fast_position(&S->raster, L->dir, L->nc, k);
    /* the command at this instant: the ramp of the block now ended has reached it
     * (tt_scan_block_end moved the new output to z_to) */
    v[TT_SCOPE_Z][b] = st->z_from;
    v[TT_SCOPE_ERROR][b] = A - S->setpoint;
    v[TT_SCOPE_AMPLITUDE][b] = A;
    v[TT_SCOPE_PHASE][b] = ph * 180 / M_PI;
    const surf_pt at = tt_scan_surface_at(L, k);
    v[TT_SCOPE_SURFACE][b] = at.topo;
    v[TT_SCOPE_MATERIAL][b] = (double)at.mat;
    v[TT_SCOPE_FOLLOWED][b] = at.h;
    v[TT_SCOPE_PIXEL][b] = (double)tt_raster_pixel(&S->raster, L->dir, L->nc, k - 1);
}
