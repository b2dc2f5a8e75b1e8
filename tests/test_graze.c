/* The grazing model (tiptap/solver/graze.h) on paths and maps whose answers are known:
 * the branch and the time of jump-in of a tip whose path near its closest approach is
 * a parabola (t_c = t* - sqrt(2 e / a) for a reach e past jump-in), and the touch
 * branch's fit of a map linear in the state and the sample and cubic in t_c, which it
 * must reproduce to rounding within the range of its touches and refuse to follow far
 * outside it. The scan on a grazing sample: tests/test_envelope.c. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/solver/graze.h"
#include "tiptap/util/error.h"

enum { M = 6 }; /* reduced observables in these tests */

typedef struct {
    tt_cantilever c;
    tt_sim *sim;
    tt_graze *g;
    double tstar, jumpin;
} fixture;

/* A graze model on the standard cantilever, its probes aimed at a closest approach at
 * 0.31 T (from samples of a cosine path), jump-in at -0.8 nm. */
static void setup(fixture *f)
{
    tt_solver sv;
    tt_solver_default(&sv);
    assert_int_equal(tt_cantilever_init(&f->c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    assert_int_equal(tt_sim_alloc(&f->sim, &f->c, &sv), TT_OK);
    double scale[M], floor[M];
    for (int i = 0; i < M; i++) {
        scale[i] = f->c.A0;
        floor[i] = 0;
    }
    assert_int_equal(tt_graze_alloc(&f->g, f->sim, M, scale, floor), TT_OK);
    f->jumpin = -0.8e-9;
    tt_graze_reset(f->g, f->jumpin);
    f->tstar = 0.31 * f->c.T;
    tt_sample smp[32];
    for (int q = 0; q < 32; q++) {
        double t = f->c.T * q / 32;
        smp[q].s = 0;
        smp[q].d = 16e-9 * cos(f->c.wd * (t - f->tstar));
    }
    assert_int_equal(tt_graze_aim(f->g, f->sim, smp, 32), 1);
    assert_non_null(tt_sim_probes(f->sim));
}

static void teardown(fixture *f)
{
    tt_graze_free(f->g);
    tt_sim_free(f->sim);
}

/* The tip's positions at the probes for a parabola reaching e past jump-in at t0, the
 * sample at s0 at rest: d - s0 = jumpin + e - a (t - t0)^2 / 2. */
static void parabola(const fixture *f, double e, double t0, double a, double s0, double *d)
{
    for (int i = 0; i < TT_GRAZE_PROBES; i++) {
        double u = tt_graze_probe_time(f->g, i) - t0;
        d[i] = s0 + f->jumpin + e - 0.5 * a * u * u;
    }
}

static void branch_of_a_parabola(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    const double A = 16e-9, a = A * f.c.wd * f.c.wd, T = f.c.T;
    double d[TT_GRAZE_PROBES], tc, reach;
    /* a reach of 1e-3 A0 and 3e-2 A0 past jump-in: a touch, at the analytic time */
    for (int k = 0; k < 2; k++) {
        const double e = (k ? 3e-2 : 1e-3) * f.c.A0;
        parabola(&f, e, f.tstar, a, 5e-9, d);
        assert_int_equal(tt_graze_branch(f.g, d, 5e-9, 0, &tc, &reach), TT_GRAZE_TOUCH);
        assert_close(tc / T, (f.tstar - sqrt(2 * e / a)) / T, 1e-9);
        assert_close(reach, f.jumpin + e, 1e-6 * e);
    }
    /* short of jump-in by 1e-3 A0: free, its closest approach the greatest indentation */
    parabola(&f, -1e-3 * f.c.A0, f.tstar, a, 5e-9, d);
    assert_int_equal(tt_graze_branch(f.g, d, 5e-9, 0, &tc, &reach), TT_GRAZE_FREE);
    assert_close(reach, f.jumpin - 1e-3 * f.c.A0, 1e-15);
    assert_close(tc / T, f.tstar / T, 1e-9);
    /* within the margin (2e-6 A0) either way: too close to call */
    for (int sgn = -1; sgn <= 1; sgn += 2) {
        parabola(&f, sgn * 1e-6 * f.c.A0, f.tstar, a, 5e-9, d);
        assert_int_equal(tt_graze_branch(f.g, d, 5e-9, 0, &tc, &reach), TT_GRAZE_UNSURE);
    }
    /* a closest approach outside the probes (the phase moved by a tenth of a cycle) */
    parabola(&f, 1e-3 * f.c.A0, f.tstar + 0.1 * T, a, 5e-9, d);
    assert_int_equal(tt_graze_branch(f.g, d, 5e-9, 0, &tc, &reach), TT_GRAZE_UNSURE);
    /* a moving sample: the gap is taken at each probe's own time */
    parabola(&f, 1e-3 * f.c.A0, f.tstar, a, 5e-9, d);
    const double sdot = 1e-6; /* m/s: 3.3 pm a cycle */
    for (int i = 0; i < TT_GRAZE_PROBES; i++)
        d[i] += sdot * tt_graze_probe_time(f.g, i);
    assert_int_equal(tt_graze_branch(f.g, d, 5e-9, sdot, &tc, &reach), TT_GRAZE_TOUCH);
    assert_close(tc / T, (f.tstar - sqrt(2 * 1e-3 * f.c.A0 / a)) / T, 1e-9);
    teardown(&f);
}

/* A map linear in (d, d', s) and cubic in t_c, in units of the free amplitude. */
static void map(const fixture *f, const double x[2], double s, double tc, double x1[2],
                double *red)
{
    const double L = f->c.A0, V = f->c.wd * f->c.A0, u = (tc - f->tstar) / (0.01 * f->c.T);
    double y[2 + M];
    for (int o = 0; o < 2 + M; o++)
        y[o] = L * (0.1 * o - 0.3 * x[0] / L + 0.2 * (o % 3) * x[1] / V + 0.7 * s / L +
                    0.05 * o * u - 0.01 * u * u + 0.002 * (o + 1) * u * u * u);
    x1[0] = y[0];
    x1[1] = y[1] * f->c.wd;
    for (int o = 0; o < M; o++)
        red[o] = y[2 + o];
}

static void fit_reproduces_a_smooth_map(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    const double L = f.c.A0, V = f.c.wd * L, T = f.c.T, s0 = 16e-9;
    double x1[2], red[M], p1[2], pr[M];
    /* twelve touches spread over 3e-3 A0 in d and d', 2e-4 A0 in s and 0.007 T in t_c */
    for (int i = 0; i < 12; i++) {
        const double x[2] = {L * (-0.3 + 3e-3 * sin(1.3 * i)), V * (0.7 + 3e-3 * cos(2.1 * i))};
        const double s = s0 + 2e-4 * L * sin(0.7 * i), tc = f.tstar - 0.007 * T * (i % 5) / 4;
        map(&f, x, s, tc, x1, red);
        tt_graze_add(f.g, x, s, tc, x1, red);
    }
    assert_int_equal(tt_graze_fit(f.g, 1e-9), 0); /* no star yet */
    double xd[2], sd;
    assert_int_equal(tt_graze_deepest(f.g, xd, &sd), 1);
    for (int i = 0; i < 6; i++) {
        double x[2] = {xd[0], xd[1]}, s = sd, h[3] = {1e-4 * L, 1e-4 * V, 1e-4 * L};
        double *in[3] = {&x[0], &x[1], &s};
        *in[i / 2] += i % 2 ? h[i / 2] : -h[i / 2];
        const double tc = f.tstar - 0.007 * T + 1e-4 * T * (i - 2.5);
        map(&f, x, s, tc, x1, red);
        tt_graze_add_pair(f.g, i, x, s, tc, x1, red);
    }
    assert_int_equal(tt_graze_fit(f.g, 1e-9), 1);
    /* inside the touches' ranges: the map to rounding */
    const double x[2] = {L * -0.299, V * 0.7005};
    const double s = s0 + 1e-4 * L, tc = f.tstar - 0.003 * T;
    assert_int_equal(tt_graze_covers(f.g, x, s, tc), 1);
    map(&f, x, s, tc, x1, red);
    tt_graze_predict(f.g, x, s, tc, p1, pr);
    assert_close(p1[0] / L, x1[0] / L, 1e-12);
    assert_close(p1[1] / V, x1[1] / V, 1e-12);
    for (int o = 0; o < M; o++)
        assert_close(pr[o] / L, red[o] / L, 1e-12);
    /* outside: t_c past the latest touch by a third of their spread, the sample 2e-3 A0
     * from them, the state 1e-2 A0 away */
    assert_int_equal(tt_graze_covers(f.g, x, s, f.tstar + 0.003 * T), 0);
    assert_int_equal(tt_graze_covers(f.g, x, s + 3e-3 * L, tc), 0);
    const double far[2] = {x[0] + 1e-2 * L, x[1]};
    assert_int_equal(tt_graze_covers(f.g, far, s, tc), 0);
    teardown(&f);
}

/* A map the fit's form cannot hold (a step in t_c) is refused, and the last good fit
 * stays in use. */
static void a_bad_fit_is_refused(void **st)
{
    (void)st;
    fixture f;
    setup(&f);
    const double L = f.c.A0, V = f.c.wd * L, T = f.c.T, s0 = 16e-9;
    double x1[2], red[M];
    for (int i = 0; i < 14; i++) {
        const double x[2] = {L * (-0.3 + 3e-3 * sin(1.3 * i)), V * (0.7 + 3e-3 * cos(2.1 * i))};
        const double s = s0 + 2e-4 * L * sin(0.7 * i), tc = f.tstar - 0.007 * T * (i % 5) / 4;
        map(&f, x, s, tc, x1, red);
        if (i >= 12)
            red[0] += 1e-6 * L * (i % 2 ? 1 : -1);
        if (i < 12 || i == 13)
            tt_graze_add(f.g, x, s, tc, x1, red);
    }
    double xd[2], sd;
    assert_int_equal(tt_graze_deepest(f.g, xd, &sd), 1);
    for (int i = 0; i < 6; i++) {
        double x[2] = {xd[0] + (i == 0 ? 1e-4 * L : 0), xd[1] + (i == 2 ? 1e-4 * V : 0)};
        double s = sd + (i == 4 ? 1e-4 * L : i == 5 ? -1e-4 * L : 0);
        const double tc = f.tstar - 0.005 * T + 1e-4 * T * i;
        map(&f, x, s, tc, x1, red);
        tt_graze_add_pair(f.g, i, x, s, tc, x1, red);
    }
    assert_int_equal(tt_graze_fit(f.g, 1e-9), 0);
    assert_int_equal(tt_graze_fitted(f.g), 0);
    teardown(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(branch_of_a_parabola),
        cmocka_unit_test(fit_reproduces_a_smooth_map),
        cmocka_unit_test(a_bad_fit_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
