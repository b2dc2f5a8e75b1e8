/* The envelope tier's local model of the cycle map (see include/tiptap/solver/envelope.h):
 * the plan and the model's build and anchor; the prediction is in envelope_predict.c. */
#include "tiptap/solver/envelope.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "envelope_private.h"

const char *tt_envelope_outcome_name(tt_envelope_outcome o)
{
    static const char *const names[TT_ENV_OUTCOMES] = {"usable", "cycle failed", "off branch",
                                                       "singular flow"};
    return o >= 0 && o < TT_ENV_OUTCOMES ? names[o] : "?";
}

/* Why a plan cannot be made (NULL: it can). */
static const char *plan_invalid(const tt_sim *sim, const tt_envelope_params *p)
{
    const int nx = p->dim > 0 ? p->dim : tt_sim_dim(sim);
    if (nx < 1 || nx > TT_SIM_DIM_MAX || p->dim < 0)
        return "a state of 1 to TT_SIM_DIM_MAX components";
    if (p->samples < 1 || p->probes < 0 || p->reduced < 0 || p->kept < 0)
        return "samples > 0 and probes, reduced and kept >= 0";
    if (p->reduced > 0 && !p->reduce)
        return "the reduction's rows";
    /* the Langevin force acts on the tip's velocity alone: a law's states after (d, d')
     * take no forcing of their own (envelope_noise.c), further modes would */
    if (p->psd > 0 && (nx < 2 || nx > 2 + TT_CONTACT_ARMS_MAX || tt_sim_cantilever(sim)->modes > 1))
        return "thermal noise on one mode, with at most TT_CONTACT_ARMS_MAX law states (the samples carry no more)";
    if (p->sd > 0 && p->reduced == 0)
        return "detector noise on reduced samples";
    return NULL;
}

/* The plan's buffers' sizes in doubles (0: not needed), from its dimensions. */
enum { B_XS, B_OSCALE, B_OA, B_J, B_C, B_R, B_RA, B_CR, B_H, B_HR, B_LJ, B_LF, B_TRK, B_PHI, B_WORK, NBUF };
static void buffer_sizes(const tt_envelope *e, size_t sz[NBUF])
{
    const size_t nx = (size_t)e->nx, ni = (size_t)e->ni, no = (size_t)e->no;
    const size_t nr = (size_t)e->nr, np = (size_t)e->npair, nq = nx + no, nn = (size_t)e->nn;
    const size_t nx2 = nx * nx, n = (size_t)e->n;
    const int reduced = e->m > 0, noisy = e->psd > 0 || e->sd > 0;
    sz[B_XS] = 4 * nx + ni;
    sz[B_OSCALE] = sz[B_OA] = no;
    sz[B_J] = nx * ni;
    sz[B_C] = no * ni;
    sz[B_R] = reduced ? (size_t)e->m * n : 0;
    sz[B_RA] = reduced ? nr : 0;
    sz[B_CR] = reduced ? nr * ni : 0;
    sz[B_H] = e->second ? nq * np : 0;
    sz[B_HR] = e->second ? nr * np : 0;
    sz[B_LJ] = sz[B_LF] = noisy ? nn * nn : 0;
    /* the state at the samples of the 2 nx cycles perturbed in each component, the
     * flow's nx x nx Jacobian at each sample and the end */
    sz[B_TRK] = e->psd > 0 ? 2 * nx2 * n : 0;
    sz[B_PHI] = e->psd > 0 ? nx2 * (n + 1) : 0;
    /* a build's outputs (the anchor's and two per input) and the second differences'
     * two more; or the covariance's */
    size_t work = (1 + 2 * ni) * nq + 2 * nq, wn = tt_envelope_noise_work(e);
    sz[B_WORK] = work > wn ? work : wn;
}

