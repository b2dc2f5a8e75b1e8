/* A live scan changed between lines (tt_scan_set_*): the change takes effect on the next
 * line, which is then the line a scan made with the new value gives (independent lines,
 * byte for byte); on continuous lines a gain change carries the loop on without a jump.
 * Values out of range are refused and change nothing. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/util/error.h"

/* A fast cantilever (Q 100) over 4 nm steps. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 16\nlines = 3\nline_rate = 40 Hz\nsettle_cycles = 1000\n"
    "channels = height, error, phase\n"
    "[surface]\ntype = steps\nstep_height = 4 nm\nstep_width = 300 nm\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

static tt_scan *make(const char *extra, tt_scene **sc) { return tt_make_scan(base, extra, sc); }

static void step(tt_scan *s, long line, tt_scan_scope *r)
{
    if (tt_scan_step(s, line, r) != TT_OK)
        fail_msg("%s", tt_error_message());
}

/* Line `line` of channels height, amplitude error and phase, trace and retrace: the same
 * bit for bit in a and b (same = 1), or the height differs somewhere (same = 0). */
static void compare_line(const tt_scan *a, const tt_scan *b, long line, int same)
{
    double x[16], y[16];
    int differ = 0;
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < 3; c++) {
            assert_int_equal(tt_scan_line_values(a, c, r, line, x), TT_OK);
            assert_int_equal(tt_scan_line_values(b, c, r, line, y), TT_OK);
            if (same)
                assert_memory_equal(x, y, sizeof x);
            differ |= memcmp(x, y, sizeof x) != 0;
        }
    assert_int_equal(differ, !same);
}

/* Independent lines: line 1 after a change is the line of a scan made with the new
 * value; line 0, before it, that of the old. */
/* The three scans a retune test compares (changed live, old scene, new scene) and
 * their scenes. */
static void free_three(tt_scan *live, tt_scan *old, tt_scan *neu, tt_scene *s1, tt_scene *s2,
                       tt_scene *s3)
{
    tt_scan_free(live);
    tt_scan_free(old);
    tt_scan_free(neu);
    tt_scene_free(s1);
    tt_scene_free(s2);
    tt_scene_free(s3);
}

static void check_change(const char *fresh, void (*change)(tt_scan *, const tt_scan *))
{
    tt_scene *s1, *s2, *s3;
    tt_scan *live = make("", &s1), *old = make("", &s2), *neu = make(fresh, &s3);
    step(live, 0, NULL);
    change(live, neu);
    step(live, 1, NULL);
    step(old, 0, NULL);
    step(old, 1, NULL);
    step(neu, 1, NULL);
    compare_line(live, old, 0, 1);
    compare_line(live, neu, 1, 1);
    compare_line(live, old, 1, 0); /* the change did something */
    free_three(live, old, neu, s1, s2, s3);
}

/* Each change sets the value the fresh scan's scene gave (ref), as read back from it. */
static void set_feedback(tt_scan *s, const tt_scan *ref)
{
    tt_feedback_params p;
    tt_scan_get_feedback(ref, &p);
    assert_int_equal(tt_scan_set_feedback(s, &p), TT_OK);
}

static void set_noise(tt_scan *s, const tt_scan *ref)
{
    tt_scan_noise n;
    tt_scan_get_noise(ref, &n);
    assert_true(n.temperature == 300 && n.seed == 7);
    assert_int_equal(tt_scan_set_noise(s, &n), TT_OK);
}

static void set_rate(tt_scan *s, const tt_scan *ref)
{
    assert_int_equal(tt_scan_set_line_rate(s, tt_scan_line_rate(ref)), TT_OK);
}

/* the amplitude first (the setpoint in metres stays below it), then the setpoint */
static void set_amplitude(tt_scan *s, const tt_scan *ref)
{
    assert_int_equal(tt_scan_set_free_amplitude(s, tt_scan_free_amplitude(ref)), TT_OK);
    set_feedback(s, ref);
}

static void gain_change_is_the_new_gains_line(void **st)
{
    (void)st;
    check_change("[feedback]\nintegral_gain = 300 Hz\nproportional_gain = 0.5\n", set_feedback);
}

