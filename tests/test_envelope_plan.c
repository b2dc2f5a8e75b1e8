/* The envelope tier's plan (tiptap/solver/envelope.h): every allocation happens at
 * tt_envelope_alloc, and each one that fails is reported as out of memory (TT_ENOMEM,
 * "out of memory ..."), with nothing leaked and no handle returned; a plan out of range
 * is TT_EINVAL; once planned, a build and a prediction allocate nothing; a build's
 * outcome names what it made of the model (usable; off the anchor's branch; a cycle that
 * failed). The library's calls to malloc and calloc go through this file's wrappers
 * (-Wl,--wrap, CMakeLists.txt), which fail the k-th of them once armed. The grazing
 * map's allocation likewise. The generic kernels of the prediction (any n) give one
 * mode's specialised ones bit for bit. On the standard cantilever out of contact and
 * tapping. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/solver/graze.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "solver/envelope_private.h"

void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t size);
void *__wrap_malloc(size_t n);
void *__wrap_calloc(size_t n, size_t size);

/* armed: the allocations counted since, and their bytes; fail_at: the one (0-based)
 * that fails (-1: none) */
static int armed;
static long calls, fail_at = -1;
static double bytes;

static int fails(size_t n)
{
    if (!armed)
        return 0;
    bytes += (double)n;
    return calls++ == fail_at;
}

void *__wrap_malloc(size_t n) { return fails(n) ? NULL : __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t size) { return fails(n * size) ? NULL : __real_calloc(n, size); }

static void arm(long at)
{
    calls = 0;
    bytes = 0;
    fail_at = at;
    armed = 1;
}

static long disarm(void)
{
    armed = 0;
    return calls;
}

enum { NS = 32 };

typedef struct {
    tt_cantilever c;
    tt_sim *sim;
    tt_sample smp[NS];
    double R[2 * NS];
} fixture;

static void setup(fixture *f)
{
    assert_int_equal(tt_cantilever_init(&f->c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    assert_int_equal(tt_sim_alloc(&f->sim, &f->c, &s), TT_OK);
    tt_sim_set_sampling(f->sim, NS, f->smp);
    tt_sim_reset_free(f->sim);
    tt_sim_set_sample(f->sim, 1e-6, 0); /* a micrometre away: no force */
    for (int q = 0; q < NS; q++) { /* the fundamental's two components */
        f->R[q] = cos(2 * M_PI * q / NS) * 2.0 / NS;
        f->R[NS + q] = sin(2 * M_PI * q / NS) * 2.0 / NS;
    }
}

/* A plan with every part: probes, a reduction, the travel, second order, kept models,
 * thermal and detector noise. */
static tt_envelope_params full_plan(const fixture *f)
{
    tt_envelope_params p = {0};
    p.samples = NS;
    p.probes = TT_GRAZE_PROBES;
    p.reduced = 2;
    p.reduce = f->R;
    p.travel = 1;
    p.second_order = 1;
    p.kept = 3;
    p.psd = 2 * f->c.c * 1.380649e-23 * 300;
    p.sd = 1e-12;
    return p;
}

/* Every allocation of the plan failed in turn: each is TT_ENOMEM, says so, and returns
 * no handle (a leak would show under the sanitizer); past the last one the plan is
 * made. */
static void every_failed_allocation_is_out_of_memory(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    const tt_envelope_params p = full_plan(&f);
    arm(-1);
    tt_envelope *e = NULL;
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_OK);
    const long n = disarm();
    tt_envelope_free(e);
    print_message("the full plan makes %ld allocations\n", n);
    assert_true(n >= 10);
    for (long k = 0; k < n; k++) {
        arm(k);
        e = (tt_envelope *)&f; /* must be cleared */
        const int rc = tt_envelope_alloc(&e, f.sim, &p);
        disarm();
        assert_int_equal(rc, TT_ENOMEM);
        assert_null(e);
        assert_non_null(strstr(tt_error_message(), "out of memory"));
        tt_error_clear();
    }
    /* the grazing map's */
    double scale[4] = {1, 1, 1, 1}, floor[4] = {0};
    tt_graze *g = NULL;
    arm(-1);
    assert_int_equal(tt_graze_alloc(&g, f.sim, 4, scale, floor), TT_OK);
    const long ng = disarm();
    tt_graze_free(g);
    for (long k = 0; k < ng; k++) {
        arm(k);
        const int rc = tt_graze_alloc(&g, f.sim, 4, scale, floor);
        disarm();
        assert_int_equal(rc, TT_ENOMEM);
        assert_null(g);
        tt_error_clear();
    }
    tt_sim_free(f.sim);
}

/* The plan's bytes as a scan's memory estimate counts them (tt_envelope_plan_bytes)
 * against what tt_envelope_alloc allocates, at one mode's state and with an arm's state
 * after it, noise on and the scan's 512 kept models (3.5 MB and more a plan): within
 * 1 %. */
static void plan_bytes_counted(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    tt_envelope_params p = full_plan(&f);
    p.kept = 512;
    for (int dim = 2; dim <= 3; dim++) {
        p.dim = dim;
        tt_envelope *e = NULL;
        arm(-1);
        assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_OK);
        disarm();
        const double est = tt_envelope_plan_bytes(&p);
        print_message("a plan of %d components: %.0f bytes allocated, %.0f estimated\n", dim,
                      bytes, est);
        assert_true(bytes > 3.5e6);
        assert_close(est, bytes, 0.01 * bytes);
        tt_envelope_free(e);
    }
    tt_sim_free(f.sim);
}

