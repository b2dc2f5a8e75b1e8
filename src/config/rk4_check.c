/* rk4's steps per cycle against the stiffest contact a run can reach, checked before it
 * starts (see include/tiptap/config/config.h). */
#include "tiptap/config/config.h"

#include <math.h>
#include <stdlib.h>

#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

/* rk4 follows an oscillation of rate w only while h w stays below 2.8; the solver's own
 * check (src/solver/rk4.c) refuses a step past 2.5, so the same bound here. */
#define RK4_STABLE_HW 2.5

/* The indentation at which the contact branch's potential reaches energy E, the
 * deepest a tip with that much energy far from the sample can press (bisection on the
 * rising side of the well). */
static double reach(const tt_contact *ct, double E)
{
    double lo = 0, hi = 1e-12;
    while (tt_contact_energy(ct, hi, 1) < E && hi < 1e-3) {
        lo = hi;
        hi *= 2;
    }
    for (int i = 0; i < 100 && hi - lo > 1e-6 * hi; i++) {
        double mid = 0.5 * (lo + hi);
        if (tt_contact_energy(ct, mid, 1) < E)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

/* The steps per cycle rk4 needs on one material: its contact stiffness at the depth
 * the free oscillation's energy reaches (and a rest position inside the sample adds
 * its push), or its interaction damping's rate, whichever is faster. */
static double need_steps(const tt_cantilever *c, const tt_material *m, double s_min,
                         double *stiffness, double *depth)
{
    tt_contact *ct;
    *stiffness = *depth = 0;
    if (tt_contact_alloc(&ct, &m->contact) != TT_OK)
        return 0; /* refused with its reason when the run builds it */
    double A = c->A0 + (s_min < 0 ? -s_min : 0);
    double dPdd = 0;
    *depth = reach(ct, 0.5 * c->k * A * A);
    (void)tt_contact_load(ct, *depth, 1, &dPdd, NULL);
    tt_contact_free(ct);
    *stiffness = c->k + (dPdd > 0 ? dPdd : 0);
    double wc = sqrt(*stiffness / c->m);
    double wi = isfinite(m->Qi) && m->Qi > 0 ? c->w0 / m->Qi : 0;
    return ceil(c->T * fmax(wc, wi) / RK4_STABLE_HW);
}

int tt_config_check_rk4(const tt_scene *s, const char *section, double s_min)
{
    tt_solver sv;
    tt_cantilever c;
    tt_material *m = NULL;
    size_t n = 0, pick = 0;
    int rc;
    if ((rc = tt_solver_from_scene(&sv, s)) || sv.method != TT_METHOD_RK4)
        return rc;
    if ((rc = tt_config_cantilever(s, &c)) || (rc = tt_config_materials(s, &m, &n)) ||
        (section && (rc = tt_config_material_index(s, section, m, n, &pick)))) {
        free(m);
        return rc;
    }
    for (size_t i = section ? pick : 0; i < (section ? pick + 1 : n) && rc == TT_OK; i++) {
        double keff, depth, need = need_steps(&c, &m[i], s_min, &keff, &depth);
        if (sv.steps_per_cycle >= need)
            continue;
        static const char *const keys[] = {"solver.steps_per_cycle", "solver.method", NULL};
        char why[320];
        double wi = isfinite(m[i].Qi) && m[i].Qi > 0 ? c.w0 / m[i].Qi : 0;
        if (wi > sqrt(keff / c.m))
            snprintf(why, sizeof why, "its interaction damping (interaction_quality_factor = %g) "
                                      "acts %.3g times faster than the drive",
                     m[i].Qi, wi / c.wd);
        else
            snprintf(why, sizeof why, "its contact stiffens to %.3g N/m (%.0f times the "
                                      "cantilever's) at the %.3g nm a tip of %.3g nm amplitude "
                                      "can press into it",
                     keff, keff / c.k, depth * 1e9, (c.A0 + (s_min < 0 ? -s_min : 0)) * 1e9);
        rc = tt_scene_fail_set(s, keys,
                               "%d steps a cycle are too few for rk4 on [material %s]: %s, and rk4 "
                               "follows that only with at least %.0f steps a cycle; raise "
                               "steps_per_cycle or use method = dopri5 (or radau, implicit, for a "
                               "contact this stiff)",
                               sv.steps_per_cycle, m[i].name, why, need);
    }
    free(m);
    return rc;
}
