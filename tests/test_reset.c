/* A run from the free state is the same whatever the sim did before: scan lines restart
 * from it on whichever thread is free, and the images must not depend on the threads. */
#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/standard.h"

static void history_is_forgotten(tt_method m)
{
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, tt_standard_scene(), "standard"), TT_OK);
    assert_int_equal(tt_scene_set(sc, m == TT_METHOD_RK4 ? "solver.method=rk4"
                                      : m == TT_METHOD_RADAU ? "solver.method=radau"
                                                             : "solver.method=dopri5"),
                     TT_OK);
    tt_setup *a, *b;
    assert_int_equal(tt_setup_alloc(&a, sc), TT_OK);
    assert_int_equal(tt_setup_alloc(&b, sc), TT_OK);
    assert_int_equal(tt_setup_use_material(a, 0), TT_OK);
    assert_int_equal(tt_setup_use_material(b, 0), TT_OK);
    tt_sample sa[32], sb[32];
    tt_sim_set_sampling(tt_setup_sim(a), 32, sa);
    tt_sim_set_sampling(tt_setup_sim(b), 32, sb);
    /* a history for a: tapping on a moving sample, step sizes and caches of its own */
    tt_cycle ca, cb;
    tt_sim_reset_free(tt_setup_sim(a));
    tt_sim_set_sample(tt_setup_sim(a), 12e-9, 1e-4);
    for (int i = 0; i < 300; i++)
        assert_int_equal(tt_sim_cycle(tt_setup_sim(a), &ca), TT_OK);
    tt_sim_reset_free(tt_setup_sim(a));
    tt_sim_reset_free(tt_setup_sim(b));
    for (int i = 0; i < 200; i++) {
        tt_sim_set_sample(tt_setup_sim(a), 16e-9, 0);
        tt_sim_set_sample(tt_setup_sim(b), 16e-9, 0);
        assert_int_equal(tt_sim_cycle(tt_setup_sim(a), &ca), TT_OK);
        assert_int_equal(tt_sim_cycle(tt_setup_sim(b), &cb), TT_OK);
        /* bit for bit: the same steps on the same numbers */
        if (ca.amplitude != cb.amplitude || ca.phase != cb.phase || ca.steps != cb.steps ||
            sa[7].d != sb[7].d)
            fail_msg("%s: cycle %d differs after a history (amplitude %.17g vs %.17g, steps %ld vs %ld)",
                     tt_method_name(m), i, ca.amplitude, cb.amplitude, ca.steps, cb.steps);
    }
    tt_setup_free(a);
    tt_setup_free(b);
    tt_scene_free(sc);
}

static void dopri5_with_free_flight(void **st)
{
    (void)st;
    history_is_forgotten(TT_METHOD_DOPRI5);
}

static void rk4(void **st)
{
    (void)st;
    history_is_forgotten(TT_METHOD_RK4);
}

static void radau(void **st)
{
    (void)st;
    history_is_forgotten(TT_METHOD_RADAU);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(dopri5_with_free_flight),
        cmocka_unit_test(rk4),
        cmocka_unit_test(radau),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