/* The plan's buffers, each zeroed; 0 when one cannot be had. */
static int plan_buffers(tt_envelope *e, const tt_envelope_params *p)
{
    size_t sz[NBUF];
    buffer_sizes(e, sz);
    e->xs = calloc(sz[B_XS], sizeof *e->xs);
    e->oscale = calloc(sz[B_OSCALE], sizeof *e->oscale);
    e->oa = calloc(sz[B_OA], sizeof *e->oa);
    e->J = calloc(sz[B_J], sizeof *e->J);
    e->C = calloc(sz[B_C], sizeof *e->C);
    int ok = e->xs && e->oscale && e->oa && e->J && e->C;
    if (ok) {
        e->xa = e->xs + e->nx;
        e->x1 = e->xa + e->nx;
        e->xb = e->x1 + e->nx;
        e->hs = e->xb + e->nx;
    }
    if (e->m > 0) {
        e->R = malloc(sz[B_R] * sizeof *e->R);
        e->ra = calloc(sz[B_RA], sizeof *e->ra);
        e->Cr = calloc(sz[B_CR], sizeof *e->Cr);
        ok = ok && e->R && e->ra && e->Cr;
    }
    if (e->second) {
        e->H = calloc(sz[B_H], sizeof *e->H);
        e->Hr = calloc(sz[B_HR], sizeof *e->Hr);
        ok = ok && e->H && e->Hr;
    }
    if (p->psd > 0 || p->sd > 0) {
        e->Lj = calloc(sz[B_LJ], sizeof *e->Lj);
        e->Lf = calloc(sz[B_LF], sizeof *e->Lf);
        ok = ok && e->Lj && e->Lf;
    }
    if (p->psd > 0) {
        e->trk = calloc(sz[B_TRK], sizeof *e->trk);
        e->phi = calloc(sz[B_PHI], sizeof *e->phi);
        ok = ok && e->trk && e->phi;
    }
    e->work = calloc(sz[B_WORK], sizeof *e->work);
    return ok && e->work;
}

/* The plan's dimensions from its parameters, for the sim's state of nx components. */
static void plan_dims(tt_envelope *e, const tt_envelope_params *p, int nx)
{
    e->nx = nx;
    e->ni = e->nx + 2;
    e->npair = e->ni * (e->ni + 1) / 2;
    e->n = p->samples;
    e->np = p->probes;
    e->no = e->n + TT_ENV_EXTRA + e->np;
    e->m = p->reduced;
    e->nr = e->m + TT_ENV_EXTRA + e->np;
    e->nin = e->nx + (p->travel ? 2 : 1);
    e->second = p->second_order != 0;
    e->psd = p->psd;
    e->sd = p->sd;
    e->nn = e->nx + e->m;
}

double tt_envelope_plan_bytes(const tt_envelope_params *p)
{
    tt_envelope e;
    memset(&e, 0, sizeof e);
    plan_dims(&e, p, p->dim > 0 ? p->dim : 2);
    size_t sz[NBUF], doubles = 0;
    buffer_sizes(&e, sz);
    for (int i = 0; i < NBUF; i++)
        doubles += sz[i];
    const double kept = e.second ? (double)p->kept : 0;
    return (double)sizeof e + (double)doubles * sizeof(double) +
           kept * ((double)tt_envelope_model_doubles(&e) * sizeof(double) +
                   (double)sizeof(tt_envelope_kept) + (double)sizeof *e.korder);
}

/* The build's central differences step each input by its own length: the modes' (d, d')
 * pairs, the sample and the travel by 1e-4 of their scales (second order 1e-3, whose
 * second differences take the same steps), where the stepper's noise (about the
 * tolerance) costs 1e-4 of the Jacobian at the default and the contact's length scales
 * (a nanometre) are far. A law's states (contact_sls.c's q, chi units) sit at
 * picometres on the free flight, by the surface's depression (R q^2)^(1/3) and its cusp
 * at q = 0: both orders step them by 1e-5 of A0 (0.2 pm), as 20 pm crossed the cusp
 * (dd/dq at 0.34 of its value) and 2 pm took dd/dq 1.2 % off (docs/dynamics.md, "Noise
 * on the envelope tier"). */
static void build_steps(tt_envelope *e)
{
    const double h1 = e->second ? 1e-3 : 1e-4;
    for (int i = 0; i < e->nx; i++)
        e->hs[i] = i < e->nmode ? h1 * e->xs[i] : 1e-5 * e->L;
    for (int i = e->nx; i < e->ni; i++)
        e->hs[i] = h1 * e->L;
}

