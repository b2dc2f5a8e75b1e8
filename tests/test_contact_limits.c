/* Contact mechanics against its analytic limits (Burnham et al. eqs. 4-8, docs/physics.md). */
#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

static tt_contact *norm(tt_contact_model m, double lambda)
{
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, m, lambda, 0.3), TT_OK);
    return c;
}

static void dmt_and_jkr_models_exactly(void **st)
{
    (void)st;
    tt_contact *c = norm(TT_CONTACT_DMT, 0);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    assert_close(s->pulloff_load, -2, 1e-12);
    assert_close(s->P0, -2, 0);
    assert_close(s->jumpout_delta, 0, 1e-12);
    assert_false(s->hysteresis);
    tt_contact_free(c);
    c = norm(TT_CONTACT_JKR, 0);
    s = tt_contact_summary_of(c);
    assert_close(s->pulloff_load, -1.5, 1e-9);                     /* load control */
    assert_close(s->jumpout_load, -5.0 / 6.0, 1e-9);               /* displacement control */
    assert_close(s->jumpout_delta, -3 * pow(6, -2.0 / 3.0), 1e-9); /* the vertical tangent */
    assert_close(s->jumpin_load, -4.0 / 3.0, 1e-9);                /* jump onto the branch at 0 */
    assert_true(s->hysteresis);
    tt_contact_free(c);
}

static void maugis_spans_dmt_to_jkr(void **st)
{
    (void)st;
    tt_contact *c = norm(TT_CONTACT_MAUGIS, 1e-3);
    assert_close(tt_contact_summary_of(c)->pulloff_load, -2, 1e-3);
    tt_contact_free(c);
    c = norm(TT_CONTACT_MAUGIS, 1e3);
    assert_close(tt_contact_summary_of(c)->pulloff_load, -1.5, 1e-5);
    assert_close(tt_contact_summary_of(c)->jumpout_load, -5.0 / 6.0, 1e-3);
    tt_contact_free(c);
    /* pull-off under load control moves monotonically from -2 to -1.5 */
    double prev = -2.0 - 1e-12;
    for (double l = 1e-3; l <= 1e3 * 1.0001; l *= 1.5) {
        c = norm(TT_CONTACT_MAUGIS, l);
        double p = tt_contact_summary_of(c)->pulloff_load;
        if (!(p > prev && p < -1.5))
            fail_msg("pull-off %.12g at lambda %g does not rise from %.12g toward -1.5", p, l, prev);
        prev = p;
        tt_contact_free(c);
    }
}

static void eq8_is_the_exact_small_A_limit(void **st)
{
    (void)st;
    /* up to lambda = 100: beyond, the printed form's -2 + ... cancels to nothing */
    for (double l = 1e-3; l <= 1.0001e2; l *= 10) {
        /* eq. 8 as printed in Burnham et al. */
        double r = sqrt(4 * pow(l, 4) * pow(M_PI - 2, 2) + 9 * M_PI * l) - 2 * l * l * (M_PI - 2);
        double P8 = -2 + 8 * l * (M_PI - 2) / (9 * M_PI) * r;
        double D8 = -8 / (9 * M_PI) * r;
        double A, D, P;
        tt_contact_maugis_point(l, 1e7, &A, &D, &P);
        assert_true(A < 1e-5);
        assert_close(P, P8, 1e-6 * fabs(P8) + 1e-9);
        /* and the closed form the library uses agrees with the curve's end itself */
        tt_contact *c0 = norm(TT_CONTACT_MAUGIS, l);
        assert_close(tt_contact_summary_of(c0)->P0, P, 1e-6 * fabs(P) + 1e-12);
        tt_contact_free(c0);
        assert_close(D, D8, 1e-6 * fabs(D8) + 1e-9);
        tt_contact *c = norm(TT_CONTACT_MAUGIS, l);
        assert_close(tt_contact_summary_of(c)->P0, P8, 1e-9); /* -2 + ... cancels: absolute */
        assert_close(tt_contact_summary_of(c)->Delta0, D8, 1e-9 * fabs(D8) + 1e-13);
        tt_contact_free(c);
    }
}

