/* Pillars, holes and spikes on a square or hexagonal lattice (docs/surfaces.md,
 * "Lattices"): pattern samples and calibration gratings (see surface_private.h). */
#include "surface_private.h"

#include <math.h>

#include "tiptap/instrument/tip.h"

void tt_surface_lattice_init(tt_surface *S, const tt_surface_params *p)
{
    S->period = p->period;
    S->height = p->height;
    S->edge = p->edge_width;
    S->ox = p->offset_x;
    S->oy = p->offset_y;
    S->lattice = (int)p->lattice;
    S->feature = (int)p->feature;
    S->fr = p->feature_radius;
    S->spike_r = p->spike_radius;
    S->spike_a = p->spike_half_angle;
    /* a spike's base: where its cone reaches the plane, height below its apex */
    tt_tip_shape cone = {TT_TIP_CONE, S->spike_r, S->spike_a};
    S->spike_reach = tt_tip_shape_reach(&cone, S->height);
}

/* One feature's rise above the plane at distance rho from its centre: a pillar's top
 * (and its sidewall of horizontal width edge), or a spike, the sphere-capped cone of
 * a cone tip turned upside down. */
static double rise(const tt_surface *S, double rho)
{
    const double H = S->height;
    if (S->feature == TT_FEATURE_SPIKE) {
        if (rho >= S->spike_reach)
            return 0;
        tt_tip_shape cone = {TT_TIP_CONE, S->spike_r, S->spike_a};
        double h = H - tt_tip_shape_height(&cone, rho);
        return h > 0 ? h : 0;
    }
    if (rho <= S->fr)
        return H;
    if (S->edge > 0 && rho < S->fr + S->edge)
        return H * (1 - (rho - S->fr) / S->edge);
    return 0;
}

/* The highest feature over (x, y), among the centres of the nine cells about it: the
 * configuration keeps a feature's reach within a period, so no other can reach. Square:
 * centres at ((i + 1/2) a, (j + 1/2) a); hexagonal: rows a sqrt(3)/2 apart, at
 * ((i + 1/2 + (j odd) / 2) a, (j + 1/2) a sqrt(3)/2). Holes are the plane at the height
 * less the same rise. */
double tt_surface_lattice_at(const tt_surface *S, double x, double y)
{
    const double a = S->period, b = S->lattice == TT_LATTICE_HEXAGONAL ? a * sqrt(3) / 2 : a;
    const double j0 = floor(y / b);
    double best = 0;
    for (double j = j0 - 1; j <= j0 + 1; j++) {
        const double shift = S->lattice == TT_LATTICE_HEXAGONAL && fmod(fabs(j), 2) == 1 ? 0.5 : 0;
        const double i0 = floor(x / a - shift), cy = (j + 0.5) * b;
        for (double i = i0 - 1; i <= i0 + 1; i++) {
            double r = rise(S, hypot(x - (i + 0.5 + shift) * a, y - cy));
            best = r > best ? r : best;
        }
    }
    return S->feature == TT_FEATURE_HOLE ? S->height - best : best;
}
