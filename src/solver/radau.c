/* The Radau IIA step type (3 stages, order 5, L-stable) for stiff or heavily damped
 * contacts: simplified Newton with a 3x3 LU, RADAU5's error estimate and the
 * collocation polynomial as dense output. */
#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "control.h"
#include "tiptap/util/error.h"

/* Hairer & Wanner, Solving ODEs II, IV.5 and IV.8. */
#define RS6 2.449489742783178098197284
static const double RC[3] = {(4.0 - RS6) / 10.0, (4.0 + RS6) / 10.0, 1.0};
static const double RA[3][3] = {
    {(88.0 - 7.0 * RS6) / 360.0, (296.0 - 169.0 * RS6) / 1800.0, (-2.0 + 3.0 * RS6) / 225.0},
    {(296.0 + 169.0 * RS6) / 1800.0, (88.0 + 7.0 * RS6) / 360.0, (-2.0 - 3.0 * RS6) / 225.0},
    {(16.0 - RS6) / 36.0, (16.0 + RS6) / 36.0, 1.0 / 9.0}};
/* error estimate of RADAU5: gamma0 = 1 / (the real eigenvalue of A^-1), and the weights
 * of the stage increments */
static const double RG0 = 0.2748888295956773677478286;
static const double RE[3] = {-(13.0 + 7.0 * RS6) / 3.0, (-13.0 + 7.0 * RS6) / 3.0, -1.0 / 3.0};
enum { NEWTON_MAX = 7 };

/* radau's own state: its step-size control, the stages' derivatives, the dense output's
 * polynomial, the last accepted step's polynomial extrapolated for the Newton starting
 * values (valid while ext_ok), and the Newton iteration's memory. */
typedef struct {
    tt_step_control ctl;
    double k[4][NYMAX];  /* the derivatives at stages 1 to 3 */
    /* the collocation polynomial of the n components in Newton form */
    double rcont[5][TT_SIM_DIM_MAX];
    double ext[4][TT_SIM_DIM_MAX], ext_tau, ext_h;
    int ext_ok;
    double tol;          /* the tolerance radau's O(h^4) estimate is held to */
    double newton_eta;   /* contraction estimate theta / (1 - theta) of the last step */
    int newton_it;       /* Newton iterations of the last step (0: it failed) */
} radau_state;

/* One step's fixed data: its start, the Jacobian there, the error scales, the drive at
 * the stage times, and the Newton matrix's LU factors (ok = 0: singular). */
typedef struct {
    double t, h, d0, v0, tol, scd, scv, Jd, Jv;
    int cs, ok, piv[3];
    double M[3][3];
    drive_val dv[3];
} radau_ctx;

/* A radau collocation polynomial of d and v in Newton form on the nodes 0, c1, c2, 1. */
static inline void radau_poly(const double (*p)[TT_SIM_DIM_MAX], double th, double *d, double *v)
{
    double out[2];
    for (int i = 0; i < 2; i++)
        out[i] = p[0][i] + th * (p[1][i] + (th - RC[0]) * (p[2][i] + (th - RC[1]) * p[3][i]));
    *d = out[0];
    *v = out[1];
}

/* LU factorisation with partial pivoting of the m x m matrix M (row stride ld), in
 * place; 0 if singular. Inline, so that radau's 3 x 3 one unrolls. */
static inline int lu_factor(double *M, int m, int ld, int *piv)
{
    for (int c = 0; c < m; c++) {
        int p = c;
        for (int r = c + 1; r < m; r++)
            if (fabs(M[r * ld + c]) > fabs(M[p * ld + c]))
                p = r;
        piv[c] = p;
        if (!(fabs(M[p * ld + c]) > 0) || !isfinite(M[p * ld + c]))
            return 0;
        if (p != c)
            for (int j = 0; j < m; j++) {
                double tmp = M[c * ld + j];
                M[c * ld + j] = M[p * ld + j];
                M[p * ld + j] = tmp;
            }
        for (int r = c + 1; r < m; r++) {
            M[r * ld + c] /= M[c * ld + c];
            for (int j = c + 1; j < m; j++)
                M[r * ld + j] -= M[r * ld + c] * M[c * ld + j];
        }
    }
    return 1;
}

