/* Villarrubia's erosion and certainty map (erosion.h) on a synthetic surface of steps
 * and a pillar dilated by a known sphere tip, and the measured surface's
 * measured_tip_shape keys that erode a scene's image (docs/surfaces.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/erosion.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/util/error.h"

#define W 96
#define H 64
#define PX 1e-9
/* rounding of s - t + t: the heights are nm, compared to 1e-6 nm */
#define EPS 1e-15

/* Two 6 nm steps up along x (at 40 and 64 px) and a 10 nm pillar of radius 6 px at
 * (18, 32) on the lowest terrace, in m. */
static void surface(double *s)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double z = (x >= 40 ? 6e-9 : 0) + (x >= 64 ? 6e-9 : 0);
            if (hypot(x - 18, y - 32) <= 6)
                z = 10e-9;
            s[y * W + x] = z;
        }
}

static tt_tip_image sphere_tip(double radius, double dh)
{
    tt_tip_shape t = {TT_TIP_SPHERE, radius, 0};
    tt_tip_image ti;
    assert_int_equal(tt_tip_image_make(&ti, &t, PX, PX, dh), TT_OK);
    return ti;
}

/* The reconstruction never falls below the true surface (it is an upper bound), is the
 * true surface where the certainty map is set, and lies below the image where the tip
 * broadened it. */
static void reconstruction(void **st)
{
    (void)st;
    static double s[W * H], im[W * H], r[W * H];
    static unsigned char c[W * H];
    surface(s);
    tt_tip_image tip = sphere_tip(8e-9, 12e-9);
    assert_int_equal(tip.rx, 8);
    tt_erosion_dilate(s, W, H, &tip, im);
    tt_erosion_erode(im, W, H, &tip, r);
    size_t n = tt_erosion_certainty(im, r, W, H, &tip, 1e-13, c), counted = 0, tighter = 0, above = 0, broad = 0;
    double worst = 0, worst_im = 0;
    for (size_t k = 0; k < W * H; k++) {
        if (!(im[k] >= s[k]))
            fail_msg("image below the surface at %zu", k);
        if (!(r[k] >= s[k] - EPS))
            fail_msg("reconstruction %g nm below the surface %g nm at (%zu, %zu)", r[k] * 1e9, s[k] * 1e9,
                     k % W, k / W);
        if (!(r[k] <= im[k]))
            fail_msg("reconstruction above the image at %zu", k);
        if (c[k]) {
            counted++;
            assert_close(r[k] * 1e9, s[k] * 1e9, 1e-6);
        }
        tighter += im[k] - r[k] > 1e-9;
        above += r[k] - s[k] > 1e-12;
        broad += im[k] - s[k] > 1e-12;
        worst = fmax(worst, r[k] - s[k]);
        worst_im = fmax(worst_im, im[k] - s[k]);
    }
    assert_int_equal(counted, n);
    /* the tip touched most of the terraces (the share is quoted in docs/surfaces.md) */
    print_message("certain: %zu of %d pixels (%.1f %%); %zu pixels > 1 nm below the image; %zu "
                  "above the surface, by up to %.2f nm (the image: %zu, by up to %.2f nm)\n",
                  n, W * H, 100.0 * (double)n / (W * H), tighter, above, worst * 1e9, broad, worst_im * 1e9);
    assert_true(n > W * H / 4);
    assert_true(tighter > 0);
    /* the pillar's top and the step's upper edge: the tip touched them */
    assert_true(c[32 * W + 18]);
    assert_close(r[32 * W + 18], 10e-9, EPS);
    /* the corner at the foot of the pillar: no tip position reaches it */
    assert_false(c[32 * W + 25]);
    assert_true(r[32 * W + 25] > s[32 * W + 25] + 1e-9);
    tt_tip_image_free(&tip);
}

/* The erosion of a dilation (a closing of the surface by the tip) does not change when
 * dilated and eroded again, and dilated it gives the same image back. */
static void idempotent(void **st)
{
    (void)st;
    static double s[W * H], im[W * H], r[W * H], im2[W * H], r2[W * H];
    surface(s);
    tt_tip_image tip = sphere_tip(8e-9, 12e-9);
    tt_erosion_dilate(s, W, H, &tip, im);
    tt_erosion_erode(im, W, H, &tip, r);
    tt_erosion_dilate(r, W, H, &tip, im2);
    tt_erosion_erode(im2, W, H, &tip, r2);
    double changed = 0;
    for (size_t k = 0; k < W * H; k++) {
        assert_close(im2[k] * 1e9, im[k] * 1e9, 1e-6);
        assert_close(r2[k] * 1e9, r[k] * 1e9, 1e-6);
        changed = fmax(changed, r[k] - s[k]);
    }
    assert_true(changed > 1e-9); /* the reconstruction is not the surface itself */
    tt_tip_image_free(&tip);
}

