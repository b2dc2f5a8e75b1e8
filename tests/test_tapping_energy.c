/* Energy balance of steady tapping (docs/physics.md "Checks that hold exactly"): drive work =
 * cantilever damping + tip-sample loss; a conservative contact loses nothing; with
 * hysteresis and no interaction damping the loss per tap is the loop's area. */
#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"
#include "tiptap/solver/integrator.h"

typedef struct {
    double K, w, Qi, gap;
} scene_t;

/* Settle the standard cantilever (40 N/m, 300 kHz, Q 400, 20 nm) on a material and
 * return its steady cycle and the contact summary. */
static void steady(const scene_t *sc, tt_method method, double tol, tt_cycle *cy,
                   tt_contact_summary *sum)
{
    tt_contact_params p = {TT_CONTACT_MAUGIS, sc->K, 10e-9, sc->w, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    *sum = *tt_contact_summary_of(ct);
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.method = method;
    s.tolerance = tol;
    s.steps_per_cycle = 2048;
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sim_set_contact(sim, ct, sc->Qi);
    tt_sim_set_sample(sim, sc->gap, 0);
    int settled;
    long n;
    assert_int_equal(tt_sim_settle(sim, 30000, 1e-9, cy, &settled, &n), TT_OK);
    assert_true(settled);
    tt_sim_free(sim);
    tt_contact_free(ct);
}

static void drive_work_equals_losses(void **st)
{
    (void)st;
    /* a sticky polymer with interaction damping: every loss channel is open */
    scene_t sc = {3e9, 0.04, 10, 15e-9};
    tt_cycle cy;
    tt_contact_summary sum;
    steady(&sc, TT_METHOD_DOPRI5, 1e-10, &cy, &sum);
    assert_true(cy.contact_fraction > 0.01);
    assert_true(cy.e_ts > 0);
    assert_close(cy.e_drive, cy.e_damp + cy.e_ts, 1e-6 * cy.e_drive);
    assert_close(cy.residual, 0, 1e-7 * cy.e_drive);
    /* the tapping lowers the amplitude and (net repulsive) the phase below 90 deg */
    assert_true(cy.amplitude < 0.9 * 20e-9);
}

static void conservative_contact_loses_nothing(void **st)
{
    (void)st;
    /* no adhesion (Hertz exactly), no interaction damping */
    scene_t hertz = {3e9, 0, NAN, 15e-9};
    tt_cycle cy;
    tt_contact_summary sum;
    steady(&hertz, TT_METHOD_DOPRI5, 1e-10, &cy, &sum);
    assert_true(cy.contact_fraction > 0.01);
    assert_close(cy.e_ts, 0, 1e-9 * cy.e_drive);
    assert_close(cy.e_drive, cy.e_damp, 1e-6 * cy.e_drive);
    /* Maugis below the fold (lambda < 0.938): adhesion but no hysteresis, no loss */
    scene_t stiff = {100e9, 0.02, NAN, 15e-9};
    steady(&stiff, TT_METHOD_DOPRI5, 1e-10, &cy, &sum);
    assert_true(sum.lambda < 0.9);
    assert_false(sum.hysteresis);
    assert_true(cy.events >= 2);
    assert_close(cy.e_ts, 0, 1e-8 * cy.e_drive);
}

static void hysteresis_loss_is_the_loop_area(void **st)
{
    (void)st;
    /* soft and sticky: lambda about 2.5, a jump-in/pull-off loop every tap */
    scene_t sc = {1e9, 0.1, NAN, 15e-9};
    tt_cycle cy;
    tt_contact_summary sum;
    steady(&sc, TT_METHOD_DOPRI5, 1e-10, &cy, &sum);
    assert_true(sum.hysteresis);
    assert_true(sum.loop_energy > 0);
    assert_int_equal(cy.events, 2);
    assert_close(cy.e_ts, sum.loop_energy, 1e-6 * sum.loop_energy);
    assert_close(cy.e_drive, cy.e_damp + cy.e_ts, 1e-6 * cy.e_drive);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(drive_work_equals_losses),
        cmocka_unit_test(conservative_contact_loses_nothing),
        cmocka_unit_test(hysteresis_loss_is_the_loop_area),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
