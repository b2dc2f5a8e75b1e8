/* Settling (tt_sim_settle): a free cantilever driven at twice its resonance settles at
 * the default tolerances. There the free mode's transient, and the pattern of the
 * adaptive steps, alternate from one drive cycle to the next (the resonance is half the
 * drive frequency), so successive changes never shrink monotonically; before the fix
 * such a point ran to max_cycles and was reported as period doubling or chaos. */
#include "tt_test.h"
#include "tiptap/error.h"
#include "tiptap/integrator.h"

/* The standard cantilever driven at 600 kHz, started off its steady state by a
 * fraction kick of the free amplitude, so that the free mode rings. */
static tt_sim *kicked(tt_cantilever *c, double kick)
{
    assert_int_equal(tt_cantilever_init(c, 40, 300e3, 400, 20e-9, 600e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s); /* dopri5 at 1e-8: it sustains a 4e-8 rad alternation */
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, c, &s), TT_OK);
    double d, v;
    int in;
    tt_sim_get_state(sim, &d, &v, &in);
    tt_sim_set_state(sim, d + kick * c->A0, v, in);
    return sim;
}

static void free_at_twice_resonance_settles(void **st)
{
    (void)st;
    tt_cantilever c;
    tt_sim *sim = kicked(&c, 1e-4);
    tt_cycle cy;
    int settled;
    long n;
    /* the approach's default settle tolerance and max_cycles */
    assert_int_equal(tt_sim_settle(sim, 20000, 1e-7, &cy, &settled, &n), TT_OK);
    print_message("settled %d after %ld cycles: amplitude %.9g nm, phase %.6f deg\n", settled, n,
                  cy.amplitude * 1e9, cy.phase * 180 / M_PI);
    assert_true(settled);
    assert_true(n < 5000);
    assert_close(cy.amplitude, 20e-9, 1e-6 * 20e-9);
    assert_close(cy.phase, c.phi0, 1e-6);
    tt_sim_free(sim);
}

static void alternation_above_tolerance_is_not_settled(void **st)
{
    (void)st;
    /* The same oscillator in its first cycles alternates by about 1e-4 per cycle: an
     * alternation larger than the tolerance is not steady. */
    tt_cantilever c;
    tt_sim *sim = kicked(&c, 1e-4);
    tt_cycle cy;
    int settled;
    long n;
    assert_int_equal(tt_sim_settle(sim, 50, 1e-7, &cy, &settled, &n), TT_OK);
    assert_false(settled);
    assert_int_equal(n, 50);
    tt_sim_free(sim);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(free_at_twice_resonance_settles),
        cmocka_unit_test(alternation_above_tolerance_is_not_settled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
