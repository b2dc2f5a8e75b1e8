/* Noise on the envelope tier (docs/dynamics.md, "Noise on the envelope tier"): the cycle
 * map's linear-noise model of the thermal force gives the free cantilever's equipartition
 * (<d^2> = kB T / k, <d'^2> = kB T / m*); a scan with thermal and detector noise on
 * skips cycles, and the noise in its images has the every-cycle tier's statistics (the sd
 * of height, amplitude and phase over seeds, and their means) within sampling error; z
 * piezo noise falls back to every cycle; the images are the same on one thread as on two. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/solver/noise.h"

enum { NS = 32 };

/* The model of a free cantilever (no sample) built on its steady cycle, iterated with the
 * thermal force's draws: the stationary variances of the state at the cycle's start
 * against equipartition, with standard errors from 40 batches (each many correlation
 * times Q / pi long). */
static void free_equipartition(double Q)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, Q, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sample smp[NS];
    tt_sim_set_sampling(sim, NS, smp);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 1e-6, 0); /* a micrometre away: no force */
    tt_envelope *e;
    assert_int_equal(tt_envelope_alloc(&e, &c, NS), TT_OK);
    double R[NS];
    for (int q = 0; q < NS; q++)
        R[q] = 1.0 / NS;
    assert_int_equal(tt_envelope_reduce(e, 1, R), TT_OK);
    const double T = 300;
    assert_int_equal(tt_envelope_set_noise(e, 2 * c.c * TT_BOLTZMANN * T, 0), TT_OK);
    assert_int_equal(tt_envelope_noise_size(e), 3);
    double x0[2];
    int c0;
    tt_sim_get_state(sim, &x0[0], &x0[1], &c0);
    tt_cycle cy;
    assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
    double *obs = malloc((size_t)tt_envelope_size(e) * sizeof *obs);
    tt_envelope_observe(e, smp, &cy, obs);
    long jac = 0;
    assert_int_equal(tt_envelope_build(e, sim, x0, c0, 1e-6, 0, &cy, obs, &jac), 1);
    /* the steady cycle is the model's fixed point; the noise moves the state off it */
    double xs[2], red[1 + TT_ENV_EXTRA], x[2] = {x0[0], x0[1]};
    tt_envelope_predict_reduced(e, x0, 1e-6, 0, xs, red);
    const uint64_t key = tt_noise_key(11, TT_NOISE_ENVELOPE, 0);
    enum { NB = 40 };
    const long burn = (long)(10 * Q), per = (long)(250 * Q);
    double bd[NB] = {0}, bv[NB] = {0};
    for (long n = 0; n < burn + NB * per; n++) {
        double x1[2], g[4], dx[2];
        tt_envelope_predict_reduced(e, x, 1e-6, 0, x1, red);
        tt_noise_pair(key, 2 * (uint64_t)n, g);
        tt_noise_pair(key, 2 * (uint64_t)n + 1, g + 2);
        tt_envelope_noise(e, g, dx, red);
        x[0] = x1[0] + dx[0];
        x[1] = x1[1] + dx[1];
        if (n >= burn) {
            long b = (n - burn) / per;
            bd[b] += (x[0] - xs[0]) * (x[0] - xs[0]) / per;
            bv[b] += (x[1] - xs[1]) * (x[1] - xs[1]) / per;
        }
    }
    const double want[2] = {TT_BOLTZMANN * T / c.k, TT_BOLTZMANN * T / c.m};
    const double *bat[2] = {bd, bv};
    for (int i = 0; i < 2; i++) {
        double m = 0, v = 0;
        for (int b = 0; b < NB; b++)
            m += bat[i][b] / NB;
        for (int b = 0; b < NB; b++)
            v += (bat[i][b] - m) * (bat[i][b] - m);
        double se = sqrt(v / (NB - 1) / NB);
        print_message("Q %g: <%s^2> / (kB T / %s) = %.4f +- %.4f\n", Q, i ? "d'" : "d", i ? "m" : "k",
                      m / want[i], se / want[i]);
        assert_true(se < 0.03 * want[i]);
        assert_close(m, want[i], 3.5 * se);
    }
    free(obs);
    tt_envelope_free(e);
    tt_sim_free(sim);
}

static void model_equipartition(void **st)
{
    (void)st;
    free_equipartition(50);
    free_equipartition(400);
}

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
    "free_amplitude = 20 nm\n"
    "[material polymer]\nyoungs_modulus = 1 GPa\nadhesion_energy = 40 mJ/m^2\n"
    "interaction_quality_factor = 5\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 2\nline_rate = 8 Hz\nsettle_cycles = 3000\n"
    "channels = height, error, phase\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

enum { SEEDS = 8, CH = 3 };

/* One scan of the base on a tier, with noise (seed > 0) or without. */
static tt_scan *noisy(const char *tier, int seed, long *integrated, long *cycles)
{
    char extra[512];
    snprintf(extra, sizeof extra,
             "[solver]\ntier = %s\n[noise]\nseed = %d\ntemperature = %s\ndetector = %s\n", tier,
             seed > 0 ? seed : 1, seed > 0 ? "300 K" : "0 K", seed > 0 ? "100 fm/sqrt(Hz)" : "0 m/sqrt(Hz)");
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, extra, &sc);
    tt_scene_free(sc);
    if (integrated) {
        *integrated += tt_scan_cycles_integrated(s);
        *cycles += tt_scan_cycles(s);
    }
    return s;
}

/* Per channel over the seeds: the mean of each seed's sd of (noisy - noiseless) over the
 * pixels of trace and retrace, its standard error, and the mean offset and its error. */
typedef struct {
    double sd, sd_se, mean, mean_se;
} noise_stats;

