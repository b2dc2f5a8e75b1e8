/* The envelope tier's local model of the cycle map (see include/tiptap/solver/envelope.h). */
#include "tiptap/solver/envelope.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "envelope_private.h"

/* The place of the input pair (i, j), i <= j, among the NPAIR second derivatives. */
static int pair_of(int i, int j)
{
    return i * NIN - i * (i - 1) / 2 + (j - i);
}

int tt_envelope_alloc(tt_envelope **out, const tt_cantilever *c, int n)
{
    *out = NULL;
    tt_envelope *e = calloc(1, sizeof *e);
    if (!e)
        return tt_error_nomem("the envelope tier's cycle map");
    e->n = n;
    e->no = n + TT_ENV_EXTRA;
    e->nin = 3;
    e->T = c->T;
    e->L = c->A0;
    e->V = c->wd * c->A0;
    e->mass = c->m;
    e->w0 = c->w0;
    e->sig = 0.5 * c->c / c->m;
    e->oscale = malloc((size_t)e->no * sizeof *e->oscale);
    e->oa = calloc((size_t)e->no, sizeof *e->oa);
    e->C = calloc((size_t)e->no * NIN, sizeof *e->C);
    if (!e->oscale || !e->oa || !e->C) {
        tt_envelope_free(e);
        return tt_error_nomem("the envelope tier's cycle map");
    }
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
    *out = e;
    return TT_OK;
}

void tt_envelope_free(tt_envelope *e)
{
    if (!e)
        return;
    free(e->oscale);
    free(e->oa);
    free(e->C);
    free(e->R);
    free(e->ra);
    free(e->Cr);
    free(e->trk);
    free(e->Lj);
    free(e->Ld);
    free(e->phi);
    free(e->Lf);
    free(e->H);
    free(e->Hr);
    tt_envelope_models_free(e);
    free(e);
}

int tt_envelope_size(const tt_envelope *e) { return e->no; }

int tt_envelope_set_probes(tt_envelope *e, int np)
{
    const int no = e->n + TT_ENV_EXTRA + np;
    double *os = realloc(e->oscale, (size_t)no * sizeof *os);
    if (!os)
        return tt_error_nomem("the envelope tier's cycle map");
    e->oscale = os;
    free(e->oa);
    free(e->C);
    e->oa = calloc((size_t)no, sizeof *e->oa);
    e->C = calloc((size_t)no * NIN, sizeof *e->C);
    if (!e->oa || !e->C)
        return tt_error_nomem("the envelope tier's cycle map");
    for (int i = e->no; i < no; i++)
        e->oscale[i] = e->L;
    e->no = no;
    e->np = np;
    return TT_OK;
}

int tt_envelope_probes(const tt_envelope *e) { return e->np; }

void tt_envelope_use_travel(tt_envelope *e) { e->nin = 4; }

int tt_envelope_use_second_order(tt_envelope *e)
{
    free(e->H);
    free(e->Hr);
    e->H = calloc((size_t)(2 + e->no) * NPAIR, sizeof *e->H);
    e->Hr = calloc((size_t)(e->m + TT_ENV_EXTRA + e->np) * NPAIR, sizeof *e->Hr);
    tt_envelope_own_views(e);
    if (!e->H || !e->Hr)
        return tt_error_nomem("the envelope tier's second-order model");
    e->second = 1;
    e->built = 0;
    return TT_OK;
}

int tt_envelope_reduce(tt_envelope *e, int m, const double *R)
{
    size_t nr = (size_t)m + TT_ENV_EXTRA + (size_t)e->np;
    free(e->R);
    free(e->ra);
    free(e->Cr);
    e->m = m;
    e->R = malloc((size_t)m * (size_t)e->n * sizeof *e->R);
    e->ra = calloc(nr, sizeof *e->ra);
    e->Cr = calloc(nr * NIN, sizeof *e->Cr);
    if (!e->R || !e->ra || !e->Cr)
        return tt_error_nomem("the envelope tier's cycle map");
    memcpy(e->R, R, (size_t)m * (size_t)e->n * sizeof *R);
    return TT_OK;
}

