/* The full-rate record of a line (the scope) is what the pixels average: a pixel's
 * error and phase are the means of its points exactly, its height the mean of the z
 * command that ramps between them; the points come at the lock-in block's rate on the
 * instrument's clock, on every tier. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/util/error.h"

/* A fast cantilever (Q 100) over 4 nm steps; line 1 of 3 recorded. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 16\nlines = 3\nline_rate = 40 Hz\nsettle_cycles = 1000\n"
    "channels = height, error, phase, topography, amplitude\n"
    "[lockin]\nperiods_per_block = 4\n"
    "[surface]\ntype = steps\nstep_height = 4 nm\nstep_width = 300 nm\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

enum { PX = 16 };

static void record_agrees_with_pixels(const char *extra)
{
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    assert_int_equal(tt_scene_load_string(sc, extra, "extra"), TT_OK);
    tt_scan *s;
    if (tt_config_scan_alloc(&s, sc) != TT_OK)
        fail_msg("%s", tt_error_message());
    tt_scan_scope *r;
    assert_int_equal(tt_scan_scope_alloc(&r), TT_OK);
    assert_int_equal(tt_scan_scope_line(r), -1);
    assert_int_equal(tt_scan_step(s, 1, r), TT_OK);
    assert_int_equal(tt_scan_scope_line(r), 1);
    /* the loop's rate: 300 kHz / 4 periods a block; 3750 cycles each way */
    assert_close(tt_scan_scope_rate(r), 75e3, 1e-6);
    for (int dir = 0; dir < 2; dir++) {
        long n = tt_scan_scope_points(r, dir);
        assert_int_equal(n, (3750 + 3) / 4);
        const double *t = tt_scan_scope_series(r, dir, TT_SCOPE_TIME),
                     *z = tt_scan_scope_series(r, dir, TT_SCOPE_Z),
                     *e = tt_scan_scope_series(r, dir, TT_SCOPE_ERROR),
                     *a = tt_scan_scope_series(r, dir, TT_SCOPE_AMPLITUDE),
                     *ph = tt_scan_scope_series(r, dir, TT_SCOPE_PHASE),
                     *hs = tt_scan_scope_series(r, dir, TT_SCOPE_SURFACE),
                     *pix = tt_scan_scope_series(r, dir, TT_SCOPE_PIXEL),
                     *x = tt_scan_scope_series(r, dir, TT_SCOPE_POSITION);
        /* line 1 of a 40 Hz raster: trace from 25 ms to 37.5 ms, retrace to 50 ms;
         * a point each block (4 / 300 kHz), the last block shorter (3750 = 937 x 4 + 2) */
        double t0 = 1 / 40.0 + dir * 0.5 / 40;
        for (long i = 0; i < n; i++) {
            long k = (i + 1) * 4 < 3750 ? (i + 1) * 4 : 3750;
            assert_close(t[i], t0 + k / 300e3, 1e-12);
            assert_close(x[i], dir ? 1e-6 * (1 - k / 3750.0) : 1e-6 * k / 3750.0, 1e-15);
            assert_close(e[i], a[i] - 16e-9, 1e-20);
        }
        double height[PX], err[PX], phase[PX], topo[PX], amp[PX];
        assert_int_equal(tt_scan_line_values(s, 0, dir, 1, height), TT_OK);
        assert_int_equal(tt_scan_line_values(s, 1, dir, 1, err), TT_OK);
        assert_int_equal(tt_scan_line_values(s, 2, dir, 1, phase), TT_OK);
        assert_int_equal(tt_scan_line_values(s, 6, dir, 1, topo), TT_OK);
        assert_int_equal(tt_scan_line_values(s, 7, dir, 1, amp), TT_OK);
        for (int p = 0; p < PX; p++) {
            double sa = 0, se = 0, sp = 0, sz = 0, sh = 0, dz = 0;
            long m = 0;
            for (long i = 0; i < n; i++) {
                if (pix[i] != p)
                    continue;
                se += e[i];
                sa += a[i];
                sp += ph[i];
                sz += z[i];
                sh += hs[i];
                if (i > 0)
                    dz = fmax(dz, fabs(z[i] - z[i - 1]));
                m++;
            }
            assert_true(m >= 58); /* 234 or 235 cycles a pixel, a point each 4 */
            /* the lock-in's channels: the means of the pixel's points */
            assert_close(err[p], se / m, 1e-21);
            assert_close(amp[p], sa / m, 1e-21);
            assert_close(amp[p] - err[p], 16e-9, 1e-20); /* the error is amplitude - setpoint */
            assert_close(phase[p], sp / m, 1e-11);
            /* the height: the mean of the command, which ramps between the points: off
             * their mean by at most one block's move */
            assert_close(height[p], sz / m, dz + 1e-15);
            /* the surface, sampled at the blocks' ends against every cycle's */
            assert_close(topo[p], sh / m, 4e-9 * 5.0 / m);
        }
    }
    tt_scan_scope_free(r);
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void every_cycle(void **st)
{
    (void)st;
    record_agrees_with_pixels("[solver]\ntier = every\n");
}

static void envelope_with_noise(void **st)
{
    (void)st;
    record_agrees_with_pixels("[solver]\ntier = envelope\n[noise]\ntemperature = 300 K\n");
}

static void averaged_continuous(void **st)
{
    (void)st;
    record_agrees_with_pixels("[solver]\ntier = averaged\n[scan]\nlines_mode = continuous\n");
}

/* A scope is refilled line by line, growing for a slower line. */
static void scope_follows_the_line_rate(void **st)
{
    (void)st;
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    assert_int_equal(tt_scene_load_string(sc, "[solver]\ntier = averaged\n", "extra"), TT_OK);
    tt_scan *s;
    assert_int_equal(tt_config_scan_alloc(&s, sc), TT_OK);
    tt_scan_scope *r;
    assert_int_equal(tt_scan_scope_alloc(&r), TT_OK);
    assert_int_equal(tt_scan_step(s, 0, r), TT_OK);
    assert_int_equal(tt_scan_scope_points(r, 0), 938);
    assert_int_equal(tt_scan_set_line_rate(s, 20), TT_OK);
    assert_int_equal(tt_scan_step(s, 2, r), TT_OK);
    assert_int_equal(tt_scan_scope_line(r), 2);
    assert_int_equal(tt_scan_scope_points(r, 1), 1875);
    assert_close(tt_scan_scope_series(r, 1, TT_SCOPE_TIME)[1874], 3 / 20.0, 1e-12);
    assert_null(tt_scan_scope_series(r, 2, TT_SCOPE_Z));
    assert_null(tt_scan_scope_series(r, 0, TT_SCOPE_COUNT));
    tt_scan_scope_free(r);
    tt_scan_free(s);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_cycle),
        cmocka_unit_test(envelope_with_noise),
        cmocka_unit_test(averaged_continuous),
        cmocka_unit_test(scope_follows_the_line_rate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
