/* Noise on the averaged tier (docs/dynamics.md, "Noise on the averaged tier"): the
 * thermal force's white noise on the slow flow reproduces the free cantilever's
 * equipartition (the in-phase and quadrature parts X, Y of the deflection's first
 * harmonic each of variance kB T / (m w^2), kB T / k at resonance, so <y^2> = kB T / k)
 * at any step, the noise entering the implicit solve; a scan's noise (thermal,
 * detector, z piezo, each alone and all together) has the every-cycle tier's
 * statistics (per line the sd, the mean and the spectrum of height, error and phase
 * over seeds) within sampling error and a few per cent; the images are the same on
 * one thread as on two. */
#include <math.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tt_noise_compare.h"
#include "tiptap/solver/averaged.h"
#include "tiptap/solver/noise.h"

/* Far from the sample (no force), the slow flow stepped by h with the thermal impulses
 * from its steady state: the variances of X and Y about it against kB T / (m w^2), with
 * standard errors from 40 batches of 500 amplitude times 2 Q / w0 each. */
static void free_equipartition(double Q, int cycles_per_step)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, Q, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_contact_params cp = {TT_CONTACT_HERTZ, 10e9, 10e-9, 0, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &cp), TT_OK);
    tt_averaged *a;
    assert_int_equal(tt_averaged_alloc(&a, &c, ct, NAN, 1), TT_OK);
    const double T = 300, h = cycles_per_step * c.T, sig = tt_averaged_thermal_density(&c, T);
    tt_averaged_state st;
    tt_averaged_out o;
    tt_averaged_state_free(&c, &st);
    for (int k = 0; k < 100000; k++) /* the steady state, to rounding */
        tt_averaged_step(a, &st, 1e-6, 64 * c.T, &o);
    const double Xs = st.X, Ys = st.Y, tau = 2 * Q / c.w0;
    enum { NB = 40 };
    const long burn = lround(10 * tau / h), per = lround(500 * tau / h);
    double bx[NB] = {0}, by[NB] = {0};
    const uint64_t key = tt_noise_key(7, TT_NOISE_ENVELOPE, 0);
    for (long n = 0; n < burn + NB * per; n++) {
        double g[2];
        tt_noise_pair(key, (uint64_t)n, g);
        const double kick[2] = {sig * sqrt(h) * g[0], sig * sqrt(h) * g[1]};
        tt_averaged_step_noisy(a, &st, 1e-6, h, kick, &o);
        if (n >= burn) {
            long b = (n - burn) / per;
            bx[b] += (st.X - Xs) * (st.X - Xs) / per;
            by[b] += (st.Y - Ys) * (st.Y - Ys) / per;
        }
    }
    const double want = TT_BOLTZMANN * T / (c.m * c.wd * c.wd);
    const double *bat[2] = {bx, by};
    for (int i = 0; i < 2; i++) {
        double se, m = nc_batch_mean(bat[i], NB, &se);
        print_message("Q %g, %d cycles a step: <%s^2> / (kB T / m w^2) = %.4f +- %.4f\n", Q,
                      cycles_per_step, i ? "dY" : "dX", m / want, se / want);
        assert_true(se < 0.03 * want);
        assert_close(m, want, 3.5 * se);
    }
    /* at resonance kB T / (m w^2) is kB T / k */
    assert_close(want, TT_BOLTZMANN * T / c.k, 1e-9 * want);
    tt_averaged_free(a);
    tt_contact_free(ct);
}

/* The lock-in's block (4 cycles) and steps of 64 cycles, at Q 400 and Q 50 (a step of
 * 64 cycles is then 2 amplitude times: noise added after the step would make the
 * variance (1 + h / (2 tau))^2 = 9 times too large). */
static void equipartition(void **st)
{
    (void)st;
    free_equipartition(400, 4);
    free_equipartition(400, 64);
    free_equipartition(50, 64);
}


/* The averaged tier's noise against every cycle's on the engaged flat polymer
 * (tt_noise_compare.h); it integrates none. */
static void vs_every(const char *what, const char *noise, int seeds, double slack, double mean_slack)
{
    assert_true(nc_compare_tiers(nc_polymer_base(), what, "", noise, "averaged", seeds, slack, mean_slack) ==
                0);
}

/* The full noise set of tiptap bench (the z piezo's at its default bandwidth) and each
 * part alone. */
static const char *full_noise = "temperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n"
                                "z_piezo = 0.3 pm/sqrt(Hz)\n";

/* The full set on the soft polymer (engaged, flat) over 12 seeds: the noise's sd, mean
 * and spectrum within their sampling error and 3 %, the means within 0.1 of the sd (measured over 16 seeds: the sd
 * -0.5 +- 0.9 % in height, 1.5 +- 1.1 % in error, -0.6 +- 1.7 % in phase). */
static void full_set(void **st)
{
    (void)st;
    vs_every("full noise set, polymer", full_noise, 12, 0.03, 0.1);
}

/* The thermal force alone over 8 seeds, within sampling error and 3 % (measured over 12:
 * the sd -0.6 +- 1.7 % in height, -3.2 +- 1.9 % in error, 1.0 +- 1.8 % in phase). */
static void thermal_alone(void **st)
{
    (void)st;
    vs_every("thermal noise, polymer", "temperature = 300 K\n", 8, 0.03, 0.1);
}

/* The detector alone over 8 seeds (10 times the bench's density), within sampling error
 * and 3 % (measured over 12: the sd 1.4 +- 1.7 % in height, 2.1 +- 2.5 % in error,
 * -2.9 +- 1.8 % in phase; the lowest band of the height's spectrum, 1 to 3 periods a
 * line, 0.75 +- 0.09, not understood). */
static void detector_alone(void **st)
{
    (void)st;
    vs_every("detector noise, polymer", "detector = 1 pm/sqrt(Hz)\n", 8, 0.03, 0.1);
}

/* The z piezo's noise alone over 2 seeds: both tiers draw the same, so the images'
 * noise agrees to the model's error: height and error to 0.1 %, the phase's sd 5 % low
 * (0.0017 deg against 0.0018: the averaged model's slope of the phase in the sample's
 * height on this lossy polymer), within 6 %; the phase's mean shift by the noise 0.0007
 * deg apart (0.4 of its sd, the same model's curvature), within 0.5 of the sd. */
static void z_piezo_alone(void **st)
{
    (void)st;
    vs_every("z piezo noise, polymer", "z_piezo = 0.3 pm/sqrt(Hz)\n", 2, 0.06, 0.5);
}

/* The same noise on one thread as on two, and on the same seed the same images: the
 * draws are a function of (seed, line, cycle), not of the thread. */
static void threads_agree(void **st)
{
    (void)st;
    tt_scan_assert_threads_agree(nc_polymer_base(),
                                 "[solver]\ntier = averaged\n[scan]\nline_rate = 20 Hz\n[noise]\nseed = 3\n"
                                 "temperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n"
                                 "z_piezo = 0.3 pm/sqrt(Hz)\n",
                                 NC_CH, 1);
}

TT_TEST_MAIN(cmocka_unit_test(equipartition),
             cmocka_unit_test(full_set),
             cmocka_unit_test(thermal_alone),
             cmocka_unit_test(detector_alone),
             cmocka_unit_test(z_piezo_alone),
             cmocka_unit_test(threads_agree))