/* An observable vector o (no) reduced: r (m + TT_ENV_EXTRA + np), the samples through R,
 * the rest as they are. */
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

double tt_envelope_reach(const tt_envelope *e, const double x[2], double s, double sdot)
{
    return tt_envelope_distance(e, e->xa, e->sa, e->ta, x, s, sdot);
}

void tt_envelope_observe(const tt_envelope *e, const tt_sample *samples, const tt_cycle *cy,
                         double *obs)
{
    for (int q = 0; q < e->n; q++)
        obs[q] = samples[q].d - samples[q].z;
    obs[e->n + TT_ENV_PEAK] = cy->peak_force;
    obs[e->n + TT_ENV_INDENT] = cy->max_indentation;
    obs[e->n + TT_ENV_ETS] = cy->e_ts;
}

void tt_envelope_observe_probes(const tt_envelope *e, const tt_sample *probes, double *obs)
{
    double *g = obs + e->n + TT_ENV_EXTRA;
    for (int q = 0; q < e->np; q++)
        g[q] = probes ? probes[q].d : NAN;
}

/* The model's inputs' offsets u from the anchor: d, d', the sample mid-cycle and its
 * travel within the cycle (0 unless the travel is an input). */
static inline void offsets(const tt_envelope *e, const double x[2], double s, double sdot,
                           double u[NIN])
{
    u[0] = x[0] - e->xa[0];
    u[1] = x[1] - e->xa[1];
    u[2] = s + 0.5 * sdot * e->T - e->sa;
    u[3] = e->nin > 3 ? sdot * e->T - e->ta : 0;
}

/* Second order: the Jacobians at a new anchor, u from the old one, are the old ones plus
 * the second derivatives times u (exact to that order), so that re-anchoring does not
 * leave them a step behind. */
static void carry(tt_envelope *e, const double u[NIN])
{
    const int no = e->no, nr = e->m + TT_ENV_EXTRA + e->np;
    for (int j = 0; j < e->nin; j++)
        for (int k = 0; k < e->nin; k++) {
            const int p = j <= k ? pair_of(j, k) : pair_of(k, j);
            for (int i = 0; i < 2; i++)
                e->J[i][j] += e->Hv[i * NPAIR + p] * u[k];
            for (int i = 0; i < no; i++)
                e->C[(size_t)j * (size_t)no + (size_t)i] += e->Hv[(size_t)(2 + i) * NPAIR + (size_t)p] * u[k];
            for (int i = 0; e->Cr && i < nr; i++)
                e->Cr[(size_t)j * (size_t)nr + (size_t)i] += e->Hrv[(size_t)i * NPAIR + (size_t)p] * u[k];
        }
}

void tt_envelope_anchor(tt_envelope *e, const double x0[2], double s, double sdot,
                        const double x1[2], const tt_cycle *cy, const double *obs)
{
    if (e->second && e->built) {
        double u[NIN];
        offsets(e, x0, s, sdot, u);
        carry(e, u);
    }
    e->xa[0] = x0[0];
    e->xa[1] = x0[1];
    e->sa = s + 0.5 * sdot * e->T;
    e->ta = sdot * e->T;
    e->x1[0] = x1[0];
    e->x1[1] = x1[1];
    e->touched = tt_envelope_touched(cy);
    memcpy(e->oa, obs, (size_t)e->no * sizeof *obs);
    reduce(e, e->oa, e->ra);
}

/* One perturbed cycle from x0 + dx with the sample at s + ds mid-cycle travelling dt more
 * within it (dx = (dd, dd', ds, dt)): end state and observables; 0 if it failed or left
 * the anchor's branch (touch, end contact flag). */
