/* The tip's shape: its height, reach and slope about the apex (see
 * include/tiptap/instrument/tip.h, docs/surfaces.md); pure geometry, apart from the
 * dilation (tip.c) so that erosion and dilation both use it without a call circle. */
#include "tiptap/instrument/tip.h"

#include <math.h>

double tt_tip_shape_height(const tt_tip_shape *t, double rho)
{
    double R = t->radius;
    rho = fabs(rho);
    switch (t->kind) {
    case TT_TIP_SPHERE:
        /* R - sqrt(R^2 - rho^2), written without the cancellation near the apex */
        return rho <= R ? rho * rho / (R + sqrt((R - rho) * (R + rho))) : INFINITY;
    case TT_TIP_CONE: {
        double rt = R * cos(t->half_angle);
        if (rho <= rt)
            return rho * rho / (R + sqrt((R - rho) * (R + rho)));
        return R * (1 - sin(t->half_angle)) + (rho - rt) / tan(t->half_angle);
    }
    default:
        return rho == 0 ? 0 : INFINITY;
    }
}

double tt_tip_shape_reach(const tt_tip_shape *t, double dh)
{
    double R = t->radius;
    if (!(dh > 0) || t->kind == TT_TIP_POINT)
        return 0;
    if (t->kind == TT_TIP_SPHERE)
        return dh >= R ? R : sqrt(dh * (2 * R - dh));
    double tc = R * (1 - sin(t->half_angle)); /* where the sphere meets the cone */
    if (dh <= tc)
        return sqrt(dh * (2 * R - dh));
    return R * cos(t->half_angle) + (dh - tc) * tan(t->half_angle);
}

double tt_tip_shape_slope_at(const tt_tip_shape *t, double s)
{
    double R = t->radius;
    if (t->kind == TT_TIP_POINT)
        return 0;
    if (t->kind == TT_TIP_CONE && s >= 1 / tan(t->half_angle))
        return INFINITY; /* the cone's flank is the steepest part of the tip */
    /* on the sphere, slope rho / sqrt(R^2 - rho^2) = s */
    return isinf(s) ? R : R * s / sqrt(1 + s * s);
}

double tt_tip_shape_normal_cos(const tt_tip_shape *t, double rho)
{
    double R = t->radius;
    rho = fabs(rho);
    if (t->kind == TT_TIP_POINT)
        return 1;
    if (t->kind == TT_TIP_CONE && rho >= R * cos(t->half_angle))
        return sin(t->half_angle); /* the flank, tangent to the sphere there */
    return rho < R ? sqrt((R - rho) * (R + rho)) / R : 0;
}