/* Solve with lu_factor's factors: all row swaps first (the multipliers were swapped
 * with their rows), then the two triangular solves. */
static inline void lu_solve(const double *M, int m, int ld, const int *piv, double *b)
{
    for (int c = 0; c < m; c++)
        if (piv[c] != c) {
            double tmp = b[c];
            b[c] = b[piv[c]];
            b[piv[c]] = tmp;
        }
    for (int c = 0; c < m; c++)
        for (int r = c + 1; r < m; r++)
            b[r] -= M[r * ld + c] * b[c];
    for (int r = m - 1; r >= 0; r--) {
        for (int j = r + 1; j < m; j++)
            b[r] -= M[r * ld + j] * b[j];
        b[r] /= M[r * ld + r];
    }
}

/* The acceleration alone: all that radau's Newton iteration needs. */
static double accel(const tt_sim *S, double tau, const drive_val *dv, double d, double v,
                    int contact)
{
    const tt_cantilever *c = &S->c;
    double s = S->sys.s0 + S->sys.sdot * tau;
    tt_contact_forces f = {0.0, 0.0, 0.0};
    if (S->sys.contact)
        f = S->sys.force(S->sys.contact, S->sys.ci, d - s, v - S->sys.sdot, contact, NULL);
    return (-c->c * (v - dv->zd) - c->k * (d - dv->z) - f.conservative - f.dissipative + dv->F) *
           S->sys.inv_m[0];
}

/* The step's fixed data. Jacobian of (d' = v, v' = f) at the step start: df/dd = -(k +
 * dP/ddelta) / m, df/dv = -(c + c_i) / m. Position increments follow linearly from the
 * velocity ones (d' = v), so Newton needs only M = I - h Jv A - h^2 Jd A^2 for the three
 * velocity increments. */
static void radau_setup(const radau_state *st, const tt_sim *S, double h, radau_ctx *R)
{
    const double *y0 = S->y;
    R->t = S->tau;
    R->h = h;
    R->d0 = y0[Y_D];
    R->v0 = y0[Y_V];
    R->cs = S->contact_state;
    R->tol = st->tol;
    R->scd = R->tol * S->c.A0;
    R->scv = R->scd * S->c.wd;
    const double t = R->t;
    tt_contact_detail law = {{0.0, 0.0, 0.0}, 0.0, 0.0, 0.0};
    if (S->sys.contact)
        tt_contact_evaluate(S->sys.contact, S->sys.ci, R->d0 - (S->sys.s0 + S->sys.sdot * t), R->v0 - S->sys.sdot,
                            R->cs, NULL, &law);
    R->Jd = -(S->c.k + law.stiffness) * S->sys.inv_m[0];
    R->Jv = -(S->c.c + law.damping) * S->sys.inv_m[0];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double a2 = RA[i][0] * RA[0][j] + RA[i][1] * RA[1][j] + RA[i][2] * RA[2][j];
            R->M[i][j] = (i == j) - h * R->Jv * RA[i][j] - h * h * R->Jd * a2;
        }
    R->ok = lu_factor(&R->M[0][0], 3, 3, R->piv);
    for (int i = 0; i < 3; i++) {
        drive_at(S, t + RC[i] * h, &R->dv[i].z, &R->dv[i].zd, &R->dv[i].F, &R->dv[i].cw,
                 &R->dv[i].sw);
        if (S->sys.nz_f)
            R->dv[i].F += noise_force(S, t + RC[i] * h);
    }
}

/* The simplified Newton iteration's progress (Hairer's RADAU5): the contraction
 * estimate eta, the last increment's norm and the stopping threshold fnewt. */
typedef struct {
    double eta, prev, fnewt;
} newton_track;

static inline newton_track newton_begin(const radau_state *st, double tol)
{
    newton_track nt = {pow(fmax(st->newton_eta, DBL_EPSILON), 0.8), 1,
                       fmax(10 * DBL_EPSILON / tol, fmin(0.03, sqrt(tol)))};
    return nt;
}

/* Iteration it's increment of norm nrm: 0 to apply it, -1 to give up (not finite,
 * diverging, or too slow to converge in the iterations left). */
