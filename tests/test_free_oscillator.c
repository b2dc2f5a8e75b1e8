/* The free cantilever: steady amplitude and phase against the transfer function, for
 * both drives, below, at and above resonance, from Q = 1 (liquid) to 1e4 (vacuum); and
 * the energy balance of a free cycle. */
#include "tt_test.h"
#include "tt_sim_test.h"
#include "tiptap/util/error.h"
#include "tiptap/solver/integrator.h"

static void check_free(tt_drive drive, double Q, double fd_ratio, tt_method method)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, Q, 20e-9, 300e3 * fd_ratio, drive), TT_OK);
    tt_sim *sim = tt_test_sim_on(&c, method, 1e-10, 512);
    /* Start from rest-free state far from steady, let it settle, then compare. */
    tt_cycle cy;
    int settled;
    long n;
    assert_int_equal(tt_sim_settle(sim, 200000, 1e-10, &cy, &settled, &n), TT_OK);
    double amp, lag;
    tt_cantilever_response(&c, c.wd, &amp, &lag);
    /* The transfer function of m y'' + c y' + k y = forcing, written out here
     * independently of the library: */
    double w = c.wd, m = c.k / (c.w0 * c.w0), cc = m * c.w0 / Q;
    double H = 1 / hypot(c.k - m * w * w, cc * w);
    double forcing = drive == TT_DRIVE_BASE ? m * w * w * c.a_d : c.F0;
    double lag_ref = atan2(cc * w, c.k - m * w * w);
    assert_close(amp, H * forcing, 1e-12 * amp);
    /* The numerical steady state carries each cycle's integration error amplified by
     * the oscillator's memory, about Q / pi cycles: the tolerance grows with Q. */
    double rel = 2e-7 * fmax(1.0, Q / 1000.0);
    assert_close(cy.amplitude, H * forcing, rel * H * forcing);
    assert_close(cy.phase, lag_ref, 10 * rel);
    if (fd_ratio == 1.0) {
        assert_close(cy.amplitude, 20e-9, rel * 20e-9);
        assert_close(cy.phase * 180 / M_PI, 90.0, 10 * rel * 180 / M_PI);
    }
    /* free steady cycle: drive work = damping loss = pi c w A^2, nothing else */
    assert_close(cy.e_damp, M_PI * cc * w * cy.amplitude * cy.amplitude, 1e-6 * cy.e_damp);
    /* the residual is an error of the stored energy (1/2 k A^2), of which the drive
     * work per cycle is only 2 pi / Q */
    assert_close(cy.residual, 0, 1e-8 * 0.5 * c.k * cy.amplitude * cy.amplitude);
    assert_close(cy.e_ts, 0, 0);
    assert_true(isnan(cy.t_contact));
    tt_sim_free(sim);
}

static void base_drive_at_resonance(void **st)
{
    (void)st;
    check_free(TT_DRIVE_BASE, 400, 1.0, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_BASE, 400, 1.0, TT_METHOD_RK4);
    check_free(TT_DRIVE_BASE, 400, 1.0, TT_METHOD_RADAU);
}

static void force_drive_at_resonance(void **st)
{
    (void)st;
    check_free(TT_DRIVE_FORCE, 400, 1.0, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_FORCE, 400, 1.0, TT_METHOD_RK4);
    check_free(TT_DRIVE_FORCE, 400, 1.0, TT_METHOD_RADAU);
}

static void off_resonance_both_sides(void **st)
{
    (void)st;
    check_free(TT_DRIVE_BASE, 400, 0.999, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_FORCE, 400, 1.0013, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_BASE, 400, 0.5, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_FORCE, 400, 3.0, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_BASE, 400, 0.999, TT_METHOD_RADAU);
    check_free(TT_DRIVE_FORCE, 400, 3.0, TT_METHOD_RADAU);
}

static void liquid_and_vacuum_quality_factors(void **st)
{
    (void)st;
    check_free(TT_DRIVE_BASE, 1, 1.0, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_FORCE, 3, 0.9, TT_METHOD_DOPRI5);
    check_free(TT_DRIVE_BASE, 1, 1.0, TT_METHOD_RADAU);
    check_free(TT_DRIVE_FORCE, 3, 0.9, TT_METHOD_RADAU);
    check_free(TT_DRIVE_FORCE, 1e4, 1.0, TT_METHOD_DOPRI5);
}

static void reset_free_is_already_steady(void **st)
{
    (void)st;
    /* tt_sim_reset_free puts the oscillator in its steady state: the first cycle
     * already has the steady amplitude, even at Q = 1e4 where settling takes 30000
     * cycles. */
    tt_cantilever c;
    tt_cantilever_init(&c, 2, 70e3, 1e4, 5e-9, 70e3 * 1.00002, TT_DRIVE_BASE);
    tt_sim *sim = tt_test_sim(&c, 1e-10);
    tt_cycle cy;
    assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
    assert_close(cy.amplitude, 5e-9, 5e-16);
    assert_close(cy.phase, c.phi0, 1e-7);
    tt_sim_free(sim);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(base_drive_at_resonance),
        cmocka_unit_test(force_drive_at_resonance),
        cmocka_unit_test(off_resonance_both_sides),
        cmocka_unit_test(liquid_and_vacuum_quality_factors),
        cmocka_unit_test(reset_free_is_already_steady),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
