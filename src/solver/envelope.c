/* The envelope tier's local model of the cycle map (see include/tiptap/solver/envelope.h). */
#include "tiptap/solver/envelope.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

/* Inputs of the model: d, d' at the cycle start and the sample's position mid-cycle. */
enum { NIN = 3 };

struct tt_envelope {
    int n, no;            /* samples per cycle; observables (n + TT_ENV_EXTRA) */
    double T, L, V;       /* period; length and velocity scales (A0, w A0) */
    double *oscale;       /* per observable: its scale */
    /* the anchor: a cycle integrated from xa with the sample at sa (mid-cycle) */
    double xa[2], sa, x1[2];
    int contact, touched;
    double *oa;
    /* Jacobians: of the end state and of the observables, by input */
    double J[2][NIN];
    double *C;            /* no x NIN, by columns (the prediction's loop vectorises) */
    /* the samples reduced (tt_envelope_reduce): m x n rows R; the anchor's reduced
     * observables ra (m + TT_ENV_EXTRA) and their Jacobian Cr, by columns */
    int m;
    double *R, *ra, *Cr;
};

int tt_envelope_alloc(tt_envelope **out, const tt_cantilever *c, int n)
{
    *out = NULL;
    tt_envelope *e = calloc(1, sizeof *e);
    if (!e)
        return tt_error_nomem("the envelope tier's cycle map");
    e->n = n;
    e->no = n + TT_ENV_EXTRA;
    e->T = c->T;
    e->L = c->A0;
    e->V = c->wd * c->A0;
    e->oscale = malloc((size_t)e->no * sizeof *e->oscale);
    e->oa = calloc((size_t)e->no, sizeof *e->oa);
    e->C = calloc((size_t)e->no * NIN, sizeof *e->C);
    if (!e->oscale || !e->oa || !e->C) {
        tt_envelope_free(e);
        return tt_error_nomem("the envelope tier's cycle map");
    }
    for (int i = 0; i < n; i++)
        e->oscale[i] = c->A0;
    e->oscale[n + TT_ENV_PEAK] = c->k * c->A0;
    e->oscale[n + TT_ENV_INDENT] = c->A0;
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
    free(e);
}

int tt_envelope_size(const tt_envelope *e) { return e->no; }

int tt_envelope_reduce(tt_envelope *e, int m, const double *R)
{
    size_t nr = (size_t)m + TT_ENV_EXTRA;
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

/* An observable vector o (no) reduced: r (m + TT_ENV_EXTRA), the samples through R. */
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
    for (int i = 0; i < TT_ENV_EXTRA; i++)
        r[e->m + i] = o[e->n + i];
}

int tt_envelope_touched(const tt_cycle *cy) { return cy->contact_fraction > 0 || cy->events > 0; }
int tt_envelope_anchor_touched(const tt_envelope *e) { return e->touched; }
int tt_envelope_anchor_contact(const tt_envelope *e) { return e->contact; }

