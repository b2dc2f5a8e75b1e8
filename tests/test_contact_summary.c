/* The contact summary (P0, Delta0, pull-off, jump-out, jump-in) is right to 1e-6 for
 * lambda from 1e-3 to 1e3 and across the onset of the fold, against an independent
 * minimisation of eq. 7 written out here. */
#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

#include <complex.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_roots.h>

/* scan range of x = ln(m - 1): A from about 1e-8 to far into the Hertz regime, where
 * the printed form of eq. 7 still has 8 correct digits */
#define X_LO -20.0
#define X_HI 20.0
#define NSCAN 2001

/* Eq. 7 as printed in Burnham et al., at m = 1 + e^x (so that m^2 - 1 keeps its digits). */
static void eq7(double lam, double x, double *A, double *D, double *P)
{
    double e = exp(x), m = 1 + e, t = sqrt(e * (2 + e)), at = atan(t);
    double a = lam / 2 * (t + (t * t - 1) * at);
    double b = 4 * lam * lam / 3 * (-e + t * at);
    double r0, r1;
    int n = gsl_poly_solve_quadratic(a, b, -1, &r0, &r1);
    *A = n == 2 ? r1 : r0; /* a, b > 0: one positive root, the larger */
    *D = *A * *A - 4 * lam * *A / 3 * t;
    *P = *A * *A * *A - lam * *A * *A * (t + m * m * at);
}

typedef struct {
    double lam;
    int which; /* 0: Delta, 1: P */
} fn_par;

static double fn(double x, void *v)
{
    const fn_par *q = v;
    double A, D, P;
    eq7(q->lam, x, &A, &D, &P);
    return q->which ? P : D;
}

/* dDelta/dx or dP/dx by a complex step, exact to round-off: eq. 7 again, in complex
 * arithmetic with the cancellation-free root of the quadratic. */
static double dfn(double x, void *v)
{
    const fn_par *q = v;
    const double h = 1e-30, lam = q->lam;
    double complex e = cexp(x + I * h), m = 1 + e, t = csqrt(e * (2 + e)), at = catan(t);
    double complex a = lam / 2 * (t + (t * t - 1) * at);
    double complex b = 4 * lam * lam / 3 * (-e + t * at);
    double complex A = 2 / (b + csqrt(b * b + 4 * a));
    double complex f = q->which ? A * A * A - lam * A * A * (t + m * m * at)
                                : A * A - 4 * lam * A / 3 * t;
    return cimag(f) / h;
}

/* The root of g in [lo, hi] (g changes sign there) by GSL's Brent solver. */
static double root(double (*g)(double, void *), void *par, double lo, double hi)
{
    gsl_function F = {g, par};
    gsl_root_fsolver *r = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(r, &F, lo, hi);
    for (int it = 0; it < 200; it++) {
        gsl_root_fsolver_iterate(r);
        lo = gsl_root_fsolver_x_lower(r);
        hi = gsl_root_fsolver_x_upper(r);
        if (gsl_root_test_interval(lo, hi, 1e-15, 0) == GSL_SUCCESS)
            break;
    }
    double x = gsl_root_fsolver_root(r);
    gsl_root_fsolver_free(r);
    return x;
}

/* The A -> 0 end: the curve leaves it as A^2 (eq. 7's first line has no term in 1/m),
 * so Richardson extrapolation from m and 2m removes that. */
static void eq7_end(double lam, double *P0, double *D0)
{
    double A1, D1, P1, A2, D2, P2;
    eq7(lam, log(1e7), &A1, &D1, &P1);
    eq7(lam, log(2e7), &A2, &D2, &P2);
    *P0 = (4 * P2 - P1) / 3;
    *D0 = (4 * D2 - D1) / 3;
}

/* Least value of Delta (which = 0) or P (which = 1) on the curve, and x there (INFINITY
 * for the A -> 0 end): a coarse scan in x, Brent's minimiser on the bracket for the
 * value, and the root of the exact derivative for x, which the minimiser leaves
 * uncertain by about sqrt(eps): enough to move the other coordinate there by 1e-7. */
static double least(double lam, int which, double end, double *xat)
{
    fn_par q = {lam, which};
    double h = (X_HI - X_LO) / (NSCAN - 1), best = INFINITY;
    int ib = 0;
    for (int i = 0; i < NSCAN; i++) {
        double f = fn(X_LO + h * i, &q);
        if (f < best) {
            best = f;
            ib = i;
        }
    }
    *xat = INFINITY;
    if (ib == NSCAN - 1 || end <= best)
        return end;
    assert_true(ib > 0);
    gsl_function F = {fn, &q};
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    double lo = X_LO + h * (ib - 1), hi = X_LO + h * (ib + 1);
    if (gsl_min_fminimizer_set(s, &F, X_LO + h * ib, lo, hi) != GSL_SUCCESS) {
        gsl_min_fminimizer_free(s);
        return fmin(best, end); /* flat to round-off (just below the fold): no better */
    }
    for (int it = 0; it < 200; it++) {
        gsl_min_fminimizer_iterate(s);
        lo = gsl_min_fminimizer_x_lower(s);
        hi = gsl_min_fminimizer_x_upper(s);
        if (gsl_min_test_interval(lo, hi, 1e-12, 0) == GSL_SUCCESS)
            break;
    }
    double x = gsl_min_fminimizer_x_minimum(s), f = gsl_min_fminimizer_f_minimum(s);
    gsl_min_fminimizer_free(s);
    lo = x - 1e-3;
    hi = x + 1e-3;
    if (dfn(lo, &q) < 0 && dfn(hi, &q) > 0) {
        x = root(dfn, &q, lo, hi);
        f = fmin(f, fn(x, &q));
    }
    *xat = x;
    return f < end ? f : end;
}

