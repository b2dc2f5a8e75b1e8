/* The envelope tier's line (scan_envelope.c) and its grazing mode (scan_envelope_graze.c):
 * the controller they share. */
#ifndef TIPTAP_SCAN_ENVELOPE_PRIVATE_H
#define TIPTAP_SCAN_ENVELOPE_PRIVATE_H

#include <math.h>
#include <string.h>

#include "scan_private.h"
#include "tiptap/util/error.h"

enum {
    M_MIN = 4,       /* a stretch's first length, and the least after a failure */
    M_MAX = 1024,    /* its longest: the checks then cost about a thousandth of the cycles */
    WAIT_MIN = 16,   /* quiet integrated cycles before the model is tried */
    WAIT_MAX = 128, /* the same after repeated failures (doubling) */
    BOUND_MAX = 64  /* the most the sample's bound and the reach grow by (1.3 nm and
                     * 3.8 nm on the standard cantilever) */
};

/* A point the line can return to: its state after a cycle, the lock-in's filter, the
 * block's samples so far and the sums of the pixels the next stretch can touch. */
typedef struct {
    line_state st;
    int contact;
    long p0, p1; /* saved pixels, p0 <= p1 (none: p0 > p1) */
    pixel_acc *pix;
    double *indent; /* the worker's greatest indentations (per material) */
} snapshot;

/* The last branch called in the grazing mode and its inputs (valid while the models
 * are unchanged). */
typedef struct {
    double x[TT_SIM_DIM_MAX], s0, sdot, tc, reach;
    int b, ok, valid;
} lookahead;

/* How a check closing a stretch came out (scan_envelope.c's check, and the grazing
 * mode's). */
typedef enum {
    CHECK_FAILED = 0,      /* the stretch does not stand, or the run was cancelled */
    CHECK_PASSED = 1,      /* it stands: the model re-anchored, or built there */
    CHECK_EXACT = 2,       /* a cycle from an integrated state: nothing to check */
    CHECK_MODEL_OFF = 3    /* it stands, but the model built there is unusable: the model
                            * is off until one is built anew */
} check_outcome;

/* The tier's controller within a phase. */
typedef struct {
    int model;       /* the model runs; else every cycle is integrated */
    long left;       /* model cycles before the stretch's check */
    long ran;        /* model cycles run in the stretch so far */
    long m;          /* the next stretch's length */
    long quiet, wait; /* integrated cycles without a change of contact or surface; needed */
    long redo;       /* integrate every cycle up to this one (a rolled-back stretch) */
    int prev_touch;
    int rebuild;     /* the Jacobians must be taken anew before the model runs */
    int fails;       /* failed shortest stretches since a check passed (noise on) */
    int graze;       /* the tip grazes: a model per branch (graze.h), the free one built
                      * with probes (free_ok) and the touch one fitted */
    int free_ok;
    int prev_branch; /* the last integrated cycle could be on a branch of the grazing model */
    int bounded;     /* the stretch was ended by the sample's bound or the reach */
    int exact;       /* the tip's state is an integrated cycle's end (no model cycle since) */
    long same;       /* integrated cycles in a row on the last one's branch (grazing) */
    lookahead la;
    double *red, *pred; /* a check's reduced observables and their prediction */
    double bound;    /* the second-order model's bounds on the sample's travel and its
                      * reach, as multiples of L->edge and L->reach: grown where the
                      * checks pass well within their allowance, shrunk where one fails */
    double smooth;   /* the sample's smooth course (its position mid-cycle less the z
                      * piezo's noise) where the model was last anchored on a cycle */
    snapshot sn;
    long integrated; /* cycles of the run integrated, each once */
    char *seen;      /* the phase's cycles integrated so far: a cycle integrated again
                      * (rolled back, a failed check) or a Jacobian's is not counted */
    long nseen;
} controller;

/* The sample's position mid-cycle, the envelope model's input. */
static inline double sample_mid(const cycle_in *in)
{
    return 0.5 * (in->sa + in->sb);
}

/* Integrate cycle k from the sim's state: its observables and end state (st->x). */
static inline int tt_scan_env_integrate(const line_ctx *L, line_state *st, const cycle_in *in, tt_cycle *cy,
                     double *obs, int *c1, controller *c)
{
    tt_sim *sim = L->W->sim;
    int rc = tt_scan_integrate(L, st, in, cy);
    if (rc)
        return rc;
    c->la.valid = 0; /* the models may change on this cycle */
    if (in->k >= 0 && in->k < c->nseen && !c->seen[in->k]) {
        c->seen[in->k] = 1;
        c->integrated++;
    }
    tt_envelope_observe(L->W->env, tt_sim_samples(sim), tt_sim_probes(sim), cy, obs);
    tt_sim_get_x(sim, st->x, c1);
    memset(st->x2, 0, sizeof st->x2);
    return TT_OK;
}

/* How much more than its last cycle's a stretch of m model cycles can drift, past what
 * the checks were measured to hold (docs/dynamics.md, "Any Q"): each cycle's local
 * error is carried on, damped over Q / pi cycles, so a stretch's drift is its check's
 * error times min(m, Q / pi). The tier's control was measured up to Q 3000 with the
 * check alone; above it (a vacuum cantilever's Q 1e4 and more, whose transients last
 * the whole line) the check is tightened to the drift of the standard cantilever's
 * stretches (Q 400: 127 cycles), so that no stretch drifts further than those do. */
static inline double tt_scan_env_drift(const line_ctx *L, long m)
{
    const double Q = L->S->cantilever.Q, held = 400 / M_PI;
    const double n = fmin((double)m, Q / M_PI);
    return Q > 3000 && n > held ? n / held : 1;
}

/* The grazing mode (scan_envelope_graze.c): whether it may run; a cycle on one of its
 * branches; leaving it; a cycle integrated in it while the model is off; a model cycle
 * in it; the check closing a stretch in it (as scan_envelope.c's check). */
int tt_scan_graze_possible(const line_ctx *L, const line_state *st);
int tt_scan_on_branch(const tt_cycle *cy, int c0, int c1);
void tt_scan_graze_leave(const line_ctx *L, controller *c);
int tt_scan_graze_full(const line_ctx *L, line_state *st, controller *c, const cycle_in *in,
                       const double *x0, const tt_cycle *cy, double *obs, int branch);
int tt_scan_graze_step(const line_ctx *L, line_state *st, controller *c, const cycle_in *in,
                       double *obs);
check_outcome tt_scan_graze_check(const line_ctx *L, line_state *st, const cycle_in *in,
                                  double *obs, controller *c, int *rc);

#endif