static void setpoint_change_is_the_new_setpoints_line(void **st)
{
    (void)st;
    check_change("[feedback]\nsetpoint = 12 nm\n", set_feedback);
}

/* the envelope tier (the default) with thermal and detector noise to first order */
static void noise_change_is_the_noisy_line(void **st)
{
    (void)st;
    check_change("[noise]\ntemperature = 300 K\ndetector = 100 fm/sqrt(Hz)\nseed = 7\n", set_noise);
}

static void line_rate_change_is_the_slower_line(void **st)
{
    (void)st;
    check_change("[scan]\nline_rate = 25 Hz\n", set_rate);
}

static void free_amplitude_change_is_the_new_drives_line(void **st)
{
    (void)st;
    check_change("[cantilever]\nfree_amplitude = 25 nm\n[feedback]\nsetpoint = 60 %\n", set_amplitude);
}

/* The rms of z about its mean over a direction's record. */
static double z_rms(const tt_scan_scope *r, int dir)
{
    long n = tt_scan_scope_points(r, dir);
    const double *z = tt_scan_scope_series(r, dir, TT_SCOPE_Z), *h = tt_scan_scope_series(r, dir, TT_SCOPE_SURFACE);
    double m = 0, q = 0;
    for (long i = 0; i < n; i++)
        m += z[i] - h[i];
    m /= (double)n;
    for (long i = 0; i < n; i++)
        q += (z[i] - h[i] - m) * (z[i] - h[i] - m);
    return sqrt(q / (double)n);
}

/* Continuous lines: a loop turned unstable between lines oscillates from the next
 * line on, and settles again when the gain comes back (within a line: the line after
 * is quiet); the output does not jump at a change from a steady loop (bumpless). */
static void continuous_gain_change_takes_effect_next_line(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = make("[scan]\nlines_mode = continuous\nlines = 4\n[surface]\ntype = flat\n", &sc);
    tt_scan_scope *r;
    assert_int_equal(tt_scan_scope_alloc(&r), TT_OK);
    double rms[4], jump[4];
    double last = NAN;
    tt_feedback_params p;
    tt_scan_get_feedback(s, &p);
    const double kis[4] = {3000, 60000, 3000, 3000};
    for (long line = 0; line < 4; line++) {
        p.ki = kis[line];
        assert_int_equal(tt_scan_set_feedback(s, &p), TT_OK);
        step(s, line, r);
        const double *z = tt_scan_scope_series(r, 0, TT_SCOPE_Z);
        jump[line] = fabs(z[0] - last);
        last = tt_scan_scope_series(r, 1, TT_SCOPE_Z)[tt_scan_scope_points(r, 1) - 1];
        rms[line] = fmax(z_rms(r, 0), z_rms(r, 1));
        print_message("line %ld, ki %g Hz: z rms %.3g nm, first z step %.3g nm\n", line,
                      kis[line], rms[line] * 1e9, jump[line] * 1e9);
    }
    assert_true(rms[0] < 0.05e-9);  /* flat sample, stable loop */
    assert_true(rms[1] > 1e-9);     /* the unstable loop oscillates */
    assert_true(rms[3] < 0.05e-9);  /* and settles again at the good gain */
    /* no jump at the first point after a change from a steady loop (a block's move) */
    assert_true(jump[1] < 0.05e-9);
    assert_true(jump[3] < 0.05e-9);
    tt_scan_scope_free(r);
    tt_scan_free(s);
    tt_scene_free(sc);
}

/* Z piezo noise turned on and off again on a live envelope-tier scan (a flat sample): its
 * model takes the sample's travel and second order for the noisy line and drops them
 * after, so that each line is the one a scan made with that noise gives, byte for byte,
 * and the model still runs on the noisy line (docs/dynamics.md, "Noise on the envelope
 * tier"). */
