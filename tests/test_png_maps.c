/* PNG maps are read as the file stores them: a transparent pixel is refused (it was
 * composited onto uninitialised memory), and 16-bit or gamma-tagged material maps keep
 * their levels (they were converted to 8-bit sRGB, so that no map_value matched). */
#include <png.h>
#include <stdlib.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/scene.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/util/error.h"

static char dir[] = "/tmp/tt_pngmap_XXXXXX";

/* A 2 x 1 PNG of the given colour type and depth from big-endian sample bytes; gamma > 0
 * adds a gAMA chunk. */
static void write_raw(const char *path, int type, int depth, double gamma, const unsigned char *row)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    assert_false(setjmp(png_jmpbuf(png)));
    png_init_io(png, f);
    png_set_IHDR(png, info, 2, 1, depth, type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (gamma > 0)
        png_set_gAMA(png, info, gamma);
    png_write_info(png, info);
    png_write_row(png, row);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
}

/* The surface of a material map at path with materials a and b of the given map_values;
 * NULL when refused (the message is then tt_error_message()). */
static tt_surface *map_of(const char *path, const char *va, const char *vb)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[material a]\nyoungs_modulus = 1 GPa\nmap_value = %s\n"
             "[material b]\nyoungs_modulus = 50 GPa\nmap_value = %s\n"
             "[surface]\nmap = png\nmap_png = %s\n", va, vb, path);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "s.ini"), TT_OK);
    tt_surface *S = NULL;
    int rc = tt_config_surface_alloc(&S, s, 1e-6, 0.5e-6); /* the 2 x 1 map's aspect */
    tt_scene_free(s);
    return rc ? NULL : S;
}

static void expect_materials(const char *path, const char *va, const char *vb)
{
    tt_surface *S = map_of(path, va, vb);
    if (!S)
        fail_msg("refused: %s", tt_error_message());
    assert_int_equal(tt_surface_material(S, 250e-9, 500e-9), 0);
    assert_int_equal(tt_surface_material(S, 750e-9, 500e-9), 1);
    tt_surface_free(S);
}

static void sixteen_bit_levels(void **st)
{
    (void)st;
    char path[256];
    snprintf(path, sizeof path, "%s/g16.png", dir);
    const unsigned char row[] = {0x00, 0x07, 0x80, 0x00}; /* 7, 32768 */
    write_raw(path, PNG_COLOR_TYPE_GRAY, 16, 0, row);
    expect_materials(path, "7", "32768");
    /* a colour names its 16-bit level x 257 */
    const unsigned char rgb[] = {0, 0, 0, 0, 0, 0, 0xff, 0xff, 0, 0, 0, 0};
    write_raw(path, PNG_COLOR_TYPE_RGB, 16, 0, rgb);
    expect_materials(path, "#000000", "#ff0000");
}

static void gamma_is_ignored(void **st)
{
    (void)st;
    char path[256];
    snprintf(path, sizeof path, "%s/gamma.png", dir);
    const unsigned char row[] = {64, 128};
    write_raw(path, PNG_COLOR_TYPE_GRAY, 8, 1.0, row); /* tagged linear */
    expect_materials(path, "64", "128");
    /* an 8-bit map has no level above 255 */
    assert_null(map_of(path, "64", "300"));
    assert_non_null(strstr(tt_error_message(), "s.ini: [material b] map_value: 300 is above 255"));
}

static void transparency_is_refused(void **st)
{
    (void)st;
    char path[256];
    snprintf(path, sizeof path, "%s/alpha.png", dir);
    const unsigned char rgba[] = {0, 0, 0, 255, 255, 0, 0, 0}; /* second pixel fully transparent */
    write_raw(path, PNG_COLOR_TYPE_RGB_ALPHA, 8, 0, rgba);
    assert_null(map_of(path, "0", "#ff0000"));
    char want[512];
    snprintf(want, sizeof want,
             "s.ini: [surface] map_png: %s: pixel (1, 0) is transparent (alpha 0 of 255); a map "
             "must be opaque", path);
    assert_string_equal(tt_error_message(), want);
    /* opaque alpha is fine */
    const unsigned char opaque[] = {0, 0, 0, 255, 255, 0, 0, 255};
    write_raw(path, PNG_COLOR_TYPE_RGB_ALPHA, 8, 0, opaque);
    expect_materials(path, "0", "#ff0000");
    /* a height map with a transparent grey pixel */
    const unsigned char ga[] = {10, 255, 20, 17};
    write_raw(path, PNG_COLOR_TYPE_GRAY_ALPHA, 8, 0, ga);
    char text[512];
    snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s\n", path);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "h.ini"), TT_OK);
    tt_surface *S = NULL;
    assert_int_equal(tt_config_surface_alloc(&S, s, 1e-6, 1e-6), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "h.ini: [surface] png:"));
    assert_non_null(strstr(tt_error_message(), "pixel (1, 0) is transparent (alpha 17 of 255)"));
    tt_scene_free(s);
}

