/* The scan frame on the sample ([scan] angle, offset_x, offset_y): the tip's position
 * against the rotation's closed form, the box the scan visits, and a scan turned by
 * 90 deg over a grating whose lines run along y: each line then stays at one x, so its
 * topography is one height, the grating's at that x, while the unturned scan crosses
 * the lines. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/instrument/scanner.h"

static void position_is_the_rotation(void **st)
{
    (void)st;
    tt_raster r = {.size_x = 1e-6, .size_y = 0.5e-6, .pixels = 10, .lines = 5, .line_rate = 1,
                   .angle = 30 * M_PI / 180, .offset_x = 10e-9, .offset_y = -20e-9};
    tt_raster flat = r;
    flat.angle = flat.offset_x = flat.offset_y = 0;
    for (long line = 0; line < 5; line++)
        for (long k = 0; k <= 100; k += 25) {
            double x, y, u, v;
            tt_raster_position(&r, line, 0, 100, k, &x, &y);
            tt_raster_position(&flat, line, 0, 100, k, &u, &v);
            double c = cos(r.angle), s = sin(r.angle), dx = u - 0.5e-6, dy = v - 0.25e-6;
            assert_close(x, 0.5e-6 + c * dx - s * dy + 10e-9, 1e-21);
            assert_close(y, 0.25e-6 + s * dx + c * dy - 20e-9, 1e-21);
            /* the distance along the fast axis does not turn */
            assert_close(tt_raster_fast_position(&r, 0, 100, k), u, 0);
        }
    double b[4];
    tt_raster_bounds(&flat, b);
    assert_true(b[0] == 0 && b[1] == 0 && b[2] == 1e-6 && b[3] == 0.5e-6);
    r.size_y = r.size_x;
    r.angle = M_PI / 4;
    tt_raster_bounds(&r, b);
    const double h = 0.5e-6 * sqrt(2);
    assert_close(b[0], 0.5e-6 - h + 10e-9, 1e-21);
    assert_close(b[3], 0.5e-6 + h - 20e-9, 1e-21);
}

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
    "free_amplitude = 20 nm\n[material silicon]\nreduced_modulus = 100 GPa\n"
    "[surface]\ntype = grating\nperiod = 400 nm\nheight = 10 nm\nedge_width = 100 nm\n"
    "[scan]\nsize = 1 um\npixels = 8\nlines = 8\nline_rate = 4 Hz\nchannels = height, topography\n"
    "[feedback]\nsetpoint = 80 %\n";

static void turned_scan_follows_the_lines(void **st)
{
    (void)st;
    tt_scene *sc, *sf;
    tt_scan *s = tt_run_scan(base, "[scan]\nangle = 90 deg\noffset_x = 30 nm\n", &sc);
    tt_scan *f = tt_run_scan(base, "", &sf);
    tt_surface *S = tt_make_surface(base, 1e-6);
    const double *t = tt_scan_image(s, 6, 0), *t0 = tt_scan_image(f, 6, 0);
    double spread0 = 0;
    for (int line = 0; line < 8; line++) {
        /* after the turn, line j runs along y at x = 1 um - (j + 1/2) pitch + offset */
        double want = tt_surface_height(S, 1e-6 - (line + 0.5) * 1e-6 / 8 + 30e-9, 0);
        double lo = INFINITY, hi = -INFINITY;
        for (int px = 0; px < 8; px++) {
            assert_close(t[line * 8 + px], want, 1e-17);
            lo = fmin(lo, t0[line * 8 + px]);
            hi = fmax(hi, t0[line * 8 + px]);
        }
        spread0 = fmax(spread0, hi - lo);
    }
    assert_true(spread0 > 5e-9); /* unturned, each line crosses the grating */
    tt_surface_free(S);
    tt_scan_free(s);
    tt_scan_free(f);
    tt_scene_free(sc);
    tt_scene_free(sf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(position_is_the_rotation),
        cmocka_unit_test(turned_scan_follows_the_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