static void piezo_noise_change_is_the_noisy_line(void **st)
{
    (void)st;
    const char *flat = "[surface]\ntype = flat\n";
    const char *zn = "[surface]\ntype = flat\n"
                     "[noise]\nz_piezo = 0.3 pm/sqrt(Hz)\nz_piezo_bandwidth = 5 kHz\nseed = 7\n";
    tt_scene *s1, *s2, *s3;
    tt_scan *live = make(flat, &s1), *old = make(flat, &s2), *neu = make(zn, &s3);
    tt_scan_noise quiet, noisy;
    tt_scan_get_noise(live, &quiet);
    tt_scan_get_noise(neu, &noisy);
    assert_true(noisy.z_piezo == 0.3e-12 && noisy.z_bandwidth == 5e3 && noisy.seed == 7);
    long all[4] = {0}, integrated[4] = {0};
    for (long line = 0; line < 3; line++) {
        assert_int_equal(tt_scan_set_noise(live, line == 1 ? &noisy : &quiet), TT_OK);
        step(live, line, NULL);
        all[line + 1] = tt_scan_cycles(live);
        integrated[line + 1] = tt_scan_cycles_integrated(live);
        step(old, line, NULL);
    }
    step(neu, 1, NULL);
    compare_line(live, old, 0, 1);
    compare_line(live, neu, 1, 1);
    compare_line(live, old, 1, 0); /* the noise did something */
    compare_line(live, old, 2, 1);
    for (int l = 0; l < 3; l++)
        print_message("line %d: %ld of %ld cycles integrated\n", l, integrated[l + 1] - integrated[l],
                      all[l + 1] - all[l]);
    /* short lines on 100 GPa at 5 kHz: 90 % of the noisy line's cycles integrated (51 %
     * at the default 2 kHz), against all of them when this noise fell back to every
     * cycle; the noiseless lines 12 % */
    const long a = all[2] - all[1], i = integrated[2] - integrated[1];
    assert_true(i < a - a / 20);
    assert_true(integrated[1] - integrated[0] < a / 5);
    free_three(live, old, neu, s1, s2, s3);
}

/* Out of range: refused, with the key named, and nothing changes. */
static void bad_values_are_refused(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = make("", &sc);
    tt_feedback_params p, q;
    tt_scan_get_feedback(s, &p);
    q = p;
    q.ki = -1;
    assert_int_equal(tt_scan_set_feedback(s, &q), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "integral_gain"));
    q = p;
    q.setpoint = 30e-9; /* above the free amplitude */
    assert_int_equal(tt_scan_set_feedback(s, &q), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "setpoint"));
    q = p;
    q.kp = NAN;
    assert_int_equal(tt_scan_set_feedback(s, &q), TT_EINVAL);
    tt_scan_get_feedback(s, &q);
    assert_memory_equal(&p, &q, sizeof p);
    tt_scan_noise n;
    tt_scan_get_noise(s, &n);
    n.temperature = 300;
    n.points = 2;
    assert_int_equal(tt_scan_set_noise(s, &n), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "points"));
    tt_scan_get_noise(s, &n);
    assert_true(n.temperature == 0);
    n.z_piezo = 1e-12;
    n.z_bandwidth = 200e3; /* above half the 300 kHz drive */
    assert_int_equal(tt_scan_set_noise(s, &n), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "z_piezo_bandwidth"));
    tt_scan_get_noise(s, &n);
    assert_true(n.z_piezo == 0);
    assert_int_equal(tt_scan_set_line_rate(s, 1e6), TT_EINVAL); /* under a block a pixel */
    assert_int_equal(tt_scan_set_line_rate(s, 0), TT_EINVAL);
    assert_true(tt_scan_line_rate(s) == 40);
    assert_int_equal(tt_scan_set_free_amplitude(s, 10e-9), TT_EINVAL); /* below the setpoint */
    assert_true(tt_scan_free_amplitude(s) == 20e-9);
    tt_scan_free(s);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(gain_change_is_the_new_gains_line),
        cmocka_unit_test(setpoint_change_is_the_new_setpoints_line),
        cmocka_unit_test(noise_change_is_the_noisy_line),
        cmocka_unit_test(line_rate_change_is_the_slower_line),
        cmocka_unit_test(free_amplitude_change_is_the_new_drives_line),
        cmocka_unit_test(continuous_gain_change_takes_effect_next_line),
        cmocka_unit_test(piezo_noise_change_is_the_noisy_line),
        cmocka_unit_test(bad_values_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
