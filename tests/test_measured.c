/* Measured surfaces: GSF and GWY images cropped, levelled and interpolated against
 * hand-computed cases, and bad files refused in one line naming key, file and what is
 * expected (docs/surfaces.md, "Measured surfaces"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tt_gsf_test.h"
#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/io/gwy.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/util/error.h"

/* 4 x 3 pixels of 1 nm, heights in nm */
#define KEYS43 "XRes = 4\nYRes = 3\nXReal = 4\nYReal = 3\nXYUnits = nm\nZUnits = nm\n"

static tt_surface *make(const char *path, const char *keys, double sx, double sy, int expect_ok)
{
    char text[1024];
    snprintf(text, sizeof text, "[material a]\nyoungs_modulus = 1 GPa\n[surface]\ntype = measured\n"
                                "image = %s\n%s", path, keys);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "s.ini"), TT_OK);
    tt_surface *S = NULL;
    int rc = tt_config_surface_alloc(&S, s, sx, sy);
    tt_scene_free(s);
    if (expect_ok && rc)
        fail_msg("%s", tt_error_message());
    if (!expect_ok && !rc)
        fail_msg("accepted: %s %s", path, keys);
    return S;
}

/* The height at pixel (i, j)'s centre, in nm. */
static double at(const tt_surface *S, double i, double j)
{
    return tt_surface_height(S, (i + 0.5) * 1e-9, (j + 0.5) * 1e-9) * 1e9;
}

static const float plane[16] = {0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15}; /* z = 4 i + j */
#define KEYS44 "XRes = 4\nYRes = 4\nXReal = 4\nYReal = 4\nXYUnits = nm\nZUnits = nm\n"

static void resampling(void **st)
{
    (void)st;
    const char *p = gsf("plane44.gsf", KEYS44, plane, 16);
    for (int cubic = 0; cubic < 2; cubic++) {
        tt_surface *S = make(p, cubic ? "interpolation = bicubic\n" : "", 4e-9, 4e-9, 1);
        assert_close(at(S, 1, 1), 5, 1e-12);
        /* between the centres: the plane itself, which both interpolations keep */
        assert_close(at(S, 0.5, 0), 2, 1e-12);
        assert_close(at(S, 0.5, 0.5), 2.5, 1e-12);
        assert_close(at(S, 2.25, 1.75), 10.75, 1e-12);
        tt_surface_free(S);
    }
    /* bilinear between four pixels 0, 8 | 2, 10 at a quarter from the first: hand-computed */
    tt_surface *S = make(p, "", 4e-9, 4e-9, 1);
    assert_close(at(S, 0.25, 0.75), 0.75 * 0.25 * 0 + 0.25 * 0.25 * 4 + 0.75 * 0.75 * 1 + 0.25 * 0.75 * 5, 1e-12);
    tt_surface_free(S);
    /* one raised pixel: bilinear weighs it by the distances, bicubic passes through it
     * with continuous slopes, so differs between the centres */
    static const float spike[16] = {0, 0, 0, 0, 0, 8, 0, 0};
    const char *q = gsf("spike.gsf", KEYS44, spike, 16);
    S = make(q, "", 4e-9, 4e-9, 1);
    assert_close(at(S, 1.5, 1), 4, 1e-12);
    assert_close(at(S, 1.25, 1.25), 8 * 0.75 * 0.75, 1e-12);
    tt_surface_free(S);
    S = make(q, "interpolation = bicubic\n", 4e-9, 4e-9, 1);
    assert_close(at(S, 1, 1), 8, 1e-12);
    assert_close(at(S, 1.5, 1), 4.6, 1e-9); /* the overshoot docs/surfaces.md quotes */
    tt_surface_free(S);
    /* edges: clamped past the image, periodic across its seam */
    S = make(p, "edges = clamp\n", 8e-9, 4e-9, 1);
    assert_close(at(S, -5, 0), 0, 1e-12);
    assert_close(at(S, 100, 0), 12, 1e-12);
    tt_surface_free(S);
    S = make(p, "edges = periodic\n", 8e-9, 4e-9, 1);
    assert_close(at(S, 4, 0), 0, 1e-12);       /* pixel 0 again */
    assert_close(at(S, 3.5, 0), 6, 1e-12);     /* half-way from pixel 3 (12) to pixel 0 (0) */
    assert_close(at(S, 1, 4 + 1), 5, 1e-12);   /* and along y */
    assert_close(at(S, -4 + 1, -4 + 1), 5, 1e-12);
    tt_surface_free(S);
    /* crop and scale */
    S = make(p, "crop = 1 1 2 2\nz_scale = 2\nz_offset = 1 nm\n", 2e-9, 2e-9, 1);
    assert_close(at(S, 0, 0), 2 * 5 + 1, 1e-12);
    assert_close(at(S, 1, 1), 2 * 10 + 1, 1e-12);
    tt_surface_free(S);
}

