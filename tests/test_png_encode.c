/* The previews' own PNG encoder (tt_png_encode_rgb24, src/io/png_encode.c) writes the
 * bytes cairo's writer writes through libpng, to the byte: on noise (every filter in
 * play), gradients, flat rows (filters that tie: libpng takes the first), antialiased
 * lines and text as the previews draw them, rows of two to four pixels, and an image
 * of several IDAT chunks; an image under 16 kB of rows, or one pixel wide or high, it
 * leaves to cairo. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tt_test.h"
#include "io/png_internal.h"

static cairo_status_t to_file(void *closure, const unsigned char *data, unsigned int len)
{
    return fwrite(data, 1, len, (FILE *)closure) == len ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

/* Both encoders' bytes of sf, compared; returns the PNG's size. */
static size_t assert_same_bytes(cairo_surface_t *sf)
{
    char *a = NULL, *b = NULL;
    size_t na = 0, nb = 0;
    FILE *f = open_memstream(&a, &na);
    assert_int_equal(cairo_surface_write_to_png_stream(sf, to_file, f), CAIRO_STATUS_SUCCESS);
    fclose(f);
    f = open_memstream(&b, &nb);
    assert_int_equal(tt_png_encode_rgb24(sf, f), 0);
    fclose(f);
    print_message("%d x %d: cairo %zu bytes, own %zu\n", cairo_image_surface_get_width(sf),
                  cairo_image_surface_get_height(sf), na, nb);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na);
    free(a);
    free(b);
    return na;
}

static cairo_surface_t *pixels(int w, int h, unsigned (*px)(int x, int y))
{
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    unsigned char *d = cairo_image_surface_get_data(sf);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            ((unsigned *)(void *)(d + (size_t)y * (size_t)cairo_image_surface_get_stride(sf)))[x] = px(x, y);
    cairo_surface_mark_dirty(sf);
    return sf;
}

static unsigned noise(int x, int y)
{
    unsigned h = (unsigned)x * 2654435761u ^ (unsigned)y * 40503u;
    h ^= h >> 13;
    return (h * 2246822519u) & 0xffffff;
}

static unsigned gradient(int x, int y)
{
    return (unsigned)(x & 255) << 16 | (unsigned)((x + y) / 3 & 255) << 8 | (unsigned)(y * 7 & 255);
}

static unsigned flat(int x, int y)
{
    return y < 40 ? 0xffffff : y < 80 ? 0 : x < 50 ? 0x808080 : 0x7f0080;
}

static void noise_and_gradients(void **st)
{
    (void)st;
    cairo_surface_t *a = pixels(300, 200, noise), *b = pixels(517, 300, gradient), *c = pixels(700, 120, flat);
    assert_true(assert_same_bytes(a) > 3 * 8192); /* several IDAT chunks */
    assert_same_bytes(b);
    assert_same_bytes(c);
    cairo_surface_destroy(a);
    cairo_surface_destroy(b);
    cairo_surface_destroy(c);
}

static void narrow_rows(void **st)
{
    (void)st;
    for (int w = 2; w <= 4; w++) {
        cairo_surface_t *sf = pixels(w, 6000, w == 3 ? gradient : noise);
        assert_same_bytes(sf);
        cairo_surface_destroy(sf);
    }
}

/* Left to cairo, nothing written: under 16 kB of rows, one pixel wide or high. */
static void assert_left_to_cairo(cairo_surface_t *sf)
{
    char *a = NULL;
    size_t na = 0;
    FILE *f = open_memstream(&a, &na);
    assert_int_equal(tt_png_encode_rgb24(sf, f), 1);
    fclose(f);
    assert_int_equal(na, 0);
    free(a);
    cairo_surface_destroy(sf);
}

/* What the previews draw: white, antialiased curves, text. */
static void drawing(void **st)
{
    (void)st;
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 706, 622);
    cairo_t *cr = cairo_create(sf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_set_source_rgb(cr, 0.2, 0.3, 0.8);
    cairo_set_line_width(cr, 1.3);
    for (int i = 0; i < 400; i++)
        cairo_line_to(cr, 20 + 1.6 * i, 300 + 120 * __builtin_sin(i * 0.05) * __builtin_cos(i * 0.011));
    cairo_stroke(cr);
    cairo_move_to(cr, 40, 60);
    cairo_set_font_size(cr, 14);
    cairo_show_text(cr, "height (trace) 1.25 nm");
    cairo_destroy(cr);
    assert_same_bytes(sf);
    cairo_surface_destroy(sf);
}

static void small_left_to_cairo(void **st)
{
    (void)st;
    assert_left_to_cairo(pixels(40, 40, noise));
    assert_left_to_cairo(pixels(1, 6000, noise));
    assert_left_to_cairo(pixels(6000, 1, noise));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(noise_and_gradients),
        cmocka_unit_test(narrow_rows),
        cmocka_unit_test(drawing),
        cmocka_unit_test(small_left_to_cairo),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
