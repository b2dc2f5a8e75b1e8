/* [tip] contact_geometry = local: the scan's law built for the geometry where the tip
 * touches (docs/surfaces.md). On a 30 deg flank a Hertz sample presses as a flat one of
 * cos^2.5 a = 0.698 of its modulus would; flat pixels keep the flat law bit for bit;
 * a wall's top corner takes the tip's own normal; the quantised laws stay within their
 * stated 1 % of the exact geometry's; threads
 * agree; the reduced tiers are refused. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "instrument/scan_private.h"

static const double DEG = M_PI / 180;

/* A 100 nm grating line whose rising flank is a plane at 30 deg (edge_width 100 nm /
 * tan 30 deg, from x = 100 nm to 273.2 nm) under a 10 nm sphere, on a Hertz sample:
 * the floor, the flank and the top in one 400 nm line of 10 nm pixels, trace only. */
static const char *slope =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material a]\nmodel = hertz\nreduced_modulus = 1 GPa\n"
    "[scan]\nsize = 400 nm\npixels = 40\nlines = 1\nline_rate = 5 Hz\nretrace = no\n"
    "settle_cycles = 3000\nchannels = height, phase, peak_force\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n"
    "[surface]\ntype = grating\nperiod = 1000 nm\nduty = 50 %\nheight = 100 nm\n"
    "edge_width = 173.2050808 nm\noffset_x = 100 nm\n"
    "[tip]\nshape = sphere\nradius = 10 nm\n[solver]\ntier = every\n";

static tt_scan *run_on(const char *base, const char *extra, tt_scene **sc)
{
    tt_scan *s = tt_make_scan(base, extra, sc);
    if (tt_scan_run(s, 1, NULL, NULL) != TT_OK)
        fail_msg("%s", tt_error_message());
    return s;
}

static tt_scan *run(const char *extra, tt_scene **sc) { return run_on(slope, extra, sc); }

/* The flank's pixels whose contact point lies on the plane (the sphere touches R sin a
 * = 5 nm ahead of its axis; a pixel's width and the feedback's settling clear of the
 * corners): 12 of them, centres 135 to 245 nm. The local law's peak force there is the
 * scaled flat sample's within the quantisation's 1 %; the axis law's is 9 % above. */
static void flank_presses_as_cos_2_5_of_the_modulus(void **st)
{
    (void)st;
    tt_scene *sa, *sl, *ss;
    tt_scan *axis = run("", &sa), *loc = run("[tip]\ncontact_geometry = local\n", &sl);
    char scaled[128];
    snprintf(scaled, sizeof scaled, "[material a]\nreduced_modulus = %.9g GPa\n", pow(cos(30 * DEG), 2.5));
    tt_scan *flat = run(scaled, &ss);
    const double *Fa = tt_scan_image(axis, 3, 0), *Fl = tt_scan_image(loc, 3, 0), *Fs = tt_scan_image(flat, 3, 0);
    double worst = 0, least_axis = INFINITY;
    for (int px = 13; px <= 24; px++) {
        worst = fmax(worst, fabs(Fl[px] / Fs[px] - 1));
        least_axis = fmin(least_axis, fabs(Fa[px] / Fs[px] - 1));
    }
    print_message("flank peak force: local %.4g N, modulus x cos^2.5 a %.4g N (worst %.2g), "
                  "axis %.4g N (least %.3g off); %ld laws built\n",
                  Fl[18], Fs[18], worst, Fa[18], least_axis, tt_scan_contact_laws_built(loc, NULL));
    assert_true(worst < 0.01);
    assert_true(least_axis > 0.05);
    /* the floor before the flank: the flat law itself, every channel bit for bit */
    for (int c = 0; c < 4; c++)
        if (tt_scan_image(axis, c, 0))
            assert_memory_equal(tt_scan_image(axis, c, 0), tt_scan_image(loc, c, 0), 8 * sizeof(double));
    assert_true(tt_scan_contact_laws_built(loc, NULL) > 0);
    assert_int_equal(tt_scan_contact_laws_built(axis, NULL), 0);
    tt_scan_free(axis);
    tt_scan_free(loc);
    tt_scan_free(flat);
    tt_scene_free(sa);
    tt_scene_free(sl);
    tt_scene_free(ss);
}

