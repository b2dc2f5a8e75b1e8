/* The envelope tier's noise (see include/tiptap/solver/envelope.h, the plan's psd and sd):
 * the thermal force's and the detector's linear response over a model's cycle, as the
 * Cholesky factor of their joint covariance, and a cycle's draw from it. */
#include "tiptap/solver/envelope.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "envelope_private.h"

/* The lower Cholesky factor L (by rows) of a symmetric positive semidefinite n x n
 * matrix A: a pivot at rounding's level of its diagonal leaves its column zero, as a
 * noise fully fixed by the ones before it has no part of its own. */
static void cholesky(int n, const double *A, double *L)
{
    for (int j = 0; j < n; j++) {
        double d = A[j * n + j];
        for (int k = 0; k < j; k++)
            d -= L[j * n + k] * L[j * n + k];
        const int pos = d > 1e-12 * A[j * n + j] && d > 0;
        L[j * n + j] = pos ? sqrt(d) : 0;
        for (int i = j + 1; i < n; i++) {
            double a = A[i * n + j];
            for (int k = 0; k < j; k++)
                a -= L[i * n + k] * L[j * n + k];
            L[i * n + j] = pos ? a / L[j * n + j] : 0;
        }
        for (int k = j + 1; k < n; k++)
            L[j * n + k] = 0;
    }
}

/* The detector's covariance of the reduced samples, sd^2 R R^T, into the lower right
 * m x m block of the nn x nn matrix A (whose first nx rows are the end state's). */
static void detector_block(const tt_envelope *e, double *A)
{
    const int n = e->n, m = e->m, nn = e->nn, nx = e->nx;
    for (int i = 0; i < m; i++)
        for (int k = 0; k < m; k++) {
            double sum = 0;
            for (int q = 0; q < n; q++)
                sum += e->R[(size_t)i * (size_t)n + (size_t)q] * e->R[(size_t)k * (size_t)n + (size_t)q];
            A[(nx + i) * nn + nx + k] += e->sd * e->sd * sum;
        }
}

/* The flow's Jacobian Phi(t_q, 0) (2 x 2 by rows, e->phi + 4 q) at the cycle's samples
 * (q < n) from the cycles perturbed by h in d and d', and at its end (q = n) the map's. */
void tt_envelope_flow_measured(tt_envelope *e, const double *h)
{
    for (int q = 0; q <= e->n; q++)
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                const double *tp = e->trk + (size_t)(4 * j) * (size_t)e->n, *tm = tp + 2 * e->n;
                e->phi[4 * q + 2 * i + j] =
                    q == e->n ? e->J[i * e->ni + j] : (tp[2 * q + i] - tm[2 * q + i]) / (2 * h[j]);
            }
}

/* The same for the free cantilever, exp(A t_q): the covariance until a model is built. */
static void flow_free(tt_envelope *e)
{
    const double wd = sqrt(fmax(e->w0 * e->w0 - e->sig * e->sig, 0.0));
    for (int q = 0; q <= e->n; q++) {
        const double t = e->T * q / e->n, E = exp(-e->sig * t), C = cos(wd * t), S = sin(wd * t);
        double *P = e->phi + 4 * q;
        P[0] = E * (C + e->sig / wd * S);
        P[1] = E * S / wd;
        P[2] = -E * e->w0 * e->w0 / wd * S;
        P[3] = E * (C - e->sig / wd * S);
    }
}

/* The thermal force's linear response over one cycle (the linear-noise approximation):
 * white force of two-sided PSD psd on the tip, so the end state's and the reduced
 * samples' noise is psd * integral of w w^T, w(t) = (Phi(T, t) b, sum_q R_q [t < t_q]
 * e1 Phi(t_q, t) b), b = (0, 1/m) and Phi(t_q, t) = Phi(t_q, 0) Phi(t, 0)^-1: the
 * trapezoid rule on the samples (the integrand is nearly periodic out of contact, where
 * it is then exact to rounding). Plus the detector's block; factored into e->Lj. One
 * mode: a law's states after (d, d') (relaxation arms) take no force, and the kick's
 * effect on them is the map's response to the tip's state it is equivalent to at the
 * cycle's start, Phi(t, 0)^-1 b through J's (d, d') columns: the tip's flow alone is
 * measured (the surface moves with the tip only in contact, a tenth of the cycle). */