int tt_envelope_alloc(tt_envelope **out, const tt_sim *sim, const tt_envelope_params *p)
{
    *out = NULL;
    const char *why = plan_invalid(sim, p);
    if (why)
        return tt_error(TT_EINVAL, "the envelope tier's plan needs %s", why);
    tt_envelope *e = calloc(1, sizeof *e);
    if (!e)
        return tt_error_nomem("the envelope tier's cycle map");
    const tt_cantilever *c = tt_sim_cantilever(sim);
    const int n = p->samples;
    plan_dims(e, p, p->dim > 0 ? p->dim : tt_sim_dim(sim));
    e->T = c->T;
    e->L = c->A0;
    e->V = c->wd * c->A0;
    e->mass = c->m;
    e->w0 = c->w0;
    e->sig = 0.5 * c->c / c->m;
    if (!plan_buffers(e, p) || tt_envelope_models_alloc(e, e->second ? p->kept : 0)) {
        tt_envelope_free(e);
        return tt_error_nomem("the envelope tier's cycle map (%d samples, %d models kept)", n,
                              p->kept);
    }
    /* the modes' (d, d') pairs, then the law's states, lengths (contact_sls.c's q_i) */
    const int nmode = 2 * (c->modes > 1 ? c->modes : 1);
    e->nmode = nmode;
    for (int i = 0; i < e->nx; i++)
        e->xs[i] = i < nmode && i % 2 ? e->V : e->L;
    build_steps(e);
    for (int i = 0; i < n; i++)
        e->oscale[i] = c->A0;
    /* the peak force and the greatest indentation are outputs, averaged into pixels and
     * fed back nowhere, and a maximum, which the linear model follows less closely than
     * the state as the time it is reached moves (on the blend's disks they alone failed
     * the checks once the transient had passed, at 1e-7 of k A0 and A0): held to a
     * hundred times the tolerance, 8 pN and 0.2 pm per cycle at the default */
    e->oscale[n + TT_ENV_PEAK] = 100 * c->k * c->A0;
    e->oscale[n + TT_ENV_INDENT] = 100 * c->A0;
    /* energies against k A0^2, as an amplitude error of tolerance A0 moves the stored
     * energy (the free loss per cycle, 2 pi / Q of it, would be Q times stricter than
     * the integrator itself keeps the energy balance) */
    e->oscale[n + TT_ENV_ETS] = c->k * c->A0 * c->A0;
    for (int i = n + TT_ENV_EXTRA; i < e->no; i++)
        e->oscale[i] = e->L;
    if (e->m > 0)
        memcpy(e->R, p->reduce, (size_t)e->m * (size_t)n * sizeof *p->reduce);
    if (e->Lj)
        tt_envelope_noise_plan(e);
    tt_envelope_own_views(e);
    *out = e;
    return TT_OK;
}

void tt_envelope_free(tt_envelope *e)
{
    if (!e)
        return;
    free(e->xs);
    free(e->oscale);
    free(e->oa);
    free(e->J);
    free(e->C);
    free(e->R);
    free(e->ra);
    free(e->Cr);
    free(e->trk);
    free(e->Lj);
    free(e->phi);
    free(e->Lf);
    free(e->H);
    free(e->Hr);
    free(e->work);
    tt_envelope_models_free(e);
    free(e);
}

int tt_envelope_size(const tt_envelope *e) { return e->no; }

/* An observable vector o (no) reduced: r (nr), the samples through R, the rest as they
 * are. */
static void reduce(const tt_envelope *e, const double *o, double *r)
{
    if (!e->R)
        return;
    for (int i = 0; i < e->m; i++) {
        const double *row = e->R + (size_t)i * (size_t)e->n;
        double sum = 0;
        for (int q = 0; q < e->n; q++)
            sum += row[q] * o[q];
        r[i] = sum;
    }
    for (int i = 0; i < TT_ENV_EXTRA + e->np; i++)
        r[e->m + i] = o[e->n + i];
}

