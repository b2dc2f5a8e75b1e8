/* The contact law's local geometry (docs/surfaces.md): the effective radius on a curved
 * feature, the contact normal on a slope, for every law, and the surface's own reading
 * of them where the tip touches. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

static const double R = 10e-9, K = 1e9, DEG = M_PI / 180;

static tt_contact_params params(tt_contact_model model, double w)
{
    tt_contact_params p = {.model = model, .K = K, .R = R, .w = w, .xi0 = 0.3e-9, .lambda = NAN};
    return p;
}

static tt_contact *local(const tt_contact_params *p, double cs, double R_eff)
{
    tt_contact_geometry g = {cs, R_eff};
    tt_contact *c;
    if (tt_contact_alloc_local(&c, p, &g))
        fail_msg("%s", tt_error_message());
    return c;
}

/* A flat's geometry is the law tt_contact_alloc builds: every load bit for bit. */
static void flat_is_the_axis_law(void **st)
{
    (void)st;
    tt_contact_geometry g = tt_contact_geometry_of(R, 1.0, 0.0, 0.0);
    assert_true(g.cos_slope == 1.0 && g.R_eff == R);
    tt_contact_model models[] = {TT_CONTACT_MAUGIS, TT_CONTACT_HERTZ, TT_CONTACT_DMT, TT_CONTACT_JKR};
    for (int m = 0; m < 4; m++) {
        tt_contact_params p = params(models[m], 0.05);
        tt_contact *a, *b;
        assert_int_equal(tt_contact_alloc(&a, &p), TT_OK);
        assert_int_equal(tt_contact_alloc_local(&b, &p, &g), TT_OK);
        for (double d = -1e-9; d < 2e-9; d += 0.13e-9)
            for (int in = 0; in < 2; in++)
                assert_true(tt_contact_load(a, d, in, NULL, NULL) == tt_contact_load(b, d, in, NULL, NULL));
        tt_contact_free(a);
        tt_contact_free(b);
    }
}

/* Hertz on a sphere of radius r: K sqrt(R_eff) delta^1.5, 1/R_eff = 1/R + 1/r (eq. 4). */
static void hertz_on_a_sphere(void **st)
{
    (void)st;
    double r = 5e-9, Re = R * r / (R + r);
    tt_contact_geometry g = tt_contact_geometry_of(R, 1.0, 1 / r, 1 / r);
    assert_close(g.R_eff, Re, 1e-12 * Re);
    tt_contact_params p = params(TT_CONTACT_HERTZ, 0);
    tt_contact *c, *flat;
    assert_int_equal(tt_contact_alloc_local(&c, &p, &g), TT_OK);
    assert_int_equal(tt_contact_alloc(&flat, &p), TT_OK);
    for (double d = 0.1e-9; d < 3e-9; d += 0.37e-9) {
        double want = K * sqrt(Re) * pow(d, 1.5), got = tt_contact_load(c, d, 1, NULL, NULL);
        assert_close(got, want, 1e-9 * want);
        /* a 10 nm tip on a 5 nm particle: sqrt(1/3) = 0.577 of the flat's force */
        assert_close(got / tt_contact_load(flat, d, 1, NULL, NULL), sqrt(1.0 / 3), 1e-9);
    }
    /* a hollow as curved as the tip is clamped to TT_CONTACT_CONCAVE_MAX tip radii */
    g = tt_contact_geometry_of(R, 1.0, -1 / R, -1 / R);
    assert_close(g.R_eff, TT_CONTACT_CONCAVE_MAX * R, 1e-12 * R);
    tt_contact_free(c);
    tt_contact_free(flat);
}

/* On a slope of angle a: F_z(delta) = P(delta cos a) cos a; Hertz cos^2.5 a, 0.698 at
 * 30 deg, its Kelvin-Voigt and film rows and the tables the same relation. */
