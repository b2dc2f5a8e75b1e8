/* The free flight (flight.c): exact exponential steps out of contact and away from the
 * surface, a step type of its own that dopri5 holds and lets take the steps it can.
 * Private to libtiptap. */
#ifndef TIPTAP_SOLVER_FLIGHT_H
#define TIPTAP_SOLVER_FLIGHT_H

#include "stepper.h"

typedef struct tt_flight tt_flight;

extern const tt_step_type tt_step_flight;

/* A flight step if the tip is far enough from the surface: TT_STEP_TAKEN or
 * TT_STEP_RETRY, or TT_STEP_PASS when it is the holder's turn. */
int tt_flight_advance(tt_flight *fl, tt_sim *S, double T);
/* Dense output of the current step, a flight step. */
void tt_flight_dense(const tt_flight *fl, const tt_sim *S, double th, double *d, double *v);
/* ... and the system's n components (the law's states exact, exp(A tau)). */
void tt_flight_dense_x(const tt_flight *fl, const tt_sim *S, double th, double *x);

#endif