static int perturbed(tt_envelope *e, tt_sim *sim, const double x0[2], int c0, double s,
                     double sdot, const double dx[NIN], int c1, double x1[2], double *obs,
                     double *trk)
{
    tt_cycle cy;
    int c;
    tt_sim_set_state(sim, x0[0] + dx[0], x0[1] + dx[1], c0);
    tt_sim_set_sample(sim, s + dx[2] - 0.5 * dx[3], sdot + dx[3] / e->T);
    if (tt_sim_cycle(sim, &cy) != TT_OK) {
        tt_error_clear();
        return 0;
    }
    tt_sim_get_state(sim, &x1[0], &x1[1], &c);
    if (c != c1 || tt_envelope_touched(&cy) != e->touched)
        return 0;
    const tt_sample *smp = tt_sim_samples(sim);
    tt_envelope_observe(e, smp, &cy, obs);
    tt_envelope_observe_probes(e, tt_sim_probes(sim), obs);
    for (int q = 0; trk && q < e->n; q++) {
        trk[2 * q] = smp[q].d;
        trk[2 * q + 1] = smp[q].v;
    }
    return 1;
}

/* The second derivatives (second order), by differences over steps hq: the diagonal
 * ones from the build's cycles at +-hq of each input (pp, pm: their outputs, by input),
 * the mixed ones from one more at (+hq_j, +hq_k) each (P0: the anchor's outputs, end
 * state then observables). */
static int second_derivatives(tt_envelope *e, tt_sim *sim, const double x0[2], int c0,
                              double s, double sdot, int c1, const double hq[NIN],
                              const double *P0, const double *pp, const double *pm,
                              long *cycles)
{
    const int nq = 2 + e->no, nr = e->m + TT_ENV_EXTRA + e->np;
    double *q = malloc(2 * (size_t)nq * sizeof *q);
    if (!q)
        return 0;
    double *r = q + nq;
    int ok = 1;
    for (int j = 0; j < e->nin; j++) {
        const double *a = pp + (size_t)j * (size_t)nq, *b = pm + (size_t)j * (size_t)nq;
        for (int i = 0; i < nq; i++)
            e->H[(size_t)i * NPAIR + (size_t)pair_of(j, j)] = (a[i] - 2 * P0[i] + b[i]) / (hq[j] * hq[j]);
    }
    for (int j = 0; j < e->nin && ok; j++)
        for (int k = j + 1; k < e->nin && ok; k++) {
            double d[NIN] = {0};
            d[j] = hq[j];
            d[k] = hq[k];
            ok = perturbed(e, sim, x0, c0, s, sdot, d, c1, q, q + 2, NULL);
            *cycles += 1;
            const double *a = pp + (size_t)j * (size_t)nq, *b = pp + (size_t)k * (size_t)nq;
            for (int i = 0; i < nq && ok; i++)
                e->H[(size_t)i * NPAIR + (size_t)pair_of(j, k)] = (q[i] - a[i] - b[i] + P0[i]) / (hq[j] * hq[k]);
        }
    /* an observable not tracked (NaN) has no curvature to add */
    for (size_t i = 0; i < (size_t)nq * NPAIR; i++)
        if (isnan(e->H[i]))
            e->H[i] = 0;
    for (int p = 0; p < NPAIR && ok && e->R; p++) {
        for (int i = 0; i < e->no; i++)
            q[i] = e->H[(size_t)(2 + i) * NPAIR + (size_t)p];
        reduce(e, q, r);
        for (int i = 0; i < nr; i++)
            e->Hr[(size_t)i * NPAIR + (size_t)p] = r[i];
    }
    free(q);
    return ok;
}

