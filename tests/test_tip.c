/* The tip's shape: the surface dilated by it against the analytic images of a step
 * (the wall drawn as the tip's own profile, apex sphere then cone) and of a sphere on
 * the plane (apparent width 4 sqrt(R r), apparent height unchanged), and the tip's
 * shape in a scan (the gap follows the dilation, the topography channel does not). */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/tip.h"
#include "tiptap/util/error.h"

/* The profile of a sphere of radius R on a cone of half-angle th, written out here
 * apart from the library's: R - sqrt(R^2 - d^2) up to the tangent at d = R cos th,
 * then a straight flank of slope 1 / tan th. */
static double profile(double R, double th, double d)
{
    d = fabs(d);
    if (th <= 0)
        return d <= R ? R - sqrt(R * R - d * d) : INFINITY;
    if (d <= R * cos(th))
        return R - sqrt(R * R - d * d);
    return R - R * sin(th) + (d - R * cos(th)) / tan(th);
}

static void tip_profile_is_smooth(void **st)
{
    (void)st;
    tt_tip_shape t = {TT_TIP_CONE, 10e-9, 20 * M_PI / 180};
    double rt = 10e-9 * cos(t.half_angle), e = 1e-15;
    /* height and slope continuous where the sphere meets the cone */
    assert_close(tt_tip_shape_height(&t, rt + e), tt_tip_shape_height(&t, rt - e), 3 * 2 * e);
    double sl = (tt_tip_shape_height(&t, rt + 1e-12) - tt_tip_shape_height(&t, rt - 1e-12)) / 2e-12;
    assert_close(sl, 1 / tan(t.half_angle), 1e-3);
    /* reach inverts height on both parts; the slope point inverts the slope */
    for (double d = 1e-9; d < 40e-9; d += 3e-9)
        assert_close(tt_tip_shape_reach(&t, tt_tip_shape_height(&t, d)), d, 1e-18);
    assert_close(tt_tip_shape_slope_at(&t, 1.0), 10e-9 / sqrt(2), 1e-20);
    assert_true(isinf(tt_tip_shape_slope_at(&t, 3.0)));
    /* the normal's cosine is 1 / sqrt(1 + t'^2) on the sphere and on the flank */
    for (double d = 0.5e-9; d < 30e-9; d += 1.7e-9) {
        double tp = (tt_tip_shape_height(&t, d + 1e-13) - tt_tip_shape_height(&t, d - 1e-13)) / 2e-13;
        assert_close(tt_tip_shape_normal_cos(&t, d), 1 / sqrt(1 + tp * tp), 1e-5);
    }
    assert_close(tt_tip_shape_normal_cos(&t, 25e-9), sin(t.half_angle), 1e-15);
    tt_tip_shape s = {TT_TIP_SPHERE, 10e-9, 0};
    assert_close(tt_tip_shape_normal_cos(&s, 5e-9), sqrt(0.75), 1e-15);
    assert_true(isinf(tt_tip_shape_height(&s, 10.1e-9)));
    assert_close(tt_tip_shape_reach(&s, 50e-9), 10e-9, 0);
}

/* A 20 nm up-step at x = 500 nm, vertical: left of the wall the apex rides the wall's
 * top corner, so the image is the tip's own profile, 20 nm - t(500 nm - x), down to the
 * lower terrace; right of it, the upper terrace. Exact for steps (no grid). */
