/* rk4 on a very stiff contact (K = 1 TPa under a 0.1 N/m cantilever, no adhesion): too few
 * steps per cycle are refused at the first tap with the contact stiffness, never a NaN, a
 * hang or a wrong number. Before the fix the stiffness was checked only at the start of a
 * step in contact, where the Hertz onset is soft, so a step entering the contact (and,
 * without adhesion, a step merely grazing it out of contact) went unstable unchecked:
 * 32 steps ended in NaN, 64 in "no progress" after 50 million events, 16 and 128 in a
 * refusal cycles later quoting a stiffness of 1e12 N/m from the wrecked state. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/config/setup.h"

static const char *stiff =
    "[cantilever]\nspring_constant = 0.1 N/m\nresonance_frequency = 10 kHz\nquality_factor = 30\n"
    "free_amplitude = 10 nm\n[tip]\nradius = 10 nm\n"
    "[material diamond]\nreduced_modulus = 1 TPa\nadhesion_energy = 0 J/m^2\n";

/* Run up to 5 cycles from the free oscillation at rest separation z; return the status of
 * the first failing cycle (TT_OK if none), how many cycles completed and the contact
 * events of those. */
static int run(int steps, double z, int *done, tt_cycle *last, long *events)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, stiff, "stiff"), TT_OK);
    char set[64];
    snprintf(set, sizeof set, "solver.steps_per_cycle=%d", steps);
    assert_int_equal(tt_scene_set(s, "solver.method=rk4"), TT_OK);
    assert_int_equal(tt_scene_set(s, set), TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_sim_reset_free(tt_setup_sim(su));
    tt_sim_set_sample(tt_setup_sim(su), z, 0);
    int rc = TT_OK;
    *events = 0;
    for (*done = 0; *done < 5; (*done)++) {
        if ((rc = tt_sim_cycle(tt_setup_sim(su), last)))
            break;
        *events += last->events;
    }
    tt_setup_free(su);
    tt_scene_free(s);
    return rc;
}

static void too_few_steps_are_refused_at_the_first_tap(void **st)
{
    (void)st;
    const int counts[] = {16, 32, 64, 128};
    for (size_t i = 0; i < sizeof counts / sizeof counts[0]; i++) {
        int done;
        long events;
        tt_cycle c;
        int rc = run(counts[i], 8e-9, &done, &c, &events);
        const char *msg = tt_error_message();
        print_message("%4d steps: %s\n", counts[i], rc ? msg : "ran");
        assert_int_equal(rc, TT_ENUM);
        assert_int_equal(done, 0);
        const char *p = strstr(msg, "contact stiffness ");
        assert_non_null(p);
        /* the stiffness of this tap (about 1e3 N/m), not of a state gone astray */
        double k = strtod(p + strlen("contact stiffness "), NULL);
        assert_between(k, 100, 1e4);
        const char *need = strstr(msg, "needs at least ");
        assert_non_null(need);
        assert_true(strtol(need + strlen("needs at least "), NULL, 10) > counts[i]);
    }
}

static void enough_steps_run(void **st)
{
    (void)st;
    int done;
    long events;
    tt_cycle c;
    assert_int_equal(run(512, 8e-9, &done, &c, &events), TT_OK);
    assert_true(events > 0);
    assert_true(c.residual_rel < 1e-3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(too_few_steps_are_refused_at_the_first_tap),
        cmocka_unit_test(enough_steps_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