typedef struct {
    double lam, target;
} level_par;

static double above_level(double x, void *v)
{
    const level_par *q = v;
    double A, D, P;
    eq7(q->lam, x, &A, &D, &P);
    return D - q->target;
}

/* The load where the stable branch (x below the fold xf) comes back up to Delta0. */
static double load_at_delta0(double lam, double D0, double xf)
{
    level_par q = {lam, D0};
    double lo = xf - 0.01;
    while (above_level(lo, &q) <= 0)
        lo -= 0.01;
    double A, D, P;
    eq7(lam, root(above_level, &q, lo, xf), &A, &D, &P);
    return P;
}

/* the summary's values in the order they are compared */
enum { V_P0, V_D0, V_PULL_LOAD, V_PULL_DELTA, V_JOUT_DELTA, V_JOUT_LOAD, V_JIN_LOAD, NV };
static const char *vname[NV] = {"P0", "Delta0", "pulloff_load", "pulloff_delta",
                                "jumpout_delta", "jumpout_load", "jumpin_load"};

/* Compares the summary at lambda with eq. 7, printing the errors and keeping the worst;
 * returns the number of values off by more than 1e-6. */
static int compare(double lam, double worst[NV])
{
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, lam, 0.3), TT_OK);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    double ref[NV], got[NV] = {s->P0, s->Delta0, s->pulloff_load, s->pulloff_delta,
                               s->jumpout_delta, s->jumpout_load, s->jumpin_load};
    double xp, xf, A;
    eq7_end(lam, &ref[V_P0], &ref[V_D0]);
    ref[V_PULL_LOAD] = least(lam, 1, ref[V_P0], &xp);
    ref[V_PULL_DELTA] = ref[V_D0];
    if (isfinite(xp))
        eq7(lam, xp, &A, &ref[V_PULL_DELTA], &ref[V_PULL_LOAD]);
    ref[V_JOUT_DELTA] = least(lam, 0, ref[V_D0], &xf);
    ref[V_JOUT_LOAD] = ref[V_JIN_LOAD] = ref[V_P0];
    if (isfinite(xf)) {
        eq7(lam, xf, &A, &ref[V_JOUT_DELTA], &ref[V_JOUT_LOAD]);
        ref[V_JIN_LOAD] = load_at_delta0(lam, ref[V_D0], xf);
    }
    int bad = 0;
    for (int k = 0; k < NV; k++) {
        double e = fabs(got[k] - ref[k]);
        worst[k] = fmax(worst[k], e);
        if (!(e <= 1e-6)) {
            print_message("lambda %.6g: %s = %.12g, eq. 7 gives %.12g\n", lam, vname[k], got[k], ref[k]);
            bad++;
        }
    }
    print_message("lambda %-9.6g fold depth %.1e, errors:", lam, ref[V_D0] - ref[V_JOUT_DELTA]);
    for (int k = 0; k < NV; k++)
        print_message(" %.0e", fabs(got[k] - ref[k]));
    print_message("\n");
    /* below the fold the stable branch runs down to the A -> 0 end */
    if (!s->hysteresis && !(s->jumpout_delta == s->Delta0 && s->jumpout_load == s->P0)) {
        print_message("lambda %.6g: no hysteresis, yet jump-out (%.12g, %.12g) is not the end "
                      "(%.12g, %.12g)\n",
                      lam, s->jumpout_delta, s->jumpout_load, s->Delta0, s->P0);
        bad++;
    }
    tt_contact_free(c);
    return bad;
}

static void print_worst(const char *what, const double worst[NV])
{
    print_message("worst %s:", what);
    for (int k = 0; k < NV; k++)
        print_message(" %s %.1e", vname[k], worst[k]);
    print_message("\n");
}

static void summary_matches_eq7(void **st)
{
    (void)st;
    double worst[NV] = {0};
    int bad = 0;
    for (int i = 0; i < 60; i++)
        bad += compare(1e-3 * pow(1e6, i / 59.0), worst);
    print_worst("for lambda 1e-3 to 1e3", worst);
    if (bad)
        fail_msg("%d values off by more than 1e-6", bad);
}

static void summary_matches_eq7_at_the_fold(void **st)
{
    (void)st;
    double worst[NV] = {0};
    int bad = 0;
    /* the fold appears at lambda = 0.93795; its depth grows as (lambda - 0.93795)^3 */
    for (int i = 0; i <= 40; i++)
        bad += compare(0.92 + 0.001 * i, worst);
    double more[] = {0.9375, 0.9379, 0.93795, 0.938, 0.93805, 0.9381, 0.9385, 0.9395};
    for (size_t i = 0; i < sizeof more / sizeof more[0]; i++)
        bad += compare(more[i], worst);
    print_worst("for lambda 0.92 to 0.96", worst);
    if (bad)
        fail_msg("%d values off by more than 1e-6", bad);
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, 0.93, 0.3), TT_OK);
    assert_false(tt_contact_summary_of(c)->hysteresis);
    tt_contact_free(c);
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, 0.94, 0.3), TT_OK);
    assert_true(tt_contact_summary_of(c)->hysteresis);
    tt_contact_free(c);
}

int main(void)
{
    gsl_set_error_handler_off();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(summary_matches_eq7),
        cmocka_unit_test(summary_matches_eq7_at_the_fold),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
