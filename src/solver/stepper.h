/* The step-type interface (after GSL's gsl_odeiv2_step_type): one table of functions per
 * method, indexed by tt_method, each type keeping its own state (alloc, reset, free), and
 * the functions the evolve loop (cycle.c, events.c, observe.c) calls on the current step.
 * Private to libtiptap.
 *
 * A step runs from (tau, y) into y1 and fills the data of its continuous extension
 * (dense output); the cycle loop (cycle.c) locates contact events on that extension and
 * takes the step in full or redoes it up to the event (events.c). The evolve loop never
 * reads a type's state: it calls the type's functions with it. */
#ifndef TIPTAP_SOLVER_STEPPER_H
#define TIPTAP_SOLVER_STEPPER_H

#include "sim.h"
#include "tiptap/util/error.h"

/* What a step type's advance did. */
enum {
    TT_STEP_TRIAL, /* a step is in y1: locate events on it, then take it */
    TT_STEP_TAKEN, /* a step is in y1 that meets no event: take it in full */
    TT_STEP_RETRY, /* nothing to take (a rejected step): advance again */
    TT_STEP_END,   /* the cycle's end is reached */
    TT_STEP_PASS   /* not this type's step here: its holder's turn (flight) */
};

struct tt_step_type {
    const char *name;
    /* The type's state for the sim S (its cantilever and solver set); NULL when out of
     * memory. */
    void *(*alloc)(const tt_sim *S);
    void (*free)(void *state);
    /* Forget the step-size controller's memory (a run from the free state). */
    void (*reset)(void *state, const tt_sim *S);
    /* The system changed (cantilever, observations, thermal force): re-plan (NULL:
     * nothing to plan). */
    void (*setup)(void *state, const tt_sim *S);
    /* The state was changed from outside the steps (NULL: nothing kept of it). */
    void (*invalidate)(void *state);
    /* A cycle starts: the time within the cycle runs from 0 again, the last cycle having
     * lasted T (NULL: nothing kept in time). */
    void (*cycle)(void *state, double T);
    /* Try the next step of the cycle [0, T): sets *outcome (TT_STEP_*); a status. */
    int (*advance)(void *state, tt_sim *S, double T, int *outcome);
    /* Redo the current step up to length h, where an event lies; a status. */
    int (*redo)(void *state, tt_sim *S, double h);
    /* The tip's d and v at fraction th of the current step (mode 0's, with one mode). */
    void (*dense)(const void *state, const tt_sim *S, double th, double *d, double *v);
    /* The system's n components at fraction th of the current step (the law's states
     * with the motion), into x. */
    void (*dense_x)(const void *state, const tt_sim *S, double th, double *x);
    /* Make the current step the point (tau, y), of length 0 (its dense output is that
     * state at every fraction; NULL: the record's y0, y1 and derivatives suffice). */
    void (*point)(void *state, const tt_sim *S);
    /* The current step was taken in full (NULL: nothing to keep). */
    void (*accept)(void *state, const tt_sim *S);
};

extern const tt_step_type tt_step_dopri5, tt_step_rk4, tt_step_radau;
/* The method dispatch: tt_step_types[solver.method] (steps.c). */
extern const tt_step_type *const tt_step_types[3];

/* The state was changed from outside the steps: the derivative at it and what the step
 * type kept of the last step no longer describe it. */
static inline void tt_sim_invalidate(tt_sim *S)
{
    S->fsal_ok = 0;
    if (S->type->invalidate)
        S->type->invalidate(S->step);
}

/* The system changed: the step type re-plans. */
static inline void tt_step_setup(tt_sim *S)
{
    if (S->type->setup)
        S->type->setup(S->step, S);
}

/* Dense output of the tip's d and v at fraction th of the current step: mode 0's, plus
 * the further modes' deflections when there are any. */
static inline void tt_step_dense(const tt_sim *S, double th, double *d, double *v)
{
    if (S->sys.modes > 1) {
        double x[TT_SIM_DIM_MAX];
        S->type->dense_x(S->step, S, th, x);
        double dt = x[0], vt = x[1];
        for (int i = 1; i < S->sys.modes; i++) {
            dt += x[2 * i];
            vt += x[2 * i + 1];
        }
        *d = dt;
        *v = vt;
        return;
    }
    S->type->dense(S->step, S, th, d, v);
}

/* Event functions on the dense output (dense.c): penetration past a threshold, and
 * the relative velocity (for turning points). The penetration is the tip's against the
 * surface where it is now, the sample's motion and the law's state together (the
 * system's, tt_system_surface_at); the velocity is against the sample's motion alone,
 * the surface's own recovery being slow next to the tip's. */
static inline double tt_event_delta(const tt_sim *S, double th, double thr)
{
    double d, v;
    tt_step_dense(S, th, &d, &v);
    double g = d - (S->sys.s0 + S->sys.sdot * (S->step_tau + th * S->step_h)) - thr;
    return S->sys.nlaw ? g - tt_system_surface_at(S, th) : g;
}

static inline double tt_event_vel(const tt_sim *S, double th)
{
    double d, v;
    tt_step_dense(S, th, &d, &v);
    return v - S->sys.sdot;
}

/* A dense-output polynomial of the n components (five coefficients, dopri5's or
 * radau's) that is the constant y: a step of length 0. */
static inline void tt_poly_point(double p[5][TT_SIM_DIM_MAX], const double *y, int n)
{
    for (int i = 0; i < n; i++) {
        p[0][i] = y[i];
        p[1][i] = p[2][i] = p[3][i] = p[4][i] = 0;
    }
}

/* The zero of an event function (which = 0: penetration minus thr, 1: relative
 * velocity) on [a, b] of the current step (dense.c). */
double tt_event_root(const tt_sim *S, int which, double thr, double a, double b, double fa,
                     double fb);

/* Contact events (events.c). */
double tt_event_find(const tt_sim *S);
int tt_event_take(tt_sim *S, double th);

/* The cycle's bookkeeping over the part [0, th] of the current step (observe.c). */
void tt_observe(tt_sim *S, double th);
/* The sample at the cycle start (k = 0), before any step. */
void tt_observe_start(tt_sim *S);

#endif