/* A flat image is its own reconstruction, certain wherever the whole tip fits; a point
 * tip erodes nothing. */
static void flat_and_point(void **st)
{
    (void)st;
    static double im[W * H], r[W * H];
    static unsigned char c[W * H];
    for (size_t k = 0; k < W * H; k++)
        im[k] = 3e-9;
    tt_tip_shape cone = {TT_TIP_CONE, 5e-9, 20 * M_PI / 180};
    tt_tip_image tip;
    assert_int_equal(tt_tip_image_make(&tip, &cone, PX, PX, 10e-9), TT_OK);
    tt_erosion_erode(im, W, H, &tip, r);
    size_t n = tt_erosion_certainty(im, r, W, H, &tip, 1e-13, c);
    for (size_t k = 0; k < W * H; k++)
        assert_close(r[k] * 1e9, 3, 1e-12);
    assert_int_equal(n, (size_t)(W - 2 * tip.rx) * (size_t)(H - 2 * tip.ry));
    tt_tip_image_free(&tip);

    static double s[W * H];
    surface(s);
    tt_tip_shape point = {TT_TIP_POINT, 5e-9, 0};
    assert_int_equal(tt_tip_image_make(&tip, &point, PX, PX, 12e-9), TT_OK);
    assert_int_equal(tip.rx, 0);
    tt_erosion_erode(s, W, H, &tip, r);
    assert_memory_equal(r, s, sizeof s);
    tt_tip_image_free(&tip);
}

/* The dilated surface as a GSF file of float heights in nm, under a fresh name the
 * caller removes. */
static const char *write_gsf(const double *z)
{
    static char path[] = "/tmp/tt-erosion-XXXXXX.gsf";
    int fd = mkstemps(path, 4);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "wb");
    assert_non_null(f);
    int len = fprintf(f, "Gwyddion Simple Field 1.0\nXRes = %d\nYRes = %d\nXReal = %d\nYReal = %d\n"
                         "XYUnits = nm\nZUnits = nm\n", W, H, W, H);
    for (int i = 0; i < 4 - len % 4; i++)
        fputc(0, f);
    for (size_t k = 0; k < W * H; k++) {
        float v = (float)(z[k] * 1e9);
        fwrite(&v, sizeof v, 1, f); /* little-endian machines (x86, arm64) */
    }
    fclose(f);
    return path;
}

static int load(tt_surface **S, const char *path, const char *keys)
{
    char text[1024];
    snprintf(text, sizeof text, "[material a]\nyoungs_modulus = 1 GPa\n[surface]\ntype = measured\n"
                                "image = %s\n%s", path, keys);
    tt_scene *sc = tt_scene_alloc();
    /* a value out of its key's range is refused as the scene is read, others here */
    int rc = tt_scene_load_string(sc, text, "s.ini");
    if (!rc)
        rc = tt_config_surface_alloc(S, sc, W * PX, H * PX);
    tt_scene_free(sc);
    return rc;
}

/* The scan's certainty channel: recorded by default with measured_tip_shape, the map
 * at each pixel's centre (pixels of 2 nm: image pixel 2 k + 1); refused without an
 * erosion. */
static void certainty_channel(const char *path, const unsigned char *c)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[material a]\nyoungs_modulus = 1 GPa\n[surface]\ntype = measured\nimage = %s\n"
             "measured_tip_shape = sphere\nmeasured_tip_radius = 8 nm\n"
             "[scan]\nsize = %g nm\nsize_y = %g nm\npixels = %d\nlines = %d\n",
             path, W * PX * 1e9, H * PX * 1e9, W / 2, H / 2);
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, text, "s.ini"), TT_OK);
    tt_scan *scan;
    if (tt_config_scan_alloc(&scan, sc) != TT_OK)
        fail_msg("%s", tt_error_message());
    assert_true(tt_scan_channels(scan) & TT_CH_CERTAINTY);
    const double *img = tt_scan_image(scan, TT_CH_CERTAINTY_INDEX, 0);
    assert_non_null(img);
    for (int j = 0; j < H / 2; j++)
        for (int i = 0; i < W / 2; i++)
            assert_close(img[j * (W / 2) + i], c[(2 * j + 1) * W + 2 * i + 1], 0);
    tt_scan_free(scan);
    tt_scene_free(sc);
    /* without the erosion there is no map to record */
    snprintf(text, sizeof text,
             "[material a]\nyoungs_modulus = 1 GPa\n[surface]\ntype = measured\nimage = %s\n"
             "[scan]\nsize = %g nm\nsize_y = %g nm\nchannels = height, certainty\n",
             path, W * PX * 1e9, H * PX * 1e9);
    sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, text, "s.ini"), TT_OK);
    assert_int_not_equal(tt_config_scan_alloc(&scan, sc), TT_OK);
    assert_non_null(strstr(tt_error_message(), "s.ini: [scan] channels: certainty is the certainty map"));
    tt_scene_free(sc);
}

