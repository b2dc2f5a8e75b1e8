/* The envelope tier's prediction and error (see include/tiptap/solver/envelope.h): the
 * model's cycle from its anchor, to first or second order, and the scaled difference of
 * two versions of a cycle. For one mode (n = 2) the outputs' product runs as one fused
 * loop over three columns, the generic one over n + 1 columns otherwise; both sum the
 * terms in the same order. */
#include "tiptap/solver/envelope.h"

#include <math.h>
#include <string.h>

#include "envelope_private.h"

/* The model's end state from x, and the inputs' offsets u in the state and the sample
 * (the travel's offset 0: add_travel); one mode's written out (the scan's hot path). */
static inline void step(const tt_envelope *e, const double *x, double s, double sdot,
                        double *u, double *x1)
{
    const int nx = e->nx, ni = e->ni;
    const double *J = e->J;
    if (nx == 2 && !e->generic) {
        u[0] = x[0] - e->xa[0];
        u[1] = x[1] - e->xa[1];
        u[2] = s + 0.5 * sdot * e->T - e->sa;
        u[3] = 0;
        x1[0] = e->x1[0] + J[0] * u[0] + J[1] * u[1] + J[2] * u[2];
        x1[1] = e->x1[1] + J[ni] * u[0] + J[ni + 1] * u[1] + J[ni + 2] * u[2];
        return;
    }
    for (int i = 0; i < nx; i++)
        u[i] = x[i] - e->xa[i];
    u[nx] = s + 0.5 * sdot * e->T - e->sa;
    u[nx + 1] = 0;
    for (int i = 0; i < nx; i++) {
        const double *Ji = J + (size_t)i * (size_t)ni;
        double y = e->x1[i];
        for (int j = 0; j <= nx; j++)
            y += Ji[j] * u[j];
        x1[i] = y;
    }
}

/* Outputs o = oa + C u (no of them) in the first nc inputs, C by columns of length ld:
 * three columns (one mode) fused, so that the loop vectorises (fused), else column by
 * column, the terms summed in the same order. */
static inline void linear(int no, int nc, int ld, const double *restrict oa,
                          const double *restrict C, const double *u, double *restrict o,
                          int fused)
{
    if (fused && nc == 3) {
        const double *restrict c0 = C, *restrict c1 = c0 + ld, *restrict c2 = c1 + ld;
        for (int i = 0; i < no; i++)
            o[i] = oa[i] + c0[i] * u[0] + c1[i] * u[1] + c2[i] * u[2];
        return;
    }
    for (int i = 0; i < no; i++)
        o[i] = oa[i] + C[i] * u[0];
    for (int j = 1; j < nc; j++) {
        const double *restrict cj = C + (size_t)j * (size_t)ld;
        for (int i = 0; i < no; i++)
            o[i] += cj[i] * u[j];
    }
}

/* The travel's part where it is an input: its offset u[nx + 1], and its column of J and
 * of C (length ld) times it added to x1 and the no outputs o, term by term as one sum
 * over the inputs would. */
static inline void add_travel(const tt_envelope *e, double sdot, double *u, double *x1, int no,
                              int ld, const double *restrict C, double *restrict o)
{
    const int it = e->nx + 1;
    u[it] = sdot * e->T - e->ta;
    for (int i = 0; i < e->nx; i++)
        x1[i] += e->J[(size_t)i * (size_t)e->ni + (size_t)it] * u[it];
    const double *restrict ct = C + (size_t)it * (size_t)ld;
    for (int i = 0; i < no; i++)
        o[i] += ct[i] * u[it];
}

/* A first-order prediction with the travel an input. Out of line, so that the path
 * without it, a noise-free scan's, compiles as lean as before. */
__attribute__((noinline)) static void predict_travel(const tt_envelope *e, const double *x,
                                                     double s, double sdot, double *x1, int no,
                                                     int ld, const double *oa, const double *C,
                                                     double *o)
{
    double u[NIN_MAX];
    step(e, x, s, sdot, u, x1);
    linear(no, e->nx + 1, ld, oa, C, u, o, !e->generic);
    add_travel(e, sdot, u, x1, no, ld, C, o);
}

/* Second order (a second-order perturbation expansion about the anchor): the state is
 * x = xl + x2, its first-order part xl iterated by the linear model from the inputs'
 * offsets u, and its second-order part x2 by x2' = dP/dx x2 + H(u, u) / 2; the
 * observables get C (x2, 0) + H(u, u) / 2. Iterating the quadratic map itself would have
 * a spurious fixed point at |u| about (1 - |mu|) / |H| (50 pm at the Floquet multiplier
 * 0.99 and the curvature 4 / A0), past which it runs off; the expansion is as accurate to
 * second order and as stable as the linear model. Ho: the outputs' second derivatives
 * (no rows of npair), Co: their Jacobian by columns of length ld. */
