/* The contact laws' small-contact bound (contact radius <= 0.5 R, indentation <= R) and
 * the scan's record of how far each material's contact went: a soft material under a
 * 1 nm tip goes far past it (29 nm deep), stiff ones under a 10 nm tip stay within.
 * The record is Hertz's a = sqrt(R delta) for a non-adhesive material, the same on one
 * thread and on two, and absent when no channel tracks the peaks. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/physics/contact.h"

static void the_bound(void **st)
{
    (void)st;
    const double R = 10e-9;
    assert_false(tt_contact_beyond_validity(0.49 * R, 0.2 * R, R));
    assert_true(tt_contact_beyond_validity(0.51 * R, 0.2 * R, R));
    assert_true(tt_contact_beyond_validity(0.2 * R, 1.01 * R, R));
    assert_false(tt_contact_beyond_validity(NAN, NAN, R)); /* no contact */
}

/* Two materials in stripes on a flat sample: soft (50 MPa, no adhesion: Hertz) and
 * stiff (100 GPa). */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n[material soft]\nyoungs_modulus = 50 MPa\n"
    "[material stiff]\nreduced_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 16\nlines = 2\nline_rate = 200 Hz\nsettle_cycles = 1000\n"
    "channels = height, indentation\n[feedback]\nsetpoint = 50 %\nintegral_gain = 3000 Hz\n"
    "[surface]\nmap = stripes\nmap_period = 500 nm\nmap_duty = 50 %\n";

static void soft_under_a_sharp_tip(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, "[tip]\nradius = 1 nm\nshape = sphere\n", &sc);
    assert_int_equal(tt_scan_materials(s), 2);
    assert_string_equal(tt_scan_material_name(s, 0), "soft");
    tt_contact_extent e[2];
    int beyond[2];
    for (size_t i = 0; i < 2; i++) {
        beyond[i] = tt_scan_contact_extent(s, i, &e[i]);
        print_message("%s: indentation %.3f nm, contact radius %.3f nm, tip %.1f nm%s\n",
                      tt_scan_material_name(s, i), e[i].indentation * 1e9, e[i].radius * 1e9,
                      e[i].tip_radius * 1e9, beyond[i] ? ": beyond" : "");
    }
    assert_true(beyond[0]);
    assert_close(e[0].tip_radius, 1e-9, 1e-21);
    assert_true(e[0].indentation > 1e-9); /* buried past the apex sphere's equator */
    /* Hertz: the contact radius of a paraboloid pressed delta deep */
    assert_close(e[0].radius, sqrt(e[0].tip_radius * e[0].indentation), 1e-6 * e[0].radius);
    /* the same on one thread: the greatest of all lines, whichever thread ran them */
    tt_scan *one;
    assert_int_equal(tt_config_scan_alloc(&one, sc), TT_OK);
    assert_int_equal(tt_scan_run(one, 1, NULL, NULL), TT_OK);
    for (size_t i = 0; i < 2; i++) {
        tt_contact_extent f;
        assert_int_equal(tt_scan_contact_extent(one, i, &f), beyond[i]);
        assert_true(f.indentation == e[i].indentation);
    }
    tt_scan_free(one);
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void stiff_under_a_blunt_tip(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, "[tip]\nradius = 10 nm\n[material soft]\n"
                                   "youngs_modulus = 200 GPa\n", &sc);
    for (size_t i = 0; i < 2; i++) {
        tt_contact_extent e;
        int beyond = tt_scan_contact_extent(s, i, &e);
        print_message("both stiff, R = 10 nm: indentation %.4f nm, contact radius %.3f nm\n",
                      e.indentation * 1e9, e.radius * 1e9);
        assert_false(beyond);
        assert_true(e.indentation > 0 && e.radius < 0.5 * e.tip_radius);
    }
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void untracked_without_the_channels(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, "[tip]\nradius = 1 nm\n[scan]\nchannels = height, phase\n", &sc);
    tt_contact_extent e;
    assert_false(tt_scan_contact_extent(s, 0, &e));
    assert_true(isnan(e.indentation));
    tt_scan_free(s);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(the_bound),
        cmocka_unit_test(soft_under_a_sharp_tip),
        cmocka_unit_test(stiff_under_a_blunt_tip),
        cmocka_unit_test(untracked_without_the_channels),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