static void levelling(void **st)
{
    (void)st;
    const char *p = gsf("plane.gsf", KEYS43, plane, 12);
    tt_surface *S = make(p, "level = plane\n", 4e-9, 3e-9, 1);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 4; i++)
            assert_close(at(S, i, j), 0, 1e-12);
    tt_surface_free(S);
    S = make(p, "level = offset\n", 4e-9, 3e-9, 1);
    assert_close(at(S, 0, 0), -7, 1e-12); /* the mean, 7 nm, taken off */
    assert_close(at(S, 3, 2), 7, 1e-12);
    tt_surface_free(S);
    /* rows: 1 2 4 9 | 1 5 2 9 | 1 2 3 10 */
    static const float rows[12] = {1, 2, 4, 9, 1, 5, 2, 9, 1, 2, 3, 10};
    p = gsf("rows.gsf", KEYS43, rows, 12);
    S = make(p, "line_level = offset\n", 4e-9, 3e-9, 1);
    const double off[4] = {-3, -2, -1, 6}; /* row 2 less its mean 4 */
    for (int i = 0; i < 4; i++)
        assert_close(at(S, i, 2), off[i], 1e-12);
    tt_surface_free(S);
    S = make(p, "line_level = slope\n", 4e-9, 3e-9, 1);
    /* row 0: mean 4, slope sum((i - 1.5) z) / 5 = 2.6 a pixel */
    const double slope[4] = {0.9, -0.7, -1.3, 1.1};
    for (int i = 0; i < 4; i++)
        assert_close(at(S, i, 0), slope[i], 1e-12);
    tt_surface_free(S);
    S = make(p, "line_level = median\n", 4e-9, 3e-9, 1);
    const double med[4] = {-2.5, 1.5, -1.5, 5.5}; /* row 1 less (2 + 5) / 2 */
    for (int i = 0; i < 4; i++)
        assert_close(at(S, i, 1), med[i], 1e-12);
    tt_surface_free(S);
    /* median of differences: 0 0 0 0 | 1 1 1 5 | 2 2 8 2: row 1 steps 1 up (median of
     * 1 1 1 5), row 2 then 2 above the shifted row 1 (median of 2 2 8 -2) */
    static const float steps[12] = {0, 0, 0, 0, 1, 1, 1, 5, 2, 2, 8, 2};
    p = gsf("steps.gsf", KEYS43, steps, 12);
    S = make(p, "line_level = median_difference\n", 4e-9, 3e-9, 1);
    const double md[12] = {0, 0, 0, 0, 0, 0, 0, 4, 0, 0, 6, 0};
    for (int k = 0; k < 12; k++)
        assert_close(at(S, k % 4, k / 4), md[k], 1e-12);
    tt_surface_free(S);
    /* plane, then rows: a tilted plane with one row lifted comes out flat */
    static const float lifted[12] = {0, 4, 8, 12, 4, 8, 12, 16, 2, 6, 10, 14};
    p = gsf("lifted.gsf", KEYS43, lifted, 12);
    S = make(p, "level = plane\nline_level = median_difference\n", 4e-9, 3e-9, 1);
    for (int k = 0; k < 12; k++)
        assert_close(at(S, k % 4, k / 4) - at(S, 0, 0), 0, 1e-12);
    tt_surface_free(S);
}

/* A refusal: one line, naming the key, the file and the words expected. */
static void refused(const char *path, const char *keys, double sx, const char *key, const char *what)
{
    make(path, keys, sx, 3e-9, 0);
    const char *m = tt_error_message();
    if (!strstr(m, key) || !strstr(m, path) || !strstr(m, what) || strchr(m, '\n'))
        fail_msg("refusal '%s' lacks '%s', '%s' or '%s', or is not one line", m, key, path, what);
}