static inline int newton_judge(newton_track *nt, double nrm, int it)
{
    if (!isfinite(nrm))
        return -1;
    if (it > 1) {
        double theta = nrm / nt->prev;
        if (theta >= 0.99)
            return -1; /* diverging */
        nt->eta = theta / (1 - theta);
        if (nt->eta * nrm * pow(theta, NEWTON_MAX - it) > nt->fnewt)
            return -1; /* would not converge in the iterations left */
    }
    nt->prev = fmax(nrm, DBL_EPSILON);
    return 0;
}

/* The iteration's end: its count (0: failed) and, converged, its contraction rate. */
static inline int newton_end(radau_state *st, const newton_track *nt, int conv, int it)
{
    st->newton_it = conv ? it : 0;
    if (conv)
        st->newton_eta = nt->eta;
    return conv;
}

/* Simplified Newton on the velocity increments zv, from the last accepted step's
 * polynomial extrapolated; stops when the estimated remaining error, eta |dz|, is a
 * small fraction of the tolerance (Hairer's fnewt). Sets newton_it (0: failed). */
static int radau_newton(radau_state *st, const tt_sim *S, const radau_ctx *R, double zv[3])
{
    const double t = R->t, h = R->h, d0 = R->d0, v0 = R->v0, tol = R->tol;
    const double scd = R->scd, scv = R->scv;
    const int cs = R->cs;
    double zd[3];
    if (st->ext_ok)
        for (int i = 0; i < 3; i++) {
            double de, ve;
            radau_poly((const double (*)[TT_SIM_DIM_MAX])st->ext, (t + RC[i] * h - st->ext_tau) / st->ext_h, &de, &ve);
            zv[i] = ve - v0;
        }
    newton_track nt = newton_begin(st, tol);
    int conv = 0, it;
    for (it = 1; R->ok && it <= NEWTON_MAX; it++) {
        double a[3], g[3];
        for (int i = 0; i < 3; i++)
            zd[i] = h * (RA[i][0] * (v0 + zv[0]) + RA[i][1] * (v0 + zv[1]) + RA[i][2] * (v0 + zv[2]));
        for (int j = 0; j < 3; j++)
            a[j] = accel(S, t + RC[j] * h, &R->dv[j], d0 + zd[j], v0 + zv[j], cs);
        for (int i = 0; i < 3; i++)
            g[i] = h * (RA[i][0] * a[0] + RA[i][1] * a[1] + RA[i][2] * a[2]) - zv[i];
        lu_solve(&R->M[0][0], 3, 3, R->piv, g);
        double nrm = 0;
        for (int i = 0; i < 3; i++) {
            double dd = h * (RA[i][0] * g[0] + RA[i][1] * g[1] + RA[i][2] * g[2]);
            nrm = fmax(nrm, fmax(fabs(g[i]) / scv, fabs(dd) / scd));
        }
        if (newton_judge(&nt, nrm, it))
            break;
        for (int i = 0; i < 3; i++)
            zv[i] += g[i];
        if (nt.eta * nrm <= nt.fnewt) {
            conv = 1;
            break;
        }
    }
    return newton_end(st, &nt, conv, it);
}

/* Component i's collocation polynomial through y0i and the three stages' increments z,
 * in Newton form on the nodes 0, c1, c2, 1. */
static inline void radau_collocation(radau_state *st, int i, double y0i, const double z[3])
{
    double f01 = z[0] / RC[0], f12 = (z[1] - z[0]) / (RC[1] - RC[0]), f23 = (z[2] - z[1]) / (1 - RC[1]);
    double f012 = (f12 - f01) / RC[1], f123 = (f23 - f12) / (1 - RC[0]);
    st->rcont[0][i] = y0i;
    st->rcont[1][i] = f01;
    st->rcont[2][i] = f012;
    st->rcont[3][i] = f123 - f012;
    st->rcont[4][i] = 0;
}

/* The step's end and dense data from the stages' increments zd (position), zv
 * (velocity): the full right-hand side at the stages (quadrature integrands included),
 * and the collocation polynomial through y0 and the three stages. */