static void slope_projects_every_law(void **st)
{
    (void)st;
    double cs = cos(30 * DEG);
    tt_contact_params hz = params(TT_CONTACT_HERTZ, 0);
    tt_contact *c = local(&hz, cs, R), *flat;
    assert_int_equal(tt_contact_alloc(&flat, &hz), TT_OK);
    double d = 1e-9, ratio = tt_contact_load(c, d, 1, NULL, NULL) / tt_contact_load(flat, d, 1, NULL, NULL);
    print_message("Hertz on 30 deg: %.6f of the flat's\n", ratio);
    assert_close(ratio, pow(cs, 2.5), 1e-12);
    assert_close(ratio, 0.698, 1e-3);
    tt_contact_free(c);
    tt_contact_free(flat);
    /* relaxation arms: the glassy response of a surface at rest, cos a P(delta cos a) */
    tt_contact_params sl = hz;
    sl.arms = 1;
    sl.arm_modulus[0] = 2e9;
    sl.arm_time[0] = 1e-6;
    c = local(&sl, cs, R);
    assert_int_equal(tt_contact_alloc(&flat, &sl), TT_OK);
    assert_int_equal((int)tt_contact_law_of(c)->state_size, 1);
    double q0 = 0, q1 = 0;
    double Pz = tt_contact_force(c, 0, d, 0, 1, &q0).conservative;
    double Pn = tt_contact_force(flat, 0, d * cs, 0, 1, &q1).conservative;
    assert_true(Pz > 0);
    assert_close(Pz, cs * Pn, 1e-12 * Pn);
    tt_contact_free(c);
    tt_contact_free(flat);
    tt_contact_params rows[4] = {params(TT_CONTACT_MAUGIS, 0.05), params(TT_CONTACT_DMT, 0.05),
                                 params(TT_CONTACT_JKR, 0.05), params(TT_CONTACT_HERTZ, 0)};
    rows[3].film_thickness = 20e-9;
    rows[3].viscosity = 1;
    rows[0].viscosity = 1;
    for (int m = 0; m < 4; m++) {
        c = local(&rows[m], cs, R);
        assert_int_equal(tt_contact_alloc(&flat, &rows[m]), TT_OK);
        for (double dd = -0.4e-9; dd < 2e-9; dd += 0.17e-9) {
            double want = cs * tt_contact_load(flat, dd * cs, 1, NULL, NULL);
            assert_close(tt_contact_load(c, dd, 1, NULL, NULL), want, 1e-9 * fabs(want) + 1e-18);
            double U = tt_contact_energy(flat, dd * cs, 1);
            assert_close(tt_contact_energy(c, dd, 1), U, 1e-9 * fabs(U) + 1e-30);
        }
        /* the viscous force's z part: eta a (rate cos a) cos a */
        tt_contact_forces fz = tt_contact_force(c, 0, 1e-9, 1e-3, 1, NULL);
        tt_contact_forces fn = tt_contact_force(flat, 0, 1e-9 * cs, 1e-3 * cs, 1, NULL);
        assert_close(fz.viscous, fn.viscous * cs, 1e-9 * fabs(fn.viscous));
        assert_true(rows[m].viscosity == 0 || fz.viscous > 0);
        /* thresholds along z: the normal's over cos a */
        assert_close(tt_contact_jumpout(c), tt_contact_jumpout(flat) / cs, 1e-12 * R);
        tt_contact_free(c);
        tt_contact_free(flat);
    }
}

/* The tables at R_eff: adhesion goes as R (JKR's pull-off 1.5 pi w R_eff), and over a
 * particle's apex an approach presses softer at every depth. */
static void tables_at_the_effective_radius(void **st)
{
    (void)st;
    double w = 0.05, Re = R / 2;
    tt_contact_params p = params(TT_CONTACT_JKR, w);
    tt_contact *c = local(&p, 1.0, Re);
    double least = INFINITY;
    for (double d = -2e-9; d < 1e-9; d += 1e-13)
        if (d >= tt_contact_jumpout(c))
            least = fmin(least, tt_contact_load(c, d, 1, NULL, NULL));
    print_message("JKR pull-off at R_eff = R/2: %.6g N, 1.5 pi w R_eff = %.6g N\n", least,
                  1.5 * M_PI * w * Re);
    assert_close(least, -1.5 * M_PI * w * Re, 1e-4 * M_PI * w * Re);
    tt_contact_free(c);
    p = params(TT_CONTACT_MAUGIS, w);
    p.lambda = 2; /* given: scaled as R^(1/3) */
    tt_contact *apex = local(&p, 1.0, Re), *flat;
    assert_close(tt_contact_summary_of(apex)->lambda, 2 * cbrt(0.5), 1e-12);
    assert_int_equal(tt_contact_alloc(&flat, &p), TT_OK);
    for (double d = 0.2e-9; d < 2e-9; d += 0.2e-9) {
        double ka, kf;
        double fa = tt_contact_load(apex, d, 1, &ka, NULL), ff = tt_contact_load(flat, d, 1, &kf, NULL);
        print_message("%.1f nm: apex %.4g N (%.4g N/m), flat %.4g N (%.4g N/m)\n", d * 1e9, fa, ka, ff, kf);
        assert_true(ka > 0 && ka < 0.9 * kf);
    }
    tt_contact_free(apex);
    tt_contact_free(flat);
}

static tt_surface *particles(void)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, "[material a]\nyoungs_modulus = 1 GPa\n"
                                             "[surface]\ntype = particles\nparticle_radius = 30 nm\n"
                                             "particle_count = 5\nseed = 3\n", "s.ini"), TT_OK);
    tt_surface *S = NULL;
    if (tt_config_surface_alloc(&S, s, 1e-6, 1e-6))
        fail_msg("%s", tt_error_message());
    tt_scene_free(s);
    return S;
}

/* The surface reads a particle's geometry: 1/r at its apex, the normal's angle on its
 * flank, and exactly a flat's between particles. */
