/* The contact law's local geometry (see include/tiptap/physics/contact.h,
 * docs/surfaces.md): a material's law rebuilt for the effective radius and the contact
 * normal where the tip meets a curved or sloped part of the sample. */
#include "tiptap/physics/contact.h"

#include <math.h>
#include <stdlib.h>

#include "contact_private.h"
#include "tiptap/util/error.h"

tt_contact_geometry tt_contact_geometry_of(double R, double cos_slope, double k1, double k2)
{
    /* a hollow flatter than the tip's own curvature conforms to it: clamp, not refuse */
    double floor_k = 1.0 / (TT_CONTACT_CONCAVE_MAX * R);
    double f1 = fmax(1.0 / R + k1, floor_k), f2 = fmax(1.0 / R + k2, floor_k);
    tt_contact_geometry g = {cos_slope, 1.0 / sqrt(f1 * f2)};
    if (k1 == 0 && k2 == 0) /* a flat: the tip's own radius, bit for bit */
        g.R_eff = R;
    else if (k1 == k2) /* one radius: 1/R + 1/r itself, without the square root's rounding */
        g.R_eff = 1.0 / f1;
    return g;
}

/* The table laws along the normal: P_z(delta) = cos a P(delta cos a), the same curve
 * with F* times cos a and d* over cos a (the energy F* d* unchanged, as it must be:
 * the work along z equals the work along the normal). */
static void table_along_normal(struct tt_contact *c, double cs)
{
    c->F *= cs;
    c->d /= cs;
    c->inv_d = 1.0 / c->d;
    c->F_per_d = c->F / c->d;
    c->eta *= cs * cs; /* eta a rate along the normal, its z part */
}

int tt_contact_alloc_local(tt_contact **out, const tt_contact_params *p,
                           const tt_contact_geometry *g)
{
    if (!g || (g->cos_slope == 1.0 && g->R_eff == p->R))
        return tt_contact_alloc(out, p);
    *out = NULL;
    double cs = g->cos_slope;
    if (!(cs > 0 && cs <= 1) || !(g->R_eff > 0) || !isfinite(g->R_eff))
        return tt_error(TT_EINVAL, "contact: a local geometry needs cos a in (0, 1] and "
                                   "R_eff > 0, got %g and %g m", cs, g->R_eff);
    tt_contact_params q = *p;
    q.R = g->R_eff;
    if (isfinite(q.lambda) && q.lambda > 0) /* eq. 3: lambda ~ R^(1/3) at fixed xi0 */
        q.lambda *= cbrt(g->R_eff / p->R);
    int hertz_row = p->w == 0 || p->model == TT_CONTACT_HERTZ;
    if (hertz_row && !(p->film_thickness > 0))
        q.R = g->R_eff * cs * cs * cs * cs * cs; /* K sqrt(R_eff) (delta cs)^1.5 cs */
    int rc = tt_contact_alloc(out, &q);
    if (rc)
        return rc;
    struct tt_contact *c = *out;
    if (hertz_row && p->film_thickness > 0) {
        /* term k goes as delta^((3 + k) / 2): cs^((3 + k) / 2) from the depth, cs from
         * the projection */
        for (int k = 0; k < 5; k++)
            c->film_k[k] *= pow(cs, 0.5 * (5 + k));
    } else if (!hertz_row) {
        table_along_normal(c, cs);
    }
    return TT_OK;
}

int tt_contact_alloc_tilted(tt_contact **out, const tt_contact *base, double cs)
{
    *out = NULL;
    if (!(cs > 0 && cs <= 1) || base->custom)
        return tt_error(TT_EINVAL, "contact: a slope needs cos a in (0, 1] and a table law, got %g", cs);
    const tt_contact_params *p = &base->p;
    /* the rows tt_contact_alloc_local builds from its parameters at R_eff: Hertz at
     * R_eff cos^5 a anew (no table), the film and the tables from base's own */
    if ((p->w == 0 || p->model == TT_CONTACT_HERTZ) && !(p->film_thickness > 0)) {
        tt_contact_params q = *p;
        q.R = p->R * cs * cs * cs * cs * cs;
        return tt_contact_alloc(out, &q);
    }
    struct tt_contact *c = malloc(sizeof *c);
    if (!c)
        return tt_error_nomem("a contact force law");
    *c = *base;
    if (c->hertz) {
        for (int k = 0; k < 5; k++)
            c->film_k[k] *= pow(cs, 0.5 * (5 + k));
    } else {
        table_along_normal(c, cs);
    }
    *out = c;
    return TT_OK;
}
