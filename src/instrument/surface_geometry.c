/* The surface's local geometry where the tip touches it: slope and principal curvatures
 * for the contact law (see include/tiptap/instrument/surface.h, docs/surfaces.md). */
#include "tiptap/instrument/surface.h"

#include <math.h>

tt_contact_geometry tt_surface_contact_geometry(const tt_surface *s, double x, double y,
                                                double step, double R)
{
    const double h = step, h0 = tt_surface_height(s, x, y);
    double xp = tt_surface_height(s, x + h, y), xm = tt_surface_height(s, x - h, y);
    double yp = tt_surface_height(s, x, y + h), ym = tt_surface_height(s, x, y - h);
    double pp = tt_surface_height(s, x + h, y + h), pm = tt_surface_height(s, x + h, y - h);
    double mp = tt_surface_height(s, x - h, y + h), mm = tt_surface_height(s, x - h, y - h);
    double gx = (xp - xm) / (2 * h), gy = (yp - ym) / (2 * h);
    double hxx = (xp - 2 * h0 + xm) / (h * h), hyy = (yp - 2 * h0 + ym) / (h * h);
    double hxy = (pp - pm - mp + mm) / (4 * h * h);
    double s2 = gx * gx + gy * gy, g = sqrt(s2);
    /* u along the gradient (x on a level spot), v across it */
    double ux = g > 0 ? gx / g : 1.0, uy = g > 0 ? gy / g : 0.0;
    double huu = ux * ux * hxx + 2 * ux * uy * hxy + uy * uy * hyy;
    double hvv = uy * uy * hxx - 2 * ux * uy * hxy + ux * ux * hyy;
    /* normal curvatures, positive convex: along the slope h'' / (1 + s^2)^1.5, across it
     * h'' / (1 + s^2)^0.5 (a sphere reads 1/r on both) */
    double k1 = -huu / ((1 + s2) * sqrt(1 + s2)), k2 = -hvv / sqrt(1 + s2);
    return tt_contact_geometry_of(R, 1.0 / sqrt(1 + s2), k1, k2);
}

double tt_surface_turn(const tt_surface *s, double x, double y, double step)
{
    const double h0 = tt_surface_height(s, x, y);
    double tx = atan((tt_surface_height(s, x + step, y) - h0) / step) -
                atan((h0 - tt_surface_height(s, x - step, y)) / step);
    double ty = atan((tt_surface_height(s, x, y + step) - h0) / step) -
                atan((h0 - tt_surface_height(s, x, y - step)) / step);
    return fmax(fabs(tx), fabs(ty));
}
