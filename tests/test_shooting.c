/* Steady points by shooting (tiptap/solver/shooting.h): the fixed point of the
 * one-period map and its Floquet multipliers on the free oscillator against the
 * analytic steady state; agreement with settling on the standard scene; and both
 * branches of the bistable scene (Garcia and San Paulo 1999). */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/standard.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/solver/shooting.h"
#include "tiptap/util/error.h"

static tt_sim *free_sim(tt_cantilever *c, double Q, double fd_ratio)
{
    assert_int_equal(tt_cantilever_init(c, 40, 300e3, Q, 20e-9, 300e3 * fd_ratio, TT_DRIVE_BASE),
                     TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.tolerance = 1e-10;
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, c, &s), TT_OK);
    return sim;
}

/* From rest, Newton lands on y = A cos(w t - lag) of the transfer function of
 * m y'' + c y' + k y = m w^2 a_d cos(w t) (Burnham et al. eq. 2 without the sample),
 * written out here independently of the library, in a few cycles. */
static void free_fixed_point_is_the_analytic_steady_state(void **st)
{
    (void)st;
    const double ratios[] = {1.0, 0.999, 1.002, 0.7};
    for (size_t i = 0; i < sizeof ratios / sizeof ratios[0]; i++) {
        tt_cantilever c;
        tt_sim *sim = free_sim(&c, 400, ratios[i]);
        double w = c.wd, m = c.k / (c.w0 * c.w0), cc = m * c.w0 / c.Q;
        double A = m * w * w * c.a_d / hypot(c.k - m * w * w, cc * w);
        double lag = atan2(cc * w, c.k - m * w * w);
        tt_sim_set_state(sim, 0, 0, 0);
        tt_shoot_params p;
        tt_shoot_default(&p);
        tt_shoot_result r;
        tt_cycle cy;
        int settled;
        assert_int_equal(tt_shoot_steady(sim, &p, 20000, 1e-7, &cy, &settled, &r), TT_OK);
        assert_true(settled);
        assert_int_equal(r.how, TT_SHOOT_NEWTON);
        assert_true(r.cycles < 100);
        /* at t = 0: d = z + y with z = a_d, y = A cos(-lag), v = y' */
        assert_close(r.d, c.a_d + A * cos(lag), 1e-9 * A);
        assert_close(r.v, A * w * sin(lag), 1e-9 * A * w);
        assert_close(cy.amplitude, A, 1e-8 * A);
        assert_close(cy.phase, lag, 1e-8);
        tt_sim_free(sim);
    }
}

/* The free oscillator's monodromy is exp(S T) of its linear system: multipliers
 * exp((-w0 / 2Q +- i w0 sqrt(1 - 1/4Q^2)) T), |mu| = exp(-w0 T / 2Q). */
static void free_multipliers_are_analytic(void **st)
{
    (void)st;
    const double Qs[] = {400, 10, 1.5}, ratios[] = {0.999, 0.8, 1.3};
    for (size_t i = 0; i < 3; i++) {
        tt_cantilever c;
        tt_sim *sim = free_sim(&c, Qs[i], ratios[i]);
        tt_sim_reset_free(sim);
        tt_shoot_params p;
        tt_shoot_default(&p);
        double re[2], im[2];
        assert_int_equal(tt_shoot_multipliers(sim, &p, re, im), TT_OK);
        double T = c.T, decay = exp(-c.w0 * T / (2 * c.Q));
        double wdamp = c.w0 * sqrt(1 - 1 / (4 * c.Q * c.Q));
        double mre = decay * cos(wdamp * T), mim = decay * fabs(sin(wdamp * T));
        for (int j = 0; j < 2; j++) {
            assert_close(re[j], mre, 1e-6);
            assert_close(fabs(im[j]), mim, 1e-6);
            assert_close(hypot(re[j], im[j]), decay, 1e-6);
        }
        assert_close(im[0], -im[1], 1e-15);
        tt_sim_free(sim);
    }
}

