/* tiptap: the tip's shape and the surface it images (the surface dilated by the tip).
 *
 * A real tip touches a sample not only at its apex: it rests where the gap over its
 * whole surface is smallest. With the tip's surface t(u, v) above its apex (t(0, 0) = 0)
 * and the sample's height h, the apex sits at the dilated height
 *   h_app(x, y) = max over (u, v) of h(x + u, y + v) - t(u, v),
 * so walls and particles image broadened by the tip's flanks. The contact mechanics
 * keeps the apex sphere (Burnham et al. eq. 7 with R = the [tip] radius): the shape
 * changes where the tip touches, not how it presses.
 *
 * Shapes: point (no dilation: the apex alone, today's behaviour), sphere (the apex
 * sphere of radius R alone, a blunt probe), cone (the apex sphere on a cone of
 * half-angle theta, tangent to it at rho = R cos theta, as real tips are).
 *
 * Surfaces that vary along x only and are made of straight pieces (steps, grating) are
 * dilated exactly at every look-up; the others on a grid computed once (see
 * tt_dilation_alloc and docs/surfaces.md for its spacing and error).
 *
 * Ownership: tt_dilation_alloc returns an object the caller frees with
 * tt_dilation_free; it reads the surface while it is made and keeps a pointer to it
 * (the surface must outlive it); read-only afterwards, it may be shared between threads.
 */
#ifndef TIPTAP_TIP_H
#define TIPTAP_TIP_H

#include "tiptap/export.h"
#include "tiptap/instrument/surface.h"

TT_BEGIN_DECLS

typedef enum { TT_TIP_POINT, TT_TIP_SPHERE, TT_TIP_CONE } tt_tip_kind;

typedef struct {
    tt_tip_kind kind;
    double radius;     /* m: the apex sphere (the [tip] radius) */
    double half_angle; /* rad: the cone's half-angle, 0 < theta < pi / 2 (cone only) */
} tt_tip_shape;

/* Height of the tip's surface above its apex at a lateral distance rho >= 0 from its
 * axis; INFINITY where the tip has no surface (a sphere tip beyond R, a point tip
 * beyond its axis). */
double tt_tip_shape_height(const tt_tip_shape *t, double rho);

/* The largest rho at which the tip's surface rises no more than dh above the apex:
 * features lower than h(x, y) - dh further away cannot touch it. */
double tt_tip_shape_reach(const tt_tip_shape *t, double dh);

/* The lateral distance from the axis at which the tip's flank has slope s >= 0
 * (dt/drho = s); INFINITY where no point of it is that steep (a cone steeper than
 * its flank). */
double tt_tip_shape_slope_at(const tt_tip_shape *t, double s);

/* The cosine of the angle between the tip's surface normal at a lateral distance
 * rho >= 0 from its axis and the axis: sqrt(1 - (rho / R)^2) on the apex sphere, the
 * cone's sin(half_angle) on its flank, 0 beyond a sphere tip, 1 for a point tip. */
double tt_tip_shape_normal_cos(const tt_tip_shape *t, double rho);

typedef struct tt_dilation tt_dilation;

/* The surface s as the tip t images it over the rectangle [x0, x1] x [y0, y1] (m),
 * which look-ups stay within; spacing (m): the grid step where a grid is used (the
 * grid has at most 4096 nodes a side: the step grows for larger areas). Fails for a
 * point tip (nothing to dilate) or out of memory. */
int tt_dilation_alloc(tt_dilation **out, const tt_surface *s, const tt_tip_shape *t, double x0,
                      double y0, double x1, double y1, double spacing);
/* As tt_dilation_alloc, with the contact points kept (contacts 1) for a surface of one
 * material too: a scan that reads the contact law's geometry there needs them. */
int tt_dilation_alloc_contacts(tt_dilation **out, const tt_surface *s, const tt_tip_shape *t,
                               double x0, double y0, double x1, double y1, double spacing,
                               int contacts);
void tt_dilation_free(tt_dilation *d);

/* The apex height h_app(x, y) (m). */
double tt_dilation_height(const tt_dilation *d, double x, double y);

/* The apex height h_app(x, y) as tt_dilation_height, and in *xc, *yc the point of the
 * surface the tip touches there (the argmax above), where the material is read. Exact
 * dilations give the analytic point (at a wall's top corner, just inside the top, so a
 * material map aligned with the wall reads the top's); grids the offset to it found at
 * the nearest node, added to (x, y), so within half a step of the true point, and
 * (x, y) itself for a surface of one material (no offsets kept, unless
 * tt_dilation_alloc_contacts asked for them) or where the apex touches. */
double tt_dilation_contact(const tt_dilation *d, double x, double y, double *xc, double *yc);

/* The grid: its step (m) and nodes; 0 and 0 when the dilation is exact (steps, grating). */
double tt_dilation_spacing(const tt_dilation *d);
long tt_dilation_nodes(const tt_dilation *d);

TT_END_DECLS
#endif
