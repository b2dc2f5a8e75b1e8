/* Where the sample is under the tip: the instrument's clock, the sample's point and
 * height at a raster position (tilt, drift, dilation), and the surface at a line's
 * cycle (see scan_private.h). */
#include "scan_private.h"

#include <math.h>

/* The instrument's clock (tt_instrument_params) at the start of cycle k of phase 0
 * (settling: the line's start), 1 (trace) or 2 (retrace). */
double tt_scan_clock_at(const tt_scan *S, long line, int phase, long nc, long k)
{
    double half = 0.5 / S->raster.line_rate, t = (double)line / S->raster.line_rate;
    if (phase == 0)
        return t;
    return t + (phase == 2 ? half : 0) + half * (double)k / (double)nc;
}

/* The sample under raster position (x, y) at time t: *x, *y become the surface's point
 * the tip touches there (drift, then the dilation's contact point, where the material
 * is read); returns the height the apex meets (dilated, tilted, drifted in z) and the
 * true height under the axis in *topo, the dilated one in *dil. */
/* The sample under the axis at (x, y) at time t; (x, y) become the contact point, rho
 * its distance from the axis. */
static double sample_at(const tt_scan *S, double *x, double *y, double t, double *topo, double *dil,
                        double *rho)
{
    const tt_instrument_params *in = &S->inst;
    *x -= in->drift_x * t;
    *y -= in->drift_y * t;
    const double ax = *x, ay = *y;
    *topo = S->flat ? 0 : tt_surface_height(S->surface, ax, ay);
    *dil = S->dilation ? tt_dilation_contact(S->dilation, ax, ay, x, y) : *topo;
    *rho = hypot(*x - ax, *y - ay);
    return *dil + in->tilt_x * ax + in->tilt_y * ay + in->drift_z * t;
}

double tt_scan_sample_at(const tt_scan *S, double *x, double *y, double t, double *topo)
{
    double dil, rho;
    return sample_at(S, x, y, t, topo, &dil, &rho);
}

/* The surface at the start of cycle k (settling: the line's first pixel). */
surf_pt tt_scan_surface_at(const line_ctx *L, long k)
{
    const tt_scan *S = L->S;
    const long kk = L->phase ? k : L->k0;
    surf_pt p = {.k = k};
    double x, y, rho = 0;
    tt_raster_position(&S->raster, L->line, L->dir, L->nc, kk, &x, &y);
    if (S->plain) {
        p.h = p.topo = p.dil = S->flat ? 0 : tt_surface_height(S->surface, x, y);
    } else {
        double t = tt_scan_clock_at(S, L->line, L->phase, L->nc, kk);
        p.h = sample_at(S, &x, &y, t, &p.topo, &p.dil, &rho);
    }
    p.mat = S->uniform ? 0 : (size_t)tt_surface_material(S->surface, x, y);
    p.geo = S->local ? tt_scan_geometry_key(S, x, y, rho, p.mat) : 0;
    return p;
}
