/* A scan stepped line by line (tt_scan_step) is the scan tt_scan_run makes: the same
 * images byte for byte and the same full-rate record, on every tier, with independent
 * and continuous lines, with noise. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/util/error.h"

/* A fast cantilever (Q 100 settles in a few hundred cycles) over 4 nm steps. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 16\nlines = 4\nline_rate = 40 Hz\nsettle_cycles = 1000\n"
    "[surface]\ntype = steps\nstep_height = 4 nm\nstep_width = 300 nm\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

static tt_scan *make(const char *extra, tt_scene **sc) { return tt_make_scan(base, extra, sc); }

/* Every channel of two scans, trace and retrace, the same bit for bit. */
static void assert_same_images(const tt_scan *a, const tt_scan *b)
{
    long n = tt_scan_xres(a) * tt_scan_yres(a);
    int seen = 0;
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < TT_CH_COUNT; c++) {
            const double *x = tt_scan_image(a, c, r), *y = tt_scan_image(b, c, r);
            assert_true((x == NULL) == (y == NULL));
            if (!x)
                continue;
            assert_memory_equal(x, y, (size_t)n * sizeof(double));
            seen++;
        }
    assert_true(seen >= 6);
}

/* tt_scan_run of the scene (with line 2's record) against the same scan stepped line by
 * line; the records of line 2 too. */
static void compare(const char *extra)
{
    tt_scene *sa, *sb;
    tt_scan *a = make(extra, &sa), *b = make(extra, &sb);
    tt_scan_scope *ra, *rb;
    assert_int_equal(tt_scan_scope_alloc(&ra), TT_OK);
    assert_int_equal(tt_scan_scope_alloc(&rb), TT_OK);
    tt_scan_scope_attach(a, 2, ra);
    assert_int_equal(tt_scan_run(a, 2, NULL, NULL), TT_OK);
    for (long line = 0; line < tt_scan_lines(b); line++)
        if (tt_scan_step(b, line, line == 2 ? rb : NULL) != TT_OK)
            fail_msg("%s", tt_error_message());
    assert_int_equal(tt_scan_lines_done(b), 4);
    assert_same_images(a, b);
    assert_int_equal(tt_scan_cycles(a), tt_scan_cycles(b));
    assert_int_equal(tt_scan_cycles_integrated(a), tt_scan_cycles_integrated(b));
    assert_int_equal(tt_scan_scope_line(ra), 2);
    assert_int_equal(tt_scan_scope_line(rb), 2);
    for (int r = 0; r < 2; r++) {
        long n = tt_scan_scope_points(ra, r);
        assert_true(n > 100);
        assert_int_equal(n, tt_scan_scope_points(rb, r));
        for (int q = 0; q < TT_SCOPE_COUNT; q++) {
            const double *x = tt_scan_scope_series(ra, r, q), *y = tt_scan_scope_series(rb, r, q);
            assert_memory_equal(x, y, (size_t)n * sizeof(double));
            for (long i = 0; i < n; i++)
                assert_false(isnan(x[i])); /* every block wrote its point */
        }
    }
    tt_scan_scope_free(ra);
    tt_scan_scope_free(rb);
    tt_scan_free(a);
    tt_scan_free(b);
    tt_scene_free(sa);
    tt_scene_free(sb);
}

static void every_cycle_independent_noise(void **st)
{
    (void)st;
    compare("[solver]\ntier = every\n[noise]\ntemperature = 300 K\ndetector = 50 fm/sqrt(Hz)\n");
}

static void every_cycle_continuous_piezo_noise(void **st)
{
    (void)st;
    compare("[solver]\ntier = every\n[scan]\nlines_mode = continuous\n"
            "[noise]\nz_piezo = 1 pm/sqrt(Hz)\ntemperature = 300 K\n");
}

static void envelope_continuous_noise(void **st)
{
    (void)st;
    compare("[solver]\ntier = envelope\n[scan]\nlines_mode = continuous\n"
            "[noise]\ntemperature = 300 K\n");
}

static void envelope_independent(void **st)
{
    (void)st;
    compare("[solver]\ntier = envelope\n");
}

static void averaged_continuous(void **st)
{
    (void)st;
    compare("[solver]\ntier = averaged\n[scan]\nlines_mode = continuous\n");
}

/* A continuous scan without retrace images still runs (and records) the retrace: the
 * next line starts where it ended. */
static void continuous_records_unrecorded_retrace(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = make("[solver]\ntier = averaged\n[scan]\nlines_mode = continuous\nretrace = no\n", &sc);
    tt_scan_scope *r;
    assert_int_equal(tt_scan_scope_alloc(&r), TT_OK);
    assert_int_equal(tt_scan_step(s, 0, r), TT_OK);
    assert_null(tt_scan_image(s, 0, 1));
    assert_true(tt_scan_scope_points(r, 1) > 0);
    /* the retrace's clock is the second half of the line's period */
    const double *t = tt_scan_scope_series(r, 1, TT_SCOPE_TIME);
    assert_true(t[0] > 0.5 / 40 && t[tt_scan_scope_points(r, 1) - 1] <= 1.0 / 40 + 1e-12);
    /* a line out of range is refused */
    assert_int_equal(tt_scan_step(s, 4, r), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "lines are 0 to 3"));
    tt_scan_scope_free(r);
    tt_scan_free(s);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_cycle_independent_noise),
        cmocka_unit_test(every_cycle_continuous_piezo_noise),
        cmocka_unit_test(envelope_continuous_noise),
        cmocka_unit_test(envelope_independent),
        cmocka_unit_test(averaged_continuous),
        cmocka_unit_test(continuous_records_unrecorded_retrace),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
