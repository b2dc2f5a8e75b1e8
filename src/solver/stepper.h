/* The stepper interface (after GSL's gsl_odeiv2_step_type): one table of functions per
 * method, indexed by tt_method, and the internal functions the solver's files share.
 * Private to libtiptap.
 *
 * A step runs from (tau, y) into y1 and fills the data of its continuous extension
 * (dense output); the cycle loop (cycle.c) locates contact events on that extension and
 * takes the step in full or redoes it up to the event (events.c). */
#ifndef TIPTAP_SOLVER_STEPPER_H
#define TIPTAP_SOLVER_STEPPER_H

#include "sim.h"
#include "tiptap/util/error.h"

/* What a step type's advance did. */
enum {
    TT_STEP_TRIAL, /* a step is in y1: locate events on it, then take it */
    TT_STEP_TAKEN, /* a step is in y1 that meets no event: take it in full */
    TT_STEP_RETRY, /* nothing to take (a rejected step): advance again */
    TT_STEP_END    /* the cycle's end is reached */
};

struct tt_step_type {
    const char *name;
    /* Try the next step of the cycle [0, T): sets *outcome (TT_STEP_*); a status. */
    int (*advance)(tt_sim *S, double T, int *outcome);
    /* One step of length h from (tau, y): the scaled error (<= 1 accepts; 0 for fixed
     * steps). */
    double (*apply)(tt_sim *S, double h);
    /* The next step's length over this one's, from apply's error (adaptive types). */
    double (*factor)(const tt_sim *S, double err);
    /* Redo the current step up to length h, where an event lies; a status (NULL: apply
     * does). */
    int (*redo)(tt_sim *S, double h);
    /* d and v at fraction th of the current step. */
    void (*dense)(const tt_sim *S, double th, double *d, double *v);
    /* The current step was taken in full (NULL: nothing to keep). */
    void (*accept)(tt_sim *S);
    /* Forget the step-size controller's memory (a run from the free state). */
    void (*reset)(tt_sim *S);
};

extern const tt_step_type tt_step_dopri5, tt_step_rk4, tt_step_radau;
/* The method dispatch: tt_step_types[solver.method]. */
extern const tt_step_type *const tt_step_types[3];

/* The step-size factor after a rejected first step of a contact. The contact branch of
 * an adhesive law starts at its fold, where the force rises like the square root of the
 * penetration, and the error of a step from there grows only about like h^2 (measured:
 * h^2.1 on the standard scene) rather than h^5: the usual 0.9 err^(-1/5) took three or
 * four rejections per contact to find the step, 0.9 err^(-1/2) takes one. */
static inline double tt_touch_factor(double err)
{
    double fac = 0.9 / sqrt(err);
    return fac < 0.2 ? 0.2 : fac;
}

/* The step-size control of the adaptive step types (dopri5, radau): a step of the
 * length the controller chose, rejected and retried shorter while its error exceeds 1.
 * Inline, with the caller's own type, so that its step and factor are direct calls. */
static inline int tt_step_adaptive(tt_sim *S, double T, const tt_step_type *type, int *outcome)
{
    const double hmin = T * 1e-13;
    double h = S->h;
    if (h > T / 8)
        h = T / 8; /* keeps turning points of a cycle within reach of the checks */
    if (h > S->radau_hmax)
        h = S->radau_hmax;
    int last = 0;
    if (S->nz_f) {
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
    double err = type->apply(S, h);
    double fac = type->factor(S, err);
    if (fac > 5)
        fac = 5;
    if (fac < 0.2)
        fac = 0.2;
    S->last_rejected = err > 1;
    if (err > 1) {
        S->rejected++;
        if (S->touch_first)
            fac = tt_touch_factor(err);
        S->h = h * fac;
        if (S->h < hmin)
            return tt_error(TT_ENUM,
                            "step size underflow at t = %.9g s (cycle %ld): the force law is "
                            "too abrupt for tolerance %g",
                            tt_sim_time(S) + S->tau, S->cycle, S->solver.tolerance);
        *outcome = TT_STEP_RETRY;
        return TT_OK;
    }
    if (!last || fac < 1)
        S->h = h * fac;
    S->touch_first = 0;
    *outcome = TT_STEP_TRIAL;
    return TT_OK;
}

/* The free flight (flight.c): exact steps out of contact, for dopri5. */
void tt_flight_setup(tt_sim *S);
void tt_flight_reset(tt_sim *S);
/* A flight step if the tip is far enough from the surface: TT_STEP_TAKEN or
 * TT_STEP_RETRY, or -1 when it is dopri5's turn. */
int tt_flight_advance(tt_sim *S, double T);
void tt_flight_dense(const tt_sim *S, double th, double *d, double *v);

/* Dense output of d and v at fraction th of the current step. */
static inline void tt_step_dense(const tt_sim *S, double th, double *d, double *v)
{
    if (S->step_flight)
        tt_flight_dense(S, th, d, v);
    else
        S->type->dense(S, th, d, v);
}

/* Event functions on the dense output (events.c): penetration past a threshold, and
 * the relative velocity (for turning points). */
static inline double tt_event_delta(const tt_sim *S, double th, double thr)
{
    double d, v;
    tt_step_dense(S, th, &d, &v);
    return d - (S->s0 + S->sdot * (S->step_tau + th * S->step_h)) - thr;
}

static inline double tt_event_vel(const tt_sim *S, double th)
{
    double d, v;
    tt_step_dense(S, th, &d, &v);
    return v - S->sdot;
}

double tt_event_root(const tt_sim *S, int which, double thr, double a, double b, double fa,
                     double fb);
double tt_event_find(const tt_sim *S);
int tt_event_take(tt_sim *S, double th);

/* The cycle's bookkeeping over the part [0, th] of the current step (observe.c). */
void tt_observe(tt_sim *S, double th);
/* The sample at the cycle start (k = 0), before any step. */
void tt_observe_start(tt_sim *S);

/* Take the current step (already computed into y1) in full (cycle.c). */
void tt_step_accept(tt_sim *S);

#endif
