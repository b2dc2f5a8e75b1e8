/* Shooting's linear algebra on the n x n monodromy (shooting.c): the Newton step's
 * solve, the Floquet multipliers and the discrete Lyapunov equation. For n = 2 the
 * closed forms (Cramer's rule, the trace and determinant), which keep one-mode outputs
 * as they were; for n > 2 Gaussian elimination with partial pivoting and GSL's
 * nonsymmetric eigensolver. Matrices are n x n by rows (J[i * n + j]); `generic` set
 * takes the n > 2 path at n = 2 too, for the test that both agree. The matrix
 * exponential too. */
#ifndef TIPTAP_SHOOTING_LINALG_H
#define TIPTAP_SHOOTING_LINALG_H

/* Solve A s = b (A is overwritten); 0 if A is singular at working precision (a pivot
 * below 1e-14 of the matrix's scale). */
int tt_shoot_solve(int n, double *A, const double *b, double *s, int generic);

/* The eigenvalues of J (n of them, as pairs re, im; a complex pair adjacent). 0 if the
 * eigensolver failed (the values NAN). */
int tt_shoot_eigen(int n, const double *J, double *re, double *im, int generic);

/* M of J^T M J - M = -I (symmetric, n x n by rows): V(e) = e^T M e falls by |e|^2 each
 * cycle of the linearised motion near a stable orbit. 0 if singular (or out of memory
 * for n > 2: the orbit is then not taken, and settling decides). */
int tt_shoot_lyapunov(int n, const double *J, double *M, int generic);

/* E = exp(A tau) for an n x n matrix by rows (n <= TT_EXPM_MAX; the free flight's and the
 * averaged tier's law-state steps): Taylor's series to degree 16 on A tau scaled to a
 * norm below 1/2 (remainder below 1e-20), then squared back. */
#define TT_EXPM_MAX 16
void tt_shoot_expm(int n, const double *A, double tau, double *E);

/* M = X Y for n x n matrices by rows (n <= TT_EXPM_MAX); M may be X or Y. */
void tt_shoot_matmul(int n, const double *X, const double *Y, double *M);

#endif