static void second_order(const tt_envelope *e, const double *u, const double *x2, double *x21,
                         int no, int ld, const double *Ho, const double *Co, double *o)
{
    const int nx = e->nx, ni = e->ni, npair = e->npair;
    double w[NIN_MAX * (NIN_MAX + 1) / 2];
    for (int j = 0; j < ni; j++)
        for (int k = j; k < ni; k++)
            w[tt_envelope_pair(e, j, k)] = (j == k ? 0.5 : 1.0) * u[j] * u[k];
    for (int i = 0; i < nx; i++) {
        const double *Ji = e->J + (size_t)i * (size_t)ni;
        double sum = Ji[0] * x2[0];
        for (int j = 1; j < nx; j++)
            sum += Ji[j] * x2[j];
        for (int p = 0; p < npair; p++)
            sum += e->Hv[(size_t)i * (size_t)npair + (size_t)p] * w[p];
        x21[i] = sum;
    }
    for (int i = 0; i < no; i++) {
        double sum = Co[i] * x2[0];
        for (int j = 1; j < nx; j++)
            sum += Co[(size_t)j * (size_t)ld + (size_t)i] * x2[j];
        const double *row = Ho + (size_t)i * (size_t)npair;
        for (int p = 0; p < npair; p++)
            sum += row[p] * w[p];
        o[i] += sum;
    }
}

void tt_envelope_predict(const tt_envelope *e, tt_envelope_view view, const double *x,
                         const double *x2, double s, double sdot, double *x1, double *x21,
                         double *out)
{
    const int nx = e->nx, k = e->m + TT_ENV_EXTRA;
    /* the view's rows: of the observables, or of the reduced ones (the probes last) */
    const int no = view == TT_ENV_ALL ? e->no : view == TT_ENV_REDUCED ? k : e->np;
    const int ld = view == TT_ENV_ALL ? e->no : e->nr, r0 = view == TT_ENV_PROBES ? k : 0;
    const double *oa = view == TT_ENV_ALL ? e->oa : e->ra + r0;
    const double *C = view == TT_ENV_ALL ? e->C : e->Cr + r0;
    const int second = x2 && e->second && e->built;
    double u[NIN_MAX], xl[TT_SIM_DIM_MAX];
    if (x2)
        for (int i = 0; i < nx; i++)
            x21[i] = 0;
    if (!second) {
        if (e->nin > nx + 1) {
            predict_travel(e, x, s, sdot, x1, no, ld, oa, C, out);
            return;
        }
        step(e, x, s, sdot, u, x1);
        linear(no, nx + 1, ld, oa, C, u, out, !e->generic);
        return;
    }
    for (int i = 0; i < nx; i++)
        xl[i] = x[i] - x2[i];
    step(e, xl, s, sdot, u, x1);
    linear(no, nx + 1, ld, oa, C, u, out, !e->generic);
    if (e->nin > nx + 1)
        add_travel(e, sdot, u, x1, no, ld, C, out);
    const double *Ho = view == TT_ENV_ALL ? e->Hv + (size_t)nx * (size_t)e->npair
                                          : e->Hrv + (size_t)r0 * (size_t)e->npair;
    second_order(e, u, x2, x21, no, ld, Ho, C, out);
    for (int i = 0; i < nx; i++)
        x1[i] += x21[i];
}

/* The end states' difference, each component over its scale. */
static double state_error(const tt_envelope *e, const double *xa, const double *xb)
{
    double err = fabs(xa[0] - xb[0]) / e->xs[0];
    for (int i = 1; i < e->nx; i++)
        err = fmax(err, fabs(xa[i] - xb[i]) / e->xs[i]);
    return err;
}

double tt_envelope_error(const tt_envelope *e, tt_envelope_view view, const double *xa,
                         const double *oa, const double *xb, const double *ob)
{
    double err = state_error(e, xa, xb);
    if (view == TT_ENV_REDUCED) {
        for (int i = 0; i < e->nr; i++) {
            const double sc = i < e->m ? e->L : e->oscale[e->n + i - e->m];
            double d = fabs(oa[i] - ob[i]) / sc;
            if (d > err)
                err = d; /* NAN (not tracked, or a probe not asked for) is skipped */
        }
        return err;
    }
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