/* [surface] measured_tip_shape erodes the image before it is interpolated; bad keys are
 * refused naming the key. */
static void scene_keys(void **st)
{
    (void)st;
    static double s[W * H], im[W * H], r[W * H];
    surface(s);
    tt_tip_image tip = sphere_tip(8e-9, 12e-9);
    tt_erosion_dilate(s, W, H, &tip, im);
    tt_tip_image_free(&tip);
    const char *p = write_gsf(im);
    /* the reference: the float file's heights eroded */
    for (size_t k = 0; k < W * H; k++)
        im[k] = (double)(float)(im[k] * 1e9) * 1e-9;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = 0; k < W * H; k++)
        lo = fmin(lo, im[k]), hi = fmax(hi, im[k]);
    tip = sphere_tip(8e-9, hi - lo);
    tt_erosion_erode(im, W, H, &tip, r);
    tt_tip_image_free(&tip);

    tt_surface *S = NULL;
    if (load(&S, p, "measured_tip_shape = sphere\nmeasured_tip_radius = 8 nm\n"))
        fail_msg("%s", tt_error_message());
    for (int y = 0; y < H; y += 3)
        for (int x = 0; x < W; x++)
            assert_close(tt_surface_height(S, (x + 0.5) * PX, (y + 0.5) * PX) * 1e9, r[y * W + x] * 1e9, 1e-6);
    /* beside the pillar the image is broadened, the eroded surface is not */
    assert_true(tt_surface_height(S, 25.5 * PX, 32.5 * PX) < im[32 * W + 25] - 1e-9);
    /* its certainty map is the library's, at a tolerance of 1e-6 of the height range, and
     * the reconstruction is the true surface where it is set */
    static unsigned char c[W * H];
    tip = sphere_tip(8e-9, hi - lo);
    size_t n = tt_erosion_certainty(im, r, W, H, &tip, 1e-6 * (hi - lo), c), seen = 0;
    tt_tip_image_free(&tip);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            double v = tt_surface_certainty(S, (x + 0.5) * PX, (y + 0.5) * PX);
            assert_close(v, c[y * W + x], 0);
            if (v == 1) {
                seen++;
                assert_close(tt_surface_height(S, (x + 0.5) * PX, (y + 0.5) * PX) * 1e9, s[y * W + x] * 1e9, 1e-5);
            }
        }
    print_message("%zu of %d pixels certain\n", seen, W * H);
    assert_int_equal(seen, n);
    assert_true(n > W * H / 3);
    tt_surface_free(S);
    if (load(&S, p, ""))
        fail_msg("%s", tt_error_message());
    assert_close(tt_surface_height(S, 25.5 * PX, 32.5 * PX), im[32 * W + 25], 1e-15);
    assert_true(isnan(tt_surface_certainty(S, 25.5 * PX, 32.5 * PX))); /* nothing eroded */
    tt_surface_free(S);
    certainty_channel(p, c);

    assert_int_not_equal(load(&S, p, "measured_tip_shape = needle\n"), TT_OK);
    assert_non_null(strstr(tt_error_message(), "measured_tip_shape"));
    assert_int_not_equal(load(&S, p, "measured_tip_shape = sphere\nmeasured_tip_radius = 0 nm\n"), TT_OK);
    assert_non_null(strstr(tt_error_message(), "measured_tip_radius"));
    assert_int_not_equal(load(&S, p, "measured_tip_shape = cone\nmeasured_tip_half_angle = 0 deg\n"), TT_OK);
    assert_non_null(strstr(tt_error_message(), "measured_tip_half_angle"));
    /* a size without the shape that uses it */
    assert_int_not_equal(load(&S, p, "measured_tip_radius = 8 nm\n"), TT_OK);
    assert_non_null(strstr(tt_error_message(), "measured_tip_radius"));
    assert_int_not_equal(load(&S, p, "measured_tip_shape = sphere\nmeasured_tip_half_angle = 20 deg\n"), TT_OK);
    assert_non_null(strstr(tt_error_message(), "measured_tip_half_angle"));
    unlink(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reconstruction),
        cmocka_unit_test(idempotent),
        cmocka_unit_test(flat_and_point),
        cmocka_unit_test(scene_keys),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
