/* Two materials whose map_value names the same pixel of a PNG material map are refused,
 * naming the scene file, both materials, their values and the map: before, every such
 * pixel silently went to one of them. The same pixel is judged at the map's own depth:
 * grey 255 and #ffffff are one pixel of an 8-bit map and two of a 16-bit one. */
#include <png.h>
#include <stdlib.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/scene.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/util/error.h"

static char dir[] = "/tmp/tt_mapvalue_XXXXXX";
static char path[256];

/* A 2 x 1 PNG of the given colour type and depth from big-endian sample bytes. */
static void write_raw(int type, int depth, const unsigned char *row)
{
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    assert_false(setjmp(png_jmpbuf(png)));
    png_init_io(png, f);
    png_set_IHDR(png, info, 2, 1, depth, type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    png_write_row(png, row);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    fclose(f);
}

/* The map's surface with materials a, b (and c, unused, when vc is given); TT_OK or the
 * status of the refusal (message in tt_error_message()). */
static int build(const char *va, const char *vb, const char *vc, tt_surface **S)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[material a]\nyoungs_modulus = 1 GPa\nmap_value = %s\n"
             "[material b]\nyoungs_modulus = 50 GPa\nmap_value = %s\n"
             "%s%s\n"
             "[surface]\nmap = png\nmap_png = %s\n", va, vb,
             vc ? "[material c]\nyoungs_modulus = 9 GPa\nmap_value = " : "", vc ? vc : "", path);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "s.ini"), TT_OK);
    *S = NULL;
    int rc = tt_config_surface_alloc(S, s, 1e-6, 0.5e-6); /* the 2 x 1 map's aspect */
    tt_scene_free(s);
    return rc;
}

static void expect_refused(const char *va, const char *vb, const char *vc, const char *want)
{
    tt_surface *S;
    int rc = build(va, vb, vc, &S);
    if (rc == TT_OK)
        fail_msg("map_values %s, %s, %s accepted", va, vb, vc ? vc : "-");
    assert_int_equal(rc, TT_EINVAL);
    char full[512];
    snprintf(full, sizeof full, "%s%s; give each material a value of its own", want, path);
    assert_string_equal(tt_error_message(), full);
}

static void same_grey_level(void **st)
{
    (void)st;
    const unsigned char row[] = {0, 128};
    write_raw(PNG_COLOR_TYPE_GRAY, 8, row);
    expect_refused("128", "128", NULL,
                   "s.ini: [material b] map_value: 128 names the same pixel as [material a] "
                   "map_value 128 in the 8-bit map ");
    /* a third material, named by neither pixel, that repeats the first one's value */
    expect_refused("0", "128", "0",
                   "s.ini: [material c] map_value: 0 names the same pixel as [material a] "
                   "map_value 0 in the 8-bit map ");
}

static void same_colour(void **st)
{
    (void)st;
    const unsigned char rgb[] = {0, 0, 0, 0xff, 0, 0};
    write_raw(PNG_COLOR_TYPE_RGB, 8, rgb);
    expect_refused("#ff0000", "#ff0000", NULL,
                   "s.ini: [material b] map_value: #ff0000 names the same pixel as [material a] "
                   "map_value #ff0000 in the 8-bit map ");
    /* grey 255 is white at 8 bits */
    expect_refused("#ffffff", "255", NULL,
                   "s.ini: [material b] map_value: 255 names the same pixel as [material a] "
                   "map_value #ffffff in the 8-bit map ");
}

static void depth_decides(void **st)
{
    (void)st;
    /* at 16 bits grey 255 is a dark level and #ffffff is 65535: two materials */
    const unsigned char row[] = {0x00, 0xff, 0xff, 0xff};
    write_raw(PNG_COLOR_TYPE_GRAY, 16, row);
    tt_surface *S;
    int rc = build("255", "#ffffff", NULL, &S);
    if (rc)
        fail_msg("refused: %s", tt_error_message());
    assert_int_equal(tt_surface_material(S, 250e-9, 500e-9), 0);
    assert_int_equal(tt_surface_material(S, 750e-9, 500e-9), 1);
    tt_surface_free(S);
    /* and 257 x 255 = 65535 is white once more */
    expect_refused("#ffffff", "65535", NULL,
                   "s.ini: [material b] map_value: 65535 names the same pixel as [material a] "
                   "map_value #ffffff in the 16-bit map ");
}

static int setup(void **st)
{
    (void)st;
    if (!mkdtemp(dir))
        return -1;
    snprintf(path, sizeof path, "%s/map.png", dir);
    return 0;
}

static int teardown(void **st)
{
    (void)st;
    unlink(path);
    return rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(same_grey_level),
        cmocka_unit_test(same_colour),
        cmocka_unit_test(depth_decides),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
