/* Step-size control of the adaptive step types (dopri5, radau), after GSL's
 * gsl_odeiv2_control: a step of the length the controller chose, rejected and retried
 * shorter while its error exceeds 1. An object of its own, held by the step type that
 * uses it. Private to libtiptap. */
#ifndef TIPTAP_SOLVER_CONTROL_H
#define TIPTAP_SOLVER_CONTROL_H

#include "stepper.h"
#include "tiptap/util/error.h"

typedef struct {
    double h;          /* the next step's length */
    double hmax;       /* the longest step (INFINITY: none) */
    int last_rejected; /* the last step was rejected */
} tt_step_control;

/* The controller's memory forgotten: the first step T / 64. */
static inline void tt_control_reset(tt_step_control *C, double T)
{
    C->h = T / 64;
    C->last_rejected = 0;
}

/* One try at the next step of the cycle [0, T): apply(state, S, h) gives the step's
 * scaled error and factor(state, err) the next step's length over this one's. Inline,
 * with the caller's own functions, so that they are direct calls. */
static inline int tt_control_advance(tt_step_control *C, void *state, tt_sim *S, double T,
                                     double (*apply)(void *, tt_sim *, double),
                                     double (*factor)(const void *, double), int *outcome)
{
    const double hmin = T * 1e-13;
    double h = C->h;
    if (h > T / 8)
        h = T / 8; /* keeps turning points of a cycle within reach of the checks */
    if (h > C->hmax)
        h = C->hmax;
    int last = 0;
    if (S->sys.nz_f) {
        /* steps end on the thermal force's points, where its slope changes */
        double tk = tt_noise_next_knot(S, hmin);
        if (S->tau + h > tk - hmin) {
            h = tk - S->tau;
            last = 1; /* a step cut short does not shorten the next */
        }
    }
    if (S->tau + h >= T - hmin) {
        h = T - S->tau;
        last = 1;
    }
    double err = apply(state, S, h);
    double fac = factor(state, err);
    if (fac > 5)
        fac = 5;
    if (fac < 0.2)
        fac = 0.2;
    C->last_rejected = err > 1;
    if (err > 1) {
        S->rejected++;
        C->h = h * fac;
        if (C->h < hmin)
            return tt_error(TT_ENUM,
                            "step size underflow at t = %.9g s (cycle %ld): the force law is "
                            "too abrupt for tolerance %g",
                            sim_time(S, S->tau), S->cycle, S->solver.tolerance);
        *outcome = TT_STEP_RETRY;
        return TT_OK;
    }
    if (!last || fac < 1)
        C->h = h * fac;
    *outcome = TT_STEP_TRIAL;
    return TT_OK;
}

#endif
