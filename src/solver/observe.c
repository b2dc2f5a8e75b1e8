/* The cycle's observables outside the state vector, read off each step's dense output:
 * the recorded samples, the deflection's extremes, the peak force and indentation. */
#include <string.h>

#include "stepper.h"

/* The law's state at fraction th of the current step into x (NULL: an elastic law). */
static const double *law_state_at(const tt_sim *S, double th, double *x)
{
    if (!S->sys.nlaw)
        return NULL;
    S->type->dense_x(S->step, S, th, x);
    return tt_system_law_state(S, x);
}

/* The force of a law with states, which reads them off the dense output: apart, so that
 * the elastic law's evaluation below stays inline. */
static __attribute__((noinline)) tt_contact_forces law_force_at(const tt_sim *S, double th,
                                                                double delta, double rate,
                                                                int contact)
{
    double x[TT_SIM_DIM_MAX];
    return S->sys.force(S->sys.contact, S->sys.ci, delta, rate, contact, law_state_at(S, th, x));
}

/* Tip-sample force on the current branch at the tip's (d, v) at fraction th of the
 * current step. */
static inline double ts_force(const tt_sim *S, double th, double d, double v, int contact,
                              double *delta)
{
    double dl = d - (S->sys.s0 + S->sys.sdot * (S->step_tau + th * S->step_h));
    *delta = dl;
    if (!S->sys.contact)
        return 0;
    tt_contact_forces f = S->sys.nlaw ? law_force_at(S, th, dl, v - S->sys.sdot, contact)
                                      : S->sys.force(S->sys.contact, S->sys.ci, dl, v - S->sys.sdot, contact, NULL);
    return f.conservative + f.dissipative;
}

/* The state at time ts of the step's part [0, th] into smp. */
static void observe_at(tt_sim *S, double ts, tt_sample *smp)
{
    double h = S->step_h, t0 = S->step_tau;
    double f = h > 0 ? (ts - t0) / h : 0;
    if (f < 0)
        f = 0;
    double z, zd, Fd, cw, sw;
    drive_at(S, ts, &z, &zd, &Fd, &cw, &sw);
    tt_step_dense(S, f, &smp->d, &smp->v);
    smp->t = sim_time(S, ts);
    smp->z = z;
    smp->s = S->sys.s0 + S->sys.sdot * ts;
    smp->contact = S->contact_state;
    smp->u = 0;
    smp->f = NAN;
    if (S->sys.nlaw) {
        /* the surface where it is: at the tip in contact, where the arms let it be out */
        double x[TT_SIM_DIM_MAX], delta;
        const double *q = law_state_at(S, f, x);
        double u = S->sys.law->surface(S->sys.contact, q);
        for (int i = 0; i < S->sys.nlaw && i < (int)(sizeof smp->q / sizeof *smp->q); i++)
            smp->q[i] = q[i];
        smp->u = smp->contact ? fmax(u, smp->d - smp->s) : u;
        smp->f = ts_force(S, f, smp->d, smp->v, smp->contact, &delta);
    }
}

/* Each mode's deflection at time ts of the current step into q (the base at z). */
static void observe_modes(const tt_sim *S, double ts, double *q, double z)
{
    double x[TT_SIM_DIM_MAX], h = S->step_h, f = h > 0 ? (ts - S->step_tau) / h : 0;
    S->type->dense_x(S->step, S, f < 0 ? 0 : f, x);
    q[0] = x[0] - z;
    for (int i = 1; i < S->sys.modes; i++)
        q[i] = x[2 * i];
}

/* Samples at k T / n inside (t0, t0 + th h]; k = 0 is taken at the cycle start. Then
 * the probes inside it. */
static void observe_samples(tt_sim *S, double th)
{
    const double end = S->step_tau + th * S->step_h * (1 + 1e-12);
    const tt_cantilever *c = &S->c;
    while (S->next_sample < S->nsamp) {
        double ts = c->T * S->next_sample / S->nsamp;
        if (ts > end)
            break;
        observe_at(S, ts, &S->samples[S->next_sample]);
        if (S->mode_samples)
            observe_modes(S, ts, S->mode_samples + (size_t)S->next_sample * (size_t)S->sys.modes,
                          S->samples[S->next_sample].z);
        S->next_sample++;
    }
    /* a probe needs the tip's position only: no drive evaluation */
    while (S->next_probe < S->nprobe) {
        double ts = S->probe_tau[S->next_probe];
        if (ts > end)
            break;
        tt_sample *smp = &S->probes[S->next_probe++];
        double f = S->step_h > 0 ? (ts - S->step_tau) / S->step_h : 0;
        tt_step_dense(S, f < 0 ? 0 : f, &smp->d, &smp->v);
        smp->t = sim_time(S, ts);
        smp->z = NAN;
        smp->s = S->sys.s0 + S->sys.sdot * ts;
        smp->contact = S->contact_state;
    }
}