static void step_images_as_tip_profile(void **st)
{
    (void)st;
    tt_surface *S = tt_make_surface("[surface]\ntype = steps\nstep_height = 20 nm\nstep_width = 500 nm\n", 1e-6);
    const double R = 10e-9, H = 20e-9;
    for (int k = 0; k < 2; k++) {
        double th = k ? 20 * M_PI / 180 : 0;
        tt_tip_shape t = {k ? TT_TIP_CONE : TT_TIP_SPHERE, R, th};
        tt_dilation *D;
        assert_int_equal(tt_dilation_alloc(&D, S, &t, 0, 0, 1e-6, 1e-6, 1e-9), TT_OK);
        assert_int_equal(tt_dilation_nodes(D), 0); /* exact, no grid */
        double worst = 0;
        for (double d = -5e-9; d < 40e-9; d += 0.37e-9) {
            double want = d <= 0 ? H : fmax(0, H - profile(R, th, d));
            worst = fmax(worst, fabs(tt_dilation_height(D, 500e-9 - d, 3e-7) - want));
        }
        print_message("%s tip: step image off the tip profile by %.2g nm at most\n",
                      k ? "cone" : "sphere", worst * 1e9);
        assert_true(worst < 1e-15);
        /* the wall's image reaches as far as the cone's flank rises 20 nm; a sphere
         * tip, lower than the wall, hangs beside it at its equator and drops there */
        double reach = k ? R * cos(th) + (H - R * (1 - sin(th))) * tan(th) : R;
        double below = k ? 0 : H - R;
        print_message("  wall broadened by %.3f nm\n", reach * 1e9);
        assert_close(tt_dilation_height(D, 500e-9 - reach + 1e-15, 0), below, 0.01e-9);
        assert_close(tt_dilation_height(D, 500e-9 - reach - 1e-12, 0), 0, 0);
        assert_true(tt_dilation_height(D, 500e-9 - reach + 0.1e-9, 0) > below + 0.01e-9);
        tt_dilation_free(D);
    }
    tt_surface_free(S);
}

/* Sloped grating edges (20 nm over 30 nm) against a brute-force search over the tip:
 * where the edge is gentler than the cone, the apex sphere touches the slope itself. */
static void sloped_edges_match_brute_force(void **st)
{
    (void)st;
    tt_surface *S = tt_make_surface("[surface]\ntype = grating\nperiod = 400 nm\nduty = 50 %\nheight = 20 nm\n"
                         "edge_width = 30 nm\n", 1e-6);
    tt_tip_shape t = {TT_TIP_CONE, 10e-9, 30 * M_PI / 180};
    tt_dilation *D;
    assert_int_equal(tt_dilation_alloc(&D, S, &t, 0, 0, 1e-6, 1e-6, 1e-9), TT_OK);
    double worst = 0;
    for (double x = 150e-9; x < 290e-9; x += 1.3e-9) {
        double best = -INFINITY;
        for (double u = -60e-9; u <= 60e-9; u += 0.002e-9)
            best = fmax(best, tt_surface_height(S, x + u, 0) - profile(10e-9, t.half_angle, u));
        worst = fmax(worst, fabs(tt_dilation_height(D, x, 0) - best));
    }
    print_message("sloped edges: exact vs brute force within %.3g nm\n", worst * 1e9);
    assert_true(worst < 0.005e-9);
    tt_dilation_free(D);
    tt_surface_free(S);
}

/* The centre of the one particle: from three nodes on its cap, where
 * (x - cx)^2 + (y - cy)^2 = r^2 - (h - r)^2 exactly. */
static void particle_centre(const tt_surface *S, double size, double r, double *cx, double *cy)
{
    double bx = 0, by = 0, bh = -1, dl = 0.5e-9;
    for (double y = 0; y < size; y += dl)
        for (double x = 0; x < size; x += dl)
            if (tt_surface_height(S, x, y) > bh) {
                bh = tt_surface_height(S, x, y);
                bx = x;
                by = y;
            }
#define Q(x, y) (r * r - (tt_surface_height(S, x, y) - r) * (tt_surface_height(S, x, y) - r))
    double q0 = Q(bx, by), qx = Q(bx + dl, by), qy = Q(bx, by + dl);
#undef Q
    /* q(x + dl) - q(x) = 2 dl (x - cx) + dl^2 */
    *cx = bx - (qx - q0 - dl * dl) / (2 * dl);
    *cy = by - (qy - q0 - dl * dl) / (2 * dl);
}

/* A sphere of radius r = 5 nm on the plane under a sphere tip of R = 10 nm: the image is
 * a sphere of radius R + r about the particle's centre, lowered by R, cut by the plane:
 * apparent width 4 sqrt(R r) = 28.3 nm (true: 10 nm), apparent height 2 r. Under a cone
 * of the same apex the image is the cone's profile with apex radius R + r (the
 * Minkowski sum of the ball and the blunt cone). On a grid of 0.25 nm. */
