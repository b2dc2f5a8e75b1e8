/* How approach moves the sample: a ramp ends at `to` (never past it), steady points are
 * joined by a continuous move that keeps a captured tip captured, and a point that does
 * not settle says why (Burnham et al.'s figure 4a cantilever). */
#include "tt_approach_test.h"

static const char *air =
    "[cantilever]\nspring_constant = 0.58 N/m\nresonance_frequency = 52 kHz\nquality_factor = 40\n"
    "[tip]\nradius = 100 nm\n"
    "[material glass]\nreduced_modulus = 100 GPa\nadhesion_energy = 100 mJ/m^2\n"
    "interatomic_distance = 0.265 nm\ninteraction_quality_factor = 0.2\n";

/* Runs the scene's approach with the given [approach] keys; returns the rows. */
static size_t run(double A0_nm, const char *keys, tt_approach_point *pt, size_t cap, int *alloc_rc)
{
    char text[2048];
    snprintf(text, sizeof text, "%s[approach]\n%s[cantilever]\nfree_amplitude = %g nm\n", air, keys,
             A0_nm);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "air"), TT_OK);
    size_t n = tt_run_approach(s, pt, cap, alloc_rc, NULL);
    tt_scene_free(s);
    return n;
}

/* 40 um/s over 130 nm is 169 cycles at 52 kHz: 171 rows would run the sample past `to`;
 * refused, and 170 rows end exactly at `to`. */
static void ramp_ends_at_to(void **st)
{
    (void)st;
    static tt_approach_point pt[400];
    int arc;
    size_t n = run(150, "mode = ramp\nfrom = 130 nm\nto = 0 nm\nspeed = 40 um/s\npoints = 171\n", pt, 400, &arc);
    assert_int_equal(arc, TT_EINVAL);
    assert_int_equal(n, 0);
    assert_non_null(strstr(tt_error_message(), "[approach] points"));
    n = run(150, "mode = ramp\nfrom = 130 nm\nto = 0 nm\nspeed = 40 um/s\npoints = 170\n", pt, 400, &arc);
    assert_int_equal(arc, TT_OK);
    assert_int_equal(n, 170);
    for (size_t i = 0; i < n; i++)
        assert_true(pt[i].z >= -1e-18 && pt[i].z <= 130e-9 + 1e-18);
    assert_close(pt[n - 1].z, 0, 1e-18);
}

/* Steady points 0.5 m apart would take the sample 5e9 cycles to move between: refused
 * before anything runs, naming the key. */
static void steady_move_too_long_refused(void **st)
{
    (void)st;
    tt_approach_point pt[2];
    int arc;
    size_t n = run(150, "mode = steady\nfrom = 0.5 m\nto = 0 nm\npoints = 2\n", pt, 2, &arc);
    assert_int_equal(arc, TT_EINVAL);
    assert_int_equal(n, 0);
    assert_non_null(strstr(tt_error_message(), "[approach] points"));
}

/* Steady points 5 nm apart: once the tip is captured (in contact all cycle long) no
 * later point of the approach finds it tapping again, since the sample moves to the
 * next point continuously instead of jumping 5 nm under a stuck tip. */
static void captured_stays_captured(void **st)
{
    (void)st;
    static tt_approach_point pt[45];
    int arc;
    size_t n = run(150, "mode = steady\nfrom = 180 nm\nto = -40 nm\npoints = 45\nretract = no\n", pt, 45, &arc);
    assert_int_equal(arc, TT_OK);
    assert_int_equal(n, 45);
    size_t first = n;
    for (size_t i = 0; i < n; i++)
        if (pt[i].cycle.contact_fraction == 1) {
            first = i;
            break;
        }
    assert_true(first < n - 5);
    for (size_t i = first; i < n; i++) {
        assert_close(pt[i].cycle.contact_fraction, 1, 1e-12);
        assert_true(pt[i].cycle.amplitude < 0.05 * 150e-9);
        assert_true(pt[i].cycles > 50); /* the 5 nm move alone is 50 cycles */
    }
}

/* Free amplitude 200 nm, approached in 0.25 nm steps from 20 nm: at 7.25 nm the tip
 * runs a period-4 orbit (amplitude 2.9 to 9.4 nm), found as such: settled, period 4,
 * the row the mean over the 4 cycles. */
static void periodic_point_says_so(void **st)
{
    (void)st;
    static tt_approach_point pt[52];
    int arc;
    size_t n = run(200, "mode = steady\nfrom = 20 nm\nto = 7.25 nm\npoints = 52\nretract = no\n"
                        "max_cycles = 1000\n", pt, 52, &arc);
    assert_int_equal(n, 52);
    const tt_approach_point *last = &pt[51];
    assert_close(last->z, 7.25e-9, 1e-18);
    assert_int_equal(last->settled, 1);
    assert_int_equal(last->period, 4);
    assert_int_equal(last->window, 4);
    assert_true(last->cycles < 1000);
    assert_close(last->amp_min, 2.93e-9, 0.05e-9);
    assert_close(last->amp_max, 9.36e-9, 0.05e-9);
    /* an orbit does not drift: its change is taken over a whole period (over 23 cycles,
     * not a multiple of 4, its phases passed for 0.28 nm per cycle) */
    assert_true(fabs(last->amp_change) < 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(ramp_ends_at_to),
        cmocka_unit_test(steady_move_too_long_refused),
        cmocka_unit_test(captured_stays_captured),
        cmocka_unit_test(periodic_point_says_so),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