void tt_envelope_reduce_obs(const tt_envelope *e, const double *obs, double *red)
{
    reduce(e, obs, red);
}

int tt_envelope_touched(const tt_cycle *cy) { return cy->contact_fraction > 0 || cy->events > 0; }
int tt_envelope_anchor_touched(const tt_envelope *e) { return e->touched; }
int tt_envelope_anchor_contact(const tt_envelope *e) { return e->contact; }

double tt_envelope_sample_offset(const tt_envelope *e, double s, double sdot)
{
    return s + 0.5 * sdot * e->T - e->sa;
}

double tt_envelope_reach(const tt_envelope *e, const double *x, double s, double sdot)
{
    return tt_envelope_distance(e, e->xa, e->sa, e->ta, x, s, sdot);
}

void tt_envelope_observe(const tt_envelope *e, const tt_sample *samples, const tt_sample *probes,
                         const tt_cycle *cy, double *obs)
{
    for (int q = 0; q < e->n; q++)
        obs[q] = samples[q].d - samples[q].z;
    obs[e->n + TT_ENV_PEAK] = cy->peak_force;
    obs[e->n + TT_ENV_INDENT] = cy->max_indentation;
    obs[e->n + TT_ENV_ETS] = cy->e_ts;
    double *g = obs + e->n + TT_ENV_EXTRA;
    for (int q = 0; q < e->np; q++)
        g[q] = probes ? probes[q].d : NAN;
}

/* The model's inputs' offsets u from the anchor: the state, the sample mid-cycle and its
 * travel within the cycle (0 unless the travel is an input). */
static inline void offsets(const tt_envelope *e, const double *x, double s, double sdot,
                           double *u)
{
    for (int i = 0; i < e->nx; i++)
        u[i] = x[i] - e->xa[i];
    u[e->nx] = s + 0.5 * sdot * e->T - e->sa;
    u[e->nx + 1] = e->nin > e->nx + 1 ? sdot * e->T - e->ta : 0;
}

/* Second order: the Jacobians at a new anchor, u from the old one, are the old ones plus
 * the second derivatives times u (exact to that order), so that re-anchoring does not
 * leave them a step behind. */
static void carry(tt_envelope *e, const double *u)
{
    const int nx = e->nx, ni = e->ni, no = e->no, nr = e->nr;
    const size_t npair = (size_t)e->npair;
    for (int j = 0; j < e->nin; j++)
        for (int k = 0; k < e->nin; k++) {
            const size_t p = (size_t)(j <= k ? tt_envelope_pair(e, j, k) : tt_envelope_pair(e, k, j));
            for (int i = 0; i < nx; i++)
                e->J[i * ni + j] += e->Hv[(size_t)i * npair + p] * u[k];
            for (int i = 0; i < no; i++)
                e->C[(size_t)j * (size_t)no + (size_t)i] += e->Hv[(size_t)(nx + i) * npair + p] * u[k];
            for (int i = 0; e->Cr && i < nr; i++)
                e->Cr[(size_t)j * (size_t)nr + (size_t)i] += e->Hrv[(size_t)i * npair + p] * u[k];
        }
}

void tt_envelope_anchor(tt_envelope *e, const double *x0, double s, double sdot,
                        const double *x1, const tt_cycle *cy, const double *obs)
{
    if (e->second && e->built) {
        double u[NIN_MAX];
        offsets(e, x0, s, sdot, u);
        carry(e, u);
    }
    memcpy(e->xa, x0, (size_t)e->nx * sizeof *x0);
    e->sa = s + 0.5 * sdot * e->T;
    e->ta = sdot * e->T;
    memcpy(e->x1, x1, (size_t)e->nx * sizeof *x1);
    e->touched = tt_envelope_touched(cy);
    memcpy(e->oa, obs, (size_t)e->no * sizeof *obs);
    reduce(e, e->oa, e->ra);
}

