/* The sim's life cycle and settings: allocation with its step type from the method
 * table (steps.c) and the type's own state, the force law and sample, the state and the
 * free steady oscillation. */
#include <stdlib.h>
#include <string.h>

#include "stepper.h"
#include "tiptap/util/error.h"

void tt_solver_default(tt_solver *s)
{
    s->method = TT_METHOD_DOPRI5;
    s->tolerance = 1e-8;
    s->steps_per_cycle = 512;
    s->tier = TT_TIER_EVERY;
}

static int method_known(tt_method m) { return m >= TT_METHOD_DOPRI5 && m <= TT_METHOD_RADAU; }

const char *tt_method_name(tt_method m)
{
    return method_known(m) ? tt_step_types[m]->name : "dopri5";
}

int tt_sim_alloc(tt_sim **out, const tt_cantilever *c, const tt_solver *solver)
{
    *out = NULL;
    if (!method_known(solver->method))
        return tt_error(TT_EINVAL, "unknown solver method %d", (int)solver->method);
    if (solver->method == TT_METHOD_RK4 && solver->steps_per_cycle < 8)
        return tt_error(TT_EINVAL, "rk4 needs at least 8 steps per cycle");
    if (solver->method != TT_METHOD_RK4 && !(solver->tolerance > 0 && solver->tolerance < 1))
        return tt_error(TT_EINVAL, "solver tolerance must lie between 0 and 1");
    tt_sim *S = calloc(1, sizeof *S);
    if (!S)
        return tt_error_nomem("the solver's state");
    S->c = *c;
    S->solver = *solver;
    tt_system_plan(S, 0);
    S->type = tt_step_types[solver->method];
    S->step = S->type->alloc(S);
    if (!S->step) {
        free(S);
        return tt_error_nomem("the %s solver's state", tt_step_types[solver->method]->name);
    }
    tt_sim_set_contact(S, NULL, NAN);
    tt_sim_reset_free(S);
    *out = S;
    return TT_OK;
}

void tt_sim_free(tt_sim *sim)
{
    if (sim) {
        free(sim->sys.nz_f);
        sim->type->free(sim->step);
    }
    free(sim);
}

void tt_sim_set_contact(tt_sim *S, const tt_contact *contact, double Qi)
{
    const tt_contact_law *was = S->sys.law;
    int nlaw = S->sys.nlaw;
    S->sys.contact = contact;
    S->sys.ci = (isfinite(Qi) && Qi > 0) ? S->c.m * S->c.w0 / Qi : 0.0;
    S->sys.force = contact ? tt_contact_law_of(contact)->force : NULL;
    if (contact) {
        S->sys.jumpin = tt_contact_jumpin(contact);
        S->sys.jumpout = tt_contact_jumpout(contact);
    } else {
        S->sys.jumpin = INFINITY;
        S->sys.jumpout = -INFINITY;
        S->contact_state = 0;
    }
    /* A re-stepped event lands a hair (the local error) on either side of its
     * threshold, and a grazing tip may end a step just past one without a sign change;
     * only past this margin is a switch forced (tiny next to any force-law length). */
    S->sys.margin = 1e-6 * S->c.A0;
    /* The law's states follow the modes: a law of the same row carries them on (a scan
     * within one material), another starts from a relaxed sample; the quadratures move
     * to the new dimension's place. */
    const tt_contact_law *law = contact ? tt_contact_law_of(contact) : NULL;
    if (law != was) {
        int n0 = S->sys.n;
        double q[NQ];
        memcpy(q, S->y + n0, sizeof q);
        tt_system_plan(S, S->sys.generic);
        for (int i = 2 * S->sys.modes; i < S->sys.n; i++)
            S->y[i] = 0;
        memcpy(S->y + S->sys.n, q, sizeof q);
        if (S->sys.nlaw != nlaw)
            tt_step_setup(S);
    }
    tt_sim_invalidate(S);
}

void tt_sim_set_sample(tt_sim *S, double s, double sdot)
{
    S->sys.s0 = s;
    S->sys.sdot = sdot;
    tt_sim_invalidate(S);
}

void tt_sim_set_sampling(tt_sim *S, int n, tt_sample *buf)
{
    S->nsamp = buf ? n : 0;
    S->samples = buf;
}

const tt_sample *tt_sim_samples(const tt_sim *S) { return S->nsamp ? S->samples : NULL; }

void tt_sim_set_mode_sampling(tt_sim *S, double *buf) { S->mode_samples = buf; }

const tt_solver *tt_sim_solver(const tt_sim *S) { return &S->solver; }

void tt_sim_set_probes(tt_sim *S, int n, const double *tau, tt_sample *buf)
{
    S->nprobe = buf && tau ? n : 0;
    S->probe_tau = tau;
    S->probes = buf;
}

const tt_sample *tt_sim_probes(const tt_sim *S) { return S->nprobe ? S->probes : NULL; }

void tt_sim_track_extremes(tt_sim *S, int on)
{
    S->track_extremes = on;
    /* the extremes are taken at step ends, which the flight's long steps would coarsen */
    tt_step_setup(S);
}

void tt_sim_track_peaks(tt_sim *S, int on) { S->skip_peaks = !on; }

