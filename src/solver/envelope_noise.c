/* The envelope tier's noise (see include/tiptap/solver/envelope.h, the plan's psd and sd):
 * the thermal force's and the detector's linear response over a model's cycle, as the
 * Cholesky factor of their joint covariance, and a cycle's draw from it. */
#include "tiptap/solver/envelope.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "envelope_private.h"
#include "shooting_linalg.h"

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

/* The flow's Jacobian Phi(t_q, 0) (nx x nx by rows, e->phi + nx^2 q) at the cycle's
 * samples (q < n) from the cycles perturbed by h in each state component, and at its
 * end (q = n) the map's. */
void tt_envelope_flow_measured(tt_envelope *e, const double *h)
{
    const int nx = e->nx, nx2 = nx * nx;
    for (int q = 0; q <= e->n; q++)
        for (int j = 0; j < nx; j++)
            for (int i = 0; i < nx; i++) {
                const double *tp = e->trk + (size_t)(2 * nx * j) * (size_t)e->n, *tm = tp + nx * e->n;
                e->phi[nx2 * q + nx * i + j] =
                    q == e->n ? e->J[i * e->ni + j] : (tp[nx * q + i] - tm[nx * q + i]) / (2 * h[j]);
            }
}

/* The same for the free cantilever, exp(A t), the law's states held (identity): the
 * covariance until a model is built. */
static void flow_free(tt_envelope *e)
{
    const int nx = e->nx, nx2 = nx * nx;
    const double wd = sqrt(fmax(e->w0 * e->w0 - e->sig * e->sig, 0.0));
    for (int q = 0; q <= e->n; q++) {
        const double t = e->T * q / e->n, E = exp(-e->sig * t), C = cos(wd * t), S = sin(wd * t);
        double *P = e->phi + nx2 * q;
        for (int i = 2; i < nx; i++)
            P[nx * i + i] = 1;
        P[0] = E * (C + e->sig / wd * S);
        P[1] = E * S / wd;
        P[nx] = -E * e->w0 * e->w0 / wd * S;
        P[nx + 1] = E * (C - e->sig / wd * S);
    }
}

/* a = P^-1 b, b = (0, 1/m, 0, ...), P nx x nx by rows (M: scratch of nx^2): shooting's
 * elimination. 0: singular. */
static int kick_at_start(int nx, const double *P, double mass, double *M, double *a)
{
    double b[TT_SIM_DIM_MAX] = {0};
    b[1] = 1 / mass;
    memcpy(M, P, (size_t)(nx * nx) * sizeof *M);
    return tt_shoot_solve(nx, M, b, a, 1);
}

/* The kick's weights w at sample p (a: Phi(t_p, 0)^-1 b, nx of them): the end state's,
 * J a, and the reduced samples', S a (S: suffix sums of R_q e1 Phi(t_q, 0), m x nx). */
static void kick_weights(const tt_envelope *e, const double *J, const double *S, const double *a,
                         double *w)
{
    const int nx = e->nx;
    for (int i = 0; i < nx; i++) {
        double sum = 0;
        for (int k = 0; k < nx; k++)
            sum += J[nx * i + k] * a[k];
        w[i] = sum;
    }
    for (int i = 0; i < e->m; i++) {
        double sum = 0;
        for (int k = 0; k < nx; k++)
            sum += S[nx * i + k] * a[k];
        w[nx + i] = sum;
    }
}

/* The thermal force's linear response over one cycle (the linear-noise approximation):
 * white force of two-sided PSD psd on the tip, so the end state's and the reduced
 * samples' noise is psd * integral of w w^T, w(t) = (Phi(T, t) b, sum_q R_q [t < t_q]
 * e1 Phi(t_q, t) b), b = (0, 1/m, 0, ...) (a law's states after (d, d'), relaxation
 * arms, take no force: the surface follows the kicked tip through the flow) and
 * Phi(t_q, t) = Phi(t_q, 0) Phi(t, 0)^-1: the trapezoid rule on the samples (the
 * integrand is nearly periodic out of contact, where it is then exact to rounding).
 * Plus the detector's block; factored into e->Lj. One mode: (d, d') in closed form,
 * with a law's states by elimination. */
int tt_envelope_thermal_covariance(tt_envelope *e)
{
    const int n = e->n, m = e->m, nn = e->nn, nx = e->nx, nx2 = nx * nx;
    double *A = e->work;
    memset(A, 0, tt_envelope_noise_work(e) * sizeof *A);
    double *S = A + nn * nn, *w = S + nx * m, *M = w + nn, *a = M + nx2;
    const double *J = e->phi + nx2 * n;
    for (int p = n; p >= 0; p--) {
        const double *P = e->phi + nx2 * p;
        if (nx == 2) {
            const double det = P[0] * P[3] - P[1] * P[2];
            if (!(fabs(det) > 0))
                return 0;
            /* a = Phi(t_p, 0)^-1 b */
            const double a0 = -P[1] / (e->mass * det), a1 = P[0] / (e->mass * det);
            w[0] = J[0] * a0 + J[1] * a1;
            w[1] = J[2] * a0 + J[3] * a1;
            for (int i = 0; i < m; i++)
                w[2 + i] = S[2 * i] * a0 + S[2 * i + 1] * a1;
        } else {
            if (!kick_at_start(nx, P, e->mass, M, a))
                return 0;
            kick_weights(e, J, S, a, w);
        }
        const double wt = (p == 0 || p == n ? 0.5 : 1.0) * e->T / n * e->psd;
        for (int i = 0; i < nn; i++)
            for (int k = 0; k <= i; k++)
                A[i * nn + k] += wt * w[i] * w[k];
        for (int i = 0; p < n && i < m; i++) {
            const double r = e->R[(size_t)i * (size_t)n + (size_t)p];
            for (int k = 0; k < nx; k++)
                S[nx * i + k] += r * P[k];
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
    const size_t nx = (size_t)e->nx;
    /* the covariance, the suffix sums (m x nx), the weights, an elimination's matrix
     * and solution */
    return e->psd > 0 || e->sd > 0 ? nn * nn + nx * (size_t)e->m + nn + nx * nx + nx : 0;
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
