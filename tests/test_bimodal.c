/* Bimodal AM-AM (tt_cantilever_set_drive2, the lock-in's second reference): far from the
 * sample mode 2's amplitude and lag are its damped oscillator's response to its drive
 * (F2 Q2 / k2, 90 deg at resonance) and mode 1's lock-in reads what it reads without
 * mode 2's drive, to the window's leakage; a conservative force gradient moves mode 2's
 * lag below 90 deg when repulsive and above when attractive, by the amount the shifted
 * resonance gives; over a lossy contact the two modes' energy balances (drive work less
 * damping, from each lock-in) add up to the tip-sample dissipation the sim integrates. */
#include <complex.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tt_sim_test.h"
#include "solver/sim.h"
#include "tiptap/config/config.h"
#include "tiptap/config/scene.h"
#include "tiptap/instrument/lockin.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

enum { N = 32, P = 4 };

/* A cantilever of two modes, mode 2 driven at its resonance to A2. */
static tt_cantilever bimodal(double k, double f0, double Q, double A0, double A2)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, k, f0, Q, A0, f0, TT_DRIVE_BASE), TT_OK);
    assert_int_equal(tt_cantilever_set_modes(&c, 2, NULL, NULL, NULL), TT_OK);
    if (A2 > 0)
        assert_int_equal(tt_cantilever_set_drive2(&c, A2, NAN), TT_OK);
    return c;
}

typedef struct {
    double A1, ph1;  /* mode 1's lock-in, last block */
    double A2, ph2;  /* mode 2's, filtered */
    double ets;      /* the sim's tip-sample loss per cycle, mean over the last half */
    double cyA, cyph; /* the sim's own per-cycle fundamental (exact quadratures), mean */
} run_out;

/* Run `cycles` cycles from the free state through a lock-in on y = d - z (mode 2's
 * reference when driven), both filters starting from zero. */
static run_out run(tt_sim *S, const tt_cantilever *c, long cycles)
{
    tt_lockin_params lp = {c->fd, N, P, 1, 10e-6 * 300e3 / c->fd, 4, c->A2 > 0 ? c->ratio2 : 0};
    tt_lockin *li;
    assert_int_equal(tt_lockin_alloc(&li, &lp), TT_OK);
    tt_lockin_reset(li, 0, 0);
    tt_lockin_reset_second(li, 0, 0);
    tt_sample smp[N];
    double y[N * P];
    tt_sim_set_sampling(S, N, smp);
    run_out o = {0};
    long half = 0;
    for (long n = 0; n < cycles; n++) {
        tt_cycle cy;
        assert_int_equal(tt_sim_cycle(S, &cy), TT_OK);
        double *yb = y + (n % P) * N;
        for (int q = 0; q < N; q++)
            yb[q] = smp[q].d - smp[q].z;
        if (c->A2 > 0)
            tt_lockin_second_period(li, yb, tt_cantilever_drive2_turns(c, tt_sim_cycles(S) - 1));
        if (n % P == P - 1)
            assert_int_equal(tt_lockin_push(li, y), TT_OK);
        if (n >= cycles / 2) {
            o.ets += cy.e_ts;
            o.cyA += cy.amplitude;
            o.cyph += cy.phase;
            half++;
        }
    }
    o.ets /= half;
    o.cyA /= half;
    o.cyph /= half;
    o.A1 = tt_lockin_amplitude(li, 1);
    o.ph1 = tt_lockin_phase(li, 1);
    if (c->A2 > 0) {
        o.A2 = tt_lockin_second_amplitude(li);
        o.ph2 = tt_lockin_second_phase(li);
    }
    tt_lockin_free(li);
    return o;
}

