/* tiptap trace honours [noise]: a free cantilever at 300 K shows the thermal deflection
 * variance kB T / k (equipartition) within its sampling error; the detector's noise adds
 * n^2 fs / 2 to the measured deflection only, not to the tip; the same seed gives the
 * same trace, another seed another; no noise, the noiseless trace. */
#include "tt_test.h"
#include "tiptap/config/read_trace.h"
#include "tiptap/instrument/trace.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

/* A soft, low-Q lever (its thermal motion forgets itself in Q / (pi f0), 3 cycles) far
 * from the sample: the drive's response is linear, and subtracted. */
static const char *scene =
    "[cantilever]\nspring_constant = 1 N/m\nresonance_frequency = 300 kHz\nquality_factor = 10\n"
    "free_amplitude = 20 nm\n"
    "[material glass]\nreduced_modulus = 50 GPa\n"
    "[trace]\nseparation = 1 um\nsettle_cycles = 200\ncycles = 20000\nsamples_per_cycle = 16\n";

enum { N = 16, CYCLES = 20000, BATCHES = 20 };

typedef struct {
    double var_tip, var_meas; /* variance of the tip's and of the measured deflection about
                               * their mean cycle, m^2 */
    double se_tip;            /* the standard error of var_tip from batch means */
    double first;             /* the first recorded deflection */
} stats;

/* The first `cycles` recorded cycles (up to CYCLES) of the scene with noise. */
static stats run_cycles(const char *noise, long cycles)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, scene, "scene"), TT_OK);
    assert_int_equal(tt_scene_load_string(s, noise, "noise"), TT_OK);
    tt_trace_params p;
    tt_setup *st;
    tt_trace *t;
    if (tt_config_trace(s, &p) || tt_setup_alloc(&st, s) || tt_trace_alloc(&t, st, &p))
        fail_msg("%s", tt_error_message());
    static double tip[CYCLES][N], meas[CYCLES][N];
    for (long c = 0; c < cycles; c++) {
        tt_trace_row r;
        if (tt_trace_iterate(t, &r))
            fail_msg("%s", tt_error_message());
        for (int q = 0; q < N; q++) {
            tip[c][q] = r.samples[q].tip - r.samples[q].base;
            meas[c][q] = r.samples[q].deflection;
        }
    }
    stats o = {.first = meas[0][0]};
    if (cycles < CYCLES) { /* the seeds' test: the first cycle and the count suffice */
        o.var_tip = tip[cycles - 1][N - 1];
        tt_trace_free(t);
        tt_setup_free(st);
        tt_scene_free(s);
        return o;
    }
    double mt[N] = {0}, mm[N] = {0}, batch[BATCHES] = {0};
    for (long c = 0; c < CYCLES; c++)
        for (int q = 0; q < N; q++) {
            mt[q] += tip[c][q] / CYCLES;
            mm[q] += meas[c][q] / CYCLES;
        }
    for (long c = 0; c < CYCLES; c++)
        for (int q = 0; q < N; q++) {
            double a = tip[c][q] - mt[q], b = meas[c][q] - mm[q];
            o.var_tip += a * a / (CYCLES * N);
            o.var_meas += b * b / (CYCLES * N);
            batch[c * BATCHES / CYCLES] += a * a / (CYCLES / BATCHES * N);
        }
    double sb = 0;
    for (int b = 0; b < BATCHES; b++)
        sb += (batch[b] - o.var_tip) * (batch[b] - o.var_tip) / (BATCHES - 1);
    o.se_tip = sqrt(sb / BATCHES);
    tt_trace_free(t);
    tt_setup_free(st);
    tt_scene_free(s);
    return o;
}

static stats run_trace(const char *noise) { return run_cycles(noise, CYCLES); }

/* The 300 K run, made once for the two tests that read it. */
static stats thermal(void)
{
    static stats o;
    static int done;
    if (!done++)
        o = run_trace("[noise]\ntemperature = 300 K\n");
    return o;
}

static void thermal_variance_is_kT_over_k(void **state)
{
    (void)state;
    const double kT_k = TT_BOLTZMANN * 300 / 1.0;
    stats o = thermal();
    print_message("deflection variance %.4g m^2 (kB T / k = %.4g), standard error %.2g (%.1f %%), "
                  "off by %.2f standard errors\n",
                  o.var_tip, kT_k, o.se_tip, 100 * o.se_tip / kT_k, (o.var_tip - kT_k) / o.se_tip);
    assert_true(o.se_tip < 0.05 * kT_k); /* the run resolves it */
    assert_close(o.var_tip, kT_k, 4 * o.se_tip);
    assert_close(o.var_meas, o.var_tip, 1e-12 * kT_k); /* no detector noise */
}

/* 1 pm/sqrt(Hz) sampled 16 times a 300 kHz cycle: 2.4e-21 m^2 more in the measured
 * deflection, none in the tip's. */
static void detector_adds_to_the_measured_deflection(void **state)
{
    (void)state;
    stats th = thermal(),
          o = run_trace("[noise]\ntemperature = 300 K\ndetector = 1 pm/sqrt(Hz)\n");
    const double add = 1e-24 * 0.5 * N * 300e3;
    assert_memory_equal(&o.var_tip, &th.var_tip, sizeof o.var_tip);
    assert_close(o.var_meas - o.var_tip, add, 0.05 * add);
}

static void seeded(void **state)
{
    (void)state;
    /* 200 cycles: var_tip holds the last sample's deflection */
    stats a = run_cycles("[noise]\ntemperature = 300 K\nseed = 3\n", 200),
          b = run_cycles("[noise]\ntemperature = 300 K\nseed = 3\n", 200),
          c = run_cycles("[noise]\ntemperature = 300 K\nseed = 4\n", 200),
          off = run_cycles("[noise]\ntemperature = 0 K\nseed = 4\n", 200),
          none = run_cycles("", 200);
    assert_true(a.first == b.first && a.var_tip == b.var_tip);
    assert_true(a.first != c.first && a.var_tip != c.var_tip);
    assert_true(off.first == none.first && off.var_tip == none.var_tip);
    assert_true(a.var_tip != none.var_tip);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thermal_variance_is_kT_over_k),
        cmocka_unit_test(detector_adds_to_the_measured_deflection),
        cmocka_unit_test(seeded),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