/* The surface of text over a 1 um square; NULL when refused. */
static tt_surface *square_of(const char *text)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "p.ini"), TT_OK);
    tt_surface *S = NULL;
    int rc = tt_config_surface_alloc(&S, s, 1e-6, 1e-6);
    tt_scene_free(s);
    return rc ? NULL : S;
}

/* A 2 x 1 map over a square scan: stretched, its pixels would be 2:1 (issue 32), so it
 * is refused unless a pixel size places it; one too small to cover the area is refused;
 * placed, a pixel sits where its size says, past the area too. */
static void pixel_size_places_the_map(void **st)
{
    (void)st;
    char path[256], text[1024];
    snprintf(path, sizeof path, "%s/wide.png", dir);
    const unsigned char grey[] = {0, 255};
    write_raw(path, PNG_COLOR_TYPE_GRAY, 8, 0, grey);
    snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s\npng_height_range = 10 nm\n", path);
    assert_null(square_of(text));
    assert_non_null(strstr(tt_error_message(), "p.ini: [surface] pixel_size:"));
    assert_non_null(strstr(tt_error_message(), "would stretch them 2:1"));
    snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s\npng_height_range = 10 nm\npixel_size = 600 nm\n",
             path);
    assert_null(square_of(text));
    assert_non_null(strstr(tt_error_message(), "cover 1200 x 600 nm, less than the 1000 x 1000 nm scan area"));
    snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s\npng_height_range = 10 nm\npixel_size = 1 um\n",
             path);
    tt_surface *S = square_of(text);
    if (!S)
        fail_msg("refused: %s", tt_error_message());
    /* pixel centres at 0.5 and 1.5 um, bilinear between: stretched, 0.75 um was 10 nm */
    assert_close(tt_surface_height(S, 0.5e-6, 0.5e-6), 0, 1e-18);
    assert_close(tt_surface_height(S, 0.75e-6, 0.5e-6), 2.5e-9, 1e-18);
    assert_close(tt_surface_height(S, 1.5e-6, 0.5e-6), 10e-9, 1e-18);
    tt_surface_free(S);
    /* a material map likewise, by map_pixel_size */
    const unsigned char rgb[] = {0, 0, 0, 255, 0, 0};
    write_raw(path, PNG_COLOR_TYPE_RGB, 8, 0, rgb);
    const char *mats = "[material a]\nyoungs_modulus = 1 GPa\nmap_value = 0\n"
                       "[material b]\nyoungs_modulus = 50 GPa\nmap_value = #ff0000\n";
    snprintf(text, sizeof text, "%s[surface]\nmap = png\nmap_png = %s\n", mats, path);
    assert_null(square_of(text));
    assert_non_null(strstr(tt_error_message(), "p.ini: [surface] map_pixel_size:"));
    snprintf(text, sizeof text, "%s[surface]\nmap = png\nmap_png = %s\nmap_pixel_size = 1 um\n", mats, path);
    S = square_of(text);
    if (!S)
        fail_msg("refused: %s", tt_error_message());
    assert_int_equal(tt_surface_material(S, 0.9e-6, 0.5e-6), 0);
    assert_int_equal(tt_surface_material(S, 1.1e-6, 0.5e-6), 1);
    tt_surface_free(S);
}

static int setup(void **st)
{
    (void)st;
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **st)
{
    (void)st;
    const char *names[] = {"g16.png", "gamma.png", "alpha.png", "wide.png"};
    char p[256];
    for (size_t i = 0; i < 4; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        unlink(p);
    }
    return rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sixteen_bit_levels),
        cmocka_unit_test(gamma_is_ignored),
        cmocka_unit_test(transparency_is_refused),
        cmocka_unit_test(pixel_size_places_the_map),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