static void hertz_at_large_A(void **st)
{
    (void)st;
    for (double l = 1e-2; l <= 1e2; l *= 10) {
        double A, D, P;
        tt_contact_maugis_point(l, 1 + 1e-14, &A, &D, &P);
        assert_true(A > 100);
        assert_close(P / (A * A * A), 1, 0.05);
        assert_close(D / (A * A), 1, 0.05);
    }
    /* in physical units the table follows P = K sqrt(R) delta^1.5 deep in contact */
    tt_contact_params p = {TT_CONTACT_MAUGIS, 1e11, 1e-8, 1e-4, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_OK);
    double delta = 5e-9;
    double F = tt_contact_load(c, delta, 1, NULL, NULL), FH = 1e11 * sqrt(1e-8) * pow(delta, 1.5);
    assert_close(F / FH, 1, 0.01);
    tt_contact_free(c);
}

static void load_continuous_at_the_junction(void **st)
{
    (void)st;
    double lams[] = {1e-3, 0.3, 0.9, 2, 30, 1e3};
    for (size_t i = 0; i < sizeof lams / sizeof lams[0]; i++) {
        tt_contact *c = norm(TT_CONTACT_MAUGIS, lams[i]);
        const tt_contact_summary *s = tt_contact_summary_of(c);
        double D0 = s->Delta0;
        /* van der Waals side equals P0 at Delta0 (eq. 10 with docs/physics.md's sign) */
        assert_close(tt_contact_load(c, D0, 0, NULL, NULL), s->P0, 1e-12 * fabs(s->P0) + 1e-15);
        assert_close(tt_contact_load(c, D0 - 1e-9, 0, NULL, NULL), s->P0, 1e-6 * fabs(s->P0) + 1e-12);
        /* below the fold the contact branch meets it there too */
        if (!s->hysteresis)
            assert_close(tt_contact_load(c, D0 + 1e-12, 1, NULL, NULL), s->P0, 1e-5 * fabs(s->P0) + 1e-8);
        /* the potential is continuous at jump-in */
        assert_close(tt_contact_energy(c, D0, 1), tt_contact_energy(c, D0, 0), 1e-9);
        tt_contact_free(c);
    }
}

static void fold_appears_at_lambda_0938(void **st)
{
    (void)st;
    tt_contact *c = norm(TT_CONTACT_MAUGIS, 0.92);
    assert_false(tt_contact_summary_of(c)->hysteresis);
    tt_contact_free(c);
    c = norm(TT_CONTACT_MAUGIS, 0.96);
    assert_true(tt_contact_summary_of(c)->hysteresis);
    tt_contact_free(c);
}

static void no_adhesion_is_exactly_hertz(void **st)
{
    (void)st;
    tt_contact_params p = {TT_CONTACT_MAUGIS, 50e9, 20e-9, 0, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_OK);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    assert_false(s->adhesive);
    assert_false(s->hysteresis);
    assert_close(tt_contact_jumpin(c), 0, 0);
    assert_close(tt_contact_jumpout(c), 0, 0);
    double a, k, d = 2e-9;
    double P = tt_contact_load(c, d, 1, &k, &a);
    assert_close(P, 50e9 * sqrt(20e-9) * pow(d, 1.5), 1e-15 * P); /* P = K a^3 / R */
    assert_close(a, sqrt(20e-9 * d), 1e-24);                      /* delta = a^2 / R */
    assert_close(k, 1.5 * 50e9 * sqrt(20e-9 * d), 1e-9 * k);
    assert_close(tt_contact_load(c, -1e-9, 0, NULL, NULL), 0, 0);  /* no van der Waals */
    tt_contact_free(c);
}

static void bad_parameters_are_refused(void **st)
{
    (void)st;
    tt_contact *c;
    tt_contact_params p = {TT_CONTACT_MAUGIS, -1, 1e-8, 0.1, 0.3e-9, NAN, 0, 0, 0, {0}, {0}};
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "modulus"));
    p.K = 1e9;
    p.R = NAN;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
    p.R = 1e-8;
    p.w = -0.1;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dmt_and_jkr_models_exactly),
        cmocka_unit_test(maugis_spans_dmt_to_jkr),
        cmocka_unit_test(eq8_is_the_exact_small_A_limit),
        cmocka_unit_test(hertz_at_large_A),
        cmocka_unit_test(load_continuous_at_the_junction),
        cmocka_unit_test(fold_appears_at_lambda_0938),
        cmocka_unit_test(no_adhesion_is_exactly_hertz),
        cmocka_unit_test(bad_parameters_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
