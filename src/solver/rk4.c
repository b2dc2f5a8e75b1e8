/* The classic fixed-step RK4 step type on a grid of steps_per_cycle steps per drive
 * cycle, with cubic Hermite dense output and a refusal of steps too coarse for the
 * contact's stiffness. */
#include <stdlib.h>
#include <string.h>

#include "stepper.h"
#include "tiptap/util/error.h"

/* rk4's own state: the grid point it steps to, its stages, and the deepest penetration
 * of the last step. */
typedef struct {
    int j;          /* index of the next grid point in the cycle */
    double dmax;    /* deepest penetration among the step's stages and end */
    double k[4][NYMAX]; /* stages 1 to 3 (stage 0 and the end are the record's dydt_in, dydt_out) */
} rk4_state;

/* One classic RK4 step of a system of n components (a constant where inlined for
 * n = 2). */
static inline __attribute__((always_inline)) void rk4_step_n(rk4_state *st, tt_sim *S, double h,
                                                             const int n)
{
    double (*k)[NYMAX] = st->k, yt[NYMAX];
    double *k0 = S->dydt_in, *k6 = S->dydt_out;
    const double *y0 = S->y;
    double t = S->tau;
    int cs = S->contact_state;
    const int ny = n + NQ;
    const size_t sz = (size_t)ny * sizeof *yt;
    ensure_fsal(S);
    memcpy(k0, S->fsal, sz);
    memcpy(yt, y0, sz); /* the stages read only the system's n components */
    double smid = S->sys.s0 + S->sys.sdot * (t + 0.5 * h), send = S->sys.s0 + S->sys.sdot * (t + h);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + 0.5 * h * k0[i];
    double dmax = yt[Y_D] - smid;
    S->sys.rhs(S, t + 0.5 * h, yt, cs, k[1]);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + 0.5 * h * k[1][i];
    dmax = fmax(dmax, yt[Y_D] - smid);
    S->sys.rhs(S, t + 0.5 * h, yt, cs, k[2]);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + h * k[2][i];
    dmax = fmax(dmax, yt[Y_D] - send);
    S->sys.rhs(S, t + h, yt, cs, k[3]);
    for (int i = 0; i < ny; i++)
        S->y1[i] = y0[i] + h / 6.0 * (k0[i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
    /* A step that enters a stiff contact (from its soft onset, where the stiffness at the
     * start says nothing) shows it in its stages: they overshoot deep into it. */
    st->dmax = fmax(dmax, S->y1[Y_D] - send);
    /* The derivative at the end serves the cubic Hermite dense output and, unless the
     * state changes there, the next step's first stage. */
    S->sys.rhs(S, t + h, S->y1, cs, k6);
    memcpy(S->y0, y0, sz);
    S->step_tau = t;
    S->step_h = h;
    S->step_long = 0;
}

/* The step: unrolled for the one-mode elastic system, over n otherwise. */
static void rk4_step(rk4_state *st, tt_sim *S, double h)
{
    if (S->sys.n == 2)
        rk4_step_n(st, S, h, 2);
    else
        rk4_step_n(st, S, h, S->sys.n);
}

/* rk4 is stable for oscillation only while h * sqrt(k_contact / m) < 2.8; past that it
 * returns wrong numbers, so refuse with the cause. The stiffness is the current branch's
 * at penetration delta: out of contact too, since a branch may already push back there
 * (Hertz without adhesion has one force law for both states). */
static int rk4_check_stiffness(tt_sim *S, double h, double delta)
{
    if (!S->sys.contact)
        return TT_OK;
    tt_contact_detail law;
    tt_contact_evaluate(S->sys.contact, S->sys.ci, delta, 0.0, S->contact_state, tt_system_law_state(S, S->y),
                        &law);
    double dPdd = law.stiffness;
    double keff = S->c.k + (dPdd > 0 ? dPdd : 0);
    double wc = sqrt(keff / S->c.m), wi = law.damping / S->c.m; /* the damping's rate, 1/s */
    if (h * wc > 2.5 || h * wi > 2.5)
        return tt_error(TT_ENUM,
                        "rk4 step too large for the contact: contact stiffness %.3g N/m (%.0f times "
                        "the cantilever's)%s needs at least %.0f steps per cycle; raise [solver] "
                        "steps_per_cycle or use method = dopri5 (or radau, implicit, for a contact "
                        "this stiff)",
                        keff, keff / S->c.k, wi > wc ? " and its damping" : "",
                        ceil(S->c.T * fmax(wc, wi) / 2.5));
    return TT_OK;
}

/* The step to the next grid time j T / N, computed from the index, never accumulated;
 * an event may have left the tip a hair short of it, or on it. */
static int rk4_advance(void *state, tt_sim *S, double T, int *outcome)
{
    rk4_state *st = state;
    const double hgrid = T / S->solver.steps_per_cycle;
    const double hmin = T * 1e-13;
    double tnext = st->j >= S->solver.steps_per_cycle ? T : st->j * hgrid;
    double h = tnext - S->tau;
    if (h <= hmin) {
        st->j++;
        if (tnext >= T) {
            S->tau = T;
            *outcome = TT_STEP_END;
        } else {
            *outcome = TT_STEP_RETRY;
        }
        return TT_OK;
    }
    int rc = rk4_check_stiffness(S, h, S->y[Y_D] - (S->sys.s0 + S->sys.sdot * S->tau));
    if (rc)
        return rc;
    rk4_step(st, S, h);
    /* ... and at the deepest stage, before an unstable step is taken */
    if ((rc = rk4_check_stiffness(S, h, st->dmax)))
        return rc;
    *outcome = TT_STEP_TRIAL;
    return TT_OK;
}

static int rk4_redo(void *state, tt_sim *S, double h)
{
    rk4_step(state, S, h);
    return TT_OK;
}

/* Cubic Hermite: d from (d, v) at both ends, v from (v, a) at both ends. */
static void rk4_dense(const void *state, const tt_sim *S, double th, double *d, double *v)
{
    (void)state;
    double h = S->step_h;
    double t2 = th * th, t3 = t2 * th;
    double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + th, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
    *d = h00 * S->y0[Y_D] + h10 * h * S->y0[Y_V] + h01 * S->y1[Y_D] + h11 * h * S->y1[Y_V];
    *v = h00 * S->y0[Y_V] + h10 * h * S->dydt_in[Y_V] + h01 * S->y1[Y_V] + h11 * h * S->dydt_out[Y_V];
}

/* Cubic Hermite on each of the n components, from their values and derivatives at the
 * step's ends. */
static void rk4_dense_x(const void *state, const tt_sim *S, double th, double *x)
{
    (void)state;
    double h = S->step_h;
    double t2 = th * th, t3 = t2 * th;
    double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + th, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
    for (int i = 0; i < S->sys.n; i++)
        x[i] = h00 * S->y0[i] + h10 * h * S->dydt_in[i] + h01 * S->y1[i] + h11 * h * S->dydt_out[i];
}

/* A step taken in full reaches its grid point. */
static void rk4_accept(void *state, const tt_sim *S)
{
    (void)S;
    ((rk4_state *)state)->j++;
}

/* A cycle starts at its first grid point's step. */
static void rk4_cycle(void *state, double T)
{
    (void)T;
    ((rk4_state *)state)->j = 1;
}

static void *rk4_alloc(const tt_sim *S)
{
    (void)S;
    rk4_state *st = calloc(1, sizeof *st);
    if (st)
        st->j = 1;
    return st;
}

const tt_step_type tt_step_rk4 = {
    .name = "rk4",
    .alloc = rk4_alloc,
    .free = free,
    .cycle = rk4_cycle,
    .advance = rk4_advance,
    .redo = rk4_redo,
    .dense = rk4_dense,
    .dense_x = rk4_dense_x,
    .accept = rk4_accept,
};