static void stats_of(const char *tier, noise_stats out[CH], long *integrated, long *cycles)
{
    tt_scan *clean = noisy(tier, 0, NULL, NULL);
    const long n = tt_scan_xres(clean) * tt_scan_yres(clean);
    double sd[CH][SEEDS], mean[CH][SEEDS];
    for (int s = 0; s < SEEDS; s++) {
        tt_scan *sc = noisy(tier, s + 1, integrated, cycles);
        for (int c = 0; c < CH; c++) {
            double sum = 0, sum2 = 0;
            for (int r = 0; r < 2; r++)
                for (long i = 0; i < n; i++) {
                    double d = tt_scan_image(sc, c, r)[i] - tt_scan_image(clean, c, r)[i];
                    sum += d;
                    sum2 += d * d;
                }
            double m = sum / (2.0 * (double)n);
            mean[c][s] = m;
            sd[c][s] = sqrt((sum2 / (2.0 * (double)n) - m * m) * (2.0 * (double)n) / (2.0 * (double)n - 1));
        }
        tt_scan_free(sc);
    }
    for (int c = 0; c < CH; c++) {
        double ms = 0, mm = 0, vs = 0, vm = 0;
        for (int s = 0; s < SEEDS; s++) {
            ms += sd[c][s] / SEEDS;
            mm += mean[c][s] / SEEDS;
        }
        for (int s = 0; s < SEEDS; s++) {
            vs += (sd[c][s] - ms) * (sd[c][s] - ms);
            vm += (mean[c][s] - mm) * (mean[c][s] - mm);
        }
        out[c] = (noise_stats){ms, sqrt(vs / (SEEDS - 1) / SEEDS), mm, sqrt(vm / (SEEDS - 1) / SEEDS)};
    }
    tt_scan_free(clean);
}

/* The envelope tier's noise against the every-cycle tier's, over eight seeds each: the sd
 * of height, amplitude and phase agree within 3.5 combined standard errors (which must
 * be under 7 % for the test to mean something), and so do their means. */
static void statistics_match(void **st)
{
    (void)st;
    noise_stats env[CH], every[CH];
    long integrated = 0, cycles = 0;
    stats_of("envelope", env, &integrated, &cycles);
    stats_of("every", every, NULL, NULL);
    print_message("envelope tier with noise: %.1f %% of the cycles integrated\n",
                  100.0 * (double)integrated / (double)cycles);
    assert_true(integrated < cycles / 2);
    const char *name[CH] = {"height (m)", "amplitude error (m)", "phase (deg)"};
    for (int c = 0; c < CH; c++) {
        double se = sqrt(env[c].sd_se * env[c].sd_se + every[c].sd_se * every[c].sd_se);
        double mse = sqrt(env[c].mean_se * env[c].mean_se + every[c].mean_se * every[c].mean_se);
        print_message("%-20s sd envelope %.4g +- %.2g, every %.4g +- %.2g (ratio %.3f); mean %.3g "
                      "+- %.2g against %.3g +- %.2g\n",
                      name[c], env[c].sd, env[c].sd_se, every[c].sd, every[c].sd_se,
                      env[c].sd / every[c].sd, env[c].mean, env[c].mean_se, every[c].mean,
                      every[c].mean_se);
        assert_true(se < 0.07 * every[c].sd);
        assert_close(env[c].sd, every[c].sd, 3.5 * se);
        assert_close(env[c].mean, every[c].mean, 3.5 * mse + 1e-3 * every[c].sd);
    }
}

/* z piezo noise moves the sample by 0.1 nm a cycle, beyond the model: every cycle is
 * integrated, and the images are the every-cycle tier's bit for bit. */
static void z_piezo_falls_back(void **st)
{
    (void)st;
    const char *extra = "[scan]\nlines = 1\nline_rate = 40 Hz\n[noise]\nz_piezo = 0.3 pm/sqrt(Hz)\n"
                        "[solver]\ntier = %s\n";
    tt_scene *s1, *s2;
    char a[256], b[256];
    snprintf(a, sizeof a, extra, "envelope");
    snprintf(b, sizeof b, extra, "every");
    tt_scan *env = tt_run_scan(base, a, &s1), *every = tt_run_scan(base, b, &s2);
    assert_int_equal(tt_scan_cycles_integrated(env), tt_scan_cycles(env));
    tt_scan_assert_identical(env, every, CH);
    tt_scan_free(env);
    tt_scan_free(every);
    tt_scene_free(s1);
    tt_scene_free(s2);
}

/* The same noise on one thread as on two: the draws are a function of (seed, line,
 * cycle), not of the thread. */
static void threads_agree(void **st)
{
    (void)st;
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    assert_int_equal(tt_scene_load_string(sc,
                                          "[scan]\nline_rate = 20 Hz\n[noise]\nseed = 3\n"
                                          "temperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n",
                                          "extra"),
                     TT_OK);
    tt_scan *a, *b;
    assert_int_equal(tt_config_scan_alloc(&a, sc), TT_OK);
    assert_int_equal(tt_config_scan_alloc(&b, sc), TT_OK);
    assert_int_equal(tt_scan_run(a, 1, NULL, NULL), TT_OK);
    assert_int_equal(tt_scan_run(b, 2, NULL, NULL), TT_OK);
    assert_true(tt_scan_cycles_integrated(a) < tt_scan_cycles(a));
    tt_scan_assert_identical(a, b, CH);
    tt_scan_free(a);
    tt_scan_free(b);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(model_equipartition),
        cmocka_unit_test(statistics_match),
        cmocka_unit_test(z_piezo_falls_back),
        cmocka_unit_test(threads_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
