/* The cantilever's flexural eigenmodes (tt_cantilever_set_modes, the generic kernels):
 * each mode's free response is its damped oscillator's transfer function, at and off each
 * resonance, for both drives; each mode's thermal variance is k_B T / k_n times the
 * interpolated Langevin force's factor; one mode keeps the specialised kernels. */
#include <complex.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tt_sim_test.h"
#include "solver/sim.h"
#include "tiptap/config/config.h"
#include "tiptap/config/scene.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

/* A cantilever of three modes at the beam's defaults, low Q so that it settles quickly. */
static tt_cantilever three_modes(double fd, tt_drive drive)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 2, 70e3, 8, 10e-9, fd, drive), TT_OK);
    assert_int_equal(tt_cantilever_set_modes(&c, 3, NULL, NULL, NULL), TT_OK);
    return c;
}

static tt_sim *sim_with(const tt_cantilever *c, tt_method m) { return tt_test_sim_on(c, m, 1e-10, 4096); }

static tt_sim *sim_of(const tt_cantilever *c) { return sim_with(c, TT_METHOD_DOPRI5); }

static void beam_defaults(void **state)
{
    (void)state;
    tt_cantilever c = three_modes(70e3, TT_DRIVE_BASE);
    /* Euler-Bernoulli: (4.6941 / 1.8751)^2 = 6.2669, (7.8548 / 1.8751)^2 = 17.547 */
    assert_true(fabs(c.mode_f[1] / c.f0 - 6.2669) < 1e-4 && fabs(c.mode_f[2] / c.f0 - 17.547) < 1e-3);
    for (int i = 0; i < 3; i++) {
        double r = c.mode_f[i] / c.f0;
        assert_true(fabs(c.mode_k[i] / (c.k * r * r) - 1) < 1e-12);
        assert_true(fabs(c.mode_Q[i] / (c.Q * r) - 1) < 1e-12);
        /* tip-normalised modes of a uniform beam: equal modal masses */
        assert_true(fabs(c.mode_m[i] / c.m - 1) < 1e-12);
        double b = tt_beam_root(i + 1);
        assert_true(fabs(cos(b) * cosh(b) + 1) < 1e-12 * cosh(b));
    }
    /* an override that puts mode 3 below mode 2 is refused */
    double f[2] = {NAN, 300e3};
    assert_int_equal(tt_cantilever_set_modes(&c, 3, f, NULL, NULL), TT_EINVAL);
    assert_int_equal(tt_cantilever_set_modes(&c, 4, NULL, NULL, NULL), TT_EINVAL);
}

/* The steady deflection y = d - z the modes' transfer functions predict: each mode
 * forced by the tip force F0, or by the base's inertia g_n m_n w^2 a_d. */
static double complex predicted(const tt_cantilever *c)
{
    double w = c->wd;
    double complex y = 0;
    for (int i = 0; i < c->modes; i++) {
        double f = c->drive == TT_DRIVE_FORCE ? c->F0 : c->mode_base[i] * c->mode_m[i] * w * w * c->a_d;
        y += f / (c->mode_k[i] - c->mode_m[i] * w * w + I * c->mode_c[i] * w);
    }
    return y;
}

static void free_response_is_the_transfer_function(void **state)
{
    (void)state;
    const double ratio[2] = {1.0, 0.93};
    /* dopri5 on every case; rk4 and radau (its general Newton) on every other one */
    const tt_method methods[3] = {TT_METHOD_DOPRI5, TT_METHOD_RK4, TT_METHOD_RADAU};
    int count = 0;
    for (int drive = 0; drive < 2; drive++)
        for (int n = 0; n < 3; n++)
            for (int r = 0; r < 2; r++, count++) {
                tt_cantilever c0 = three_modes(70e3, (tt_drive)drive);
                tt_cantilever c = three_modes(c0.mode_f[n] * ratio[r], (tt_drive)drive);
                tt_method m = methods[count % 2 ? 1 + (count / 2) % 2 : 0];
                tt_sim *S = sim_with(&c, m);
                assert_int_equal(tt_sim_dim(S), 6);
                /* every mode decays at c_n / 2 m_n = pi f_1 / Q_1: 30 e-folds */
                long cycles = (long)(30 * c.Q / (M_PI * c.f0) * c.fd) + 2;
                tt_cycle cy;
                for (long k = 0; k < cycles; k++)
                    assert_int_equal(tt_sim_cycle(S, &cy), TT_OK);
                double complex y = predicted(&c);
                double amp = cabs(y), lag = -carg(y);
                if (lag < -M_PI / 2)
                    lag += 2 * M_PI;
                if (fabs(cy.amplitude / amp - 1) > 1e-6 || fabs(cy.phase - lag) > 1e-6)
                    fail_msg("%s, %s drive at %.2f f_%d: amplitude %.9g m, lag %.9f rad; the "
                             "transfer functions give %.9g m, %.9f rad",
                             tt_method_name(m), drive ? "force" : "base", ratio[r], n + 1,
                             cy.amplitude, cy.phase, amp, lag);
                /* on mode n's resonance its own oscillator dominates: a lag near pi/2
                 * (a base drive's mode 2 couples with the opposite sign: -pi/2) */
                if (r == 0) {
                    double want = (drive == TT_DRIVE_BASE && n == 1) ? 1.5 * M_PI : M_PI / 2;
                    assert_true(fabs(cy.phase - want) < 0.2);
                }
                /* the energy balance closes with the further modes' work booked */
                assert_true(fabs(cy.residual_rel) < 1e-6);
                tt_sim_free(S);
            }
}