double tt_envelope_sample_offset(const tt_envelope *e, double s, double sdot)
{
    return s + 0.5 * sdot * e->T - e->sa;
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

void tt_envelope_anchor(tt_envelope *e, const double x0[2], double s, double sdot,
                        const double x1[2], const tt_cycle *cy, const double *obs)
{
    e->xa[0] = x0[0];
    e->xa[1] = x0[1];
    e->sa = s + 0.5 * sdot * e->T;
    e->x1[0] = x1[0];
    e->x1[1] = x1[1];
    e->touched = tt_envelope_touched(cy);
    memcpy(e->oa, obs, (size_t)e->no * sizeof *obs);
    reduce(e, e->oa, e->ra);
}

/* One perturbed cycle from x0 + dx with the sample at s + ds: end state and
 * observables; 0 if it failed or left the anchor's branch (touch, end contact flag). */
static int perturbed(tt_envelope *e, tt_sim *sim, const double x0[2], int c0, double s,
                     double sdot, const double dx[NIN], int c1, double x1[2], double *obs)
{
    tt_cycle cy;
    int c;
    tt_sim_set_state(sim, x0[0] + dx[0], x0[1] + dx[1], c0);
    tt_sim_set_sample(sim, s + dx[2], sdot);
    if (tt_sim_cycle(sim, &cy) != TT_OK) {
        tt_error_clear();
        return 0;
    }
    tt_sim_get_state(sim, &x1[0], &x1[1], &c);
    if (c != c1 || tt_envelope_touched(&cy) != e->touched)
        return 0;
    const tt_sample *smp = tt_sim_samples(sim);
    tt_envelope_observe(e, smp, &cy, obs);
    return 1;
}

int tt_envelope_build(tt_envelope *e, tt_sim *sim, const double x0[2], int c0, double s,
                      double sdot, const tt_cycle *cy, const double *obs, long *cycles)
{
    double x1[2], xp[2], xm[2];
    int c1;
    tt_sim_get_state(sim, &x1[0], &x1[1], &c1);
    tt_envelope_anchor(e, x0, s, sdot, x1, cy, obs);
    e->contact = c0;
    /* central differences: steps of 1e-4 of the scales, where the stepper's noise
     * (about the tolerance) costs 1e-4 of the Jacobian at the default, and the
     * contact's length scales (a nanometre) are far */
    const double h[NIN] = {1e-4 * e->L, 1e-4 * e->V, 1e-4 * e->L};
    double *op = malloc(2 * (size_t)e->no * sizeof *op);
    if (!op)
        return 0;
    double *om = op + e->no;
    int ok = 1;
    for (int j = 0; j < NIN && ok; j++) {
        double dp[NIN] = {0}, dm[NIN] = {0};
        dp[j] = h[j];
        dm[j] = -h[j];
        ok = perturbed(e, sim, x0, c0, s, sdot, dp, c1, xp, op) &&
             perturbed(e, sim, x0, c0, s, sdot, dm, c1, xm, om);
        *cycles += 2;
        for (int i = 0; i < 2 && ok; i++)
            e->J[i][j] = (xp[i] - xm[i]) / (2 * h[j]);
        for (int i = 0; i < e->no && ok; i++)
            e->C[j * e->no + i] = (op[i] - om[i]) / (2 * h[j]);
    }
    free(op);
    for (int j = 0; j < NIN && ok; j++)
        reduce(e, e->C + (size_t)j * (size_t)e->no, e->Cr + (size_t)j * (size_t)(e->m + TT_ENV_EXTRA));
    tt_sim_set_state(sim, x1[0], x1[1], c1);
    return ok;
}

/* The model's inputs' offsets from the anchor, and its end state from x. */
static void step(const tt_envelope *e, const double x[2], double s, double sdot, double u[NIN],
                 double x1[2])
{
    u[0] = x[0] - e->xa[0];
    u[1] = x[1] - e->xa[1];
    u[2] = s + 0.5 * sdot * e->T - e->sa;
    for (int i = 0; i < 2; i++)
        x1[i] = e->x1[i] + e->J[i][0] * u[0] + e->J[i][1] * u[1] + e->J[i][2] * u[2];
}

/* Observables o = oa + C u, C by columns of length no. */
static void linear(int no, const double *restrict oa, const double *restrict C,
                   const double u[NIN], double *restrict o)
{
    const double *restrict c0 = C, *restrict c1 = c0 + no, *restrict c2 = c1 + no;
    for (int i = 0; i < no; i++)
        o[i] = oa[i] + c0[i] * u[0] + c1[i] * u[1] + c2[i] * u[2];
}

void tt_envelope_predict(const tt_envelope *e, const double x[2], double s, double sdot,
                         double x1[2], double *obs)
{
    double u[NIN];
    step(e, x, s, sdot, u, x1);
    linear(e->no, e->oa, e->C, u, obs);
}

void tt_envelope_predict_reduced(const tt_envelope *e, const double x[2], double s, double sdot,
                                 double x1[2], double *red)
{
    double u[NIN];
    step(e, x, s, sdot, u, x1);
    linear(e->m + TT_ENV_EXTRA, e->ra, e->Cr, u, red);
}

double tt_envelope_error(const tt_envelope *e, const double xa[2], const double *oa,
                         const double xb[2], const double *ob)
{
    double err = fmax(fabs(xa[0] - xb[0]) / e->L, fabs(xa[1] - xb[1]) / e->V);
    for (int i = 0; i < e->no; i++) {
        double d = fabs(oa[i] - ob[i]) / e->oscale[i];
        if (d > err)
            err = d; /* NAN (a channel not tracked) is skipped */
    }
    return err;
}
