/* The dilation channel: the true surface as the tip's shape images it, per pixel, no
 * dynamics. A sphere of R = 20 nm over a grating of vertical walls (5 nm lines from 0
 * to 100 nm, trench to 200 nm): in the trench, within r = sqrt(H (2 R - H)) = 13.2 nm of
 * a wall, the sphere rests on the wall's top corner, at H - R + sqrt(R^2 - d^2); the
 * channel's pixels are the means of that over their cycles, on the every-cycle,
 * envelope and averaged tiers alike. A point tip's channel is the topography. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material silicon]\nreduced_modulus = 100 GPa\n"
    "[surface]\ntype = grating\nperiod = 200 nm\nduty = 50 %\nheight = 5 nm\n"
    "[scan]\nsize = 200 nm\npixels = 100\nlines = 1\nline_rate = 20 Hz\n"
    "channels = height, topography, dilation\n[feedback]\nsetpoint = 80 %\n";

enum { DIL = TT_CH_DILATION_INDEX, TOPO = 6 };

static double sphere_on_grating(double x)
{
    const double H = 5e-9, R = 20e-9, r = sqrt(H * (2 * R - H));
    if (x < 100e-9)
        return H;
    double d = fmin(x - 100e-9, 200e-9 - x);
    return d < r ? H - R + sqrt(R * R - d * d) : 0;
}

static void sphere_over_walls(const char *tier)
{
    char extra[256];
    snprintf(extra, sizeof extra, "[tip]\nshape = sphere\nradius = 20 nm\n[solver]\ntier = %s\n", tier);
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, extra, &sc);
    const double dx = 2e-9;
    double worst = 0, lifted = 0;
    for (int r = 0; r < 2; r++) {
        const double *d = tt_scan_image(s, DIL, r), *t = tt_scan_image(s, TOPO, r);
        for (int p = 0; p < 100; p++) {
            double want = 0;
            for (int j = 0; j < 1000; j++)
                want += sphere_on_grating((p + (j + 0.5) / 1000) * dx) / 1000;
            worst = fmax(worst, fabs(d[p] - want));
            lifted = fmax(lifted, d[p] - t[p]);
            assert_true(d[p] >= t[p] - 1e-15); /* a dilation never lies below the surface */
        }
    }
    print_message("%s: dilation channel within %.3g nm of the closed form; up to %.3g nm above "
                  "the topography\n", tier, worst * 1e9, lifted * 1e9);
    /* the pixel's cycles sample it at 37.5 points, not continuously: a few pm */
    assert_true(worst < 0.02e-9);
    assert_true(lifted > 4e-9); /* beside the walls, the trench is out of reach */
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void sphere_every(void **st) { (void)st; sphere_over_walls("every"); }
static void sphere_envelope(void **st) { (void)st; sphere_over_walls("envelope"); }
static void sphere_averaged(void **st) { (void)st; sphere_over_walls("averaged"); }

static void point_tip_is_the_topography(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, "", &sc);
    for (int r = 0; r < 2; r++)
        assert_memory_equal(tt_scan_image(s, DIL, r), tt_scan_image(s, TOPO, r), 100 * sizeof(double));
    tt_scan_free(s);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sphere_every),
        cmocka_unit_test(sphere_envelope),
        cmocka_unit_test(sphere_averaged),
        cmocka_unit_test(point_tip_is_the_topography),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
