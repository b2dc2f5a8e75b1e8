/* The higher-harmonic image channels: on a tapping scan they equal what the lock-in
 * gives on the steady deflection at the height the feedback found, they vanish where
 * the tip never touches, and asking for more harmonics than [lockin] offers is refused. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/lockin.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/config/setup.h"

/* test_scan.c's fast cantilever (Q 100) on a stiff sample. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 2\nline_rate = 20 Hz\nsettle_cycles = 3000\n"
    "channels = height, error, topography, harmonic2, harmonic3, harmonic2_phase\n"
    "[lockin]\nharmonics = 3\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

static tt_scan *run_scan(const char *extra, tt_scene **sc) { return tt_run_scan(base, extra, sc); }

static double row_mean(const double *img, long row)
{
    double m = 0;
    for (long i = 2; i < 30; i++)
        m += img[row * 32 + i];
    return m / 28;
}

/* The steady deflection at a fixed sample position, demodulated without a filter. */
static void steady_lockin(tt_scene *sc, double s, double A[4], double *phase2)
{
    enum { N = 32, P = 4 };
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, sc), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_sample smp[N];
    double y[N * P];
    tt_sim_reset_free(tt_setup_sim(su));
    tt_sim_set_sampling(tt_setup_sim(su), N, smp);
    tt_sim_set_sample(tt_setup_sim(su), s, 0);
    tt_lockin_params lp = {tt_setup_cantilever(su)->fd, N, P, 3, 0, 1, 0};
    tt_lockin *l;
    assert_int_equal(tt_lockin_alloc(&l, &lp), TT_OK);
    for (int b = 0; b < 500; b++) { /* 2000 cycles: about 60 ring-down times at Q 100 */
        for (int j = 0; j < P; j++) {
            tt_cycle c;
            assert_int_equal(tt_sim_cycle(tt_setup_sim(su), &c), TT_OK);
            for (int q = 0; q < N; q++)
                y[j * N + q] = smp[q].d - smp[q].z;
        }
        assert_int_equal(tt_lockin_push(l, y), TT_OK);
    }
    for (int h = 1; h <= 3; h++)
        A[h] = tt_lockin_raw_amplitude(l, h);
    *phase2 = tt_lockin_raw_phase(l, 2) * 180 / M_PI;
    tt_lockin_free(l);
    tt_setup_free(su);
}

static void harmonics_match_the_lockin_on_the_steady_deflection(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = run_scan("[surface]\nmap = uniform\n", &sc);
    int i2 = TT_CH_HARMONIC_INDEX, i3 = TT_CH_HARMONIC_INDEX + 1, p2 = TT_CH_HARMONIC_PHASE_INDEX;
    assert_string_equal(tt_scan_channel_name(i3), "harmonic3");
    assert_string_equal(tt_scan_channel_unit(i3), "m");
    assert_string_equal(tt_scan_channel_name(p2), "harmonic2_phase");
    assert_null(tt_scan_image(s, TT_CH_HARMONIC_INDEX + 2, 0)); /* harmonic4: not asked for */
    for (int r = 0; r < 2; r++) {
        double h = row_mean(tt_scan_image(s, 0, r), 1);
        double a2 = row_mean(tt_scan_image(s, i2, r), 1), a3 = row_mean(tt_scan_image(s, i3, r), 1);
        double ph2 = row_mean(tt_scan_image(s, p2, r), 1);
        /* on the flat sample the sample sits at setpoint - 0 + height (src/instrument/scan.c) */
        double A[4], ph;
        steady_lockin(sc, 16e-9 + h, A, &ph);
        print_message("%s: harmonic2 %.4f pm (lock-in %.4f pm), harmonic3 %.4f pm (%.4f pm), "
                      "harmonic2_phase %.3f deg (%.3f deg), fundamental %.4f nm\n",
                      r ? "retrace" : "trace", a2 * 1e12, A[2] * 1e12, a3 * 1e12, A[3] * 1e12, ph2,
                      ph, A[1] * 1e9);
        assert_close(A[1], 16e-9, 0.01e-9); /* the same operating point as the feedback's */
        assert_true(a2 > 1e-13);            /* tapping is not a sinusoid... */
        assert_true(a2 < 0.01 * A[1]);      /* ...but nearly one */
        assert_close(a2, A[2], 1e-3 * A[2]);
        assert_close(a3, A[3], 1e-3 * A[3]);
        assert_close(ph2, ph, 0.05);
    }
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void harmonics_vanish_where_the_tip_never_touches(void **st)
{
    (void)st;
    tt_scene *sc;
    /* lines sunk 100 nm into a flat sample, deeper than the z piezo can follow: over
     * them the tip oscillates freely, a linear oscillator under a sinusoidal drive */
    tt_scan *s = run_scan("[surface]\ntype = grating\nperiod = 1 um\nheight = -100 nm\n"
                          "[feedback]\nz_range = 10 nm\n",
                          &sc);
    const double *topo = tt_scan_image(s, 6, 0), *a2 = tt_scan_image(s, TT_CH_HARMONIC_INDEX, 0);
    double free_max = 0, touch_min = INFINITY;
    int nfree = 0, ntouch = 0;
    for (long px = 3; px < 29; px++) {
        /* pixels with three of the same kind either side, past the lock-in's transient */
        int sunk = 1, top = 1;
        for (long q = px - 3; q <= px + 3; q++) {
            sunk &= topo[32 + q] < -50e-9;
            top &= topo[32 + q] > -1e-9;
        }
        if (sunk) {
            free_max = fmax(free_max, a2[32 + px]);
            nfree++;
        }
        if (top) {
            touch_min = fmin(touch_min, a2[32 + px]);
            ntouch++;
        }
    }
    print_message("harmonic2: at most %.3g pm over %d free pixels, at least %.3f pm over %d "
                  "tapping pixels\n",
                  free_max * 1e12, nfree, touch_min * 1e12, ntouch);
    assert_true(nfree >= 4 && ntouch >= 4);
    assert_true(touch_min > 1e-13);
    assert_true(free_max < 1e-4 * touch_min);
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void harmonics_beyond_the_lockin_are_refused(void **st)
{
    (void)st;
    static const struct {
        const char *text, *message;
    } cases[] = {
        {"[scan]\nchannels = height, harmonic3\n[lockin]\nharmonics = 2\n",
         "bad.ini: [scan] channels: harmonic3 needs [lockin] harmonics = 3 or more (it is 2)"},
        {"[scan]\nchannels = harmonic1\n", "unknown channel 'harmonic1'"},
        {"[scan]\nchannels = harmonic9\n", "harmonic2 to harmonic8, harmonic2_phase to harmonic8_phase"},
        {"[lockin]\nharmonics = 8\nsamples_per_period = 16\n",
         "[lockin] harmonics: 8 harmonics need more than 16 samples per period"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        tt_expect_scan_refused(base, cases[i].text, cases[i].message);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(harmonics_match_the_lockin_on_the_steady_deflection),
        cmocka_unit_test(harmonics_vanish_where_the_tip_never_touches),
        cmocka_unit_test(harmonics_beyond_the_lockin_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
