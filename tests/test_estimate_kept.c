/* The error estimate's companion where the scan asks for fewer channels than it compares
 * (tt_scan_kept_channels): on independent lines of the noisy viscoelastic blend (the
 * whole hardest line runs), a scan without the error channel gives the same estimate,
 * to the bit, as one with it, from the tight line alone (half the companion's cycles:
 * before, the run's setting ran the line again beside it), and does not show the
 * channel it kept; the estimate in parts (tt_scan_estimate_plan, _job, _finish), its
 * lines in reverse order, is tt_scan_estimate_error's. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"

static const char *base = TT_TEST_BLEND
    "[scan]\nsize = 1 um\npixels = 16\nlines = 3\nline_rate = 8 Hz\nprofile_line = 1\n"
    "[feedback]\nsetpoint = 80 %\n[solver]\ntolerance = 3e-8\n"
    "[noise]\nseed = 3\ntemperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n";

static void assert_same_estimate(const tt_scan_error *a, const tt_scan_error *b)
{
    assert_true(a->height_max == b->height_max && a->height_rms == b->height_rms);
    assert_true(a->amplitude_max == b->amplitude_max && a->amplitude_rms == b->amplitude_rms);
    assert_true(a->phase_max == b->phase_max && a->phase_rms == b->phase_rms);
    assert_int_equal(a->line, b->line);
    assert_int_equal(a->pixels, b->pixels);
    assert_int_equal(a->stretches, b->stretches);
}

static void kept_error_channel(void **st)
{
    (void)st;
    tt_scene *sa, *sb;
    tt_scan *a = tt_run_scan(base, "[scan]\nchannels = height, phase, dissipation\n", &sa);
    tt_scan *b = tt_run_scan(base, "[scan]\nchannels = height, error, phase, dissipation\n", &sb);
    tt_scan_error ea, eb;
    assert_int_equal(tt_scan_estimate_error(a, &ea), TT_OK);
    assert_int_equal(tt_scan_estimate_error(b, &eb), TT_OK);
    print_message("without error: height %.6g m, phase %.6g deg, amplitude %.6g, %ld cycles; "
                  "with: %.6g, %.6g, %.6g, %ld cycles\n", ea.height_max, ea.phase_max,
                  ea.amplitude_max, ea.cycles, eb.height_max, eb.phase_max, eb.amplitude_max,
                  eb.cycles);
    assert_true(ea.over && ea.height_max > 0 && ea.phase_max > 0 && ea.amplitude_max > 0);
    assert_same_estimate(&ea, &eb);
    assert_int_equal(ea.cycles, eb.cycles); /* the tight line alone */
    assert_null(tt_scan_image(a, 1, 0));
    assert_null(tt_scan_image(a, 1, 1));
    assert_non_null(tt_scan_image(b, 1, 0));
    tt_scan_free(a);
    tt_scan_free(b);
    tt_scene_free(sa);
    tt_scene_free(sb);
}

static void estimate_in_parts(void **st)
{
    (void)st;
    tt_scene *sc;
    /* continuous lines: the run's setting runs again beside the tight line, two jobs */
    tt_scan *s = tt_run_scan(base, "[scan]\nlines_mode = continuous\n", &sc);
    tt_scan_error whole, parts;
    assert_int_equal(tt_scan_estimate_error(s, &whole), TT_OK);
    tt_scan_estimate *E;
    assert_int_equal(tt_scan_estimate_plan(s, &E), TT_OK);
    const int n = tt_scan_estimate_jobs(E);
    assert_int_equal(n, 2 * whole.stretches);
    for (int j = n - 1; j >= 0; j--)
        assert_int_equal(tt_scan_estimate_job(E, j), TT_OK);
    assert_int_equal(tt_scan_estimate_finish(E, &parts), TT_OK);
    assert_same_estimate(&whole, &parts);
    assert_int_equal(whole.cycles, parts.cycles);
    tt_scan_free(s);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(kept_error_channel),
        cmocka_unit_test(estimate_in_parts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
