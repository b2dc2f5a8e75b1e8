/* Material maps from data: a label image whose labels are materials' map_values, and a
 * phase channel split at a threshold, taken pixel by pixel (never interpolated); bad
 * images and keys refused in one line (docs/surfaces.md, "Material maps from data"). */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tt_gsf_test.h"
#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/io/gwy.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/util/error.h"

/* Materials a (map_value 0), b (1), c (7), then the [surface] keys given. */
static tt_surface *make(const char *keys, double sx, double sy, int expect_ok)
{
    char text[2048];
    snprintf(text, sizeof text, "[material a]\nyoungs_modulus = 1 GPa\nmap_value = 0\n"
                                "[material b]\nyoungs_modulus = 2 GPa\nmap_value = 1\n"
                                "[material c]\nyoungs_modulus = 3 GPa\nmap_value = 7\n[surface]\n%s", keys);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "s.ini"), TT_OK);
    tt_surface *S = NULL;
    int rc = tt_config_surface_alloc(&S, s, sx, sy);
    tt_scene_free(s);
    if (expect_ok && rc)
        fail_msg("%s", tt_error_message());
    if (!expect_ok && !rc)
        fail_msg("accepted: %s", keys);
    return S;
}

/* The material at (x, y) in nm. */
static int mat(const tt_surface *S, double x, double y) { return tt_surface_material(S, x * 1e-9, y * 1e-9); }

/* 4 x 2 pixels of 10 nm:  0 0 1 7
 *                         1 0 0 0   */
static const float labels42[8] = {0, 0, 1, 7, 1, 0, 0, 0};
#define KEYS42 "XRes = 4\nYRes = 2\nXReal = 40\nYReal = 20\nXYUnits = nm\n"

static void two_labels(void **st)
{
    (void)st;
    char keys[512];
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\n", gsf("l.gsf", KEYS42, labels42, 8));
    tt_surface *S = make(keys, 40e-9, 20e-9, 1);
    /* each pixel's centre: the material its label names */
    for (int k = 0; k < 8; k++) {
        int want = labels42[k] == 0 ? 0 : labels42[k] == 1 ? 1 : 2;
        assert_int_equal(mat(S, (k % 4 + 0.5) * 10, (k / 4 + 0.5) * 10), want);
    }
    /* nearest neighbour, no blending: either side of the edge at x = 20 nm on row 0 */
    assert_int_equal(mat(S, 19.99, 5), 0);
    assert_int_equal(mat(S, 20.01, 5), 1);
    assert_int_equal(mat(S, 29.99, 9.99), 1);
    assert_int_equal(mat(S, 30.01, 10.01), 0);
    assert_false(tt_surface_uniform(S));
    tt_surface_free(S);
}

/* A phase image in degrees, 3 x 2 pixels of 5 nm; 60 deg splits it. */
static const float phase32[6] = {30, 59.9f, 60, 80, 45, 90};

/* Below 60 deg: c (2); at or above: b (1); checked at each pixel's centre, then freed. */
static void phase_domains(tt_surface *S)
{
    const int want[6] = {2, 2, 1, 1, 2, 1};
    for (int k = 0; k < 6; k++)
        assert_int_equal(mat(S, (k % 3 + 0.5) * 5, (k / 3 + 0.5) * 5), want[k]);
    tt_surface_free(S);
}

static void thresholds(void **st)
{
    (void)st;
    char keys[512];
    const char *p = gsf("phase.gsf", "XRes = 3\nYRes = 2\nXReal = 15\nYReal = 10\nXYUnits = nm\nZUnits = deg\n",
                        phase32, 6);
    snprintf(keys, sizeof keys, "map = threshold\nmap_image = %s\nmap_threshold = 60 deg\nmap_materials = c, b\n", p);
    tt_surface *S = make(keys, 15e-9, 10e-9, 1);
    phase_domains(S);

    /* a .gwy channel chosen by title, tiptap's own writer */
    double z[6];
    for (int k = 0; k < 6; k++)
        z[k] = phase32[k];
    tt_gwy_channel ch[2] = {{"Height", 3, 2, 15e-9, 10e-9, 0, 0, "m", "m", z},
                            {"Phase", 3, 2, 15e-9, 10e-9, 0, 0, "m", "deg", z}};
    char gwy[128];
    snprintf(gwy, sizeof gwy, "%s/phase.gwy", dir);
    assert_int_equal(tt_gwy_write(gwy, ch, 2, NULL, NULL, 0), TT_OK);
    snprintf(keys, sizeof keys, "map = threshold\nmap_image = %s\nmap_channel = Phase\nmap_threshold = 60 deg\n"
                                "map_materials = c, b\n", gwy);
    S = make(keys, 15e-9, 10e-9, 1);
    phase_domains(S);
    /* a length threshold compares across prefixes: the Height channel holds 30 to 90 m,
     * which 60000 mm splits as 60 deg splits the phase */
    snprintf(keys, sizeof keys, "map = threshold\nmap_image = %s\nmap_channel = Height\nmap_threshold = 60000 mm\n"
                                "map_materials = c, b\n", gwy);
    S = make(keys, 15e-9, 10e-9, 1);
    phase_domains(S);
}

