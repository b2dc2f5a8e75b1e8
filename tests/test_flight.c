/* The free flight (dopri5's exponential steps out of contact): exact on the free
 * oscillator in a few steps per cycle, and on a law with a long-range attraction the
 * same steady cycle as dopri5's own steps (forced by tracking the extremes, which keeps
 * the flight off), near the surface and touching it. */
#include "tt_test.h"
#include "tiptap/util/error.h"
#include "tiptap/solver/integrator.h"

/* An attraction -F a0^2 / (a0 - delta)^2 out of contact (van der Waals-like, F = 1 nN at
 * delta = 0), a cubic repulsion added in contact; contact at delta = 0 both ways. */
typedef struct {
    double F, a0, k3;
} law;

static double law_load(double delta, int in, double *dPdd, void *user)
{
    const law *L = user;
    if (in) {
        double dp = delta > 0 ? delta : 0;
        if (dPdd)
            *dPdd = 3 * L->k3 * dp * dp;
        return L->k3 * dp * dp * dp - L->F;
    }
    double r = L->a0 / (L->a0 - fmin(delta, 0.5 * L->a0));
    if (dPdd)
        *dPdd = -2 * L->F * r * r / (L->a0 - fmin(delta, 0.5 * L->a0));
    return -L->F * r * r;
}

static double law_energy(double delta, int in, void *user)
{
    const law *L = user;
    if (in) {
        double dp = delta > 0 ? delta : 0;
        return 0.25 * L->k3 * dp * dp * dp * dp - L->F * delta - L->F * L->a0;
    }
    return -L->F * L->a0 * L->a0 / (L->a0 - fmin(delta, 0.5 * L->a0));
}

static void free_exact(tt_drive drive, double Q, double fd_ratio)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, Q, 20e-9, 300e3 * fd_ratio, drive), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_cycle cy;
    for (int n = 0; n < 3; n++)
        assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
    /* from the free steady state the flight is the exact solution */
    /* steps of min(T, 2 pi / w0) / 8, the flight's longest */
    double h0 = fmin(c.T, 2 * M_PI / c.w0) / 8;
    if (cy.steps > (long)ceil(c.T / h0) + 1)
        fail_msg("Q %g fd/f0 %g: %ld steps per cycle", Q, fd_ratio, cy.steps);
    assert_close(cy.amplitude, c.A0, 1e-11 * c.A0);
    assert_close(cy.phase, c.phi0, 1e-10);
    double loss = M_PI * c.c * c.wd * c.A0 * c.A0;
    assert_close(cy.e_damp, loss, 1e-10 * loss);
    assert_close(cy.e_drive, loss, 1e-10 * loss);
    tt_sim_free(sim);
}

static void free_oscillator_exact(void **st)
{
    (void)st;
    free_exact(TT_DRIVE_BASE, 400, 1.0);
    free_exact(TT_DRIVE_BASE, 1e4, 0.97);
    free_exact(TT_DRIVE_FORCE, 1, 1.3);
    free_exact(TT_DRIVE_FORCE, 3, 0.5);
}

/* The steady cycle at rest separation gap, with the flight (tol) or without (1e-12). */
static void steady(double gap, int flight, double tol, tt_cycle *out)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 50, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.tolerance = tol;
    static law L = {1e-9, 0.2e-9, 1e20};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc_custom(&ct, law_load, law_energy, &L, 0, 0), TT_OK);
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sim_set_contact(sim, ct, 20);
    tt_sim_set_sample(sim, gap, 0);
    tt_sim_track_extremes(sim, !flight);
    tt_sim_reset_free(sim);
    for (int n = 0; n < 800; n++)
        assert_int_equal(tt_sim_cycle(sim, out), TT_OK);
    tt_sim_free(sim);
    tt_contact_free(ct);
}

static void same_cycle_as_dopri5(void **st)
{
    (void)st;
    /* 25 nm: the attraction pulls at the top without a touch; 18 nm: it taps */
    const double gaps[2] = {25e-9, 18e-9};
    for (int g = 0; g < 2; g++) {
        tt_cycle ref, fl, pl;
        steady(gaps[g], 0, 1e-12, &ref);
        steady(gaps[g], 1, 1e-9, &fl);
        steady(gaps[g], 0, 1e-9, &pl);
        double A = ref.amplitude;
        /* the flight is at least as accurate as dopri5's own steps, with fewer of them */
        double tolA = fmax(3 * fabs(pl.amplitude - A), 1e-9 * A);
        assert_close(fl.amplitude, A, tolA);
        assert_close(fl.phase, ref.phase, fmax(3 * fabs(pl.phase - ref.phase), 1e-8));
        assert_close(fl.e_ts, ref.e_ts, fmax(3 * fabs(pl.e_ts - ref.e_ts), 1e-9 * fabs(ref.e_drive)));
        assert_true(fl.steps < pl.steps);
        assert_true((fl.events > 0) == (g == 1));
        assert_true(fl.events == ref.events);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(free_oscillator_exact),
        cmocka_unit_test(same_cycle_as_dopri5),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