/* A plan out of range is refused before anything is allocated, naming what it needs. */
static void a_plan_out_of_range_is_einval(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    tt_envelope *e = NULL;
    tt_envelope_params p = {0};
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_EINVAL); /* no samples */
    assert_non_null(strstr(tt_error_message(), "samples"));
    p.samples = NS;
    p.sd = 1e-12; /* detector noise needs the reduced samples it falls on */
    arm(-1);
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_EINVAL);
    assert_int_equal(disarm(), 0);
    assert_null(e);
    assert_non_null(strstr(tt_error_message(), "detector"));
    p.sd = 0;
    p.reduced = 2; /* rows promised, none given */
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_EINVAL);
    p.reduced = 0;
    p.dim = TT_SIM_DIM_MAX + 1; /* a law's states past what a state holds */
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "components"));
    p.dim = 3; /* a plan for an arm's state, the thermal noise on it too */
    p.psd = 1e-30;
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_OK);
    assert_int_equal(tt_envelope_noise_size(e), 3);
    tt_envelope_free(e);
    tt_error_clear();
    tt_sim_free(f.sim);
}

/* Planned, the model builds, predicts, keeps, recalls and resets with no allocation (a
 * failing allocator armed throughout: the sim's cycles need none either), and a free
 * cycle's model predicts the next integrated cycle's state and lock-in components to
 * the integrator's tolerance. */