/* One steady point of the standard scene (16 nm) by each steady mode of approach. */
static tt_approach_point standard_point(const char *steady)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, tt_standard_scene(), "standard"), TT_OK);
    char set[64];
    snprintf(set, sizeof set, "approach.steady=%s", steady);
    assert_int_equal(tt_scene_set(s, set), TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_approach_params p;
    assert_int_equal(tt_config_approach(s, &p), TT_OK);
    tt_approach *a;
    assert_int_equal(tt_approach_alloc(&a, tt_setup_sim(su), &p), TT_OK);
    tt_approach_point pt;
    assert_int_equal(tt_approach_iterate(a, &pt), TT_OK);
    assert_true(tt_approach_done(a));
    tt_approach_free(a);
    tt_setup_free(su);
    tt_scene_free(s);
    return pt;
}

static void standard_scene_agrees_with_settling(void **st)
{
    (void)st;
    tt_approach_point sh = standard_point("shooting"), se = standard_point("settle");
    print_message("shooting %ld cycles, settling %ld: amplitude %.9g / %.9g nm, phase %.9g / "
                  "%.9g deg, |mu| %.6g\n", sh.cycles, se.cycles, sh.cycle.amplitude * 1e9,
                  se.cycle.amplitude * 1e9, sh.cycle.phase * 180 / M_PI,
                  se.cycle.phase * 180 / M_PI, sh.shot.mu_abs);
    assert_true(sh.settled && se.settled);
    assert_int_equal(sh.shot.how, TT_SHOOT_NEWTON);
    assert_true(sh.shot.mu_abs < 1);
    assert_true(sh.cycle.contact_fraction > 0); /* a tapping orbit, not the free one */
    assert_close(sh.cycle.amplitude, se.cycle.amplitude, 1e-6 * se.cycle.amplitude);
    assert_close(sh.cycle.phase, se.cycle.phase, 1e-4);
    assert_close(sh.cycle.e_ts, se.cycle.e_ts, 1e-5 * se.cycle.e_ts);
    assert_true(sh.cycles * 5 < se.cycles);
}

/* examples/extreme/bistable.ini at 4 nm: started near the attractive orbit (amplitude
 * 3.9 nm, lag 128 deg) the tip finds it (never touching, phase above 90 deg); started on
 * a tapping motion (4.1 nm, lag 60 deg) it finds the repulsive one (phase below
 * 90 deg). Both are Newton's, both stable; else shooting says which it could not find. */
static void bistable_scene_shows_both_branches(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load(s, TT_SOURCE_DIR "/examples/extreme/bistable.ini"), TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_shoot_params p;
    tt_shoot_default(&p);
    tt_shoot_result r[2];
    tt_cycle cy[2];
    for (int b = 0; b < 2; b++) {
        int settled;
        const tt_cantilever *c = tt_sim_cantilever(tt_setup_sim(su));
        double A = b ? 4.1e-9 : 3.9e-9, lag = (b ? 60 : 128) * M_PI / 180;
        tt_sim_set_state(tt_setup_sim(su), c->a_d + A * cos(lag), A * c->wd * sin(lag), 0);
        tt_sim_set_sample(tt_setup_sim(su), 4e-9, 0);
        assert_int_equal(tt_shoot_steady(tt_setup_sim(su), &p, 20000, 1e-7, &cy[b], &settled, &r[b]), TT_OK);
        print_message("%s: %s, amplitude %.6f nm, phase %.3f deg, |mu| %.6g, %ld cycles %s\n",
                      b ? "from tapping" : "from hovering",
                      r[b].how == TT_SHOOT_NEWTON ? "Newton" : "settled", cy[b].amplitude * 1e9,
                      cy[b].phase * 180 / M_PI, r[b].mu_abs, r[b].cycles, r[b].why);
        assert_true(settled);
        if (r[b].how != TT_SHOOT_NEWTON)
            assert_true(strlen(r[b].why) > 0);
        else
            assert_true(r[b].mu_abs < 1);
    }
    assert_int_equal(r[0].how, TT_SHOOT_NEWTON);
    assert_int_equal(r[1].how, TT_SHOOT_NEWTON);
    assert_true(cy[0].phase > M_PI / 2 && cy[0].contact_fraction == 0);
    assert_true(cy[1].phase < M_PI / 2 && cy[1].contact_fraction > 0);
    assert_true(cy[1].amplitude > cy[0].amplitude + 0.02 * 5e-9);
    tt_setup_free(su);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(free_fixed_point_is_the_analytic_steady_state),
        cmocka_unit_test(free_multipliers_are_analytic),
        cmocka_unit_test(standard_scene_agrees_with_settling),
        cmocka_unit_test(bistable_scene_shows_both_branches),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
