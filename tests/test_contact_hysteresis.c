/* The hysteresis loop of jump-in and pull-off: its energy equals an independent
 * quadrature of the area between the approach and retract branches. */
#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

static double simpson(const tt_contact *c, int in, double a, double b)
{
    int n = 20000;
    double h = (b - a) / n, s = 0;
    for (int i = 0; i <= n; i++) {
        double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        s += w * tt_contact_load(c, a + i * h, in, NULL, NULL);
    }
    return s * h / 3;
}

static void loop_energy_is_the_area(void **st)
{
    (void)st;
    double lams[] = {1.5, 5, 50, 500};
    for (size_t i = 0; i < 4; i++) {
        tt_contact *c;
        assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, lams[i], 0.3), TT_OK);
        const tt_contact_summary *s = tt_contact_summary_of(c);
        assert_true(s->hysteresis);
        /* area = integral over [jumpout, jumpin] of (approach load - retract load):
         * approaching on the van der Waals branch, retracting on the contact branch */
        double area = simpson(c, 0, s->jumpout_delta, s->jumpin_delta) -
                      simpson(c, 1, s->jumpout_delta, s->jumpin_delta);
        print_message("lambda %g: loop %.9f, quadrature %.9f\n", lams[i], s->loop_energy, area);
        assert_true(area > 0);
        assert_close(s->loop_energy, area, 1e-5 * area);
        tt_contact_free(c);
    }
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, 0.5, 0.3), TT_OK);
    assert_close(tt_contact_summary_of(c)->loop_energy, 0, 0);
    tt_contact_free(c);
}

static void branches_continue_past_their_ends(void **st)
{
    (void)st;
    /* stages of a step overshoot the switch points: the branches must stay finite and
     * continuous a little beyond them */
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, 5, 0.3), TT_OK);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    double d0 = s->jumpout_delta;
    double in = tt_contact_load(c, d0, 1, NULL, NULL), below = tt_contact_load(c, d0 - 1e-6, 1, NULL, NULL);
    assert_true(isfinite(below));
    assert_close(below, in, 1e-2);
    double j = s->jumpin_delta;
    double v = tt_contact_load(c, j, 0, NULL, NULL), past = tt_contact_load(c, j + 1e-3, 0, NULL, NULL);
    assert_true(isfinite(past));
    assert_close(past, v, 1e-1 * fabs(v) + 1e-6);
    assert_true(isfinite(tt_contact_load(c, 50, 0, NULL, NULL))); /* far past the pole */
    tt_contact_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(loop_energy_is_the_area),
        cmocka_unit_test(branches_continue_past_their_ends),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