/* In contact the force (load plus interaction damping) may peak anywhere in the step:
 * sample it at quarter steps of [0, th] and refine an interior maximum by a parabola. */
static void observe_contact_peak(tt_sim *S, double th)
{
    double d, v, delta;
    double f[5], tq[5];
    int best = 0;
    for (int q = 0; q < 5; q++) {
        tq[q] = th * q / 4.0;
        tt_step_dense(S, tq[q], &d, &v);
        f[q] = ts_force(S, tq[q], d, v, 1, &delta);
        if (f[q] > f[best])
            best = q;
    }
    double fmax = f[best];
    if (best > 0 && best < 4) {
        double den = f[best - 1] - 2 * f[best] + f[best + 1];
        if (den < 0) {
            double off = 0.5 * (f[best - 1] - f[best + 1]) / den; /* in quarter steps */
            if (fabs(off) <= 1) {
                tt_step_dense(S, tq[best] + off * th / 4.0, &d, &v);
                double fr = ts_force(S, tq[best] + off * th / 4.0, d, v, 1, &delta);
                if (fr > fmax)
                    fmax = fr;
            }
        }
    }
    if (fmax > S->peak_force)
        S->peak_force = fmax;
}

static void observe_peaks(tt_sim *S, double th, double d, double v);

/* Bookkeeping for the part [0, th] of the current step: samples, extremes, peak force. */
void tt_observe(tt_sim *S, double th)
{
    observe_samples(S, th);
    if (!S->track_extremes && S->skip_peaks)
        return;
    /* deflection extremes (on request: they cost a drive evaluation) and force at the
     * (sub)step end */
    double d, v;
    tt_step_dense(S, th, &d, &v);
    if (S->track_extremes) {
        double z, zd, Fd, cw, sw;
        drive_at(S, S->step_tau + th * S->step_h, &z, &zd, &Fd, &cw, &sw);
        double y = d - z;
        if (y < S->y_min)
            S->y_min = y;
        if (y > S->y_max)
            S->y_max = y;
    }
    if (!S->skip_peaks)
        observe_peaks(S, th, d, v);
}

/* The peak force and the greatest indentation over the part [0, th] of the current step
 * whose end state is (d, v). */
static void observe_peaks(tt_sim *S, double th, double d, double v)
{
    double delta;
    double F = ts_force(S, th, d, v, S->contact_state, &delta);
    if (F > S->peak_force)
        S->peak_force = F;
    if (delta > S->max_indent)
        S->max_indent = delta;
    /* a maximum of the penetration inside: locate it for the indentation */
    double v0 = tt_event_vel(S, 0), v1 = tt_event_vel(S, th);
    if (v0 > 0 && v1 < 0) {
        double tm = tt_event_root(S, 1, 0, 0, th, v0, v1);
        tt_step_dense(S, tm, &d, &v);
        F = ts_force(S, tm, d, v, S->contact_state, &delta);
        if (F > S->peak_force)
            S->peak_force = F;
        if (delta > S->max_indent)
            S->max_indent = delta;
    }
    /* A flight step's ends are too far apart to stand for the far turning point, where an
     * attraction is weakest and the force greatest: locate a minimum of the penetration. */
    if (S->step_long && v0 < 0 && v1 > 0) {
        double tm = tt_event_root(S, 1, 0, 0, th, v0, v1);
        tt_step_dense(S, tm, &d, &v);
        F = ts_force(S, tm, d, v, S->contact_state, &delta);
        if (F > S->peak_force)
            S->peak_force = F;
    }
    if (S->contact_state && th > 0)
        observe_contact_peak(S, th);
}

/* The sample at k = 0 is the cycle-start state: a step of length 0 whose dense output,
 * for every step type, is that state. */
void tt_observe_start(tt_sim *S)
{
    if (S->nsamp <= 0)
        return;
    S->step_tau = 0;
    S->step_h = 0;
    sim_copy(S, S->y0, S->y);
    sim_copy(S, S->y1, S->y);
    ensure_fsal(S);
    sim_copy(S, S->dydt_in, S->fsal);
    sim_copy(S, S->dydt_out, S->fsal);
    if (S->type->point)
        S->type->point(S->step, S);
    tt_observe(S, 0);
}