/* One perturbed cycle from x0 + dx with the sample at s + ds mid-cycle travelling dt more
 * within it (dx: the state's, then ds, dt): end state and observables; its outcome (the
 * anchor's branch: touch, end contact flag). trk: the state at the samples (the tip's
 * (d, d'), then the law's states). */
static tt_envelope_outcome perturbed(tt_envelope *e, tt_sim *sim, const double *x0, int c0,
                                     double s, double sdot, const double *dx, int c1,
                                     double *x1, double *obs, double *trk)
{
    const int nx = e->nx;
    double xp[TT_SIM_DIM_MAX];
    tt_cycle cy;
    int c;
    for (int i = 0; i < nx; i++)
        xp[i] = x0[i] + dx[i];
    tt_sim_set_x(sim, xp, c0);
    tt_sim_set_sample(sim, s + dx[nx] - 0.5 * dx[nx + 1], sdot + dx[nx + 1] / e->T);
    if (tt_sim_cycle(sim, &cy) != TT_OK) {
        tt_error_clear();
        return TT_ENV_CYCLE_FAILED;
    }
    tt_sim_get_x(sim, x1, &c);
    if (c != c1 || tt_envelope_touched(&cy) != e->touched)
        return TT_ENV_OFF_BRANCH;
    const tt_sample *smp = tt_sim_samples(sim);
    tt_envelope_observe(e, smp, tt_sim_probes(sim), &cy, obs);
    for (int q = 0; trk && q < e->n; q++) {
        trk[nx * q] = smp[q].d;
        trk[nx * q + 1] = smp[q].v;
        for (int i = 2; i < nx; i++)
            trk[nx * q + i] = smp[q].q[i - 2];
    }
    return TT_ENV_USABLE;
}

/* The second derivatives (second order), by differences over steps hq: the diagonal
 * ones from the build's cycles at +-hq of each input (pp, pm: their outputs, by input),
 * the mixed ones from one more at (+hq_j, +hq_k) each (P0: the anchor's outputs, end
 * state then observables; q: scratch of 2 nq). */
static tt_envelope_outcome second_derivatives(tt_envelope *e, tt_sim *sim, const double *x0,
                                              int c0, double s, double sdot, int c1,
                                              const double *hq, const double *P0,
                                              const double *pp, const double *pm, double *q,
                                              long *cycles)
{
    const int nx = e->nx, nq = nx + e->no, nr = e->nr;
    const size_t npair = (size_t)e->npair;
    double *r = q + nq;
    tt_envelope_outcome how = TT_ENV_USABLE;
    for (int j = 0; j < e->nin; j++) {
        const double *a = pp + (size_t)j * (size_t)nq, *b = pm + (size_t)j * (size_t)nq;
        const size_t p = (size_t)tt_envelope_pair(e, j, j);
        for (int i = 0; i < nq; i++)
            e->H[(size_t)i * npair + p] = (a[i] - 2 * P0[i] + b[i]) / (hq[j] * hq[j]);
    }
    for (int j = 0; j < e->nin && how == TT_ENV_USABLE; j++)
        for (int k = j + 1; k < e->nin && how == TT_ENV_USABLE; k++) {
            double d[NIN_MAX] = {0};
            d[j] = hq[j];
            d[k] = hq[k];
            how = perturbed(e, sim, x0, c0, s, sdot, d, c1, q, q + nx, NULL);
            *cycles += 1;
            const double *a = pp + (size_t)j * (size_t)nq, *b = pp + (size_t)k * (size_t)nq;
            const size_t p = (size_t)tt_envelope_pair(e, j, k);
            for (int i = 0; i < nq && how == TT_ENV_USABLE; i++)
                e->H[(size_t)i * npair + p] = (q[i] - a[i] - b[i] + P0[i]) / (hq[j] * hq[k]);
        }
    /* an observable not tracked (NaN) has no curvature to add */
    for (size_t i = 0; i < (size_t)nq * npair; i++)
        if (isnan(e->H[i]))
            e->H[i] = 0;
    for (size_t p = 0; p < npair && how == TT_ENV_USABLE && e->R; p++) {
        for (int i = 0; i < e->no; i++)
            q[i] = e->H[(size_t)(nx + i) * npair + p];
        reduce(e, q, r);
        for (int i = 0; i < nr; i++)
            e->Hr[(size_t)i * npair + p] = r[i];
    }
    return how;
}