static void radau_finish(radau_state *st, tt_sim *S, const radau_ctx *R, const double *y0, const double zd[3],
                         const double zv[3])
{
    double (*k)[NYMAX] = st->k;
    const double h = R->h;
    double Yst[NYMAX];
    sim_copy(S, Yst, y0);
    for (int j = 0; j < 3; j++) {
        Yst[Y_D] = R->d0 + zd[j];
        Yst[Y_V] = R->v0 + zv[j];
        rhs_with(S, R->t + RC[j] * h, &R->dv[j], Yst, R->cs, k[1 + j]);
    }
    /* stiffly accurate: the end is the last stage (not y0 + h b.f, which would amplify
     * the Newton error of the stiff part by h |J|) */
    S->y1[Y_D] = R->d0 + zd[2];
    S->y1[Y_V] = R->v0 + zv[2];
    for (int q = Y_WDRIVE; q < NY; q++) /* n = 2: the quadratures at their enum indexes */
        S->y1[q] = y0[q] + h * (RA[2][0] * k[1][q] + RA[2][1] * k[2][q] + RA[2][2] * k[3][q]);
    sim_copy(S, S->dydt_out, k[3]);
    for (int i = 0; i < 2; i++)
        radau_collocation(st, i, y0[i], i ? zv : zd);
}

/* RADAU5's error estimate (I - h g0 J)^-1 (g0 h f0 + g0 sum e_i Z_i) on d and v. */
static double radau_error(const radau_state *st, const tt_sim *S, const radau_ctx *R, const double zd[3],
                          const double zv[3], int first)
{
    const double h = R->h, Jd = R->Jd, Jv = R->Jv, scd = R->scd, scv = R->scv;
    const double hg = h * RG0, det = (1 - hg * Jv) - hg * hg * Jd;
    double rd = hg * S->dydt_in[Y_D] + RG0 * (RE[0] * zd[0] + RE[1] * zd[1] + RE[2] * zd[2]);
    double rv = hg * S->dydt_in[Y_V] + RG0 * (RE[0] * zv[0] + RE[1] * zv[1] + RE[2] * zv[2]);
    double ed = ((1 - hg * Jv) * rd + hg * rv) / det, ev = (hg * Jd * rd + rv) / det;
    double err = fmax(fabs(ed) / scd, fabs(ev) / scv);
    if (err >= 1 && (first || st->ctl.last_rejected)) {
        /* Hairer's second estimate, with f at y0 + err: keeps stiff components from
         * inflating the first estimate after a discontinuity */
        drive_val d0v;
        drive_at(S, R->t, &d0v.z, &d0v.zd, &d0v.F, &d0v.cw, &d0v.sw);
        if (S->sys.nz_f)
            d0v.F += noise_force(S, R->t);
        double a1 = accel(S, R->t, &d0v, R->d0 + ed, R->v0 + ev, R->cs);
        rd = hg * (R->v0 + ev) + RG0 * (RE[0] * zd[0] + RE[1] * zd[1] + RE[2] * zd[2]);
        rv = hg * a1 + RG0 * (RE[0] * zv[0] + RE[1] * zv[1] + RE[2] * zv[2]);
        ed = ((1 - hg * Jv) * rd + hg * rv) / det;
        ev = (hg * Jd * rd + rv) / det;
        err = fmax(fabs(ed) / scd, fabs(ev) / scv);
    }
    return isfinite(err) ? err : INFINITY;
}

/* ---- the system of any dimension: the law's states beside the motion ---- */

enum { RN = 3 * TT_SIM_DIM_MAX };

/* One general step's fixed data: the Jacobian of the n components at the start (by
 * differences), the Newton matrix I - h A (x) J and the error's I - h g0 J in LU form,
 * and each component's error scale. */
typedef struct {
    int n, ok, piv[RN], epiv[TT_SIM_DIM_MAX];
    double J[TT_SIM_DIM_MAX][TT_SIM_DIM_MAX], M[RN][RN], E[RN][RN], sc[TT_SIM_DIM_MAX];
} radau_gen;

