/* Seeded noise against analytic results: the free cantilever's thermal mean square
 * deflection kB T / k (equipartition), the detector noise's spectral density, the
 * energy balance with the Langevin force booked; same seed identical, other seed
 * different, any number of threads identical. Continuous lines: a stable loop agrees
 * with independent lines away from the line starts, an unstable one rings differently
 * on every line. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/solver/integrator.h"
#include "tiptap/solver/noise.h"

enum { NS = 32 };

/* <y_thermal^2> of a free, driven cantilever at Q = 2 (correlation time 0.6 cycles) over
 * `cycles` cycles after 50 cycles of burn-in, with its standard error from 25 batches.
 * The motion is linear, so the thermal part is y minus the steady driven oscillation. */
static void thermal_msd(tt_method method, double temp, uint64_t key, long cycles, double *msd,
                        double *se, double *worst_residual, double *first)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 2, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.method = method;
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    assert_int_equal(tt_sim_set_thermal(sim, temp, 64), TT_OK);
    tt_sim_noise_key(sim, key);
    tt_sample smp[NS];
    tt_sim_set_sampling(sim, NS, smp);
    tt_sim_reset_free(sim);
    enum { NB = 25 };
    double batch[NB] = {0};
    *worst_residual = 0;
    for (long n = 0; n < 50 + cycles; n++) {
        tt_cycle cy;
        assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
        if (n == 0)
            *first = smp[NS / 2].d;
        if (cy.residual_rel > *worst_residual)
            *worst_residual = cy.residual_rel;
        if (n < 50)
            continue;
        for (int q = 0; q < NS; q++) {
            double y = smp[q].d - smp[q].z - c.A0 * cos(c.wd * smp[q].t - c.phi0);
            batch[(n - 50) * NB / cycles] += y * y;
        }
    }
    double m = 0, v = 0, per = (double)cycles / NB * NS;
    for (int b = 0; b < NB; b++)
        m += (batch[b] /= per);
    m /= NB;
    for (int b = 0; b < NB; b++)
        v += (batch[b] - m) * (batch[b] - m);
    *msd = m;
    *se = sqrt(v / (NB - 1) / NB);
    tt_sim_free(sim);
}

/* Equipartition: <y^2> = kB T / k within 3.5 standard errors (and the error is small
 * enough for that to mean something: under 3 %). Printed for docs/dynamics.md. */
static void thermal_equipartition(void **st)
{
    (void)st;
    const tt_method methods[] = {TT_METHOD_DOPRI5, TT_METHOD_RADAU, TT_METHOD_RK4};
    for (int i = 0; i < 3; i++) {
        double msd, se, res, first;
        thermal_msd(methods[i], 300, tt_noise_key(7, TT_NOISE_THERMAL, 0), 20000, &msd, &se, &res,
                    &first);
        double want = TT_BOLTZMANN * 300 / 40;
        printf("%s: <y^2> = %.4g m^2 +- %.2g (kB T / k = %.4g), ratio %.4f +- %.4f; worst "
               "energy residual %.2g\n",
               tt_method_name(methods[i]), msd, se, want, msd / want, se / want, res);
        assert_true(se < 0.03 * want);
        assert_close(msd, want, 3.5 * se);
        /* the Langevin force's work is booked with the drive's: the balance still closes */
        assert_true(res < 1e-6);
    }
}

static void thermal_seeded(void **st)
{
    (void)st;
    double a[4], se, res;
    thermal_msd(TT_METHOD_DOPRI5, 300, 11, 200, &a[0], &se, &res, &a[2]);
    thermal_msd(TT_METHOD_DOPRI5, 300, 11, 200, &a[1], &se, &res, &a[3]);
    assert_true(a[0] == a[1] && a[2] == a[3]);
    thermal_msd(TT_METHOD_DOPRI5, 300, 12, 200, &a[1], &se, &res, &a[3]);
    assert_true(a[0] != a[1] && a[2] != a[3]);
    /* temperature 0: no noise, the steady oscillation exactly as without it */
    thermal_msd(TT_METHOD_DOPRI5, 0, 11, 200, &a[0], &se, &res, &a[2]);
    assert_true(a[0] < 1e-30);
}