/* The same line with a vertical rising wall at x = 100 nm, 100 GPa: the stencil
 * straddles the wall where the tip's side touches its top corner (pixel 9, 90 to 100
 * nm) and just past it (pixel 10); there the contact is the sphere's own normal at the
 * corner. Past the corner the indentation is axis's within 10 %; on the corner it is
 * the z-penetration of a normal tilted by up to 90 deg (delta_z = delta_n / cos a),
 * within 5 times axis's. The wall's slope read there instead (cos a at its 0.1 floor:
 * a law nearly without force) gave 1.5 and 13.5 times (docs/surfaces.md). */
static void corner_takes_the_tips_normal(void **st)
{
    (void)st;
    tt_scene *sa, *sl;
    const char *wall = "[surface]\nedge_width = 0 nm\n[scan]\nsize = 200 nm\npixels = 20\n"
                       "channels = height, indentation\n[material a]\nreduced_modulus = 100 GPa\n";
    char local[256];
    snprintf(local, sizeof local, "%s[tip]\ncontact_geometry = local\n", wall);
    tt_scan *axis = run(wall, &sa), *loc = run(local, &sl);
    const double *da = tt_scan_image(axis, 4, 0), *dl = tt_scan_image(loc, 4, 0);
    print_message("indentation on the corner: local %.3g nm, axis %.3g nm; past it %.3g, %.3g nm\n",
                  dl[9] * 1e9, da[9] * 1e9, dl[10] * 1e9, da[10] * 1e9);
    assert_true(da[10] > 0 && fabs(dl[10] / da[10] - 1) < 0.1);
    assert_true(da[9] > 0 && dl[9] < 5 * da[9]);
    tt_scan_free(axis);
    tt_scan_free(loc);
    tt_scene_free(sa);
    tt_scene_free(sl);
}

/* A flat sample: local and axis give the same images, bit for bit. */
static void flat_sample_is_the_same(void **st)
{
    (void)st;
    tt_scene *sa, *sl;
    const char *flat = "[surface]\ntype = flat\n[scan]\nsize = 100 nm\npixels = 10\nlines = 1\nline_rate = 20 Hz\n"
                       "retrace = no\nchannels = height, phase, peak_force\n"
                       "[material a]\nadhesion_energy = 30 mJ/m^2\n"
                       "[tip]\nshape = sphere\n[solver]\ntier = every\n";
    tt_scan *a = run_on(flat, "", &sa), *l = run_on(flat, "[tip]\ncontact_geometry = local\n", &sl);
    for (int c = 0; c < 4; c++)
        if (tt_scan_image(a, c, 0))
            assert_memory_equal(tt_scan_image(a, c, 0), tt_scan_image(l, c, 0), 10 * sizeof(double));
    assert_int_equal(tt_scan_contact_laws_built(l, NULL), 0);
    tt_scan_free(a);
    tt_scan_free(l);
    tt_scene_free(sa);
    tt_scene_free(sl);
}

/* The largest difference of the z force between two laws over indentations from -1 to
 * 3 nm, approach and retract, relative to the force there or to a's pull-off force,
 * whichever is larger (an adhesive force crosses zero), where both laws are in the same
 * state (between their jump thresholds one is in contact and the other not) and more
 * than 0.02 nm past the later jump-out (the curve is vertical there: a 0.2 % shift of
 * the pull-off point moved the force by 1.2 % of the pull-off force). */
static double law_difference(const tt_contact *a, const tt_contact *b)
{
    double worst = 0, pull = 0;
    for (double d = -1e-9; d <= 3e-9; d += 0.01e-9)
        pull = fmax(pull, -tt_contact_load(a, d, 1, NULL, NULL));
    const double lo = fmax(tt_contact_jumpout(a), tt_contact_jumpout(b));
    const double hi = fmin(tt_contact_jumpin(a), tt_contact_jumpin(b));
    for (double d = -1e-9; d <= 3e-9; d += 0.01e-9)
        for (int in = 0; in < 2; in++) {
            if ((in && d < lo + 0.02e-9) || (!in && d > hi))
                continue;
            double fa = tt_contact_load(a, d, in, NULL, NULL), fb = tt_contact_load(b, d, in, NULL, NULL);
            worst = fmax(worst, fabs(fb - fa) / fmax(fabs(fa), fmax(pull, 1e-15)));
        }
    return worst;
}