/* Linear interpolation of white points dt apart filters the force by sinc^2(f dt): the
 * variance of a high-Q mode at f falls by sinc^4(f dt) (docs/physics.md). */
static double interpolation_factor(double f, double dt)
{
    double x = M_PI * f * dt;
    double s = sin(x) / x;
    return s * s * s * s;
}

static void equipartition_per_mode(void **state)
{
    (void)state;
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 2, 70e3, 5, 1e-10, 70e3, TT_DRIVE_BASE), TT_OK);
    /* Q off the beam's rule, so that each mode's damping (and its force's density)
     * differs from mode 1's: a force shared among the modes would miss by 3 and 0.5 */
    const double Q[2] = {3 * 5 * 6.2669, 0.5 * 5 * 17.547};
    assert_int_equal(tt_cantilever_set_modes(&c, 3, NULL, NULL, Q), TT_OK);
    c.a_d = 0; /* no drive: the thermal force alone */
    tt_sim *S = sim_of(&c);
    S->solver.tolerance = 1e-6;
    const int points = 64;
    const double temp = 300;
    assert_int_equal(tt_sim_set_thermal(S, temp, points), TT_OK);
    tt_sim_noise_key(S, tt_noise_key(11, 0, 0));
    double sum[3] = {0}, sum2[3] = {0};
    long count = 0;
    tt_cycle cy;
    for (int k = 0; k < 200; k++)
        assert_int_equal(tt_sim_cycle(S, &cy), TT_OK);
    /* a mode's correlation time is 2 m / c_n = Q_n / (pi f_n), 1.6 cycles for mode 1 and
     * 4.8 for mode 2: 12000 cycles give each variance to 2 % or better */
    for (int k = 0; k < 12000; k++) {
        assert_int_equal(tt_sim_cycle(S, &cy), TT_OK);
        double x[TT_SIM_DIM_MAX];
        int contact;
        tt_sim_get_x(S, x, &contact);
        for (int i = 0; i < 3; i++) {
            sum[i] += x[2 * i];
            sum2[i] += x[2 * i] * x[2 * i];
        }
        count++;
    }
    for (int i = 0; i < 3; i++) {
        double mean = sum[i] / count, var = sum2[i] / count - mean * mean;
        double want = TT_BOLTZMANN * temp / c.mode_k[i] * interpolation_factor(c.mode_f[i], c.T / points);
        print_message("mode %d: variance %.4g m^2, k_B T / k_n times the interpolation's %.4f: %.4g m^2 (%+.2f %%)\n",
                      i + 1, var, interpolation_factor(c.mode_f[i], c.T / points), want,
                      100 * (var / want - 1));
        if (fabs(var / want - 1) > 0.08)
            fail_msg("mode %d: thermal variance %.4g m^2, equipartition says %.4g m^2", i + 1, var, want);
    }
    tt_sim_free(S);
}

/* One mode asked for keeps the specialised kernels (its outputs the same bits). */
static void one_mode_stays_specialised(void **state)
{
    (void)state;
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    assert_int_equal(tt_cantilever_set_modes(&c, 1, NULL, NULL, NULL), TT_OK);
    tt_sim *S = sim_of(&c);
    assert_int_equal(tt_sim_dim(S), 2);
    assert_ptr_equal(S->sys.rhs, tt_sim_rhs);
    tt_sim_free(S);
}

/* The scene's keys: the defaults and an override read; a further mode's key beyond
 * `modes` refused in one line naming it. */
static int cantilever_of(const char *text, tt_cantilever *c)
{
    tt_scene *s = tt_scene_alloc();
    assert_non_null(s);
    int rc = tt_scene_load_string(s, text, "modes.ini");
    if (rc == TT_OK)
        rc = tt_config_cantilever(s, c);
    tt_scene_free(s);
    return rc;
}

static void scene_keys(void **state)
{
    (void)state;
    tt_cantilever c;
    assert_int_equal(cantilever_of("[cantilever]\nmodes = 3\nmode2_frequency = 2 MHz\n", &c), TT_OK);
    assert_int_equal(c.modes, 3);
    assert_true(c.mode_f[1] == 2e6 && fabs(c.mode_k[1] / (40 * (2e6 / 300e3) * (2e6 / 300e3)) - 1) < 1e-12);
    assert_true(fabs(c.mode_f[2] / (300e3 * 17.547) - 1) < 1e-4);
    assert_int_equal(cantilever_of("[cantilever]\n", &c), TT_OK);
    assert_true(c.modes == 0); /* the point mass: tt_cantilever_init's one mode */
    assert_int_not_equal(cantilever_of("[cantilever]\nmodes = 2\nmode3_quality_factor = 900\n", &c), TT_OK);
    assert_message_has("mode3_quality_factor");
    assert_int_not_equal(cantilever_of("[cantilever]\nmodes = 3\nmode3_frequency = 1 MHz\n", &c), TT_OK);
    assert_message_has("[cantilever] mode3_frequency: mode 3's frequency");
}

TT_TEST_MAIN(cmocka_unit_test(beam_defaults),
             cmocka_unit_test(free_response_is_the_transfer_function),
             cmocka_unit_test(equipartition_per_mode),
             cmocka_unit_test(one_mode_stays_specialised),
             cmocka_unit_test(scene_keys))