static void free_mode2_is_its_oscillator(void **state)
{
    (void)state;
    const double A2 = 0.5e-9;
    tt_cantilever c = bimodal(40, 300e3, 100, 20e-9, A2), c1 = bimodal(40, 300e3, 100, 20e-9, 0);
    /* mode 2's own oscillator at resonance: F2 Q2 / k2, F2 = |g_2| m_2 w2^2 a_d2 */
    double F2 = fabs(c.mode_base[1] * c.a_d2) * c.mode_m[1] * c.wd2 * c.wd2;
    double Aosc = F2 * c.mode_Q[1] / c.mode_k[1];
    /* the other mode's share at w2 is a part in |g_2| Q_2 of it */
    assert_true(fabs(Aosc / A2 - 1) < 2.0 / (fabs(c.mode_base[1]) * c.mode_Q[1]));
    tt_sim *S = tt_test_sim(&c, 1e-10), *S1 = tt_test_sim(&c1, 1e-10);
    run_out o = run(S, &c, 600), o1 = run(S1, &c1, 600);
    tt_sim_free(S);
    tt_sim_free(S1);
    /* 600 cycles are 19 ring times of either mode (Q / pi cycles) and 900 filter times;
     * mode 1's share at w2 puts the lag 0.16 deg short of 90 here (0.49999979 nm against
     * 0.50000024 nm, 89.83 deg measured) */
    if (fabs(o.A2 / Aosc - 1) > 2e-3 || fabs(o.ph2 * 180 / M_PI - 90) > 0.3)
        fail_msg("free mode 2: %.6g m at %.4f deg, its oscillator %.6g m at 90 deg", o.A2,
                 o.ph2 * 180 / M_PI, Aosc);
    /* mode 1's block (P whole periods) sees mode 2 through its rectangular window:
     * A2 |sin(pi frac(r P))| / (pi (r - 1) P) at most; and the sim's exact per-cycle
     * fundamental the same bound per period */
    double r = c.ratio2, fr = r * P - floor(r * P);
    double leak = A2 * fabs(sin(M_PI * fr)) / (M_PI * (r - 1) * P);
    if (fabs(o.A1 - o1.A1) > leak + 1e-14 || fabs(o.ph1 - o1.ph1) > leak / c.A0 + 1e-9)
        fail_msg("mode 1 with mode 2 driven: %.9g m %.6f deg, without %.9g m %.6f deg (bound %.3g m)",
                 o.A1, o.ph1 * 180 / M_PI, o1.A1, o1.ph1 * 180 / M_PI, leak);
    /* and the bound is not empty: mode 2 does leak in, or the check would be vacuous */
    assert_true(leak < 1e-3 * c.A0);
}

/* A linear force gradient kappa on the tip (conservative): P = kappa (delta - delta0). */
static double gradient_load(double delta, int in_contact, double *dPdd, void *user)
{
    (void)in_contact;
    const double *g = user;
    if (dPdd)
        *dPdd = g[0];
    return g[0] * (delta - g[1]);
}

static double gradient_energy(double delta, int in_contact, void *user)
{
    (void)in_contact;
    const double *g = user;
    return 0.5 * g[0] * (delta - g[1]) * (delta - g[1]);
}

/* Mode 2's lag with a gradient kappa on the tip: the coupled modes' linear response
 * at w2, solved exactly (two modes, the tip's d = q0 + q1). */
static double predicted_lag(const tt_cantilever *c, double kappa)
{
    double w = c->wd2;
    double complex D0 = c->k - c->m * w * w + I * c->c * w;
    double complex D1 = c->mode_k[1] - c->mode_m[1] * w * w + I * c->mode_c[1] * w;
    /* base z = a e^{iwt}: mode 0 (absolute) D0 q0 + kappa (q0 + q1) = (k + i c w) z,
     * mode 1: D1 q1 + kappa (q0 + q1) = g m1 w^2 z; y = q0 + q1 - z */
    double complex a = c->a_d2, f0 = (c->k + I * c->c * w) * a;
    double complex f1 = c->mode_base[1] * c->mode_m[1] * w * w * a;
    double complex A11 = D0 + kappa, A12 = kappa, A21 = kappa, A22 = D1 + kappa;
    double complex det = A11 * A22 - A12 * A21;
    double complex q0 = (f0 * A22 - A12 * f1) / det, q1 = (A11 * f1 - A21 * f0) / det;
    /* a_d2 carries g_2's sign: the reference is cos(w2 t) itself */
    double complex y = q0 + q1 - a;
    double lag = -carg(y);
    return lag < -M_PI / 2 ? lag + 2 * M_PI : lag;
}

static void gradient_moves_mode2_phase(void **state)
{
    (void)state;
    tt_cantilever c = bimodal(40, 300e3, 100, 20e-9, 0.5e-9);
    /* one mode-2 bandwidth's worth of stiffness: the lag moves by about 45 deg */
    const double kappas[2] = {c.mode_k[1] / c.mode_Q[1], -c.mode_k[1] / c.mode_Q[1]};
    double lags[2];
    for (int i = 0; i < 2; i++) {
        double g[2] = {kappas[i], -10e-9}; /* no force at rest 10 nm below the tip's rest */
        tt_contact *ct;
        assert_int_equal(tt_contact_alloc_custom(&ct, gradient_load, gradient_energy, g, 1, -1),
                         TT_OK);
        tt_sim *S = tt_test_sim(&c, 1e-10);
        tt_sim_set_contact(S, ct, NAN);
        tt_sim_set_sample(S, 10e-9, 0);
        run_out o = run(S, &c, 600);
        tt_sim_free(S);
        tt_contact_free(ct);
        lags[i] = o.ph2;
        double want = predicted_lag(&c, kappas[i]);
        if (fabs(o.ph2 - want) * 180 / M_PI > 0.05) /* 1e-4 deg measured */
            fail_msg("gradient %.4g N/m: mode 2's lag %.3f deg, the coupled modes' %.3f deg", kappas[i],
                     o.ph2 * 180 / M_PI, want * 180 / M_PI);
    }
    /* repulsive (stiffer): below 90 deg; attractive (softer): above */
    assert_true(lags[0] * 180 / M_PI < 60 && lags[1] * 180 / M_PI > 120);
}