static void planned_model_allocates_nothing(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    const tt_envelope_params p = full_plan(&f);
    tt_envelope *e;
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_OK);
    const int no = tt_envelope_size(e);
    assert_int_equal(no, NS + TT_ENV_EXTRA + TT_GRAZE_PROBES);
    assert_int_equal(tt_envelope_noise_size(e), 2 + 2);
    double *obs = malloc(3 * (size_t)no * sizeof *obs), *pred = obs + no, *red = pred + no;
    assert_non_null(obs);
    tt_cycle cy;
    for (int i = 0; i < 3000; i++) /* settle (Q 400) */
        assert_int_equal(tt_sim_cycle(f.sim, &cy), TT_OK);
    double x0[2], x1[2], xp[2], xp2[2], x2[2] = {0, 0};
    int c0, c1;
    tt_sim_get_x(f.sim, x0, &c0);
    arm(0); /* the first allocation would fail */
    assert_int_equal(tt_sim_cycle(f.sim, &cy), TT_OK);
    tt_envelope_observe(e, f.smp, tt_sim_probes(f.sim), &cy, obs);
    long jac = 0;
    assert_int_equal(tt_envelope_build(e, f.sim, x0, c0, 1e-6, 0, &cy, obs, &jac), TT_ENV_USABLE);
    /* 2 (n + 2) first differences and one per pair of the 4 inputs */
    assert_int_equal(jac, 2 * 4 + 6);
    tt_envelope_keep(e, 0);
    tt_sim_get_x(f.sim, x1, &c1);
    /* a state off the orbit by 1e-3 of A0 in d and d' */
    const double xq[2] = {x1[0] + 1e-3 * f.c.A0, x1[1] - 1e-3 * f.c.wd * f.c.A0};
    tt_envelope_predict(e, TT_ENV_ALL, xq, x2, 1e-6, 0, xp, xp2, pred);
    tt_envelope_reduce_obs(e, pred, red);
    tt_sim_set_x(f.sim, xq, c1);
    assert_int_equal(tt_sim_cycle(f.sim, &cy), TT_OK);
    tt_envelope_observe(e, f.smp, tt_sim_probes(f.sim), &cy, obs);
    double xi[2];
    tt_sim_get_x(f.sim, xi, &c1);
    const double err = tt_envelope_error(e, TT_ENV_ALL, xp, pred, xi, obs);
    assert_true(tt_envelope_recall(e, x1, 1e-6, 0, c0, 0, 0, 1e-2));
    tt_envelope_reset(e);
    assert_false(tt_envelope_switch(e, x1, 1e-6, 0, 0, 1e-2)); /* forgotten */
    assert_int_equal(disarm(), 0);
    /* the state and the lock-in's components to the integrator's tolerance (the
     * observables' error, a greatest indentation whose time moves, is held on its own
     * looser scale) */
    double ri[2 + TT_ENV_EXTRA + TT_GRAZE_PROBES];
    tt_envelope_reduce_obs(e, obs, ri);
    double xerr = fmax(fabs(xp[0] - xi[0]) / f.c.A0, fabs(xp[1] - xi[1]) / (f.c.wd * f.c.A0));
    for (int i = 0; i < 2; i++)
        xerr = fmax(xerr, fabs(red[i] - ri[i]) / f.c.A0);
    print_message("a free cycle's prediction errs by %.2e of A0 (%.2e in the scaled observables)\n",
                  xerr, err);
    assert_true(xerr < 1e-7);
    assert_true(err < 1e-4);
    free(obs);
    tt_envelope_free(e);
    tt_sim_free(f.sim);
}

/* The outcomes: a build whose anchor cycle claims a touch that its perturbed cycles do
 * not make is off the branch; one whose cycles are cancelled failed; each has a name. */
static void build_outcomes(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    const tt_envelope_params p = {.samples = NS, .reduced = 2, .reduce = f.R};
    tt_envelope *e;
    assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_OK);
    double *obs = malloc((size_t)tt_envelope_size(e) * sizeof *obs);
    assert_non_null(obs);
    double x0[2];
    int c0;
    tt_sim_get_x(f.sim, x0, &c0);
    tt_cycle cy;
    assert_int_equal(tt_sim_cycle(f.sim, &cy), TT_OK);
    tt_envelope_observe(e, f.smp, NULL, &cy, obs);
    long jac = 0;
    tt_cycle touch = cy;
    touch.events = 2;
    assert_int_equal(tt_envelope_build(e, f.sim, x0, c0, 1e-6, 0, &touch, obs, &jac),
                     TT_ENV_OFF_BRANCH);
    tt_cancel_request();
    assert_int_equal(tt_envelope_build(e, f.sim, x0, c0, 1e-6, 0, &cy, obs, &jac),
                     TT_ENV_CYCLE_FAILED);
    tt_cancel_reset();
    assert_int_equal(tt_envelope_build(e, f.sim, x0, c0, 1e-6, 0, &cy, obs, &jac), TT_ENV_USABLE);
    const char *seen[TT_ENV_OUTCOMES];
    for (int o = 0; o < TT_ENV_OUTCOMES; o++) {
        seen[o] = tt_envelope_outcome_name((tt_envelope_outcome)o);
        assert_string_not_equal(seen[o], "?");
        for (int k = 0; k < o; k++)
            assert_string_not_equal(seen[o], seen[k]);
    }
    assert_string_equal(tt_envelope_outcome_name(TT_ENV_OUTCOMES), "?");
    free(obs);
    tt_envelope_free(e);
    tt_sim_free(f.sim);
}