static void surface_reads_a_particle(void **st)
{
    (void)st;
    double r = 30e-9, step = r / 100;
    tt_surface *S = particles();
    double best = -1, bx = 0, by = 0;
    for (int j = 0; j < 400; j++)
        for (int i = 0; i < 400; i++) {
            double h = tt_surface_height(S, i * 2.5e-9, j * 2.5e-9);
            if (h > best)
                best = h, bx = i * 2.5e-9, by = j * 2.5e-9;
        }
    /* the sphere's centre, r above the flat: from the gradient there */
    tt_contact_geometry g = tt_surface_contact_geometry(S, bx, by, step, R);
    double gx = (tt_surface_height(S, bx + step, by) - tt_surface_height(S, bx - step, by)) / (2 * step);
    double gy = (tt_surface_height(S, bx, by + step) - tt_surface_height(S, bx, by - step)) / (2 * step);
    double cx = bx + gx * (best - r), cy = by + gy * (best - r);
    g = tt_surface_contact_geometry(S, cx, cy, step, R);
    print_message("apex: cos a %.9f, R_eff %.6f nm (R r / (R + r) = %.6f nm)\n", g.cos_slope,
                  g.R_eff * 1e9, R * r / (R + r) * 1e9);
    assert_close(g.cos_slope, 1, 1e-6);
    assert_close(g.R_eff, R * r / (R + r), 1e-3 * R);
    g = tt_surface_contact_geometry(S, cx + r * sin(30 * DEG), cy, step, R);
    print_message("flank at 30 deg: cos a %.6f, R_eff %.6f nm\n", g.cos_slope, g.R_eff * 1e9);
    assert_close(g.cos_slope, cos(30 * DEG), 1e-4);
    assert_close(g.R_eff, R * r / (R + r), 1e-3 * R);
    /* far from every particle: the flat itself */
    int found = 0;
    for (int i = 0; i < 400 && !found; i++) {
        double x = i * 2.5e-9, y = 0.5e-6;
        g = tt_surface_contact_geometry(S, x, y, step, R);
        if (tt_surface_height(S, x, y) == 0 && tt_surface_height(S, x + 2 * step, y) == 0 &&
            tt_surface_height(S, x - 2 * step, y) == 0) {
            found = 1;
            assert_true(g.cos_slope == 1.0 && g.R_eff == R);
        }
    }
    assert_true(found);
    tt_surface_free(S);
}

/* A flat's law at R_eff tilted (its table copied and scaled) is the law built for the
 * slope and R_eff, every load bit for bit, for every row. */
static void tilted_is_the_local_law(void **st)
{
    (void)st;
    tt_contact_params rows[6] = {params(TT_CONTACT_MAUGIS, 0.05), params(TT_CONTACT_DMT, 0.05),
                                 params(TT_CONTACT_JKR, 0.05), params(TT_CONTACT_HERTZ, 0),
                                 params(TT_CONTACT_HERTZ, 0), params(TT_CONTACT_MAUGIS, 0.05)};
    rows[0].viscosity = 1;
    rows[4].film_thickness = 20e-9;
    rows[5].lambda = 2;
    const double radii[2] = {R, 0.6 * R}, slopes[3] = {1.0, cos(30 * DEG), cos(70 * DEG)};
    for (int m = 0; m < 6; m++)
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 3; j++) {
                tt_contact *base = local(&rows[m], 1.0, radii[i]), *want = local(&rows[m], slopes[j], radii[i]);
                tt_contact *got;
                assert_int_equal(tt_contact_alloc_tilted(&got, base, slopes[j]), TT_OK);
                for (double d = -1e-9; d < 2e-9; d += 0.013e-9)
                    for (int in = 0; in < 2; in++)
                        assert_true(tt_contact_load(got, d, in, NULL, NULL) == tt_contact_load(want, d, in, NULL, NULL));
                assert_true(tt_contact_jumpin(got) == tt_contact_jumpin(want));
                assert_true(tt_contact_jumpout(got) == tt_contact_jumpout(want));
                assert_true(tt_contact_force(got, 0, 1e-9, 1e-3, 1, NULL).viscous ==
                            tt_contact_force(want, 0, 1e-9, 1e-3, 1, NULL).viscous);
                tt_contact_free(base);
                tt_contact_free(want);
                tt_contact_free(got);
            }
}

static void bad_geometry_is_refused(void **st)
{
    (void)st;
    tt_contact_params p = params(TT_CONTACT_HERTZ, 0);
    tt_contact_geometry g = {0, R};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_local(&c, &p, &g), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "cos a in (0, 1]"));
    g.cos_slope = 1;
    g.R_eff = -R;
    assert_int_equal(tt_contact_alloc_local(&c, &p, &g), TT_EINVAL);
}

int main(void)
{
    const struct CMUnitTest t[] = {
        cmocka_unit_test(flat_is_the_axis_law),
        cmocka_unit_test(hertz_on_a_sphere),
        cmocka_unit_test(slope_projects_every_law),
        cmocka_unit_test(tables_at_the_effective_radius),
        cmocka_unit_test(surface_reads_a_particle),
        cmocka_unit_test(tilted_is_the_local_law),
        cmocka_unit_test(bad_geometry_is_refused),
    };
    return cmocka_run_group_tests(t, NULL, NULL);
}