/* Edges as a measured image's: a smaller image is refused unless clamped or periodic. */
static void edges(void **st)
{
    (void)st;
    char keys[512];
    const char *p = gsf("l.gsf", KEYS42, labels42, 8);
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\nedges = periodic\n", p);
    tt_surface *S = make(keys, 100e-9, 100e-9, 1);
    assert_int_equal(mat(S, 45, 5), mat(S, 5, 5));
    assert_int_equal(mat(S, 65, 25), 1); /* pixel (2, 0) again */
    assert_int_equal(mat(S, 5, 35), 1);  /* pixel (0, 1) again */
    tt_surface_free(S);
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\nedges = clamp\n", p);
    S = make(keys, 100e-9, 100e-9, 1);
    assert_int_equal(mat(S, 95, 5), 2);  /* the last column, label 7, continued */
    assert_int_equal(mat(S, 5, 95), 1);  /* the last row's first pixel, label 1 */
    tt_surface_free(S);
}

static void refused(const char *keys, double sx, double sy, const char *key, const char *what)
{
    make(keys, sx, sy, 0);
    const char *m = tt_error_message();
    if (!strstr(m, key) || !strstr(m, what) || strchr(m, '\n'))
        fail_msg("refusal '%s' lacks '%s' or '%s', or is not one line", m, key, what);
}

/* A w x h 8-bit PNG of colour type type, every row the same row. */
static const char *png_file(const char *name, int w, int h, int type, const unsigned char *row)
{
    static char path[128];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    assert_false(setjmp(png_jmpbuf(png)));
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, 8, type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int j = 0; j < h; j++)
        png_write_row(png, row);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
    return path;
}

/* A w x h grey PNG of level 0 everywhere (w at most 64). */
static const char *grey_png(const char *name, int w, int h)
{
    static const unsigned char zeros[64];
    return png_file(name, w, h, PNG_COLOR_TYPE_GRAY, zeros);
}

