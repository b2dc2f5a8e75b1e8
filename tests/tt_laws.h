/* Force laws for tests, given to tt_contact_alloc_custom, and the tapping run the
 * convergence tests share. */
#ifndef TT_LAWS_H
#define TT_LAWS_H

#include "tiptap/util/error.h"
#include "tiptap/solver/integrator.h"

/* A smooth law, P = k3 delta^3 in contact (user points to k3): the solution stays smooth
 * through the contact events, so a method must show its full order, event times
 * included. */
static inline double tt_cubic_load(double delta, int in_contact, double *dPdd, void *user)
{
    (void)in_contact;
    double k3 = *(double *)user;
    if (delta <= 0) {
        if (dPdd)
            *dPdd = 0;
        return 0;
    }
    if (dPdd)
        *dPdd = 3 * k3 * delta * delta;
    return k3 * delta * delta * delta;
}

/* Its potential, dU/ddelta = P. */
static inline double tt_cubic_energy(double delta, int in_contact, void *user)
{
    (void)in_contact;
    double k3 = *(double *)user;
    return delta <= 0 ? 0 : 0.25 * k3 * delta * delta * delta * delta;
}

/* The convergence bench: the standard cantilever (40 N/m, 300 kHz, Q 400, 20 nm, base
 * drive) at 15 nm over ct, 40 cycles from the free steady state (a deterministic map,
 * no settling criterion in the way); the last cycle, and the mean steps per cycle in
 * *spc unless NULL. steps is rk4's, tol the adaptive methods'. */
static inline tt_cycle tt_run_tapping(const tt_contact *ct, double Qi, tt_method m, int steps,
                                      double tol, double *spc)
{
    tt_cantilever c;
    tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE);
    tt_solver s;
    tt_solver_default(&s);
    s.method = m;
    if (steps > 0)
        s.steps_per_cycle = steps;
    s.tolerance = tol > 0 ? tol : s.tolerance;
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sim_set_contact(sim, ct, Qi);
    tt_sim_set_sample(sim, 15e-9, 0);
    tt_cycle cy;
    long total = 0;
    const int n = 40;
    for (int i = 0; i < n; i++) {
        assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
        total += cy.steps;
    }
    if (spc)
        *spc = (double)total / n;
    tt_sim_free(sim);
    return cy;
}

#endif