static void sphere_images_wide_not_tall(void **st)
{
    (void)st;
    const double r = 5e-9, R = 10e-9, size = 100e-9, dx = 0.25e-9;
    tt_surface *S = tt_make_surface("[surface]\ntype = particles\nparticle_radius = 5 nm\nparticle_count = 1\n"
                         "seed = 3\n", size);
    double cx, cy;
    particle_centre(S, size, r, &cx, &cy);
    assert_close(tt_surface_height(S, cx, cy), 2 * r, 1e-13);
    for (int k = 0; k < 2; k++) {
        double th = k ? 20 * M_PI / 180 : 0;
        tt_tip_shape t = {k ? TT_TIP_CONE : TT_TIP_SPHERE, R, th};
        tt_dilation *D;
        assert_int_equal(tt_dilation_alloc(&D, S, &t, 0, 0, size, size, dx), TT_OK);
        assert_close(tt_dilation_spacing(D), dx, 1e-15);
        double top = tt_dilation_height(D, cx, cy);
        /* the base: where the image meets the plane, along x from the centre */
        double lo = 0, hi = 30e-9;
        while (hi - lo > 1e-13) {
            double m = 0.5 * (lo + hi);
            if (tt_dilation_height(D, cx + m, cy) > 1e-13)
                lo = m;
            else
                hi = m;
        }
        double width = 2 * lo, want = 4 * sqrt(R * r), worst = 0;
        if (k)
            for (want = 0; 2 * r - profile(R + r, th, want / 2) > 0; want += 1e-13)
                ;
        for (double d = 0; d < 0.95 * want / 2; d += 0.3e-9)
            worst = fmax(worst, fabs(tt_dilation_height(D, cx, cy + d) - (2 * r - profile(R + r, th, d))));
        print_message("%s tip: height %.4f nm (2r %.1f), width %.3f nm (analytic %.3f), profile "
                      "within %.3f nm\n", k ? "cone" : "sphere", top * 1e9, 2 * r * 1e9, width * 1e9,
                      want * 1e9, worst * 1e9);
        assert_close(top, 2 * r, 0.01e-9);
        assert_close(width, want, 2 * dx);
        assert_true(worst < 0.15e-9);
        tt_dilation_free(D);
    }
    tt_surface_free(S);
}

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 1\nline_rate = 20 Hz\nsettle_cycles = 3000\n"
    "channels = height, topography\n[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n"
    "[surface]\ntype = grating\nperiod = 1 um\nheight = 20 nm\n";

/* A blunt cone (60 deg) broadens the falling wall at 500 nm by 37 nm into pixel 16: the
 * retrace climbs it earlier than with a point tip, while the topography channel, the
 * true height, stays the same. */
static void scan_meets_the_dilated_surface(void **st)
{
    (void)st;
    tt_scene *sp, *sc;
    tt_scan *p = tt_run_scan(base, "[tip]\nshape = point\n", &sp);
    tt_scan *c = tt_run_scan(base, "[tip]\nshape = cone\nhalf_angle = 60 deg\n", &sc);
    assert_null(tt_scan_dilation(p));
    assert_non_null(tt_scan_dilation(c));
    const double *hp = tt_scan_image(p, 0, 1), *hc = tt_scan_image(c, 0, 1);
    const double *tp = tt_scan_image(p, 6, 1), *tc = tt_scan_image(c, 6, 1);
    for (int i = 0; i < 32; i++)
        assert_close(tc[i], tp[i], 1e-15);
    print_message("retrace pixel 16: point %.2f nm, cone %.2f nm; pixel 8: %.3f, %.3f nm\n",
                  hp[16] * 1e9, hc[16] * 1e9, hp[8] * 1e9, hc[8] * 1e9);
    assert_true(hc[16] > hp[16] + 3e-9);
    assert_close(hc[8], hp[8], 0.05e-9); /* on the line's top, far from a wall: the same */
    tt_scan_free(p);
    tt_scan_free(c);
    tt_scene_free(sp);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(tip_profile_is_smooth),
        cmocka_unit_test(step_images_as_tip_profile),
        cmocka_unit_test(sloped_edges_match_brute_force),
        cmocka_unit_test(sphere_images_wide_not_tall),
        cmocka_unit_test(scan_meets_the_dilated_surface),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