static void radau_gen_setup(const radau_state *st, const tt_sim *S, double h, radau_gen *G)
{
    const int n = S->sys.n, nm = 2 * S->sys.modes;
    double y[NYMAX], f[NYMAX];
    G->n = n;
    sim_copy(S, y, S->y);
    for (int i = 0; i < n; i++)
        G->sc[i] = st->tol * S->c.A0 * (i < nm && (i & 1) ? S->c.wd : 1.0);
    for (int j = 0; j < n; j++) {
        /* a step of sqrt(eps) of the component's scale (its tolerance over tol) */
        double e = 1.5e-8 * fmax(fabs(y[j]), G->sc[j] / st->tol);
        y[j] = S->y[j] + e;
        S->sys.rhs(S, S->tau, y, S->contact_state, f);
        y[j] = S->y[j];
        for (int i = 0; i < n; i++)
            G->J[i][j] = (f[i] - S->dydt_in[i]) / e;
    }
    for (int a = 0; a < 3; a++)
        for (int i = 0; i < n; i++)
            for (int b = 0; b < 3; b++)
                for (int j = 0; j < n; j++)
                    G->M[a * n + i][b * n + j] = (a == b && i == j) - h * RA[a][b] * G->J[i][j];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            G->E[i][j] = (i == j) - h * RG0 * G->J[i][j];
    G->ok = lu_factor(&G->M[0][0], 3 * n, RN, G->piv) && lu_factor(&G->E[0][0], n, RN, G->epiv);
}

/* Simplified Newton on the stages' increments Z (3 x n, stage-major), from the last
 * accepted step's polynomial where there is one; sets newton_it (0: failed). */
static int radau_gen_newton(radau_state *st, const tt_sim *S, double h, const radau_gen *G, double *Z)
{
    const int n = G->n, m = 3 * n;
    const double t = S->tau, *y0 = S->y;
    for (int a = 0; a < 3; a++) {
        double x[TT_SIM_DIM_MAX];
        if (st->ext_ok)
            for (int i = 0; i < n; i++)
                x[i] = st->ext[0][i] + ((t + RC[a] * h - st->ext_tau) / st->ext_h) *
                       (st->ext[1][i] + ((t + RC[a] * h - st->ext_tau) / st->ext_h - RC[0]) *
                        (st->ext[2][i] + ((t + RC[a] * h - st->ext_tau) / st->ext_h - RC[1]) * st->ext[3][i]));
        for (int i = 0; i < n; i++)
            Z[a * n + i] = st->ext_ok ? x[i] - y0[i] : 0.0;
    }
    newton_track nt = newton_begin(st, st->tol);
    int conv = 0, it;
    for (it = 1; G->ok && it <= NEWTON_MAX; it++) {
        double F[3][NYMAX], g[RN], y[NYMAX];
        sim_copy(S, y, y0);
        for (int a = 0; a < 3; a++) {
            for (int i = 0; i < n; i++)
                y[i] = y0[i] + Z[a * n + i];
            S->sys.rhs(S, t + RC[a] * h, y, S->contact_state, F[a]);
        }
        for (int a = 0; a < 3; a++)
            for (int i = 0; i < n; i++)
                g[a * n + i] = h * (RA[a][0] * F[0][i] + RA[a][1] * F[1][i] + RA[a][2] * F[2][i]) - Z[a * n + i];
        lu_solve(&G->M[0][0], m, RN, G->piv, g);
        double nrm = 0;
        for (int k = 0; k < m; k++)
            nrm = fmax(nrm, fabs(g[k]) / G->sc[k % n]);
        if (newton_judge(&nt, nrm, it))
            break;
        for (int k = 0; k < m; k++)
            Z[k] += g[k];
        if (nt.eta * nrm <= nt.fnewt) {
            conv = 1;
            break;
        }
    }
    return newton_end(st, &nt, conv, it);
}

/* The end, the stages' full derivatives (quadratures included) and the collocation
 * polynomial of every component; then RADAU5's estimate (I - h g0 J)^-1 (g0 h f0 + g0
 * sum e_i Z_i), with Hairer's second estimate after a rejection. */