void tt_sim_set_cantilever(tt_sim *S, const tt_cantilever *c)
{
    /* Same drive period required: the cycle bookkeeping assumes it. */
    S->c = *c;
    int n0 = S->sys.n, m0 = S->sys.modes;
    double q[NQ];
    memcpy(q, S->y + n0, sizeof q);
    tt_system_plan(S, S->sys.generic);
    if (S->sys.n != n0) {
        /* other modes: the new ones (and the law's states behind them) start at rest,
         * the quadratures move to the new dimension's place */
        for (int i = 2 * (m0 < S->sys.modes ? m0 : S->sys.modes); i < S->sys.n; i++)
            S->y[i] = 0;
        memcpy(S->y + S->sys.n, q, sizeof q);
    }
    tt_step_setup(S);
    tt_sim_set_contact(S, S->sys.contact, S->sys.ci > 0 ? S->c.m * S->c.w0 / S->sys.ci : NAN);
}

const tt_cantilever *tt_sim_cantilever(const tt_sim *S) { return &S->c; }

double tt_sim_time(const tt_sim *S) { return sim_time(S, 0.0); }
long tt_sim_cycles(const tt_sim *S) { return S->cycle; }
long tt_sim_work(const tt_sim *S) { return S->work; }

void tt_sim_get_state(const tt_sim *S, double *d, double *v, int *contact)
{
    double dt = S->y[Y_D], vt = S->y[Y_V];
    /* the tip: the further modes' deflections added to mode 0 */
    for (int i = 1; i < S->sys.modes; i++) {
        dt += S->y[2 * i];
        vt += S->y[2 * i + 1];
    }
    *d = dt;
    *v = vt;
    *contact = S->contact_state;
}

void tt_sim_set_state(tt_sim *S, double d, double v, int contact)
{
    /* mode 0 takes what the further modes' deflections leave of the tip's */
    for (int i = 1; i < S->sys.modes; i++) {
        d -= S->y[2 * i];
        v -= S->y[2 * i + 1];
    }
    S->y[Y_D] = d;
    S->y[Y_V] = v;
    S->contact_state = S->sys.contact ? contact : 0;
    tt_sim_invalidate(S);
}

int tt_sim_dim(const tt_sim *S)
{
    return S->sys.n;
}

void tt_sim_get_x(const tt_sim *S, double *x, int *contact)
{
    for (int i = 0; i < S->sys.n; i++)
        x[i] = S->y[i];
    *contact = S->contact_state;
}

void tt_sim_set_x(tt_sim *S, const double *x, int contact)
{
    for (int i = 0; i < S->sys.n; i++)
        S->y[i] = x[i];
    S->contact_state = S->sys.contact ? contact : 0;
    tt_sim_invalidate(S);
}

void tt_sim_reset_free(tt_sim *S)
{
    /* y = A0 cos(w t - phi0) at t = 0, and d = z + y. */
    const tt_cantilever *c = &S->c;
    double z = c->drive == TT_DRIVE_BASE ? c->a_d : 0.0;
    double y = c->A0 * cos(-c->phi0);
    double ydot = -c->A0 * c->wd * sin(-c->phi0);
    memset(S->y, 0, sizeof S->y);
    S->y[Y_D] = z + y;
    S->y[Y_V] = ydot; /* z' = 0 at t = 0 */
    if (c->A2 > 0 && S->sys.modes > 1) {
        /* mode 2 on its own free response to its drive at this cycle's start (the other
         * modes' share of it, a few parts in Q_2 of A2, rings in) */
        double th = 2 * M_PI * tt_cantilever_drive2_turns(c, S->cycle);
        double m = c->mode_m[1], w = c->wd2, dr = c->mode_k[1] - m * w * w, di = c->mode_c[1] * w;
        double f = c->drive == TT_DRIVE_BASE ? c->mode_base[1] * m * w * w * c->a_d2 : c->F02;
        double gain = f / hypot(dr, di), lag = atan2(di, dr);
        S->y[2] = gain * cos(th - lag);
        S->y[3] = -gain * w * sin(th - lag);
        /* mode 0 moves with the base's second sinusoid too */
        S->y[Y_D] += c->a_d2 * cos(th);
        S->y[Y_V] -= c->a_d2 * w * sin(th);
        S->sys.th2 = th;
    }
    S->contact_state = 0;
    S->tau = 0;
    /* the step controllers' memory too: a run from the free state must not depend on
     * what the sim did before (scan lines give the same images on any thread) */
    if (S->type->reset)
        S->type->reset(S->step, S);
    tt_sim_invalidate(S);
}

double tt_sim_force(const tt_sim *S, const tt_sample *smp, double *a)
{
    if (!S->sys.contact) {
        if (a)
            *a = 0;
        return 0;
    }
    tt_contact_detail law;
    tt_contact_evaluate(S->sys.contact, S->sys.ci, smp->d - smp->s, smp->v - S->sys.sdot, smp->contact, NULL,
                        &law);
    if (a)
        *a = law.radius;
    /* a law with states: the force the sim recorded with the sample (the radius is the
     * paraboloid's at the penetration, whatever the state) */
    if (S->sys.nlaw && isfinite(smp->f))
        return smp->f;
    return law.f.conservative + law.f.dissipative;
}
