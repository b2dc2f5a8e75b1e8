/* The scan's dissipation per mechanism (dissipation_hysteresis, _damping, _viscous):
 * the three add up to the dissipation channel in every pixel on the every-cycle and the
 * envelope tier, each mechanism is zero where the sample has none of it, the envelope
 * tier's split follows the every-cycle tier's, and the channels are recorded by default
 * only where a material is viscous and refused on the averaged tier. */
#include <stdio.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"

enum { HYST = TT_CH_LOSS_INDEX, DAMP = TT_CH_LOSS_INDEX + 1, VISC = TT_CH_LOSS_INDEX + 2, DISS = 5 };

/* A fast cantilever (Q 100 settles in a few hundred cycles) over disks of `domain` in a
 * `matrix`, both 1 GPa; the test adds the materials' losses. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[surface]\ntype = flat\nmap = disks\nmap_materials = matrix, domain\nmap_period = 500 nm\n"
    "map_radius = 150 nm\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 2\nline_rate = 20 Hz\nsettle_cycles = 3000\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

/* Viscous disks in an elastic matrix, neither sticky nor damped (the Hertz law). */
static const char *viscous_only =
    "[material matrix]\nyoungs_modulus = 1 GPa\npoisson_ratio = 0.4\n"
    "[material domain]\nyoungs_modulus = 1 GPa\npoisson_ratio = 0.4\nviscosity = 300 Pa s\n";

/* Every mechanism at once: sticky, damped and viscous disks in a sticky matrix. */
static const char *all_three =
    "[material matrix]\nyoungs_modulus = 0.3 GPa\npoisson_ratio = 0.4\nadhesion_energy = 100 mJ/m^2\n"
    "[material domain]\nyoungs_modulus = 0.3 GPa\npoisson_ratio = 0.4\nadhesion_energy = 100 mJ/m^2\n"
    "interaction_quality_factor = 50\nviscosity = 100 Pa s\n";


/* The largest dissipation of the scan's pixels (trace and retrace). */
static double largest(const tt_scan *s, int ch)
{
    const long n = tt_scan_xres(s) * tt_scan_yres(s);
    double m = 0;
    for (int r = 0; r < 2; r++)
        for (long i = 0; i < n; i++)
            m = fmax(m, fabs(tt_scan_image(s, ch, r)[i]));
    return m;
}

/* In every pixel the three add up to the dissipation, to rounding. */
static void assert_sum(const tt_scan *s)
{
    const long n = tt_scan_xres(s) * tt_scan_yres(s);
    const double scale = largest(s, DISS);
    assert_true(scale > 0);
    for (int r = 0; r < 2; r++) {
        const double *h = tt_scan_image(s, HYST, r), *c = tt_scan_image(s, DAMP, r),
                     *v = tt_scan_image(s, VISC, r), *d = tt_scan_image(s, DISS, r);
        assert_non_null(h);
        assert_non_null(c);
        assert_non_null(v);
        for (long i = 0; i < n; i++)
            assert_close(h[i] + c[i] + v[i], d[i], 1e-12 * scale);
    }
}

static void viscous_blend_loses_only_to_viscosity(void **st)
{
    (void)st;
    /* the every-cycle tier, the envelope tier, and the envelope tier with noise on (its
     * second-order model and the noise's response on the model's cycles) */
    const char *tiers[3] = {"every", "envelope", "envelope"};
    char noisy[2048];
    snprintf(noisy, sizeof noisy, "%s[noise]\ntemperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n", viscous_only);
    for (int t = 0; t < 3; t++) {
        tt_scene *sc;
        tt_scan *s = tt_run_scan_on(base, t < 2 ? viscous_only : noisy, tiers[t], &sc);
        /* no [scan] channels: a viscous material brings the three in */
        assert_true((tt_scan_channels(s) & TT_CH_LOSSES) == TT_CH_LOSSES);
        assert_sum(s);
        const long n = tt_scan_xres(s) * tt_scan_yres(s);
        for (int r = 0; r < 2; r++)
            for (long i = 0; i < n; i++) {
                /* no adhesion, no interaction damping: nothing of either, exactly */
                assert_true(tt_scan_image(s, HYST, r)[i] == 0);
                assert_true(tt_scan_image(s, DAMP, r)[i] == 0);
            }
        /* the disks lose energy (41 aJ a cycle at the most on this cantilever) */
        print_message("%s%s: largest viscous loss %.3f aJ\n", tiers[t], t == 2 ? " with noise" : "", largest(s, VISC) * 1e18);
        assert_true(largest(s, VISC) > 5e-18);
        tt_scan_free(s);
        tt_scene_free(sc);
    }
}

