/* Time traces (tt_trace) on the standard tapping scene: after settling, the recorded
 * cycles are the steady state tt_sim_settle finds; rows advance one drive period each
 * while the sample moves from separation to separation_end; a ramped key runs from its
 * first to its last value; the pressure is the Hertzian mean pressure K a / (pi R).
 * And the [trace] reader: defaults, and a ramp missing an end refused by name. */
#include "tt_test.h"
#include "tiptap/config/read_trace.h"
#include "tiptap/config/standard.h"
#include "tiptap/instrument/trace.h"
#include "tiptap/physics/material.h"
#include "tiptap/util/error.h"

static tt_scene *standard(const char *extra)
{
    tt_scene *s = tt_scene_alloc();
    assert_non_null(s);
    assert_int_equal(tt_scene_load_string(s, tt_standard_scene(), "standard scene"), TT_OK);
    if (extra)
        assert_int_equal(tt_scene_load_string(s, extra, "test"), TT_OK);
    return s;
}

/* A trace on the standard scene with the [trace] keys of extra. */
typedef struct {
    tt_scene *s;
    tt_setup *st;
    tt_trace_params p;
    tt_trace *t;
} run;

static void start(run *r, const char *extra)
{
    r->s = standard(extra);
    assert_int_equal(tt_config_trace(r->s, &r->p), TT_OK);
    assert_int_equal(tt_setup_alloc(&r->st, r->s), TT_OK);
    assert_int_equal(tt_trace_alloc(&r->t, r->st, &r->p), TT_OK);
}

static void stop(run *r)
{
    tt_trace_free(r->t);
    tt_setup_free(r->st);
    tt_scene_free(r->s);
}

static void settled_trace_is_the_steady_state(void **state)
{
    (void)state;
    /* the steady state found directly on the standard scene */
    tt_scene *s = standard(NULL);
    tt_setup *st;
    assert_int_equal(tt_setup_alloc(&st, s), TT_OK);
    assert_int_equal(tt_setup_use_material(st, 0), TT_OK);
    tt_sim_reset_free(tt_setup_sim(st));
    tt_sim_set_sample(tt_setup_sim(st), 16e-9, 0);
    tt_cycle ref;
    int settled;
    long n;
    assert_int_equal(tt_sim_settle(tt_setup_sim(st), 40000, 1e-9, &ref, &settled, &n), TT_OK);
    assert_true(settled);
    print_message("settled after %ld cycles: amplitude %.9g nm, phase %.6f deg\n", n,
                  ref.amplitude * 1e9, ref.phase * 180 / M_PI);
    tt_setup_free(st);

    /* a trace that settles as many cycles, then records five */
    char extra[128];
    snprintf(extra, sizeof extra, "[trace]\nsettle_cycles = %ld\ncycles = 5\nsamples_per_cycle = 32\n", n);
    run r;
    start(&r, extra);
    assert_int_equal(r.p.settle_cycles, n);
    assert_close(r.p.separation_end, r.p.separation, 0);
    tt_trace *t = r.t;
    assert_int_equal(tt_trace_rows(t), 5);
    tt_trace_row row;
    while (!tt_trace_done(t)) {
        assert_int_equal(tt_trace_iterate(t, &row), TT_OK);
        assert_close(row.summary.amplitude, ref.amplitude, 1e-7 * ref.amplitude);
        assert_close(row.summary.phase, ref.phase, 1e-7);
        assert_true(row.summary.contact_fraction > 0); /* it taps */
    }
    assert_int_equal(tt_trace_iterate(t, &row), TT_EINVAL);
    stop(&r);
    tt_scene_free(s);
}

static void rows_advance_and_ramp_reaches_its_end(void **state)
{
    (void)state;
    run r;
    start(&r, "[trace]\nseparation_end = 10 nm\nsettle_cycles = 20\ncycles = 5\n"
              "samples_per_cycle = 20\nramp = material.polymer.adhesion_energy\n"
              "ramp_from = 10 mJ/m^2\nramp_to = 50 mJ/m^2\n");
    assert_close(r.p.ramp_from, 0.010, 1e-15);
    assert_close(r.p.ramp_to, 0.050, 1e-15);
    tt_trace *t = r.t;
    double T = tt_setup_cantilever(r.st)->T, last_t = -1;
    tt_trace_row row;
    long rows = 0;
    while (!tt_trace_done(t)) {
        assert_int_equal(tt_trace_iterate(t, &row), TT_OK);
        assert_int_equal(row.cycle, rows);
        assert_int_equal(row.nsamples, 20);
        /* one drive period per row, after the settling cycles */
        assert_close(row.samples[0].t, (double)(20 + rows) * T, 1e-9 * T);
        for (size_t k = 0; k < row.nsamples; k++) {
            assert_true(row.samples[k].t > last_t);
            last_t = row.samples[k].t;
        }
        /* the sample moves 16 -> 10 nm over the five recorded cycles */
        assert_close(row.samples[0].sample, 16e-9 - 6e-9 * (double)rows / 5, 1e-15);
        assert_close(row.ramp_value, 0.010 + 0.010 * (double)rows, 1e-15);
        rows++;
    }
    assert_int_equal(rows, 5);
    assert_close(row.ramp_value, 0.050, 0);
    /* the scene holds the ramp's end value: later builds see what the sim ran with */
    double w;
    assert_int_equal(tt_scene_get_double(r.s, "material", "polymer", "adhesion_energy", &w), TT_OK);
    assert_close(w, 0.050, 1e-15);
    stop(&r);
}

static void pressure_is_hertzian_mean_pressure(void **state)
{
    (void)state;
    run r;
    start(&r, "[trace]\nsettle_cycles = 200\ncycles = 2\nsamples_per_cycle = 200\n");
    tt_trace *t = r.t;
    tt_contact_params cp = tt_setup_material(r.st, 0)->contact;
    tt_trace_row row;
    int in_contact = 0;
    while (!tt_trace_done(t)) {
        assert_int_equal(tt_trace_iterate(t, &row), TT_OK);
        for (size_t k = 0; k < row.nsamples; k++) {
            const tt_trace_sample *x = &row.samples[k];
            if (!x->contact) {
                assert_close(x->pressure, 0, 0);
                continue;
            }
            in_contact++;
            assert_true(x->contact_radius > 0);
            assert_close(x->pressure, cp.K * x->contact_radius / (M_PI * cp.R), 1e-12 * x->pressure);
            /* a few GPa at most on a 2 GPa polymer under a 10 nm tip */
            assert_between(x->pressure, 0, 5e9);
        }
    }
    assert_true(in_contact > 0);
    stop(&r);
}

static void ramp_without_an_end_is_refused(void **state)
{
    (void)state;
    tt_scene *s = standard("[trace]\nramp = material.polymer.adhesion_energy\nramp_from = 10 mJ/m^2\n");
    tt_trace_params p;
    assert_int_equal(tt_config_trace(s, &p), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "[trace] ramp_to"));
    tt_scene_free(s);
    s = standard("[trace]\nramp = polymer\nramp_from = 1\nramp_to = 2\n");
    assert_int_equal(tt_config_trace(s, &p), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "[trace] ramp"));
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(settled_trace_is_the_steady_state),
        cmocka_unit_test(rows_advance_and_ramp_reaches_its_end),
        cmocka_unit_test(pressure_is_hertzian_mean_pressure),
        cmocka_unit_test(ramp_without_an_end_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
