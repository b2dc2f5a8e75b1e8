/* Sims for tests: a cantilever's sim on a chosen method, tolerance and fixed step. */
#ifndef TT_SIM_TEST_H
#define TT_SIM_TEST_H

#include "tiptap/solver/integrator.h"

/* The sim of cantilever c on solver s (the caller frees it). */
static inline tt_sim *tt_test_sim_of(const tt_cantilever *c, const tt_solver *s)
{
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, c, s), TT_OK);
    return sim;
}

/* The sim of cantilever c on the default method at tolerance tol. */
static inline tt_sim *tt_test_sim(const tt_cantilever *c, double tol)
{
    tt_solver s;
    tt_solver_default(&s);
    s.tolerance = tol;
    return tt_test_sim_of(c, &s);
}

/* The sim of cantilever c on method m at tolerance tol, steps_per_cycle steps a cycle
 * where m takes fixed steps. */
static inline tt_sim *tt_test_sim_on(const tt_cantilever *c, tt_method m, double tol, int steps_per_cycle)
{
    tt_solver s;
    tt_solver_default(&s);
    s.method = m;
    s.tolerance = tol;
    s.steps_per_cycle = steps_per_cycle;
    return tt_test_sim_of(c, &s);
}

#endif