/* The quantisation's cost: the law at a geometry's bin centre against the law at the
 * geometry itself, over slopes 0 to 80 deg and R_eff from 0.1 R to 10 R, Hertz and
 * Maugis-Dugdale: within 1 %. */
static void quantisation_within_one_percent(void **st)
{
    (void)st;
    tt_contact_params p[2] = {{.model = TT_CONTACT_HERTZ, .K = 1e9, .R = 10e-9, .xi0 = 0.3e-9, .lambda = NAN},
                              {.model = TT_CONTACT_MAUGIS, .K = 1e9, .R = 10e-9, .w = 0.03, .xi0 = 0.3e-9,
                               .lambda = NAN}};
    const double cs[] = {1.0, cos(3.7 * DEG), cos(17 * DEG), cos(30 * DEG), cos(52 * DEG), cos(80 * DEG)};
    const double rr[] = {0.1, 0.577, 0.93, 1.0, 2.3, 10};
    double worst[2] = {0, 0};
    for (int m = 0; m < 2; m++)
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j += m ? 2 : 1) {
                tt_contact_geometry g = {cs[i], rr[j] * p[m].R};
                /* the key as tt_scan_geometry_key quantises */
                long kc = lround(-log(g.cos_slope) / 0.004), kr = lround(log(rr[j]) / 0.01);
                uint32_t key = (uint32_t)kc | (uint32_t)(uint16_t)(int16_t)kr << 16;
                tt_contact_geometry q = tt_scan_geometry_of_key(key, p[m].R);
                assert_true(fabs(log(q.cos_slope / g.cos_slope)) <= 0.002 + 1e-12);
                assert_true(fabs(log(q.R_eff / g.R_eff)) <= 0.005 + 1e-12);
                tt_contact *exact, *bin;
                assert_int_equal(tt_contact_alloc_local(&exact, &p[m], &g), TT_OK);
                assert_int_equal(tt_contact_alloc_local(&bin, &p[m], &q), TT_OK);
                worst[m] = fmax(worst[m], law_difference(exact, bin));
                tt_contact_free(exact);
                tt_contact_free(bin);
            }
    print_message("quantisation: Hertz within %.3g, Maugis-Dugdale within %.3g of the exact law\n",
                  worst[0], worst[1]);
    assert_true(worst[0] < 0.01 && worst[0] > 0);
    assert_true(worst[1] < 0.01);
}

/* A particle under a sphere on one thread and on two: the same images bit for bit. */
static void threads_agree(void **st)
{
    (void)st;
    const char *base =
        "[material a]\nmodel = maugis\nyoungs_modulus = 2 GPa\nadhesion_energy = 20 mJ/m^2\n"
        "[scan]\nsize = 100 nm\npixels = 16\nlines = 3\nline_rate = 80 Hz\nsettle_cycles = 1000\n"
        "channels = height, error, phase, peak_force\n"
        "[surface]\ntype = particles\nparticle_radius = 20 nm\nparticle_count = 1\nseed = 3\n"
        "[tip]\nshape = sphere\nradius = 10 nm\ncontact_geometry = local\n[solver]\ntier = every\n";
    tt_scan_assert_threads_agree(base, "", 4, 0);
}

/* The envelope and averaged tiers key their models on the material: refused, naming the key. */
static void reduced_tiers_refused(void **st)
{
    (void)st;
    tt_expect_scan_refused(slope, "[tip]\ncontact_geometry = local\n[solver]\ntier = envelope\n",
                           "[tip] contact_geometry");
    tt_expect_scan_refused(slope, "[tip]\ncontact_geometry = local\n[solver]\ntier = averaged\n",
                           "expected [solver] tier = every");
}

int main(int argc, char **argv)
{
    if (argc > 1)
        cmocka_set_test_filter(argv[1]);
    const struct CMUnitTest t[] = {
        cmocka_unit_test(flank_presses_as_cos_2_5_of_the_modulus),
        cmocka_unit_test(corner_takes_the_tips_normal),
        cmocka_unit_test(flat_sample_is_the_same),
        cmocka_unit_test(quantisation_within_one_percent),
        cmocka_unit_test(threads_agree),
        cmocka_unit_test(reduced_tiers_refused),
    };
    return cmocka_run_group_tests(t, NULL, NULL);
}