int tt_envelope_build(tt_envelope *e, tt_sim *sim, const double x0[2], int c0, double s,
                      double sdot, const tt_cycle *cy, const double *obs, long *cycles)
{
    double x1[2];
    int c1;
    tt_sim_get_state(sim, &x1[0], &x1[1], &c1);
    e->built = 0;
    tt_envelope_own_views(e);
    tt_envelope_anchor(e, x0, s, sdot, x1, cy, obs);
    e->contact = c0;
    /* central differences: steps of 1e-4 of the scales, where the stepper's noise
     * (about the tolerance) costs 1e-4 of the Jacobian at the default, and the
     * contact's length scales (a nanometre) are far. Second order: over the second
     * differences' steps (below), whose cycles then give both: the Jacobian's error from
     * the third derivatives, hq^2 / 6 of them, is a ninth of the model's own third-order
     * error at its reach (3e-3 of A0 against 1e-3) */
    const double h1 = e->second ? 1e-3 : 1e-4;
    const double h[NIN] = {h1 * e->L, h1 * e->V, h1 * e->L, h1 * e->L};
    const int nq = 2 + e->no;
    /* the anchor's outputs and the perturbed ones, by input: end state, observables */
    double *P = malloc((size_t)(1 + 2 * NIN) * (size_t)nq * sizeof *P);
    if (!P)
        return 0;
    double *pp = P + nq, *pm = pp + (size_t)NIN * (size_t)nq;
    P[0] = x1[0];
    P[1] = x1[1];
    memcpy(P + 2, obs, (size_t)e->no * sizeof *obs);
    int ok = 1;
    for (int j = 0; j < e->nin && ok; j++) {
        double dp[NIN] = {0}, dm[NIN] = {0};
        dp[j] = h[j];
        dm[j] = -h[j];
        /* the states along the cycles perturbed in d and d' give the flow's Jacobian for
         * the thermal noise's covariance */
        double *tp = e->trk && j < 2 ? e->trk + (size_t)(4 * j) * (size_t)e->n : NULL;
        double *a = pp + (size_t)j * (size_t)nq, *b = pm + (size_t)j * (size_t)nq;
        ok = perturbed(e, sim, x0, c0, s, sdot, dp, c1, a, a + 2, tp) &&
             perturbed(e, sim, x0, c0, s, sdot, dm, c1, b, b + 2, tp ? tp + 2 * e->n : NULL);
        *cycles += 2;
        for (int i = 0; i < 2 && ok; i++)
            e->J[i][j] = (a[i] - b[i]) / (2 * h[j]);
        for (int i = 0; i < e->no && ok; i++)
            e->C[j * e->no + i] = (a[2 + i] - b[2 + i]) / (2 * h[j]);
    }
    for (int j = 0; j < e->nin && ok; j++)
        reduce(e, e->C + (size_t)j * (size_t)e->no,
               e->Cr + (size_t)j * (size_t)(e->m + TT_ENV_EXTRA + e->np));
    /* second differences over 1e-3 of the scales: over 1e-4 the stepper's noise (about
     * 1e-7 of A0 a cycle, over h^2) biased the curvature of outputs that barely respond
     * (the phase on a soft polymer) enough for u^2 H / 2 to drift it over a stretch;
     * three times more erred by their third-order term on stiff contact (30 GPa) */
    if (ok && e->second)
        ok = second_derivatives(e, sim, x0, c0, s, sdot, c1, h, P, pp, pm, cycles);
    free(P);
    if (ok && e->trk) {
        tt_envelope_flow_measured(e, h);
        ok = tt_envelope_thermal_covariance(e);
    }
    e->built = ok && e->second;
    e->xb[0] = e->xa[0];
    e->xb[1] = e->xa[1];
    e->sb = e->sa;
    e->tb = e->ta;
    tt_sim_set_state(sim, x1[0], x1[1], c1);
    return ok;
}

/* The model's end state from x, and the inputs' offsets u, in the first three inputs (the
 * travel's part: add_travel). */
static inline void step(const tt_envelope *e, const double x[2], double s, double sdot,
                        double u[NIN], double x1[2])
{
    u[0] = x[0] - e->xa[0];
    u[1] = x[1] - e->xa[1];
    u[2] = s + 0.5 * sdot * e->T - e->sa;
    for (int i = 0; i < 2; i++)
        x1[i] = e->x1[i] + e->J[i][0] * u[0] + e->J[i][1] * u[1] + e->J[i][2] * u[2];
}

/* Observables o = oa + C u (no of them) in the first three inputs, C by columns of length
 * ld. */
