/* Shooting's linear algebra (see shooting_linalg.h). */
#include "shooting_linalg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>

/* Gaussian elimination with partial pivoting on A (n x n, overwritten) for A s = b;
 * a pivot below tiny is singular. */
static int gauss(int n, double *A, const double *b, double *s, double tiny)
{
    double *r = s;
    memmove(r, b, (size_t)n * sizeof *b);
    for (int k = 0; k < n; k++) {
        int p = k;
        for (int i = k + 1; i < n; i++)
            if (fabs(A[i * n + k]) > fabs(A[p * n + k]))
                p = i;
        if (!(fabs(A[p * n + k]) > tiny))
            return 0;
        if (p != k) {
            for (int j = 0; j < n; j++) {
                const double t = A[k * n + j];
                A[k * n + j] = A[p * n + j];
                A[p * n + j] = t;
            }
            const double t = r[k];
            r[k] = r[p];
            r[p] = t;
        }
        for (int i = k + 1; i < n; i++) {
            const double f = A[i * n + k] / A[k * n + k];
            for (int j = k; j < n; j++)
                A[i * n + j] -= f * A[k * n + j];
            r[i] -= f * r[k];
        }
    }
    for (int k = n - 1; k >= 0; k--) {
        double v = r[k];
        for (int j = k + 1; j < n; j++)
            v -= A[k * n + j] * r[j];
        r[k] = v / A[k * n + k];
    }
    return 1;
}

int tt_shoot_solve(int n, double *A, const double *b, double *s, int generic)
{
    if (n == 2 && !generic) {
        const double det = A[0] * A[3] - A[1] * A[2];
        const double scale = fabs(A[0] * A[3]) + fabs(A[1] * A[2]);
        if (!(fabs(det) > 1e-14 * scale))
            return 0;
        s[0] = (b[0] * A[3] - b[1] * A[1]) / det;
        s[1] = (b[1] * A[0] - b[0] * A[2]) / det;
        return 1;
    }
    double scale = 0;
    for (int i = 0; i < n * n; i++)
        scale = fmax(scale, fabs(A[i]));
    return gauss(n, A, b, s, 1e-14 * scale);
}

int tt_shoot_eigen(int n, const double *J, double *re, double *im, int generic)
{
    if (n == 2 && !generic) {
        double tr = J[0] + J[3], det = J[0] * J[3] - J[1] * J[2];
        double disc = 0.25 * tr * tr - det;
        if (disc >= 0) {
            double r = sqrt(disc);
            re[0] = 0.5 * tr + r;
            re[1] = 0.5 * tr - r;
            im[0] = im[1] = 0;
        } else {
            re[0] = re[1] = 0.5 * tr;
            im[0] = sqrt(-disc);
            im[1] = -im[0];
        }
        return 1;
    }
    for (int i = 0; i < n; i++)
        re[i] = im[i] = NAN;
    /* GSL's error handler is process-wide, so toggling it off around the call raced
     * between threads (the scan's workers each shoot). It is not needed: the QR
     * iteration's non-convergence is a return code (GSL_EMAXITER, never through the
     * handler), and the handler's other paths are size mismatches, which views of our
     * own n x n and n buffers cannot have. Only the workspace's allocation can reach it
     * (out of memory), as any GSL allocation in the library does. */
    double *buf = malloc((size_t)n * ((size_t)n + 2) * sizeof *buf);
    gsl_eigen_nonsymm_workspace *w = buf ? gsl_eigen_nonsymm_alloc((size_t)n) : NULL;
    int ok = w != NULL;
    if (ok) {
        memcpy(buf, J, (size_t)n * (size_t)n * sizeof *J); /* rows, contiguous */
        gsl_matrix_view A = gsl_matrix_view_array(buf, (size_t)n, (size_t)n);
        gsl_vector_complex_view ev = gsl_vector_complex_view_array(buf + n * n, (size_t)n);
        ok = gsl_eigen_nonsymm(&A.matrix, &ev.vector, w) == GSL_SUCCESS;
        for (int i = 0; ok && i < n; i++) {
            gsl_complex z = gsl_vector_complex_get(&ev.vector, (size_t)i);
            re[i] = GSL_REAL(z);
            im[i] = GSL_IMAG(z);
        }
    }
    if (w)
        gsl_eigen_nonsymm_free(w);
    free(buf);
    return ok;
}

