/* Cooperative cancellation (tiptap/util/cancel.h) reaches into the drive cycle: a cycle
 * asked to stop part way returns TT_EINTR unfinished, and settling, shooting and an
 * approach point return TT_EINTR instead of a result (a Newton cut short is no orbit
 * that failed to converge, a point cut short no unsettled point); after
 * tt_cancel_reset the same sim runs on to the steady point. */
#include <pthread.h>
#include <time.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/standard.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/solver/shooting.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

/* The standard scene (tapping at 16 nm) with extra --set assignments (NULL-ended). */
static tt_setup *standard_setup(tt_scene **scene, const char *const *sets)
{
    tt_scene *s = tt_scene_alloc();
    assert_non_null(s);
    assert_int_equal(tt_scene_load_string(s, tt_standard_scene(), "standard"), TT_OK);
    for (; sets && *sets; sets++)
        assert_int_equal(tt_scene_set(s, *sets), TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_sim_set_sample(tt_setup_sim(su), 16e-9, 0);
    *scene = s;
    return su;
}

static void *request_later(void *arg)
{
    (void)arg;
    struct timespec ts = {0, 100 * 1000 * 1000};
    nanosleep(&ts, NULL);
    tt_cancel_request();
    return NULL;
}

/* rk4 at 1e7 steps a cycle: a second or more of steps; cancelled 0.1 s in, the first
 * cycle returns TT_EINTR and is not counted (polled only between cycles, it would end
 * in TT_OK a second later). */
static void cycle_stops_part_way(void **st)
{
    (void)st;
    const char *sets[] = {"solver.method=rk4", "solver.steps_per_cycle=10000000", NULL};
    tt_scene *s;
    tt_setup *su = standard_setup(&s, sets);
    tt_sim *sim = tt_setup_sim(su);
    tt_sim_reset_free(sim);
    tt_cancel_reset();
    pthread_t th;
    assert_int_equal(pthread_create(&th, NULL, request_later, NULL), 0);
    tt_cycle cy;
    int rc = tt_sim_cycle(sim, &cy);
    pthread_join(th, NULL);
    assert_int_equal(rc, TT_EINTR);
    assert_int_equal(tt_sim_cycles(sim), 0);
    assert_non_null(strstr(tt_error_message(), "interrupted"));
    tt_cancel_reset();
    tt_setup_free(su);
    tt_scene_free(s);
}

/* With cancellation requested every way to a steady point stops with TT_EINTR, none
 * claims a result; after the reset shooting finds the point as usual. */
static void steady_points_return_eintr(void **st)
{
    (void)st;
    tt_scene *s;
    tt_setup *su = standard_setup(&s, NULL);
    tt_sim *sim = tt_setup_sim(su);
    tt_shoot_params p;
    tt_shoot_default(&p);
    tt_shoot_result res;
    tt_cycle cy;
    int settled = -1, converged = -1, iterations;
    long cycles;
    double mr[2], mi[2];

    tt_sim_reset_free(sim);
    tt_cancel_request();
    assert_int_equal(tt_sim_cycle(sim, &cy), TT_EINTR);
    assert_int_equal(tt_sim_settle(sim, 1000, 1e-7, &cy, &settled, &cycles), TT_EINTR);
    assert_int_equal(settled, 0);
    settled = -1;
    assert_int_equal(tt_shoot_steady(sim, &p, 20000, 1e-7, &cy, &settled, &res), TT_EINTR);
    assert_int_equal(settled, 0);
    assert_int_equal(tt_shoot_newton(sim, &p, &converged, &iterations, &cycles), TT_EINTR);
    assert_int_equal(converged, 0);
    assert_int_equal(tt_shoot_multipliers(sim, &p, mr, mi), TT_EINTR);

    tt_approach_params ap;
    assert_int_equal(tt_config_approach(s, &ap), TT_OK);
    ap.points = 2;
    tt_approach *a;
    assert_int_equal(tt_approach_alloc(&a, sim, &ap), TT_OK);
    tt_approach_point pt;
    assert_int_equal(tt_approach_iterate(a, &pt), TT_EINTR);
    tt_approach_free(a);

    tt_cancel_reset();
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 16e-9, 0);
    assert_int_equal(tt_shoot_steady(sim, &p, 20000, 1e-7, &cy, &settled, &res), TT_OK);
    assert_int_equal(settled, 1);
    assert_true(cy.contact_fraction > 0);
    tt_setup_free(su);
    tt_scene_free(s);
}

static void *ask_on_another_thread(void *arg)
{
    *(int *)arg = tt_cancel_requested();
    return NULL;
}

/* A thread's own cancellation (tt_cancel_watch): its runs see it, the other threads do
 * not, and clearing the flag ends it. */
static void a_watched_flag_cancels_its_thread_only(void **st)
{
    (void)st;
    int flag = 0, other = -1;
    assert_null(tt_cancel_watch(&flag));
    assert_false(tt_cancel_requested());
    __atomic_store_n(&flag, 1, __ATOMIC_RELAXED);
    assert_true(tt_cancel_requested());
    pthread_t t;
    assert_int_equal(pthread_create(&t, NULL, ask_on_another_thread, &other), 0);
    pthread_join(t, NULL);
    assert_int_equal(other, 0);
    __atomic_store_n(&flag, 0, __ATOMIC_RELAXED);
    assert_false(tt_cancel_requested());
    assert_ptr_equal(tt_cancel_watch(NULL), &flag);
    __atomic_store_n(&flag, 1, __ATOMIC_RELAXED);
    assert_false(tt_cancel_requested());
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cycle_stops_part_way),
        cmocka_unit_test(steady_points_return_eintr),
        cmocka_unit_test(a_watched_flag_cancels_its_thread_only),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
