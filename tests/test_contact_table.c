/* The precomputed table against direct evaluation of eq. 7 across lambda 1e-3 to 1e3 and
 * finely across the onset of the fold, and the physical summary of Burnham et al.'s figure-4a
 * contact. */
#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

/* Largest error of the table's load, relative to max(1, |P|), over points of eq. 7 on
 * the stable branch, and (*near) over its part within 0.04 of its end in Delta; the
 * contact radius is checked on the way. */
static double table_error(double l, double *near)
{
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, l, 0.3), TT_OK);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    double A_end; /* the stable branch is A >= A_end */
    tt_contact_load(c, s->jumpout_delta, 1, NULL, &A_end);
    double worst = 0;
    *near = 0;
    for (int k = 0; k < 6000; k++) {
        double t = exp(-9 + 21.0 * k / 6000), A, D, P, a;
        tt_contact_maugis_point(l, sqrt(1 + t * t), &A, &D, &P);
        /* within 1e-12 of the end the square root turns Delta's round-off into an error
         * of 1e-8 in where on the branch the point is: no test of the table there */
        if (A < A_end || D < s->jumpout_delta + 1e-12)
            continue;
        double e = fabs(tt_contact_load(c, D, 1, NULL, &a) - P) / fmax(1, fabs(P));
        worst = fmax(worst, e);
        if (D < s->jumpout_delta + 0.04)
            *near = fmax(*near, e);
        assert_close(a, A, 1e-6 * fmax(1, A));
    }
    tt_contact_free(c);
    return worst;
}

static void table_matches_eq7(void **st)
{
    (void)st;
    double worst = 0, worst_near = 0, near;
    for (double l = 1e-3; l <= 1.0001e3; l *= sqrt(10)) {
        double e = table_error(l, &near);
        print_message("lambda %-8.3g largest table error %.2e, near the end %.2e\n", l, e, near);
        worst = fmax(worst, e);
        worst_near = fmax(worst_near, near);
    }
    print_message("largest table error, lambda 1e-3 to 1e3: %.2e, near the end %.2e\n", worst,
                  worst_near);
    /* 1.4e-9 measured, from the ln s grid just past s = 8; 1.5e-10 near the end */
    assert_true(worst < 2e-9);
    assert_true(worst_near < 1e-9);
}

static void table_matches_eq7_at_the_fold(void **st)
{
    (void)st;
    /* near the fold's onset (lambda = 0.93795) the branch's end goes as
     * (Delta - Delta0)^(2/3) down to a scale that vanishes there: the inner ln s grid */
    static const double extra[] = {0.8, 0.85, 0.9379, 0.93795, 0.938, 0.9381, 0.9382, 0.9385, 0.939};
    double worst = 0, worst_near = 0, wl = 0, near;
    for (size_t i = 0; i < 41 + sizeof extra / sizeof extra[0]; i++) {
        double l = i < 41 ? 0.9 + 0.0025 * (double)i : extra[i - 41];
        double e = table_error(l, &near);
        worst = fmax(worst, e);
        if (near > worst_near) {
            worst_near = near;
            wl = l;
        }
    }
    print_message("largest table error, lambda 0.8 to 1: %.2e, near the end %.2e (lambda %g)\n", worst,
                  worst_near, wl);
    assert_true(worst < 2e-9);
    assert_true(worst_near < 1e-9);
}

/* The self-check every `tiptap contact` run reports agrees with the test above: small,
 * but not trivially zero, on every model that has a table. */
static void table_self_check(void **st)
{
    (void)st;
    for (double l = 1e-3; l <= 1.0001e3; l *= 10) {
        tt_contact *c;
        assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, l, 0.3), TT_OK);
        double e = tt_contact_table_error(c, 2000);
        assert_true(e > 0 && e < 2e-9);
        tt_contact_free(c);
    }
    tt_contact_params p = {TT_CONTACT_MAUGIS, 50e9, 20e-9, 0, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *h;
    assert_int_equal(tt_contact_alloc(&h, &p), TT_OK); /* w = 0: exact Hertz, no table */
    assert_true(tt_contact_table_error(h, 2000) == 0);
    tt_contact_free(h);
}

static void seed_figure_4a_summary(void **st)
{
    (void)st;
    tt_contact_params p = {TT_CONTACT_MAUGIS, 100e9, 100e-9, 0.1, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_OK);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    /* lambda from eq. 3 computed here independently */
    double lam = 2.06 / 0.265e-9 * cbrt(0.01 * 100e-9 / (M_PI * 1e22));
    assert_close(s->lambda, lam, 1e-12 * lam);
    assert_close(s->force_scale, M_PI * 0.1 * 100e-9, 1e-20);
    /* the Hamaker constant by continuity is of the order of 1e-19 J (docs/physics.md) */
    assert_between(s->hamaker, 0.5e-19, 5e-19);
    double xin = 0.265e-9 / s->depth_scale;
    double H = 6 * fabs(s->P0) * s->force_scale * pow(fabs(s->Delta0) + xin, 2) *
               pow(s->depth_scale, 2) / 100e-9;
    assert_close(s->hamaker, H, 1e-12 * H);
    /* far out of contact the force is the sphere-flat van der Waals law, eq. 9 */
    double gap = 5e-9;
    double F = tt_contact_load(c, -gap, 0, NULL, NULL);
    assert_close(F, -s->hamaker * 100e-9 / (6 * pow(gap + 0.265e-9, 2)), 1e-9 * fabs(F));
    tt_contact_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(table_matches_eq7),
        cmocka_unit_test(table_matches_eq7_at_the_fold),
        cmocka_unit_test(table_self_check),
        cmocka_unit_test(seed_figure_4a_summary),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