/* The detector noise as the scan draws it (sigma = n sqrt(fs / 2) per sample): its
 * averaged periodogram is the set one-sided density n^2 within its statistical error. */
static void detector_density(void **st)
{
    (void)st;
    enum { L = 256, K = 200 };
    const double n = 50e-15, fs = 32 * 300e3, sigma = n * sqrt(fs / 2);
    const uint64_t key = tt_noise_key(3, TT_NOISE_DETECTOR, 5);
    double psd = 0;
    long bins = 0;
    double *x = malloc(L * sizeof *x);
    for (int k = 0; k < K; k++) {
        for (int i = 0; i < L; i++)
            x[i] = sigma * tt_noise_gauss(key, (uint64_t)k * L + (uint64_t)i);
        for (int f = 1; f < L / 2; f++) {
            double re = 0, im = 0;
            for (int i = 0; i < L; i++) {
                re += x[i] * cos(2 * M_PI * f * i / L);
                im -= x[i] * sin(2 * M_PI * f * i / L);
            }
            psd += 2 * (re * re + im * im) / (fs * L); /* one-sided */
            bins++;
        }
    }
    free(x);
    psd /= (double)bins;
    /* each bin is chi-square with 2 degrees of freedom: relative error 1 / sqrt(bins) */
    double rel = 1 / sqrt((double)bins);
    printf("detector: PSD %.4g (m/sqrt(Hz))^2 against %.4g: ratio %.4f +- %.4f\n", psd, n * n,
           psd / (n * n), rel);
    assert_close(psd, n * n, 3.5 * rel * n * n);
}

/* The pairs the envelope tier draws (tt_noise_pair, the ziggurat): over 2e6 numbers
 * their mean, variance and fourth moment are the standard normal's (0, 1, 3), the two
 * of a pair and neighbouring pairs are uncorrelated, the share within one sd is 0.6827
 * (the boxes and wedges) and beyond three sd 0.0027 (the tail past the base at 3.44),
 * each within 4 standard errors. */
static void pair_normal(void **st)
{
    (void)st;
    const uint64_t key = tt_noise_key(5, TT_NOISE_ENVELOPE, 3);
    enum { N = 1000000 };
    double m1 = 0, m2 = 0, m4 = 0, c01 = 0, cnext = 0, within = 0, beyond = 0, prev = 0;
    for (long i = 0; i < N; i++) {
        double g[2];
        tt_noise_pair(key, (uint64_t)i, g);
        for (int k = 0; k < 2; k++) {
            m1 += g[k];
            m2 += g[k] * g[k];
            m4 += g[k] * g[k] * g[k] * g[k];
            within += fabs(g[k]) < 1;
            beyond += fabs(g[k]) > 3;
        }
        c01 += g[0] * g[1];
        cnext += prev * g[0];
        prev = g[1];
    }
    const double n = 2.0 * N, p = 0.682689492137086, t = 0.002699796063260;
    printf("pairs: mean %.5f var %.5f m4 %.4f corr %.5f next %.5f within 1 sd %.5f beyond 3 sd "
           "%.5f\n",
           m1 / n, m2 / n, m4 / n, c01 / N, cnext / N, within / n, beyond / n);
    assert_true(fabs(m1 / n) < 4 / sqrt(n));
    assert_true(fabs(m2 / n - 1) < 4 * sqrt(2 / n));
    assert_true(fabs(m4 / n - 3) < 4 * sqrt(96 / n));
    assert_true(fabs(c01 / N) < 4 / sqrt((double)N));
    assert_true(fabs(cnext / N) < 4 / sqrt((double)N));
    assert_true(fabs(within / n - p) < 4 * sqrt(p * (1 - p) / n));
    assert_true(fabs(beyond / n - t) < 4 * sqrt(t * (1 - t) / n));
}

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[surface]\ntype = grating\nperiod = 500 nm\nheight = 10 nm\nedge_width = 100 nm\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 4\nline_rate = 20 Hz\nsettle_cycles = 2000\n"
    "channels = height, error\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