static inline void linear(int no, int ld, const double *restrict oa, const double *restrict C,
                          const double u[NIN], double *restrict o)
{
    const double *restrict c0 = C, *restrict c1 = c0 + ld, *restrict c2 = c1 + ld;
    for (int i = 0; i < no; i++)
        o[i] = oa[i] + c0[i] * u[0] + c1[i] * u[1] + c2[i] * u[2];
}

/* The travel's part where it is an input (tt_envelope_use_travel): its offset u[3], and
 * its column of J and of C (length ld) times it added to x1 and the no outputs o, term
 * by term as one sum over the four inputs would. */
static inline void add_travel(const tt_envelope *e, double sdot, double u[NIN], double x1[2],
                              int no, int ld, const double *restrict C, double *restrict o)
{
    u[3] = sdot * e->T - e->ta;
    for (int i = 0; i < 2; i++)
        x1[i] += e->J[i][3] * u[3];
    const double *restrict c3 = C + 3 * (size_t)ld;
    for (int i = 0; i < no; i++)
        o[i] += c3[i] * u[3];
}

/* A first-order prediction with the travel an input: the end state x1 and no outputs
 * from oa and C (columns of length ld). Out of line, so that the three inputs' paths, a
 * noise-free scan's, compile as lean as without it. */
__attribute__((noinline)) static void predict_travel(const tt_envelope *e, const double x[2],
                                                     double s, double sdot, double x1[2],
                                                     int no, int ld, const double *oa,
                                                     const double *C, double *o)
{
    double u[NIN];
    step(e, x, s, sdot, u, x1);
    linear(no, ld, oa, C, u, o);
    add_travel(e, sdot, u, x1, no, ld, C, o);
}

/* Second order (a second-order perturbation expansion about the anchor): the state is
 * x = xl + x2, its first-order part xl iterated by the linear model from the inputs'
 * offsets u, and its second-order part x2 by x2' = dP/dx x2 + H(u, u) / 2; the
 * observables get C (x2, 0) + H(u, u) / 2. Iterating the quadratic map itself would have
 * a spurious fixed point at |u| about (1 - |mu|) / |H| (50 pm at the Floquet multiplier
 * 0.99 and the curvature 4 / A0), past which it runs off; the expansion is as accurate to
 * second order and as stable as the linear model. Ho: the outputs' second derivatives
 * (no rows of NPAIR), Co: their Jacobian by columns of length ld. */
static void second_order(const tt_envelope *e, const double u[NIN], const double x2[2],
                         double x21[2], int no, int ld, const double *Ho, const double *Co,
                         double *o)
{
    double w[NPAIR];
    for (int j = 0; j < NIN; j++)
        for (int k = j; k < NIN; k++)
            w[pair_of(j, k)] = (j == k ? 0.5 : 1.0) * u[j] * u[k];
    for (int i = 0; i < 2; i++) {
        double sum = e->J[i][0] * x2[0] + e->J[i][1] * x2[1];
        for (int p = 0; p < NPAIR; p++)
            sum += e->Hv[i * NPAIR + p] * w[p];
        x21[i] = sum;
    }
    for (int i = 0; i < no; i++) {
        double sum = Co[i] * x2[0] + Co[ld + i] * x2[1];
        const double *row = Ho + (size_t)i * NPAIR;
        for (int p = 0; p < NPAIR; p++)
            sum += row[p] * w[p];
        o[i] += sum;
    }
}

void tt_envelope_predict2(const tt_envelope *e, const double x[2], const double x2[2], double s,
                          double sdot, double x1[2], double x21[2], double *obs)
{
    double u[NIN] = {0, 0, 0, 0}, xl[2] = {x[0] - x2[0], x[1] - x2[1]};
    step(e, xl, s, sdot, u, x1);
    linear(e->no, e->no, e->oa, e->C, u, obs);
    if (e->nin > 3)
        add_travel(e, sdot, u, x1, e->no, e->no, e->C, obs);
    x21[0] = x21[1] = 0;
    if (e->second && e->built) {
        second_order(e, u, x2, x21, e->no, e->no, e->Hv + 2 * NPAIR, e->C, obs);
        x1[0] += x21[0];
        x1[1] += x21[1];
    }
}