static double radau_gen_finish(radau_state *st, tt_sim *S, double h, const radau_gen *G, const double *Z,
                               int first)
{
    const int n = G->n;
    const double t = S->tau, *y0 = S->y;
    double (*k)[NYMAX] = st->k, y[NYMAX];
    sim_copy(S, y, y0);
    for (int a = 0; a < 3; a++) {
        for (int i = 0; i < n; i++)
            y[i] = y0[i] + Z[a * n + i];
        S->sys.rhs(S, t + RC[a] * h, y, S->contact_state, k[1 + a]);
    }
    for (int i = 0; i < n; i++)
        S->y1[i] = y0[i] + Z[2 * n + i];
    for (int q = n; q < sim_ny(S); q++)
        S->y1[q] = y0[q] + h * (RA[2][0] * k[1][q] + RA[2][1] * k[2][q] + RA[2][2] * k[3][q]);
    sim_copy(S, S->dydt_out, k[3]);
    for (int i = 0; i < n; i++) {
        const double z[3] = {Z[i], Z[n + i], Z[2 * n + i]};
        radau_collocation(st, i, y0[i], z);
    }
    double e[TT_SIM_DIM_MAX], err = 0;
    for (int pass = 0; pass < 2; pass++) {
        const double *f0 = S->dydt_in;
        double f1[NYMAX];
        if (pass) {
            for (int i = 0; i < n; i++)
                y[i] = y0[i] + e[i];
            S->sys.rhs(S, t, y, S->contact_state, f1);
            f0 = f1;
        }
        for (int i = 0; i < n; i++)
            e[i] = RG0 * (h * f0[i] + RE[0] * Z[i] + RE[1] * Z[n + i] + RE[2] * Z[2 * n + i]);
        lu_solve(&G->E[0][0], n, RN, G->epiv, e);
        err = 0;
        for (int i = 0; i < n; i++)
            err = fmax(err, fabs(e[i]) / G->sc[i]);
        if (!(err >= 1 && (first || st->ctl.last_rejected)))
            break;
    }
    return isfinite(err) ? err : INFINITY;
}

/* The step of a system with the law's states (first order, no d' = v to lean on): the
 * simplified Newton of RADAU5 on all n components, its Jacobian by differences. */
static double radau_step_general(radau_state *st, tt_sim *S, double h)
{
    const int first = !st->ext_ok;
    static _Thread_local radau_gen G;
    double Z[RN];
    radau_gen_setup(st, S, h, &G);
    int conv = radau_gen_newton(st, S, h, &G, Z);
    double err = radau_gen_finish(st, S, h, &G, Z, first);
    return conv ? err : INFINITY;
}

/* Radau IIA, 3 stages, order 5, is L-stable, so a stiff or heavily damped contact
 * limits its step only through accuracy. Simplified Newton on the motion (d, v) with
 * the step start's Jacobian; the quadrature components do not feed back, so they follow
 * from the converged stages with the weights b (the last row of A). Returns the scaled
 * error (RADAU5's embedded estimate; <= 1 accepts), or INFINITY with newton_it = 0. */
static double radau_step(void *state, tt_sim *S, double h)
{
    radau_state *st = state;
    const double *y0 = S->y;
    const int first = !st->ext_ok;
    ensure_fsal(S);
    sim_copy(S, S->dydt_in, S->fsal);
    sim_copy(S, S->y0, y0);
    S->step_tau = S->tau;
    S->step_h = h;
    S->step_long = 0;
    if (S->sys.n != 2)
        return radau_step_general(st, S, h);
    radau_ctx R;
    radau_setup(st, S, h, &R);
    double zv[3] = {0, 0, 0}, zd[3];
    int conv = radau_newton(st, S, &R, zv);
    /* the converged stages */
    for (int i = 0; i < 3; i++)
        zd[i] = h * (RA[i][0] * (R.v0 + zv[0]) + RA[i][1] * (R.v0 + zv[1]) + RA[i][2] * (R.v0 + zv[2]));
    radau_finish(st, S, &R, y0, zd, zv);
    if (!conv)
        return INFINITY;
    return radau_error(st, S, &R, zd, zv, first);
}

/* Hairer's safety factor, smaller after a slow Newton iteration; the estimate is
 * O(h^4). */
