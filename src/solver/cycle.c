/* One drive cycle: the loop that advances the method's steps (stepper.h) to the cycle's
 * end, takes each step in full or up to a contact event, and turns the per-cycle
 * integrals into the observables of tt_cycle with the energy-balance residual. */
#include <string.h>

#include "stepper.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

/* Take the current step (already computed into y1) in full. */
static void step_accept(tt_sim *S)
{
    tt_observe(S, 1);
    sim_copy(S, S->y, S->y1);
    sim_copy(S, S->fsal, S->dydt_out);
    S->fsal_ok = !S->step_long; /* a long step computes no derivative at its end */
    if (S->type->accept)
        S->type->accept(S->step, S);
    S->tau = S->step_tau + S->step_h;
    S->steps++;
}

static int check_finite(tt_sim *S)
{
    if (!isfinite(S->y[Y_D]) || !isfinite(S->y[Y_V]))
        return tt_error(TT_ENUM,
                        "the solution became NaN or infinite at t = %.9g s (cycle %ld); "
                        "tighten [solver] tolerance or raise steps_per_cycle",
                        sim_time(S, S->tau), S->cycle);
    return TT_OK;
}

/* Clear the per-cycle integrals and accumulators at the cycle start. */
static void cycle_begin(tt_sim *S)
{
    for (int i = S->sys.n; i < sim_ny(S); i++)
        S->y[i] = 0;
    S->tau = 0;
    S->peak_force = -INFINITY;
    S->max_indent = -INFINITY;
    S->y_min = INFINITY;
    S->y_max = -INFINITY;
    S->e_jumps = 0;
    S->switched_at = -1;
    S->switches_there = S->switches_near = 0;
    S->t_contact = S->t_release = NAN;
    S->steps = S->rejected = S->events = 0;
    S->next_sample = 0;
    S->next_probe = 0;
    S->step_long = 0;
    if (S->type->cycle)
        S->type->cycle(S->step, S->c.T);
    if (S->sys.nz_f)
        tt_noise_cycle(S);
    if (S->c.A2 > 0)
        S->sys.th2 = 2 * M_PI * tt_cantilever_drive2_turns(&S->c, S->cycle);
}

/* Take the step the method computed: up to a contact event on it, or in full. */
static int cycle_take(tt_sim *S, int outcome)
{
    if (outcome == TT_STEP_TRIAL) {
        double th = tt_event_find(S);
        if (th <= 1)
            return tt_event_take(S, th);
    }
    step_accept(S);
    return TT_OK;
}

/* The observables from the per-cycle integrals: the deflection's fundamental (amplitude,
 * phase), its mean, the energies and the energy-balance residual. */
static void cycle_result(const tt_sim *S, double E_start, tt_cycle *out)
{
    const tt_cantilever *c = &S->c;
    const double T = c->T;
    double E_end = S->sys.energy(S, T, S->y, S->contact_state);
    const double *q = sim_quad(S, S->y);
    double X = 2.0 / T * q[Y_IC], Yq = 2.0 / T * q[Y_IS];
    out->amplitude = hypot(X, Yq);
    double ph = atan2(Yq, X);
    if (ph < -M_PI / 2)
        ph += 2 * M_PI; /* lags run from about 0 to past 180 degrees */
    out->phase = ph;
    out->mean = q[Y_IY] / T;
    out->y_min = S->y_min;
    out->y_max = S->y_max;
    out->peak_force = S->skip_peaks ? NAN : S->peak_force;
    out->max_indentation = S->skip_peaks ? NAN : S->max_indent;
    out->contact_fraction = q[Y_TC] / T;
    out->e_drive = q[Y_WDRIVE];
    out->e_damp = q[Y_WDAMP];
    out->e_ts = q[Y_WCI] + q[Y_WVISC] + S->e_jumps;
    out->e_hyst = S->e_jumps;
    out->e_ci = q[Y_WCI];
    out->e_visc = q[Y_WVISC];
    out->e_sample = q[Y_WS];
    out->residual = out->e_drive - out->e_damp - out->e_ts - out->e_sample - (E_end - E_start);
    out->residual_rel = fabs(out->residual) / (M_PI * c->c * c->wd * c->A0 * c->A0);
    out->t_contact = S->t_contact;
    out->t_release = S->t_release;
    out->steps = S->steps;
    out->rejected = S->rejected;
    out->events = S->events;
}

int tt_sim_cycle(tt_sim *S, tt_cycle *out)
{
    const double T = S->c.T;
    memset(out, 0, sizeof *out);
    cycle_begin(S);
    double E_start = S->sys.energy(S, 0, S->y, S->contact_state);
    tt_observe_start(S);
    long guard = 0;
    while (S->tau < T) {
        /* Cancellation is polled at the cycle's start and every 1024 steps (a few
         * milliseconds at most), so that a run stops within a cycle that never ends and
         * the mask costs the step loop next to nothing. */
        if ((guard & 1023) == 0 && tt_cancel_requested())
            return tt_error(TT_EINTR, "interrupted in cycle %ld", S->cycle);
        if (++guard > 50000000L)
            return tt_error(TT_ENUM, "no progress within cycle %ld", S->cycle);
        int outcome, rc;
        if ((rc = S->type->advance(S->step, S, T, &outcome)))
            return rc;
        if (outcome == TT_STEP_RETRY)
            continue;
        if (outcome == TT_STEP_END)
            break;
        if ((rc = cycle_take(S, outcome)) || (rc = check_finite(S)))
            return rc;
        if (S->tau > T)
            S->tau = T;
    }
    cycle_result(S, E_start, out);
    S->work += S->steps + S->rejected;
    /* the next cycle starts at tau = 0 with the sample carried on */
    S->cycle++;
    S->sys.s0 += S->sys.sdot * T;
    S->tau = 0;
    return TT_OK;
}
