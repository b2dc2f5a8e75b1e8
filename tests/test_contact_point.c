/* The material where the tip touches, not under its axis: a sphere tip over a
 * two-material step edge (exact dilation) and a two-material particle (grid) switches
 * material where the hand-computed contact point crosses the edge; in a trench too
 * narrow for it, the scan's phase stays the rim's. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/tip.h"
#include "tiptap/util/error.h"

static const char *materials = "[material soft]\nyoungs_modulus = 0.5 GPa\nadhesion_energy = 30 mJ/m^2\n"
                               "interaction_quality_factor = 20\n"
                               "[material stiff]\nyoungs_modulus = 100 GPa\n";

/* A 5 nm grating line from 0 to 100 nm (stiff), floor from 100 to 200 nm (soft), under
 * a sphere of R = 20 nm. Past the falling wall the tip rests on its top corner until the
 * apex reaches the floor, at a lateral distance sqrt(H (2 R - H)) = 13.229 nm from the
 * wall; before the rising wall at 200 nm, from the same distance on. So the material is
 * the top's for x < 113.229 nm and x > 186.771 nm, the floor's between; the axis would
 * switch at 100 and 200 nm. */
static void step_edge_switches_at_the_contact_point(void **st)
{
    (void)st;
    const double H = 5e-9, R = 20e-9, r = sqrt(H * (2 * R - H)), size = 400e-9;
    char text[1024];
    snprintf(text, sizeof text,
             "%s[surface]\ntype = grating\nperiod = 200 nm\nduty = 50 %%\nheight = 5 nm\n"
             "map = stripes\nmap_materials = soft, stiff\nmap_period = 200 nm\nmap_duty = 50 %%\n",
             materials);
    tt_surface *S = tt_make_surface(text, size);
    int top = tt_surface_material(S, 50e-9, 0), floor_ = tt_surface_material(S, 150e-9, 0);
    assert_int_not_equal(top, floor_);
    tt_tip_shape t = {TT_TIP_SPHERE, R, 0};
    tt_dilation *D;
    assert_int_equal(tt_dilation_alloc(&D, S, &t, 0, 0, size, size, 1e-9), TT_OK);
    assert_int_equal(tt_dilation_nodes(D), 0); /* exact */
    long checked = 0, beside = 0;
    for (double x = 1e-9; x < 200e-9; x += 0.05e-9) {
        double d1 = x - (100e-9 + r), d2 = x - (200e-9 - r);
        if (fabs(d1) < 1e-12 || fabs(d2) < 1e-12)
            continue;
        double xc, yc;
        double h = tt_dilation_contact(D, x, 0, &xc, &yc);
        assert_close(h, tt_dilation_height(D, x, 0), 0);
        assert_close(yc, 0, 0);
        int want = (d1 < 0 || d2 > 0) ? top : floor_;
        assert_int_equal(tt_surface_material(S, xc, yc), want);
        /* on the floor the apex touches: the contact point is the axis */
        if (want == floor_)
            assert_close(xc, x, 1e-15);
        beside += tt_surface_material(S, x, 0) != want;
        checked++;
    }
    /* the axis alone is wrong over both 13.2 nm bands */
    print_message("%ld of %ld points read a material other than the axis's\n", beside, checked);
    assert_true(beside > (long)(2 * 13e-9 / 0.05e-9));
    tt_dilation_free(D);
    tt_surface_free(S);
}

/* A stiff particle of r = 5 nm (an island of the map) on a soft plane under a sphere of
 * R = 5 nm, on a grid of 0.25 nm: the tip touches the particle while its axis is within
 * 2 sqrt(R r) = 10 nm of the particle's centre (the spheres' centres R + r apart), the
 * plane beyond; the axis leaves the island at 5 nm. */