/* The 3 x 3 determinant of rows m. */
static double det3(double m[3][3])
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* n = 2: the 3 x 3 system for a, b, c of M = [a b; b c], by Cramer's rule. */
static int lyapunov2(const double *J, double *M)
{
    double A[3][3];
    for (int u = 0; u < 3; u++) {
        double B[2][2] = {{u == 0, u == 1}, {u == 1, u == 2}}, G[2][2];
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                G[i][j] = -B[i][j];
                for (int k = 0; k < 2; k++)
                    for (int l = 0; l < 2; l++)
                        G[i][j] += J[k * 2 + i] * B[k][l] * J[l * 2 + j];
            }
        A[0][u] = G[0][0];
        A[1][u] = G[0][1];
        A[2][u] = G[1][1];
    }
    double rhs[3] = {-1, 0, -1}, sol[3];
    const double d = det3(A);
    if (!(fabs(d) > 0))
        return 0;
    for (int u = 0; u < 3; u++) {
        double C[3][3];
        memcpy(C, A, sizeof C);
        for (int i = 0; i < 3; i++)
            C[i][u] = rhs[i];
        sol[u] = det3(C) / d;
    }
    M[0] = sol[0];
    M[1] = M[2] = sol[1];
    M[3] = sol[2];
    return 1;
}

int tt_shoot_lyapunov(int n, const double *J, double *M, int generic)
{
    if (n == 2 && !generic)
        return lyapunov2(J, M);
    /* the unknowns: M's upper triangle (a <= b); the equations: G's, G = J^T B J - B
     * for each unknown's symmetric unit B (the columns of the system) */
    const int nu = n * (n + 1) / 2;
    double *A = calloc((size_t)nu * (size_t)nu + 2 * (size_t)nu, sizeof *A);
    if (!A)
        return 0;
    double *rhs = A + (size_t)nu * (size_t)nu, *sol = rhs + nu;
    for (int a = 0, u = 0; a < n; a++)
        for (int b = a; b < n; b++, u++)
            for (int i = 0, e = 0; i < n; i++)
                for (int j = i; j < n; j++, e++) {
                    /* (J^T B J)_ij with B = E_ab + E_ba (E_aa once) */
                    double g = J[a * n + i] * J[b * n + j];
                    if (a != b)
                        g += J[b * n + i] * J[a * n + j];
                    g -= (i == a && j == b) || (i == b && j == a);
                    A[(size_t)e * (size_t)nu + (size_t)u] = g;
                }
    for (int i = 0, e = 0; i < n; i++)
        for (int j = i; j < n; j++, e++)
            rhs[e] = i == j ? -1 : 0;
    int ok = gauss(nu, A, rhs, sol, 0);
    for (int a = 0, u = 0; ok && a < n; a++)
        for (int b = a; b < n; b++, u++)
            M[a * n + b] = M[b * n + a] = sol[u];
    free(A);
    return ok;
}

void tt_shoot_expm(int n, const double *A, double tau, double *E)
{
    double nrm = 0;
    for (int i = 0; i < n; i++) {
        double r = 0;
        for (int j = 0; j < n; j++)
            r += fabs(A[i * n + j] * tau);
        nrm = fmax(nrm, r);
    }
    int sq = 0;
    while (nrm > 0.5 && sq < 64) {
        nrm *= 0.5;
        sq++;
    }
    double f = ldexp(tau, -sq), T[TT_EXPM_MAX * TT_EXPM_MAX], P[TT_EXPM_MAX * TT_EXPM_MAX];
    for (int i = 0; i < n * n; i++)
        E[i] = T[i] = i % (n + 1) == 0;
    for (int k = 1; k <= 16; k++) {
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                double acc = 0;
                for (int l = 0; l < n; l++)
                    acc += T[i * n + l] * A[l * n + j];
                P[i * n + j] = acc * f / k;
            }
        for (int i = 0; i < n * n; i++) {
            T[i] = P[i];
            E[i] += P[i];
        }
    }
    for (int s = 0; s < sq; s++)
        tt_shoot_matmul(n, E, E, E);
}

void tt_shoot_matmul(int n, const double *X, const double *Y, double *M)
{
    double P[TT_EXPM_MAX * TT_EXPM_MAX];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double acc = 0;
            for (int l = 0; l < n; l++)
                acc += X[i * n + l] * Y[l * n + j];
            P[i * n + j] = acc;
        }
    memcpy(M, P, sizeof(double) * (size_t)(n * n));
}
