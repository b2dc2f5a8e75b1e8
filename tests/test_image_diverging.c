/* An error image's diverging map is white at zero: its range is symmetric about zero
 * (it ran from the data's minimum to its maximum, so white sat at their middle, -5 nm in
 * the teaching set's gain-low). */
#include <png.h>
#include <stdlib.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/io/image.h"

/* the pixel at (x, y) of the PNG at path, as 8-bit RGB */
static void pixel(const char *path, int x, int y, int rgb[3])
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    assert_true(png_image_begin_read_from_file(&im, path));
    im.format = PNG_FORMAT_RGB;
    png_bytep buf = malloc(PNG_IMAGE_SIZE(im));
    assert_non_null(buf);
    assert_true(png_image_finish_read(&im, NULL, buf, 0, NULL));
    for (int k = 0; k < 3; k++)
        rgb[k] = buf[(size_t)y * PNG_IMAGE_ROW_STRIDE(im) + 3 * (size_t)x + k];
    free(buf);
}

static void zero_is_white(void **st)
{
    (void)st;
    char dir[] = "/tmp/tt_diverging_XXXXXX", path[64];
    assert_non_null(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/e.png", dir);
    /* two pixels, 0 and +4 nm: symmetric, 0 is the map's middle; min to max, its low end */
    const double data[2] = {0, 4e-9};
    tt_image im = {2, 1, 1e-6, 1e-6, data, "error", "nm", 1e9, TT_CMAP_DIVERGING};
    assert_int_equal(tt_image_write_png(path, &im), 0);
    int rgb[3];
    /* the image area starts at (20, 50) and is 512 px square: pixel 0 is its left half */
    pixel(path, 20 + 128, 50 + 256, rgb);
    /* the map's middle anchor, 0.87 grey (222); its low end is blue (59, 77, 191) */
    assert_int_equal(rgb[0], 222);
    assert_int_equal(rgb[1], 222);
    assert_int_equal(rgb[2], 222);
    pixel(path, 20 + 384, 50 + 256, rgb);
    assert_int_equal(rgb[0], 181); /* +4 nm is the top: the map's red end, 0.71 */
    unlink(path);
    rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(zero_is_white)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
