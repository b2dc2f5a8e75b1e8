/* The envelope tier's kept models (tiptap/solver/envelope.h; docs/dynamics.md, "Noise on
 * the envelope tier", Kept models): a model switched to predicts from its own anchor, the
 * cycle its build integrated, exactly there; its second-order prediction of a cycle from
 * a state r away errs as r^3 (halving r cuts the error about eight times); a switch takes
 * the nearest kept model within reach that has the anchor's contact, touch and tag, and
 * none beyond it (the present model then stays as it was); a full store replaces the
 * model unused the longest and still finds the others; a place is worth a model the
 * second time the state misses near it. On the standard cantilever tapping a 3 GPa
 * adhesive sample. */
#include <math.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/util/error.h"

enum { NS = 32 };

typedef struct {
    tt_cantilever c;
    tt_sim *sim;
    tt_contact *ct;
    tt_envelope *e;
    tt_sample smp[NS];
    double *obs;
    double x0[2], s; /* the steady tapping cycle's start, the sample mid-cycle */
    int c0;
} fixture;

static void fixture_init(fixture *f, int keep)
{
    assert_int_equal(tt_cantilever_init(&f->c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.tolerance = 1e-12; /* the integration's error far below the model's */
    assert_int_equal(tt_sim_alloc(&f->sim, &f->c, &s), TT_OK);
    tt_contact_params p = {TT_CONTACT_MAUGIS, 3e9, 10e-9, 0.04, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    assert_int_equal(tt_contact_alloc(&f->ct, &p), TT_OK);
    tt_sim_set_sampling(f->sim, NS, f->smp);
    tt_sim_reset_free(f->sim);
    tt_sim_set_contact(f->sim, f->ct, 2);
    f->s = 15e-9;
    tt_sim_set_sample(f->sim, f->s, 0);
    tt_cycle cy;
    for (int i = 0; i < 600; i++)
        assert_int_equal(tt_sim_cycle(f->sim, &cy), TT_OK);
    assert_true(cy.events > 0); /* it taps */
    tt_sim_get_state(f->sim, &f->x0[0], &f->x0[1], &f->c0);
    double R[NS];
    for (int q = 0; q < NS; q++)
        R[q] = 1.0 / NS;
    const tt_envelope_params plan = {.samples = NS, .reduced = 1, .reduce = R,
                                     .second_order = 1, .kept = keep};
    assert_int_equal(tt_envelope_alloc(&f->e, f->sim, &plan), TT_OK);
    f->obs = malloc(2 * (size_t)tt_envelope_size(f->e) * sizeof *f->obs);
    assert_non_null(f->obs);
}

static void fixture_free(fixture *f)
{
    free(f->obs);
    tt_envelope_free(f->e);
    tt_contact_free(f->ct);
    tt_sim_free(f->sim);
}

/* The steady cycle's start moved by (dd, dv) in units of A0 and w A0. */
static void offset(const fixture *f, double dd, double dv, double x[2])
{
    x[0] = f->x0[0] + dd * f->c.A0;
    x[1] = f->x0[1] + dv * f->c.wd * f->c.A0;
}

/* One cycle integrated from x with the sample at s (still): its end state. */
static tt_cycle integrate(fixture *f, const double x[2], double s, double x1[2])
{
    tt_cycle cy;
    tt_sim_set_state(f->sim, x[0], x[1], f->c0);
    tt_sim_set_sample(f->sim, s, 0);
    assert_int_equal(tt_sim_cycle(f->sim, &cy), TT_OK);
    int c1;
    tt_sim_get_state(f->sim, &x1[0], &x1[1], &c1);
    return cy;
}

/* A model built on the cycle from x and kept under tag. */
static void build_keep(fixture *f, const double x[2], double s, int tag)
{
    double x1[2];
    tt_cycle cy = integrate(f, x, s, x1);
    tt_envelope_observe(f->e, f->smp, NULL, &cy, f->obs);
    long jac = 0;
    assert_int_equal(tt_envelope_build(f->e, f->sim, x, f->c0, s, 0, &cy, f->obs, &jac),
                     TT_ENV_USABLE);
    tt_envelope_keep(f->e, tag);
}

/* The present model's end state from x, over A0 away from the integrated one's. */
static double model_error(fixture *f, const double x[2], double s)
{
    const double x2[2] = {0, 0};
    double xm[2], x21[2], xi[2];
    tt_envelope_predict(f->e, TT_ENV_ALL, x, x2, s, 0, xm, x21, f->obs);
    integrate(f, x, s, xi);
    return fmax(fabs(xm[0] - xi[0]) / f->c.A0, fabs(xm[1] - xi[1]) / (f->c.wd * f->c.A0));
}

/* A store of 8 with models of material 0 kept at the steady cycle's start (xa) and db of
 * A0 from it along d (xb), the present one. */
static void two_models(fixture *f, double db, double xa[2], double xb[2])
{
    fixture_init(f, 8);
    offset(f, 0, 0, xa);
    offset(f, db, 0, xb);
    build_keep(f, xa, f->s, 0);
    build_keep(f, xb, f->s, 0);
}

static void switch_predicts_from_its_anchor(void **st)
{
    (void)st;
    fixture f;
    double xa[2], xb[2], x[2];
    two_models(&f, 4e-3, xa, xb);
    /* from 1e-3 of A0 off xa, the model built there, anchored on its own cycle */
    offset(&f, 1e-3, 0, x);
    assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 0, 3e-3), 1);
    assert_true(fabs(tt_envelope_model_reach(f.e, x, f.s, 0) - 1e-3) < 1e-9);
    const double at = model_error(&f, xa, f.s);
    print_message("error at the anchor after a switch: %.3g of A0\n", at);
    assert_true(at < 1e-12); /* the integration's own repeatability: its first step
                              * follows the last cycle's */
    /* the second-order error grows with the cube of the distance along d (central
     * differences: no lower-order term of their own) */
    double err[3];
    const double r[3] = {2e-3, 4e-3, 8e-3};
    for (int i = 0; i < 3; i++) {
        offset(&f, -r[i], 0, x);
        err[i] = model_error(&f, x, f.s);
    }
    print_message("error at 2, 4, 8e-3 of A0 from the anchor: %.3g %.3g %.3g (ratios %.2f %.2f)\n",
                  err[0], err[1], err[2], err[1] / err[0], err[2] / err[1]);
    assert_true(err[2] / err[1] > 5 && err[2] / err[1] < 11);
    assert_true(err[1] / err[0] > 5 && err[1] / err[0] < 11);
    fixture_free(&f);
}

static void switch_takes_the_nearest_of_its_kind(void **st)
{
    (void)st;
    fixture f;
    double xa[2], xb[2], x[2];
    two_models(&f, 5e-3, xa, xb);
    build_keep(&f, xa, f.s, 1);  /* the same place, another material */
    build_keep(&f, xa, 1e-6, 0); /* the same state with the sample far: free, untouched */
    build_keep(&f, xb, f.s, 0);  /* back to a touching model of material 0, at xb */
    offset(&f, 1.5e-3, 0, x);
    assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 0, 3e-3), 1);
    assert_true(fabs(tt_envelope_model_reach(f.e, x, f.s, 0) - 1.5e-3) < 1e-9);
    assert_int_equal(tt_envelope_anchor_touched(f.e), 1);
    offset(&f, 3.6e-3, 0, x); /* nearer xb */
    assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 0, 3e-3), 1);
    assert_true(fabs(tt_envelope_model_reach(f.e, x, f.s, 0) - 1.4e-3) < 1e-9);
    /* beyond reach of all: none, and the model stays xb's */
    offset(&f, 2.5e-3, 0, x);
    assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 0, 2e-3), 0);
    assert_true(fabs(tt_envelope_model_reach(f.e, x, f.s, 0) - 2.5e-3) < 1e-9);
    /* the other material's model at xa */
    offset(&f, 1e-3, 0, x);
    assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 1, 3e-3), 1);
    assert_true(fabs(tt_envelope_model_reach(f.e, x, f.s, 0) - 1e-3) < 1e-9);
    /* the sample's offset counts: 2e-3 of A0 away in s, xa's model is 2e-3 away */
    offset(&f, 0, 0, x);
    assert_int_equal(tt_envelope_switch(f.e, x, f.s + 2e-3 * f.c.A0, 0, 0, 3e-3), 1);
    assert_true(fabs(tt_envelope_model_reach(f.e, x, f.s + 2e-3 * f.c.A0, 0) - 2e-3) < 1e-9);
    fixture_free(&f);
}