static void bad_files(void **st)
{
    (void)st;
    float nan12[12];
    memcpy(nan12, plane, sizeof nan12);
    nan12[6] = NAN;
    refused(gsf("nounits.gsf", "XRes = 4\nYRes = 3\nXReal = 4\nYReal = 3\nXYUnits = nm\n", plane, 12),
            "", 4e-9, "[surface] image", "no ZUnits in the GSF header; expected a length unit");
    refused(gsf("nolateral.gsf", "XRes = 4\nYRes = 3\nXReal = 4\nYReal = 3\nZUnits = nm\n", plane, 12),
            "", 4e-9, "[surface] image", "no XYUnits");
    refused(gsf("volts.gsf", "XRes = 4\nYRes = 3\nXReal = 4\nYReal = 3\nXYUnits = nm\nZUnits = V\n", plane, 12),
            "", 4e-9, "[surface] image", "ZUnits = V; expected a length unit");
    refused(gsf("zerosize.gsf", "XRes = 4\nYRes = 3\nXReal = 0\nYReal = 3\nXYUnits = nm\nZUnits = nm\n", plane, 12),
            "", 4e-9, "[surface] image", "XReal = 0; expected a size above 0");
    refused(gsf("zeropixels.gsf", "XRes = 0\nYRes = 3\nXReal = 4\nYReal = 3\nXYUnits = nm\nZUnits = nm\n", plane, 12),
            "", 4e-9, "[surface] image", "XRes = 0; expected a number of pixels");
    refused(gsf("absurd.gsf", "XRes = 4\nYRes = 3\nXReal = 4\nYReal = 3\nXYUnits = m\nZUnits = nm\n", plane, 12),
            "", 4e-9, "[surface] image", "expected 1 pm to 1 mm a pixel");
    refused(gsf("nan.gsf", KEYS43, nan12, 12), "", 4e-9, "[surface] image", "pixel (2, 1) is nan");
    refused(gsf("truncated.gsf", KEYS43, plane, 7), "", 4e-9, "[surface] image",
            "truncated: 28 bytes of data, 4 x 3 pixels need 48");
    refused(gsf("plane.gsf", KEYS43, plane, 12), "", 8e-9, "[surface] edges",
            "covers 4 x 3 nm");
    refused(gsf("plane.gsf", KEYS43, plane, 12), "crop = 3 0 2 2\n", 4e-9, "[surface] crop",
            "within the image's 4 x 3 pixels");
    /* .gwy: tiptap's own, then cut short */
    double h[12], ph[12];
    for (int k = 0; k < 12; k++) {
        h[k] = plane[k] * 1e-9;
        ph[k] = 10;
    }
    tt_gwy_channel ch[2] = {{"Height", 4, 3, 4e-9, 3e-9, 0, 0, "m", "m", h},
                            {"Phase", 4, 3, 4e-9, 3e-9, 0, 0, "m", "deg", ph}};
    char gwy[128];
    snprintf(gwy, sizeof gwy, "%s/two.gwy", dir);
    assert_int_equal(tt_gwy_write(gwy, ch, 2, NULL, NULL, 0), TT_OK);
    tt_surface *S = make(gwy, "channel = Height\n", 4e-9, 3e-9, 1);
    assert_close(at(S, 1, 1), 5, 1e-9);
    tt_surface_free(S);
    S = make(gwy, "channel = 0\n", 4e-9, 3e-9, 1);
    assert_close(at(S, 2, 2), 10, 1e-9);
    tt_surface_free(S);
    refused(gwy, "channel = Amplitude\n", 4e-9, "[surface] image", "no channel 'Amplitude'; expected a title "
            "or number of those it holds: 0 'Height', 1 'Phase'");
    refused(gwy, "channel = 7\n", 4e-9, "[surface] image", "no channel '7'");
    refused(gwy, "channel = Phase\n", 4e-9, "[surface] image", "in 'm' across and 'deg' high; expected lengths");
    FILE *f = fopen(gwy, "r+b");
    assert_non_null(f);
    assert_int_equal(ftruncate(fileno(f), 200), 0);
    fclose(f);
    refused(gwy, "channel = Height\n", 4e-9, "[surface] image", "not a GWY file of data fields, or damaged or truncated");
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/tt-measured-XXXXXX");
    if (!mkdtemp(dir))
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(resampling),
        cmocka_unit_test(levelling),
        cmocka_unit_test(bad_files),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        rc = 1;
    return rc;
}