/* The prediction's generic kernels (any n) against one mode's written-out ones, bit for
 * bit, in every view, to first and second order, with and without the travel: on a
 * tapping cycle's model (second order, thermal noise) from states and samples about it. */
static void generic_kernels_equal_specialised(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    tt_contact_params cp = {TT_CONTACT_MAUGIS, 3e9, 10e-9, 0.04, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &cp), TT_OK);
    tt_sim_set_contact(f.sim, ct, 2);
    const double s = 15e-9;
    tt_sim_set_sample(f.sim, s, 0);
    tt_cycle cy;
    for (int i = 0; i < 600; i++)
        assert_int_equal(tt_sim_cycle(f.sim, &cy), TT_OK);
    assert_true(cy.events > 0); /* it taps */
    for (int travel = 0; travel < 2; travel++) {
        tt_envelope_params p = full_plan(&f);
        p.travel = travel;
        p.probes = 0;
        tt_envelope *e;
        assert_int_equal(tt_envelope_alloc(&e, f.sim, &p), TT_OK);
        const int no = tt_envelope_size(e);
        double *obs = malloc(4 * (size_t)no * sizeof *obs), *a = obs + no, *b = a + no;
        assert_non_null(obs);
        double x0[2], xa[2], xb[2], x21a[2], x21b[2];
        int c0;
        tt_sim_get_x(f.sim, x0, &c0);
        assert_int_equal(tt_sim_cycle(f.sim, &cy), TT_OK);
        tt_envelope_observe(e, f.smp, NULL, &cy, obs);
        long jac = 0;
        assert_int_equal(tt_envelope_build(e, f.sim, x0, c0, s, 0, &cy, obs, &jac),
                         TT_ENV_USABLE);
        int compared = 0;
        /* offsets as large as the terms they are added to (a kernel's order of summation
         * shows in the last bits), not where the model holds: this compares arithmetic */
        for (int k = 0; k < 125; k++) {
            const double w0 = 0.37 * (k % 5 - 2), w1 = 0.29 * (k / 5 % 5 - 2), w2 = 0.23 * (k / 25 - 2);
            const double x[2] = {x0[0] * (1 + w0) + w1 * f.c.A0, x0[1] * (1 - w1) + w2 * f.c.wd * f.c.A0};
            const double x2[2] = {1e-2 * w2 * f.c.A0, -3e-2 * w0 * f.c.wd * f.c.A0};
            const double sk = s * (1 + w2) + w0 * f.c.A0, sdot = 1e-3 * w1;
            for (int view = TT_ENV_ALL; view <= TT_ENV_REDUCED; view++)
                for (int order = 1; order <= 2; order++) {
                    const double *x2p = order == 2 ? x2 : NULL;
                    memset(a, 0, 2 * (size_t)no * sizeof *a);
                    e->generic = 0;
                    tt_envelope_predict(e, (tt_envelope_view)view, x, x2p, sk, sdot, xa, x21a, a);
                    e->generic = 1;
                    tt_envelope_predict(e, (tt_envelope_view)view, x, x2p, sk, sdot, xb, x21b, b);
                    assert_memory_equal(xa, xb, sizeof xa);
                    assert_memory_equal(a, b, (size_t)no * sizeof *a);
                    if (x2p)
                        assert_memory_equal(x21a, x21b, sizeof x21a);
                    compared++;
                }
        }
        assert_int_equal(compared, 125 * 4);
        free(obs);
        tt_envelope_free(e);
    }
    tt_contact_free(ct);
    tt_sim_free(f.sim);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_failed_allocation_is_out_of_memory),
        cmocka_unit_test(plan_bytes_counted),
        cmocka_unit_test(a_plan_out_of_range_is_einval),
        cmocka_unit_test(planned_model_allocates_nothing),
        cmocka_unit_test(build_outcomes),
        cmocka_unit_test(generic_kernels_equal_specialised),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
