/* Burnham et al.'s experiments: capture by adhesion on the figure-4a cantilever, and tapping
 * in water without adhesion (figure 4b). */
#include "tt_approach_test.h"

static const char *air =
    "[cantilever]\nspring_constant = 0.58 N/m\nresonance_frequency = 52 kHz\nquality_factor = 40\n"
    "free_amplitude = 150 nm\n[tip]\nradius = 100 nm\n"
    "[material glass]\nreduced_modulus = 100 GPa\nadhesion_energy = 100 mJ/m^2\n"
    "interatomic_distance = 0.265 nm\ninteraction_quality_factor = 0.2\n"
    "[approach]\nfrom = 170 nm\nto = -10 nm\npoints = 37\nretract = yes\n";

static void capture_by_adhesion(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, air, "air"), TT_OK);
    tt_approach_point pt[74];
    int arc;
    size_t n = tt_run_approach(s, pt, 74, &arc, NULL);
    assert_int_equal(arc, TT_OK);
    assert_int_equal(n, 74);
    /* free far away: the free amplitude and 90 degrees */
    assert_close(pt[0].cycle.amplitude, 150e-9, 1e-3 * 150e-9);
    assert_close(pt[0].cycle.phase * 180 / M_PI, 90, 0.5);
    assert_close(pt[0].cycle.contact_fraction, 0, 0);
    /* tapping: the amplitude is limited by the separation (Burnham et al.'s regime 2) */
    int tapping = 0;
    for (size_t i = 0; i < 37; i++)
        if (pt[i].cycle.contact_fraction > 0 && pt[i].cycle.contact_fraction < 0.5 && pt[i].z > 20e-9) {
            tapping++;
            assert_close(pt[i].cycle.amplitude, pt[i].z, 0.1 * 150e-9);
        }
    assert_true(tapping > 10);
    /* captured at the end: in contact all cycle long, a small residual amplitude */
    assert_close(pt[36].cycle.contact_fraction, 1, 1e-12);
    assert_true(pt[36].cycle.amplitude < 0.1 * 150e-9);
    /* hysteresis: on the way back the tip is still captured where it tapped before */
    size_t k = 37 + 36 - 25; /* retract row at the separation of approach row 25 */
    assert_close(pt[k].z, pt[25].z, 1e-15);
    assert_true(pt[25].cycle.contact_fraction < 0.5);
    assert_close(pt[k].cycle.contact_fraction, 1, 1e-12);
    tt_scene_free(s);
}

static void tapping_in_water_without_adhesion(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s,
                                          "[cantilever]\nspring_constant = 0.38 N/m\n"
                                          "resonance_frequency = 14.1 kHz\nquality_factor = 3\n"
                                          "free_amplitude = 20 nm\n[tip]\nradius = 20 nm\n"
                                          "[material glass]\nreduced_modulus = 100 GPa\n"
                                          "interaction_quality_factor = 0.03\n",
                                          "water"),
                     TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    assert_false(tt_contact_summary_of(tt_setup_contact(su, 0))->adhesive); /* w = 0: Hertz exactly */
    double prev_phase = 0;
    for (double z = 15e-9; z > -15e-9; z -= 10e-9) {
        tt_sim_reset_free(tt_setup_sim(su));
        tt_sim_set_sample(tt_setup_sim(su), z, 0);
        tt_cycle c;
        int settled;
        long n;
        assert_int_equal(tt_sim_settle(tt_setup_sim(su), 5000, 1e-8, &c, &settled, &n), TT_OK);
        assert_true(settled);
        assert_int_equal(c.events, 2);          /* one touch per cycle, no chatter */
        assert_true(c.contact_fraction > 0);
        /* without adhesion all the loss is interaction damping, and it balances */
        assert_true(c.e_ts > 0);
        assert_close(c.e_drive, c.e_damp + c.e_ts, 1e-5 * c.e_drive);
        /* pressing harder pushes the deflection towards anti-phase (Burnham et al.: pi/2 to pi) */
        assert_true(c.phase > prev_phase);
        prev_phase = c.phase;
    }
    assert_true(prev_phase > 120 * M_PI / 180);
    tt_setup_free(su);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(capture_by_adhesion),
        cmocka_unit_test(tapping_in_water_without_adhesion),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