static void energy_balance_of_both_modes(void **state)
{
    (void)state;
    tt_cantilever c = bimodal(40, 300e3, 100, 20e-9, 1e-9);
    /* an adhesive, damped Maugis contact (K 1 GPa, R 10 nm, w 0.1 J/m^2, Qi 30) at 15 nm */
    tt_contact_params p = {TT_CONTACT_MAUGIS, 1e9, 10e-9, 0.1, 0.3e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    tt_sim *S = tt_test_sim(&c, 1e-10);
    tt_sim_set_contact(S, ct, 30);
    tt_sim_set_sample(S, 15e-9, 0);
    run_out o = run(S, &c, 800);
    tt_sim_free(S);
    tt_contact_free(ct);
    /* per mode-1 period: mode n's drive work less its damping at its drive frequency,
     * pi k_n A_n / Q_n (A0n sin(phi_n) - A_n) (w_n / w_1) (Cleveland et al.; Lozano &
     * Garcia, PRL 100, 076102, for mode 2) */
    double A01 = c.A0, A02 = fabs(c.mode_base[1] * c.a_d2) * c.mode_Q[1];
    double e1 = M_PI * c.k * o.cyA / c.Q * (A01 * sin(o.cyph) - o.cyA);
    double e2 = M_PI * c.mode_k[1] * o.A2 / c.mode_Q[1] * (A02 * sin(o.ph2) - o.A2) * c.ratio2;
    /* the modes' share of the loss at other frequencies (mode 1's harmonics, their
     * mixing with mode 2) is left out: it was 0.5 % of the total here (6.84e-17 J, the
     * balances 5.75e-17 + 1.13e-17 J) */
    if (!(e2 > 0.1 * o.ets) || fabs(e1 + e2 - o.ets) > 0.02 * o.ets)
        fail_msg("tip-sample loss %.5g J a cycle, the lock-ins' balances %.5g + %.5g = %.5g J", o.ets, e1,
                 e2, e1 + e2);
}

/* [cantilever] of a scene's text through the configuration layer. */
static int scene_cantilever(const char *text, tt_cantilever *c)
{
    tt_scene *s = tt_scene_alloc();
    assert_non_null(s);
    int rc = tt_scene_load_string(s, text, "bimodal.ini");
    rc = rc ? rc : tt_config_cantilever(s, c);
    tt_scene_free(s);
    return rc;
}

static void keys_and_refusals(void **state)
{
    (void)state;
    tt_cantilever c;
    assert_int_equal(scene_cantilever("[cantilever]\nmodes = 2\nmode2_free_amplitude = 1 nm\n"
                                      "mode2_drive_frequency = 1.9 MHz\n", &c), TT_OK);
    assert_true(c.A2 == 1e-9 && c.fd2 == 1.9e6 && fabs(c.ratio2 - 1.9e6 / 300e3) < 1e-15);
    /* one line naming the key: no mode 2, or a frequency without an amplitude */
    assert_int_not_equal(scene_cantilever("[cantilever]\nmode2_free_amplitude = 1 nm\n", &c), TT_OK);
    assert_message_has("[cantilever] mode2_free_amplitude: drives mode 2");
    assert_int_not_equal(scene_cantilever("[cantilever]\nmodes = 2\nmode2_drive_frequency = 2 MHz\n", &c),
                         TT_OK);
    assert_message_has("mode2_drive_frequency: is set but mode2_free_amplitude");
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    /* one mode: no mode 2 to drive */
    assert_int_equal(tt_cantilever_set_drive2(&c, 1e-9, NAN), TT_EINVAL);
    assert_int_equal(tt_cantilever_set_modes(&c, 2, NULL, NULL, NULL), TT_OK);
    assert_int_equal(tt_cantilever_set_drive2(&c, -1e-9, NAN), TT_EINVAL);
    assert_int_equal(tt_cantilever_set_drive2(&c, 1e-9, 300e3), TT_EINVAL);
    assert_int_equal(tt_cantilever_set_drive2(&c, 1e-9, NAN), TT_OK);
    assert_true(c.fd2 == c.mode_f[1] && fabs(c.phi2 - M_PI / 2) < 1e-2);
    /* the second reference's sum frequency must stay below the samples' Nyquist */
    tt_lockin_params lp = {300e3, 16, 4, 1, 1e-4, 2, c.ratio2};
    tt_lockin *li;
    assert_int_equal(tt_lockin_alloc(&li, &lp), TT_EINVAL);
    lp.samples_per_period = 32;
    assert_int_equal(tt_lockin_alloc(&li, &lp), TT_OK);
    tt_lockin_free(li);
}

TT_TEST_MAIN(cmocka_unit_test(keys_and_refusals),
             cmocka_unit_test(free_mode2_is_its_oscillator),
             cmocka_unit_test(gradient_moves_mode2_phase),
             cmocka_unit_test(energy_balance_of_both_modes))