void tt_envelope_predict2_reduced(const tt_envelope *e, const double x[2], const double x2[2],
                                  double s, double sdot, double x1[2], double x21[2], double *red)
{
    x21[0] = x21[1] = 0;
    if (!(e->second && e->built)) {
        tt_envelope_predict_reduced(e, x, s, sdot, x1, red);
        return;
    }
    double u[NIN] = {0, 0, 0, 0}, xl[2] = {x[0] - x2[0], x[1] - x2[1]};
    const int nr = e->m + TT_ENV_EXTRA, ld = nr + e->np;
    step(e, xl, s, sdot, u, x1);
    linear(nr, ld, e->ra, e->Cr, u, red);
    if (e->nin > 3)
        add_travel(e, sdot, u, x1, nr, ld, e->Cr, red);
    second_order(e, u, x2, x21, nr, ld, e->Hrv, e->Cr, red);
    x1[0] += x21[0];
    x1[1] += x21[1];
}

void tt_envelope_predict(const tt_envelope *e, const double x[2], double s, double sdot,
                         double x1[2], double *obs)
{
    const double x2[2] = {0, 0};
    double x21[2];
    tt_envelope_predict2(e, x, x2, s, sdot, x1, x21, obs);
}

void tt_envelope_predict_reduced(const tt_envelope *e, const double x[2], double s, double sdot,
                                 double x1[2], double *red)
{
    double u[NIN];
    const int nr = e->m + TT_ENV_EXTRA, ld = nr + e->np;
    if (e->nin > 3) {
        predict_travel(e, x, s, sdot, x1, nr, ld, e->ra, e->Cr, red);
        return;
    }
    step(e, x, s, sdot, u, x1);
    linear(nr, ld, e->ra, e->Cr, u, red);
}

void tt_envelope_predict_probes(const tt_envelope *e, const double x[2], double s, double sdot,
                                double *g)
{
    double u[NIN], x1[2];
    const int k = e->m + TT_ENV_EXTRA;
    step(e, x, s, sdot, u, x1);
    linear(e->np, k + e->np, e->ra + k, e->Cr + k, u, g);
}

double tt_envelope_error_reduced(const tt_envelope *e, const double xa[2], const double *ra,
                                 const double xb[2], const double *rb)
{
    double err = fmax(fabs(xa[0] - xb[0]) / e->L, fabs(xa[1] - xb[1]) / e->V);
    for (int i = 0; i < e->m + TT_ENV_EXTRA + e->np; i++) {
        const double sc = i < e->m ? e->L : e->oscale[e->n + i - e->m];
        double d = fabs(ra[i] - rb[i]) / sc;
        if (d > err)
            err = d; /* NAN (not tracked, or a probe not asked for) is skipped */
    }
    return err;
}

double tt_envelope_error(const tt_envelope *e, const double xa[2], const double *oa,
                         const double xb[2], const double *ob)
{
    double err = fmax(fabs(xa[0] - xb[0]) / e->L, fabs(xa[1] - xb[1]) / e->V);
    int i0 = 0;
    if (e->second && e->R) {
        /* the samples as the lock-in reads them, its components (over A0), rather than
         * each sample: near the impact single samples move far from the model at second
         * order (a sample crosses into contact), and the projection averages that out */
        for (int i = 0; i < e->m; i++) {
            const double *row = e->R + (size_t)i * (size_t)e->n;
            double d = 0;
            for (int q = 0; q < e->n; q++)
                d += row[q] * (oa[q] - ob[q]);
            err = fmax(err, fabs(d) / e->L);
        }
        i0 = e->n;
    }
    for (int i = i0; i < e->no; i++) {
        double d = fabs(oa[i] - ob[i]) / e->oscale[i];
        if (d > err)
            err = d; /* NAN (a channel not tracked) is skipped */
    }
    return err;
}
