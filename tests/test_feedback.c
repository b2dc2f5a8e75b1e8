/* The PI loop on a plant whose amplitude is limited by the gap (A = min(A0, gap)). */
#include "tt_test.h"
#include "tiptap/instrument/feedback.h"

/* Run the loop against a surface at height h; returns the final amplitude error. */
static double run(tt_feedback *f, double h, int steps, double dt, double *zmin, double *zmax)
{
    double A = 0;
    *zmin = INFINITY;
    *zmax = -INFINITY;
    for (int i = 0; i < steps; i++) {
        double gap = 16e-9 - h + f->z;
        A = fmin(20e-9, fmax(gap, 0));
        tt_feedback_update(f, A, dt);
        if (i > steps / 2) {
            *zmin = fmin(*zmin, f->z);
            *zmax = fmax(*zmax, f->z);
        }
    }
    return A - f->setpoint;
}

static void integral_action_removes_the_error(void **st)
{
    (void)st;
    tt_feedback f;
    double lo, hi;
    tt_feedback_init(&f, &(tt_feedback_params){.setpoint = 15e-9, .kp = 0, .ki = 2000, .z_range = 2e-6}, 0);
    double e = run(&f, 3e-9, 4000, 1e-5, &lo, &hi);
    assert_close(e, 0, 1e-15);
    assert_close(f.z, 3e-9 - 1e-9, 1e-15); /* z tracks the surface */
    /* proportional control alone leaves an error */
    tt_feedback_init(&f, &(tt_feedback_params){.setpoint = 15e-9, .kp = 0.5, .ki = 0, .z_range = 2e-6}, 0);
    e = run(&f, 3e-9, 4000, 1e-5, &lo, &hi);
    assert_true(fabs(e) > 0.5e-9);
}

static void clamp_and_anti_windup(void **st)
{
    (void)st;
    tt_feedback f;
    double lo, hi;
    /* a surface 50 nm high with 20 nm of range: z sits at its limit */
    tt_feedback_init(&f, &(tt_feedback_params){.setpoint = 15e-9, .kp = 0, .ki = 2000, .z_range = 20e-9}, 0);
    run(&f, 50e-9, 2000, 1e-5, &lo, &hi);
    assert_close(f.z, 10e-9, 0);
    assert_true(f.clamped);
    /* back within range: recovery within a few loop time constants, no wound-up integral */
    run(&f, 0, 300, 1e-5, &lo, &hi); /* 3 ms = 6 time constants */
    assert_close(f.z, -1e-9, 0.1e-9); /* a wound-up integral would hold z at the stop */
    assert_false(f.clamped);
}

static void too_much_gain_oscillates(void **st)
{
    (void)st;
    tt_feedback f;
    double lo, hi;
    /* the discrete loop is stable for ki dt < 2 */
    tt_feedback_init(&f, &(tt_feedback_params){.setpoint = 15e-9, .kp = 0, .ki = 1.5e5, .z_range = 2e-6}, 0);
    run(&f, 3e-9, 2000, 1e-5, &lo, &hi);
    assert_true(hi - lo < 1e-15);
    tt_feedback_init(&f, &(tt_feedback_params){.setpoint = 15e-9, .kp = 0, .ki = 2.5e5, .z_range = 2e-6}, 0);
    run(&f, 3e-9, 2000, 1e-5, &lo, &hi);
    assert_true(hi - lo > 1e-9);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(integral_action_removes_the_error),
        cmocka_unit_test(clamp_and_anti_windup),
        cmocka_unit_test(too_much_gain_oscillates),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