static tt_scan *scan_on(const char *extra, int threads)
{
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    if (tt_scene_load_string(sc, extra, "extra") != TT_OK)
        fail_msg("%s", tt_error_message());
    tt_scan *s;
    if (tt_config_scan_alloc(&s, sc) != TT_OK || tt_scan_run(s, threads, NULL, NULL) != TT_OK)
        fail_msg("%s", tt_error_message());
    tt_scene_free(sc);
    return s;
}

static int same_image(const tt_scan *a, const tt_scan *b, int ch)
{
    size_t n = (size_t)tt_scan_xres(a) * (size_t)tt_scan_yres(a);
    return memcmp(tt_scan_image(a, ch, 0), tt_scan_image(b, ch, 0), n * sizeof(double)) == 0 &&
           memcmp(tt_scan_image(a, ch, 1), tt_scan_image(b, ch, 1), n * sizeof(double)) == 0;
}

static const char *noisy = "[noise]\nseed = 4\ntemperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n"
                           "z_piezo = 1 pm/sqrt(Hz)\n";

/* Same seed: identical images on one thread and on three; another seed: different. */
static void scan_seeded_any_threads(void **st)
{
    (void)st;
    tt_scan *a = scan_on(noisy, 1), *b = scan_on(noisy, 3), *q = scan_on("", 2);
    assert_true(same_image(a, b, 0) && same_image(a, b, 1));
    assert_false(same_image(a, q, 0)); /* noise changes the height */
    tt_scan *c = scan_on("[noise]\nseed = 5\ntemperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n"
                         "z_piezo = 1 pm/sqrt(Hz)\n", 2);
    assert_false(same_image(a, c, 0));
    tt_scan_free(a);
    tt_scan_free(b);
    tt_scan_free(c);
    tt_scan_free(q);
}

/* A stable loop: continuous lines agree with independent ones away from each line's
 * start (past its first 4 pixels the turnaround's transient has died out) within
 * 0.3 nm, on a 10 nm grating. */
static void continuous_stable_agrees(void **st)
{
    (void)st;
    tt_scan *a = scan_on("", 2), *b = scan_on("[scan]\nlines_mode = continuous\n", 2);
    const double *ha = tt_scan_image(a, 0, 0), *hb = tt_scan_image(b, 0, 0);
    double worst = 0;
    for (long l = 0; l < 4; l++)
        for (long p = 4; p < 32; p++)
            worst = fmax(worst, fabs(ha[l * 32 + p] - hb[l * 32 + p]));
    printf("stable loop: continuous - independent, worst %.3g nm past pixel 4\n", worst * 1e9);
    assert_true(worst < 0.3e-9);
    /* line 0 is engaged and settled the same way in both */
    assert_true(memcmp(ha, hb, 32 * sizeof *ha) == 0);
    tt_scan_free(a);
    tt_scan_free(b);
}

/* An unstable loop (integral gain far above the amplitude bandwidth) rings differently
 * on each line when lines carry on; independent lines repeat one another on a surface
 * that does not change along y. */
static void continuous_unstable_rings(void **st)
{
    (void)st;
    const char *hot = "[feedback]\nintegral_gain = 60 kHz\n";
    tt_scan *a = scan_on(hot, 2);
    char text[256];
    snprintf(text, sizeof text, "%s[scan]\nlines_mode = continuous\n", hot);
    tt_scan *b = scan_on(text, 2);
    const double *ha = tt_scan_image(a, 0, 0), *hb = tt_scan_image(b, 0, 0);
    assert_true(memcmp(ha + 32, ha + 64, 32 * sizeof *ha) == 0);
    double diff = 0;
    for (long p = 0; p < 32; p++)
        diff = fmax(diff, fabs(hb[32 + p] - hb[64 + p]));
    printf("unstable loop: consecutive continuous lines differ by up to %.3g nm\n", diff * 1e9);
    assert_true(diff > 1e-9);
    tt_scan_free(a);
    tt_scan_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thermal_equipartition), cmocka_unit_test(thermal_seeded),
        cmocka_unit_test(detector_density),      cmocka_unit_test(pair_normal),
        cmocka_unit_test(scan_seeded_any_threads),
        cmocka_unit_test(continuous_stable_agrees), cmocka_unit_test(continuous_unstable_rings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