int tt_envelope_thermal_covariance(tt_envelope *e)
{
    const int n = e->n, m = e->m, nn = e->nn, nx = e->nx;
    double *A = e->work;
    memset(A, 0, tt_envelope_noise_work(e) * sizeof *A);
    double *S = A + nn * nn, *w = S + 2 * m; /* suffix sums of R_q e1 Phi(t_q, 0) */
    const double *J = e->phi + 4 * n;
    for (int p = n; p >= 0; p--) {
        const double *P = e->phi + 4 * p;
        const double det = P[0] * P[3] - P[1] * P[2];
        if (!(fabs(det) > 0))
            return 0;
        /* a = Phi(t_p, 0)^-1 b */
        const double a0 = -P[1] / (e->mass * det), a1 = P[0] / (e->mass * det);
        w[0] = J[0] * a0 + J[1] * a1;
        w[1] = J[2] * a0 + J[3] * a1;
        /* a law's states take the kick through the map's (d, d') columns: the force does
         * not act on them, but what it does to the tip moves the surface */
        for (int i = 2; i < nx; i++)
            w[i] = e->J[i * e->ni] * a0 + e->J[i * e->ni + 1] * a1;
        for (int i = 0; i < m; i++)
            w[nx + i] = S[2 * i] * a0 + S[2 * i + 1] * a1;
        const double wt = (p == 0 || p == n ? 0.5 : 1.0) * e->T / n * e->psd;
        for (int i = 0; i < nn; i++)
            for (int k = 0; k <= i; k++)
                A[i * nn + k] += wt * w[i] * w[k];
        for (int i = 0; p < n && i < m; i++) {
            const double r = e->R[(size_t)i * (size_t)n + (size_t)p];
            S[2 * i] += r * P[0];
            S[2 * i + 1] += r * P[1];
        }
    }
    for (int i = 0; i < nn; i++)
        for (int k = i + 1; k < nn; k++)
            A[i * nn + k] = A[k * nn + i];
    detector_block(e, A);
    cholesky(nn, A, e->Lj);
    return 1;
}

size_t tt_envelope_noise_work(const tt_envelope *e)
{
    const size_t nn = (size_t)e->nn;
    return e->psd > 0 || e->sd > 0 ? nn * nn + 2 * (size_t)e->m + nn : 0;
}

void tt_envelope_noise_plan(tt_envelope *e)
{
    const size_t nn = (size_t)e->nn;
    double *A = e->work;
    memset(A, 0, nn * nn * sizeof *A);
    detector_block(e, A);
    cholesky(e->nn, A, e->Lj);
    /* until a model is built, the free cantilever's response (its flow is never
     * singular: det exp(A t) = exp(-2 sig t)) */
    if (e->psd > 0) {
        flow_free(e);
        tt_envelope_thermal_covariance(e);
    }
    memcpy(e->Lf, e->Lj, nn * nn * sizeof *e->Lf);
}

int tt_envelope_noise_size(const tt_envelope *e) { return e->Lj ? e->nn : 0; }

void tt_envelope_noise(const tt_envelope *e, const double *g, double *dx, double *dc)
{
    const int nn = e->nn, nx = e->nx;
    for (int i = 0; i < nn; i++) {
        const double *row = e->Ljv + (size_t)i * (size_t)nn;
        double sum = 0;
        for (int k = 0; k <= i; k++)
            sum += row[k] * g[k];
        if (i < nx)
            dx[i] = sum;
        else
            dc[i - nx] += sum;
    }
}