tt_envelope_outcome tt_envelope_build(tt_envelope *e, tt_sim *sim, const double *x0, int c0,
                                      double s, double sdot, const tt_cycle *cy,
                                      const double *obs, long *cycles)
{
    const int nx = e->nx, ni = e->ni;
    double x1[TT_SIM_DIM_MAX];
    int c1;
    tt_sim_get_x(sim, x1, &c1);
    e->built = 0;
    tt_envelope_own_views(e);
    tt_envelope_anchor(e, x0, s, sdot, x1, cy, obs);
    e->contact = c0;
    /* central differences over each input's step (build_steps); second order: over the
     * second differences' steps too (below), whose cycles then give both: the Jacobian's
     * error from the third derivatives, hq^2 / 6 of them, is a ninth of the model's own
     * third-order error at its reach (3e-3 of A0 against 1e-3) */
    const double *h = e->hs;
    const int nq = nx + e->no;
    /* the anchor's outputs and the perturbed ones, by input: end state, observables */
    double *P = e->work, *pp = P + nq, *pm = pp + (size_t)ni * (size_t)nq;
    memcpy(P, x1, (size_t)nx * sizeof *x1);
    memcpy(P + nx, obs, (size_t)e->no * sizeof *obs);
    tt_envelope_outcome how = TT_ENV_USABLE;
    for (int j = 0; j < e->nin && how == TT_ENV_USABLE; j++) {
        double dp[NIN_MAX] = {0}, dm[NIN_MAX] = {0};
        dp[j] = h[j];
        dm[j] = -h[j];
        /* the states along the cycles perturbed in d and d' give the flow's Jacobian for
         * the thermal noise's covariance */
        double *tp = e->trk && j < nx ? e->trk + (size_t)(2 * nx * j) * (size_t)e->n : NULL;
        double *a = pp + (size_t)j * (size_t)nq, *b = pm + (size_t)j * (size_t)nq;
        how = perturbed(e, sim, x0, c0, s, sdot, dp, c1, a, a + nx, tp);
        if (how == TT_ENV_USABLE)
            how = perturbed(e, sim, x0, c0, s, sdot, dm, c1, b, b + nx, tp ? tp + nx * e->n : NULL);
        *cycles += 2;
        for (int i = 0; i < nx && how == TT_ENV_USABLE; i++)
            e->J[i * ni + j] = (a[i] - b[i]) / (2 * h[j]);
        for (int i = 0; i < e->no && how == TT_ENV_USABLE; i++)
            e->C[j * e->no + i] = (a[nx + i] - b[nx + i]) / (2 * h[j]);
    }
    for (int j = 0; j < e->nin && how == TT_ENV_USABLE && e->R; j++)
        reduce(e, e->C + (size_t)j * (size_t)e->no, e->Cr + (size_t)j * (size_t)e->nr);
    /* second differences over 1e-3 of the scales: over 1e-4 the stepper's noise (about
     * 1e-7 of A0 a cycle, over h^2) biased the curvature of outputs that barely respond
     * (the phase on a soft polymer) enough for u^2 H / 2 to drift it over a stretch;
     * three times more erred by their third-order term on stiff contact (30 GPa) */
    if (how == TT_ENV_USABLE && e->second)
        how = second_derivatives(e, sim, x0, c0, s, sdot, c1, h, P, pp, pm,
                                 pm + (size_t)ni * (size_t)nq, cycles);
    if (how == TT_ENV_USABLE && e->trk) {
        tt_envelope_flow_measured(e, h);
        if (!tt_envelope_thermal_covariance(e))
            how = TT_ENV_SINGULAR_FLOW;
    }
    e->built = how == TT_ENV_USABLE && e->second;
    memcpy(e->xb, e->xa, (size_t)nx * sizeof *e->xa);
    e->sb = e->sa;
    e->tb = e->ta;
    tt_sim_set_x(sim, x1, c1);
    return how;
}