static void refusals(void **st)
{
    (void)st;
    char keys[512];
    float l2[8], half[8];
    memcpy(l2, labels42, sizeof l2);
    memcpy(half, labels42, sizeof half);
    l2[5] = 2;
    half[6] = 0.5f;
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\n", gsf("l2.gsf", KEYS42, l2, 8));
    refused(keys, 40e-9, 20e-9, "[surface] map_image", "pixel (1, 1) has label 2, which no [material] map_value names");
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\n", gsf("half.gsf", KEYS42, half, 8));
    refused(keys, 40e-9, 20e-9, "[surface] map_image", "pixel (2, 1) is 0.5; a label image holds whole numbers");
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\n", gsf("l.gsf", KEYS42, labels42, 8));
    refused(keys, 50e-9, 20e-9, "[surface] edges", "covers 40 x 20 nm");
    refused("map = labels\n", 40e-9, 20e-9, "[surface] map", "labels needs [surface] map_image");
    const char *p = gsf("phase.gsf", "XRes = 3\nYRes = 2\nXReal = 15\nYReal = 10\nXYUnits = nm\nZUnits = deg\n",
                        phase32, 6);
    snprintf(keys, sizeof keys, "map = threshold\nmap_image = %s\nmap_threshold = 1 rad\n", p);
    refused(keys, 15e-9, 10e-9, "[surface] map_threshold", "1 rad, but");
    snprintf(keys, sizeof keys, "map = threshold\nmap_image = %s\nmap_threshold = 1 nm\n", p);
    refused(keys, 15e-9, 10e-9, "[surface] map_threshold", "is in 'deg'; expected a threshold in the image's unit");
    snprintf(keys, sizeof keys, "map = threshold\nmap_image = %s\nmap_threshold = sixty\n", p);
    refused(keys, 15e-9, 10e-9, "[surface] map_threshold", "expected a number and the image's unit");
    snprintf(keys, sizeof keys, "map = threshold\nmap_image = %s\nmap_threshold = 60 deg\nmap_materials = a, z\n", p);
    refused(keys, 15e-9, 10e-9, "[surface] map_materials", "no [material z]");
    /* a PNG without a pixel size spans the area only when its pixels stay square */
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\n", grey_png("g.png", 4, 2));
    refused(keys, 40e-9, 40e-9, "[surface] map_pixel_size", "would stretch them 2:1");
    tt_surface *S = make(keys, 40e-9, 20e-9, 1);
    assert_int_equal(mat(S, 35, 15), 0);
    tt_surface_free(S);
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\nmap_pixel_size = 10 nm\n", grey_png("g.png", 4, 2));
    refused(keys, 40e-9, 40e-9, "[surface] edges", "covers 40 x 20 nm");
    static const unsigned char red[6] = {255, 0, 0, 255, 0, 0};
    snprintf(keys, sizeof keys, "map = labels\nmap_image = %s\n", png_file("red.png", 2, 1, PNG_COLOR_TYPE_RGB, red));
    make(keys, 20e-9, 10e-9, 0);
    assert_non_null(strstr(tt_error_message(), "s.ini: [surface] map_image: "));
    assert_non_null(strstr(tt_error_message(), "pixel (0, 0) has colour (255, 0, 0); a label or threshold image is grey"));
    /* and as a measured height image: the section named once */
    snprintf(keys, sizeof keys, "type = measured\nimage = %s/red.png\npixel_size = 1 nm\npng_height_range = 1 nm\n", dir);
    make(keys, 2e-9, 1e-9, 0);
    assert_non_null(strstr(tt_error_message(), "s.ini: [surface] image: "));
    assert_null(strstr(tt_error_message(), "[surface] [surface]"));
}

/* A 4 x 1 RGB PNG map: red, an anti-aliased red, a purple midway to blue, blue. */
static const char *rgb_png(void)
{
    static const unsigned char row[12] = {255, 0, 0, 240, 10, 10, 128, 0, 128, 0, 0, 255};
    return png_file("aa.png", 4, 1, PNG_COLOR_TYPE_RGB, row);
}

/* map = png with map_tolerance: an anti-aliased pixel takes the nearest named colour
 * within it (8-bit levels, Euclidean), ties the first material; beyond it, refused. */
static void nearest_colour(void **st)
{
    (void)st;
    const char *path = rgb_png();
    for (int t = 0; t < 4; t++) {
        static const char *const tol[] = {"0", "20", "25", "200"};
        char text[1024];
        snprintf(text, sizeof text, "[material a]\nmap_value = #ff0000\n[material b]\nmap_value = #0000ff\n"
                                    "[surface]\nmap = png\nmap_png = %s\nmap_tolerance = %s\n", path, tol[t]);
        tt_scene *s = tt_scene_alloc();
        assert_int_equal(tt_scene_load_string(s, text, "s.ini"), TT_OK);
        tt_surface *S = NULL;
        int rc = tt_config_surface_alloc(&S, s, 4e-9, 1e-9);
        tt_scene_free(s);
        if (t < 2) {
            /* (240, 10, 10) is 20.6 levels from red */
            assert_int_not_equal(rc, TT_OK);
            assert_non_null(strstr(tt_error_message(), "pixel (1, 0) has colour #f00a0a, which no [material] map_value names"));
            assert_true(t == 0 || strstr(tt_error_message(), "within [surface] map_tolerance = 20 levels"));
            continue;
        }
        if (t == 2) {
            /* the purple is 180.3 levels from both */
            assert_int_not_equal(rc, TT_OK);
            assert_non_null(strstr(tt_error_message(), "pixel (2, 0) has colour #800080"));
            continue;
        }
        assert_int_equal(rc, TT_OK);
        const int want[4] = {0, 0, 0, 1};
        for (int i = 0; i < 4; i++)
            assert_int_equal(mat(S, i + 0.5, 0.5), want[i]);
        tt_surface_free(S);
    }
}

int main(void)
{
    snprintf(dir, sizeof dir, "/tmp/tt-labels-XXXXXX");
    if (!mkdtemp(dir))
        return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(two_labels),
        cmocka_unit_test(thresholds),
        cmocka_unit_test(edges),
        cmocka_unit_test(refusals),
        cmocka_unit_test(nearest_colour),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        rc = 1;
    return rc;
}