static void every_mechanism_is_booked_and_the_envelope_follows(void **st)
{
    (void)st;
    tt_scene *sa, *sb;
    tt_scan *every = tt_run_scan_on(base, all_three, "every", &sa);
    tt_scan *env = tt_run_scan_on(base, all_three, "envelope", &sb);
    assert_sum(every);
    assert_sum(env);
    const double scale = largest(every, DISS);
    print_message("largest: dissipation %.3f aJ, hysteresis %.3f, damping %.3f, viscous %.3f\n", scale * 1e18,
                  largest(every, HYST) * 1e18, largest(every, DAMP) * 1e18, largest(every, VISC) * 1e18);
    /* each mechanism is there: hysteresis on both materials, damping and viscosity on
     * the disks only (a pixel without the one has none of the other, and sticks) */
    assert_true(largest(every, HYST) > 0.02 * scale);
    assert_true(largest(every, DAMP) > 0.02 * scale);
    assert_true(largest(every, VISC) > 0.02 * scale);
    const long n = tt_scan_xres(every) * tt_scan_yres(every);
    long matrix = 0;
    for (int r = 0; r < 2; r++)
        for (long i = 0; i < n; i++)
            if (tt_scan_image(every, VISC, r)[i] == 0) {
                matrix++;
                assert_true(tt_scan_image(every, DAMP, r)[i] == 0);
                assert_true(tt_scan_image(every, HYST, r)[i] > 0.5 * largest(every, HYST));
            }
    assert_true(matrix > n / 2);
    /* the envelope tier's model cycles (most of them) split their total as its
     * integrated cycles did: each mechanism within 1e-4 of the largest loss of the
     * every-cycle tier's (1e-5 measured; the tier's own error in the total is 1e-6) */
    print_message("envelope: %ld of %ld cycles integrated\n", tt_scan_cycles_integrated(env),
                  tt_scan_cycles(env));
    assert_true(tt_scan_cycles_integrated(env) < tt_scan_cycles(env) / 2);
    const int chs[4] = {DISS, HYST, DAMP, VISC};
    for (int i = 0; i < 4; i++) {
        const int ch = chs[i];
        double max, rms;
        tt_scan_diff(every, env, ch, &max, &rms);
        print_message("%s: envelope - every: largest %.2e, rms %.2e of the largest loss\n",
                      tt_scan_channel_name(ch), max / scale, rms / scale);
        assert_true(max < 1e-4 * scale);
    }
    tt_scan_free(every);
    tt_scan_free(env);
    tt_scene_free(sa);
    tt_scene_free(sb);
}

static void channels_only_where_asked_or_viscous(void **st)
{
    (void)st;
    tt_scene *sc;
    /* an elastic scene keeps its channels as they were */
    tt_scan *s = tt_make_scan(base,
                              "[material matrix]\nyoungs_modulus = 1 GPa\n"
                              "[material domain]\nyoungs_modulus = 2 GPa\n",
                              &sc);
    assert_int_equal(tt_scan_channels(s) & TT_CH_LOSSES, 0);
    tt_scan_free(s);
    tt_scene_free(sc);
    /* a scene that names its channels gets those, viscous or not */
    char text[2048];
    snprintf(text, sizeof text, "%s[scan]\nchannels = height, dissipation_damping\n", viscous_only);
    s = tt_make_scan(base, text, &sc);
    assert_int_equal(tt_scan_channels(s) & TT_CH_LOSSES, TT_CH_DISSIPATION_DAMPING);
    tt_scan_free(s);
    tt_scene_free(sc);
    /* the averaged tier books the loss as a whole: not added, and refused when named */
    snprintf(text, sizeof text, "%s[solver]\ntier = averaged\n", viscous_only);
    s = tt_make_scan(base, text, &sc);
    assert_int_equal(tt_scan_channels(s) & TT_CH_LOSSES, 0);
    tt_scan_free(s);
    tt_scene_free(sc);
    snprintf(text, sizeof text, "%s[solver]\ntier = averaged\n[scan]\nchannels = dissipation_viscous\n",
             viscous_only);
    tt_expect_scan_refused(base, text, "[scan] channels: the averaged tier books the tip-sample loss");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(viscous_blend_loses_only_to_viscosity),
        cmocka_unit_test(every_mechanism_is_booked_and_the_envelope_follows),
        cmocka_unit_test(channels_only_where_asked_or_viscous),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