static void full_store_replaces_the_oldest(void **st)
{
    (void)st;
    fixture f;
    fixture_init(&f, 3);
    double x[2];
    for (int i = 0; i < 3; i++) {
        offset(&f, 2e-3 * i, 0, x);
        build_keep(&f, x, f.s, 0);
    }
    offset(&f, 0, 0, x);
    assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 0, 5e-4), 1); /* uses the first */
    offset(&f, 6e-3, 0, x);
    build_keep(&f, x, f.s, 0); /* replaces the second (2e-3), unused the longest */
    const double want[5] = {1, 0, 1, 1, 0};
    for (int i = 0; i < 5; i++) {
        offset(&f, 2e-3 * i, 0, x);
        assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 0, 5e-4), want[i]);
    }
    /* a new line forgets them all */
    tt_envelope_reset(f.e);
    offset(&f, 0, 0, x);
    assert_int_equal(tt_envelope_switch(f.e, x, f.s, 0, 0, 5e-4), 0);
    fixture_free(&f);
}

static void revisit_on_the_second_miss(void **st)
{
    (void)st;
    fixture f;
    fixture_init(&f, 4);
    double x[2];
    offset(&f, 0, 0, x);
    assert_int_equal(tt_envelope_revisit(f.e, x, f.s, 0, 0, 1e-3), 0);
    assert_int_equal(tt_envelope_revisit(f.e, x, f.s, 0, 1, 1e-3), 0); /* another material */
    offset(&f, 2e-3, 0, x);
    assert_int_equal(tt_envelope_revisit(f.e, x, f.s, 0, 0, 1e-3), 0); /* too far */
    offset(&f, 5e-4, 5e-4, x);
    assert_int_equal(tt_envelope_revisit(f.e, x, f.s, 0, 0, 1e-3), 1);
    assert_int_equal(tt_envelope_revisit(f.e, x, f.s, 0, 1, 1e-3), 1);
    tt_envelope_reset(f.e);
    assert_int_equal(tt_envelope_revisit(f.e, x, f.s, 0, 0, 1e-3), 0);
    fixture_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(switch_predicts_from_its_anchor),
        cmocka_unit_test(switch_takes_the_nearest_of_its_kind),
        cmocka_unit_test(full_store_replaces_the_oldest),
        cmocka_unit_test(revisit_on_the_second_miss),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