static void particle_edge_switches_at_the_contact_point(void **st)
{
    (void)st;
    const double r = 5e-9, R = 5e-9, size = 100e-9, dx = 0.25e-9;
    char text[1024];
    snprintf(text, sizeof text,
             "%s[surface]\ntype = particles\nparticle_radius = 5 nm\nparticle_count = 1\nseed = 3\n"
             "map = islands\nmap_materials = soft, stiff\n",
             materials);
    tt_surface *S = tt_make_surface(text, size);
    /* the particle's centre: the highest sample, refined by symmetry of the island */
    double cx = 0, cy = 0, bh = -1;
    for (double y = 0; y < size; y += 0.25e-9)
        for (double x = 0; x < size; x += 0.25e-9)
            if (tt_surface_height(S, x, y) > bh) {
                bh = tt_surface_height(S, x, y);
                cx = x;
                cy = y;
            }
    int island = tt_surface_material(S, cx, cy), plane = tt_surface_material(S, 1e-9, 1e-9);
    assert_int_not_equal(island, plane);
    tt_tip_shape t = {TT_TIP_SPHERE, R, 0};
    tt_dilation *D;
    assert_int_equal(tt_dilation_alloc(&D, S, &t, 0, 0, size, size, dx), TT_OK);
    const double edge = 2 * sqrt(R * r);
    long beside = 0, checked = 0;
    for (int dir = 0; dir < 4; dir++) {
        double ux = dir == 0 ? 1 : dir == 1 ? -1 : 0, uy = dir == 2 ? 1 : dir == 3 ? -1 : 0;
        for (double d = 0; d < 20e-9; d += 0.1e-9) {
            if (fabs(d - edge) < 4 * dx) /* the grid's step, and the centre's within dx */
                continue;
            double x = cx + ux * d, y = cy + uy * d, xc, yc;
            tt_dilation_contact(D, x, y, &xc, &yc);
            int want = d < edge ? island : plane;
            assert_int_equal(tt_surface_material(S, xc, yc), want);
            beside += tt_surface_material(S, x, y) != want;
            checked++;
        }
    }
    print_message("%ld of %ld points read a material other than the axis's\n", beside, checked);
    assert_true(beside > 4 * 30);
    tt_dilation_free(D);
    tt_surface_free(S);
}

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[scan]\nsize = 200 nm\npixels = 40\nlines = 1\nline_rate = 20 Hz\nsettle_cycles = 3000\n"
    "channels = height, phase\n[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

/* A 10 nm trench 25 nm deep every 100 nm (x from 90 to 100 nm and 190 to 200 nm), its
 * floor soft, the lines stiff, under a sphere of R = 10 nm: the apex reaches
 * R - sqrt(R^2 - (5 nm)^2) = 1.34 nm into it and touches only the rims, so the phase in
 * the trench's pixels (5 nm each: 18, 19, 38, 39) is the lines', not the floor's. */
static void unreachable_trench_keeps_the_rims_material(void **st)
{
    (void)st;
    char text[2048];
    snprintf(text, sizeof text,
             "%s%s[surface]\ntype = grating\nperiod = 100 nm\nduty = 90 %%\nheight = 25 nm\n"
             "map = stripes\nmap_materials = soft, stiff\nmap_period = 100 nm\nmap_duty = 90 %%\n"
             "[tip]\nshape = sphere\nradius = 10 nm\n",
             base, materials);
    tt_scene *sc, *sf;
    tt_scan *s = tt_run_scan(text, "", &sc);
    /* the floor's material everywhere, for its phase */
    tt_scan *f = tt_run_scan(text, "[surface]\nmap_materials = soft, soft\n", &sf);
    const double *ph = tt_scan_image(s, 2, 0), *pf = tt_scan_image(f, 2, 0);
    const double *h = tt_scan_image(s, 0, 0);
    double line = 0, soft = 0;
    for (int i = 4; i < 15; i++) {
        line += ph[i] / 11;
        soft += pf[i] / 11;
    }
    print_message("phase: lines %.2f deg, floor's material %.2f deg; trench pixels %.2f %.2f "
                  "%.2f %.2f deg; height there %.2f nm (lines %.2f nm)\n",
                  line, soft, ph[18], ph[19], ph[38], ph[39], h[18] * 1e9, h[8] * 1e9);
    assert_true(fabs(soft - line) > 5); /* a contrast the test can see */
    const int trench[] = {18, 19, 38, 39};
    for (int k = 0; k < 4; k++) {
        assert_true(fabs(ph[trench[k]] - line) < 0.2 * fabs(soft - line));
        assert_true(h[trench[k]] > h[8] - 3e-9); /* the tip stays near the rims */
    }
    tt_scan_free(s);
    tt_scan_free(f);
    tt_scene_free(sc);
    tt_scene_free(sf);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(step_edge_switches_at_the_contact_point),
        cmocka_unit_test(particle_edge_switches_at_the_contact_point),
        cmocka_unit_test(unreachable_trench_keeps_the_rims_material),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
