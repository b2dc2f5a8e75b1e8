/* Scans for tests: run one on a scene base plus extra text, or expect one refused. */
#ifndef TT_SCAN_TEST_H
#define TT_SCAN_TEST_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/scan.h"

/* The scan of base plus extra, made but not run; *sc receives the scene (the caller
 * frees both). */
static inline tt_scan *tt_make_scan(const char *base, const char *extra, tt_scene **sc)
{
    *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(*sc, base, "base"), TT_OK);
    if (tt_scene_load_string(*sc, extra, "extra") != TT_OK)
        fail_msg("%s", tt_error_message());
    tt_scan *s;
    if (tt_config_scan_alloc(&s, *sc) != TT_OK)
        fail_msg("%s", tt_error_message());
    return s;
}

/* The scan of base plus extra, run on two threads; *sc receives the scene (the caller
 * frees both). */
static inline tt_scan *tt_run_scan(const char *base, const char *extra, tt_scene **sc)
{
    tt_scan *s = tt_make_scan(base, extra, sc);
    if (tt_scan_run(s, 2, NULL, NULL) != TT_OK)
        fail_msg("%s", tt_error_message());
    return s;
}

/* The scan of base plus extra on [solver] tier, run on two threads. */
static inline tt_scan *tt_run_scan_on(const char *base, const char *extra, const char *tier, tt_scene **sc)
{
    char text[4096];
    snprintf(text, sizeof text, "%s\n[solver]\ntier = %s\n", extra, tier);
    return tt_run_scan(base, text, sc);
}

/* Largest and rms difference of channel c between two scans, trace and retrace. */
static inline void tt_scan_diff(const tt_scan *a, const tt_scan *b, int c, double *max, double *rms)
{
    long n = tt_scan_xres(a) * tt_scan_yres(a);
    double m = 0, s = 0;
    for (int r = 0; r < 2; r++) {
        const double *x = tt_scan_image(a, c, r), *y = tt_scan_image(b, c, r);
        for (long i = 0; i < n; i++) {
            double d = fabs(x[i] - y[i]);
            m = d > m ? d : m;
            s += d * d;
        }
    }
    *max = m;
    *rms = sqrt(s / (double)(2 * n));
}

/* Channels 0 .. channels-1 of two scans are the same, bit for bit, trace and retrace. */
static inline void tt_scan_assert_identical(const tt_scan *a, const tt_scan *b, int channels)
{
    long n = tt_scan_xres(a) * tt_scan_yres(a);
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < channels; c++)
            assert_memory_equal(tt_scan_image(a, c, r), tt_scan_image(b, c, r),
                                (size_t)n * sizeof(double));
}

/* The scan of base plus extra run on one thread and on two: channels 0 .. channels-1 the
 * same bit for bit; with reduced, the one-thread run integrated fewer cycles than it
 * ran (the reduced tier, not a fallback to every cycle, made the images). */
static inline void tt_scan_assert_threads_agree(const char *base, const char *extra, int channels,
                                                int reduced)
{
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    assert_int_equal(tt_scene_load_string(sc, extra, "extra"), TT_OK);
    tt_scan *a, *b;
    assert_int_equal(tt_config_scan_alloc(&a, sc), TT_OK);
    assert_int_equal(tt_config_scan_alloc(&b, sc), TT_OK);
    assert_int_equal(tt_scan_run(a, 1, NULL, NULL), TT_OK);
    assert_int_equal(tt_scan_run(b, 2, NULL, NULL), TT_OK);
    if (reduced)
        assert_true(tt_scan_cycles_integrated(a) < tt_scan_cycles(a));
    tt_scan_assert_identical(a, b, channels);
    tt_scan_free(a);
    tt_scan_free(b);
    tt_scene_free(sc);
}

/* The surface of a scene's text over a square of side size (the caller frees it). */
static inline tt_surface *tt_make_surface(const char *text, double size)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "s.ini"), TT_OK);
    tt_surface *S = NULL;
    if (tt_config_surface_alloc(&S, s, size, size) != TT_OK)
        fail_msg("%s", tt_error_message());
    tt_scene_free(s);
    return S;
}

/* The scene base plus text must be refused, by the loader or by tt_scan_alloc, with a
 * message containing fragment. */
static inline void tt_expect_scan_refused(const char *base, const char *text, const char *fragment)
{
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    int rc = tt_scene_load_string(sc, text, "bad.ini");
    tt_scan *s = NULL;
    if (rc == TT_OK)
        rc = tt_config_scan_alloc(&s, sc);
    if (rc == TT_OK)
        fail_msg("accepted: %s", text);
    assert_message_has(fragment);
    tt_scene_free(sc);
}

/* The viscoelastic blend of examples/viscoelastic-blend (domains of 300 Pa s in an
 * elastic matrix, both 1 GPa) under the standard cantilever: a scene's text up to its
 * [scan] section. */
#define TT_TEST_BLEND                                                                      \
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\n"                \
    "quality_factor = 400\nfree_amplitude = 20 nm\n"                                        \
    "[material matrix]\nyoungs_modulus = 1 GPa\npoisson_ratio = 0.4\n"                     \
    "[material domain]\nyoungs_modulus = 1 GPa\npoisson_ratio = 0.4\nviscosity = 300 Pa s\n" \
    "[surface]\ntype = flat\nmap = disks\nmap_materials = matrix, domain\n"                 \
    "map_period = 500 nm\nmap_radius = 150 nm\n"

#endif