static double radau_factor(const void *state, double err)
{
    const radau_state *st = state;
    if (!st->newton_it)
        return 0.5; /* Newton failed: the step was too long for the Jacobian */
    double safe = fmin(0.9, 0.9 * (1 + 2 * NEWTON_MAX) / (st->newton_it + 2 * NEWTON_MAX));
    return err > 0 ? safe * pow(err, -0.25) : 5.0;
}

static int radau_advance(void *state, tt_sim *S, double T, int *outcome)
{
    radau_state *st = state;
    return tt_control_advance(&st->ctl, st, S, T, radau_step, radau_factor, outcome);
}

/* The step's polynomial: the next step's Newton start. */
static void radau_accept(void *state, const tt_sim *S)
{
    radau_state *st = state;
    memcpy(st->ext, st->rcont, sizeof st->ext);
    st->ext_tau = S->step_tau;
    st->ext_h = S->step_h;
    st->ext_ok = 1;
}

static int radau_redo(void *state, tt_sim *S, double h)
{
    radau_state *st = state;
    /* the step's own polynomial gives the redo's Newton iteration its start */
    radau_accept(st, S);
    (void)radau_step(st, S, h);
    if (!st->newton_it)
        return tt_error(TT_ENUM,
                        "radau: Newton iteration failed at a contact event at t = %.9g s "
                        "(cycle %ld); tighten [solver] tolerance",
                        sim_time(S, S->step_tau), S->cycle);
    return TT_OK;
}

static void radau_dense(const void *state, const tt_sim *S, double th, double *d, double *v)
{
    (void)S;
    radau_poly(((const radau_state *)state)->rcont, th, d, v);
}

/* The collocation polynomial of every component. */
static void radau_dense_x(const void *state, const tt_sim *S, double th, double *x)
{
    const radau_state *st = state;
    for (int i = 0; i < S->sys.n; i++)
        x[i] = st->rcont[0][i] +
               th * (st->rcont[1][i] + (th - RC[0]) * (st->rcont[2][i] + (th - RC[1]) * st->rcont[3][i]));
}

/* The step of length 0 at (tau, y): its polynomial is the constant y. */
static void radau_point(void *state, const tt_sim *S)
{
    tt_poly_point(((radau_state *)state)->rcont, S->y, S->sys.n);
}

static void radau_reset(void *state, const tt_sim *S)
{
    tt_control_reset(&((radau_state *)state)->ctl, S->c.T);
}

/* The last step's polynomial no longer starts the next Newton iteration, nor does the
 * last contraction rate: without it one Newton step could pass for converged on a new
 * branch. */
static void radau_invalidate(void *state)
{
    radau_state *st = state;
    st->ext_ok = 0;
    st->newton_eta = 1.0;
}

/* The last step's polynomial, in the new cycle's time. */
static void radau_cycle(void *state, double T)
{
    ((radau_state *)state)->ext_tau -= T;
}

static void *radau_alloc(const tt_sim *S)
{
    radau_state *st = calloc(1, sizeof *st);
    if (!st)
        return NULL;
    const double tol = S->solver.tolerance;
    tt_control_reset(&st->ctl, S->c.T);
    /* Radau's estimate is of an order-3 solution while the order-5 one is kept, so as in
     * Hairer's RADAU5 it is held to 0.1 tol^(2/3): about dopri5's accuracy at equal tol. */
    st->tol = 0.1 * pow(tol, 2.0 / 3.0);
    /* The per-cycle integrals are quadratures over the steps, off by about 1e-5 (w h)^6
     * of the amplitude (measured), which the motion's estimate does not see. */
    st->ctl.hmax = pow(1e5 * tol, 1.0 / 6.0) / S->c.wd;
    st->newton_eta = 1.0;
    return st;
}

const tt_step_type tt_step_radau = {
    .name = "radau",
    .alloc = radau_alloc,
    .free = free,
    .reset = radau_reset,
    .invalidate = radau_invalidate,
    .cycle = radau_cycle,
    .advance = radau_advance,
    .redo = radau_redo,
    .dense = radau_dense,
    .dense_x = radau_dense_x,
    .point = radau_point,
    .accept = radau_accept,
};
