/* Convergence as the step shrinks: amplitude, phase and the contact-event times of a
 * tapping cantilever converge at the method's order (docs/physics.md). */
#include "tt_test.h"
#include "tt_laws.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"
#include "tiptap/solver/integrator.h"

static tt_cycle run(const tt_contact *ct, double Qi, tt_method m, int steps, double tol)
{
    return tt_run_tapping(ct, Qi, m, steps, tol, NULL);
}

static double order(double a, double b, double c)
{
    return log2(fabs(a - b) / fabs(b - c));
}

static void rk4_converges_at_fourth_order(void **st)
{
    (void)st;
    double k3 = 3e18; /* N/m^3: 3 N/m of contact stiffness at 1 nm */
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc_custom(&ct, tt_cubic_load, tt_cubic_energy, &k3, 0, 0), TT_OK);
    tt_cycle c1 = run(ct, 10, TT_METHOD_RK4, 256, 0);
    tt_cycle c2 = run(ct, 10, TT_METHOD_RK4, 512, 0);
    tt_cycle c3 = run(ct, 10, TT_METHOD_RK4, 1024, 0);
    assert_true(c3.contact_fraction > 0.05);
    double pa = order(c1.amplitude, c2.amplitude, c3.amplitude);
    double pp = order(c1.phase, c2.phase, c3.phase);
    double pt = order(c1.t_contact, c2.t_contact, c3.t_contact);
    double pr = order(c1.t_release, c2.t_release, c3.t_release);
    print_message("rk4 on a smooth law: amplitude %.2f phase %.2f contact time %.2f release %.2f\n",
                  pa, pp, pt, pr);
    assert_between(pa, 3.5, 4.6);
    assert_between(pp, 3.5, 4.6);
    assert_between(pt, 3.5, 4.6);
    assert_between(pr, 3.5, 4.6);
    tt_contact_free(ct);
}

static void rk4_on_hertz_converges(void **st)
{
    (void)st;
    /* Hertz contact (P ~ delta^1.5 at onset): the solution is only a few times
     * differentiable at the events, so the order drops below 4, but the error still
     * falls steadily and is small at the default step counts. */
    tt_contact_params p = {TT_CONTACT_MAUGIS, 3e9, 10e-9, 0, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    tt_cycle ref = run(ct, 10, TT_METHOD_RK4, 8192, 0);
    double prev = INFINITY;
    for (int n = 128; n <= 1024; n *= 2) {
        tt_cycle c = run(ct, 10, TT_METHOD_RK4, n, 0);
        double e = fabs(c.amplitude - ref.amplitude) / ref.amplitude;
        print_message("rk4 Hertz %4d steps: amplitude error %.3g\n", n, e);
        assert_true(e < prev / 1.6); /* at least order 0.7 between doublings */
        prev = e;
    }
    assert_true(prev < 1e-7);
    tt_contact_free(ct);
}

static void dopri5_error_follows_tolerance(void **st)
{
    (void)st;
    /* An adaptive method's error scales with its tolerance: a hundredfold tighter
     * tolerance must cut the amplitude error at least tenfold against a reference. */
    tt_contact_params p = {TT_CONTACT_MAUGIS, 3e9, 10e-9, 0.04, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    tt_cycle ref = run(ct, 10, TT_METHOD_DOPRI5, 0, 1e-13);
    tt_cycle a = run(ct, 10, TT_METHOD_DOPRI5, 0, 1e-6);
    tt_cycle b = run(ct, 10, TT_METHOD_DOPRI5, 0, 1e-8);
    double ea = fabs(a.amplitude - ref.amplitude), eb = fabs(b.amplitude - ref.amplitude);
    double ta = fabs(a.t_contact - ref.t_contact), tb = fabs(b.t_contact - ref.t_contact);
    print_message("dopri5 amplitude error %.3g at 1e-6, %.3g at 1e-8; contact time %.3g, %.3g\n",
                  ea / ref.amplitude, eb / ref.amplitude, ta / 3.33e-6, tb / 3.33e-6);
    assert_true(eb < ea / 10);
    assert_true(tb < ta / 10);
    assert_true(ea / ref.amplitude < 1e-4);
    tt_contact_free(ct);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rk4_converges_at_fourth_order),
        cmocka_unit_test(rk4_on_hertz_converges),
        cmocka_unit_test(dopri5_error_follows_tolerance),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
