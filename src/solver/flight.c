/* The free flight: exact exponential steps out of contact and away from the surface,
 * taken for dopri5 (docs/dynamics.md, "The free flight"), with their dense output and
 * the hand-over back to dopri5 near jump-in. */
#include <stdlib.h>
#include <string.h>

#include "flight.h"
#include "shooting_linalg.h"

/* Gauss-Legendre nodes per step, rungs of the step ladder, and the most law states the
 * flight advances (a Maxwell sample's arms). */
enum { FL_N = 6, FL_RUNGS = 12, FL_NL = TT_CONTACT_ARMS_MAX };

/* The free oscillator's propagator and the drive's rotation at the nodes and the end
 * (index FL_N) of a flight step of length h. */
typedef struct {
    double h;
    double e[FL_N + 1], cd[FL_N + 1], sd[FL_N + 1]; /* exp(-sig tau), cos, sin(wdm tau) */
    double cw[FL_N + 1], sw[FL_N + 1];              /* cos, sin(w tau) */
    double E[FL_N + 1][FL_NL * FL_NL];              /* the law states' exp(A tau) */
    int ok;
} fl_cache;

/* The flight's own state. */
struct tt_flight {
    int ok;           /* this sim may fly: dopri5, underdamped, no extremes tracked */
    int rung;         /* ladder rung of the flight's next step */
    int nrung;        /* rungs usable (w0 h >= 0.1; see flight_particular) */
    int skip;         /* dopri5 steps to take before the flight is tried again */
    int wait;         /* handed over near the surface: dopri5 until the tip recedes */
    int rej;          /* the last flight attempt was rejected: do not lengthen the next */
    double h0;        /* the ladder's longest step, min(T, 2 pi / w0) / 8 */
    double sig, wdm, w02; /* decay rate c / 2m, damped frequency, k / m */
    double hr[FL_RUNGS]; /* the rungs' step lengths, h0 2^(-r/4) */
    double Dr, Di;    /* steady drive response d_p = Dr cos(w t) - Di sin(w t) */
    double margin;    /* hand over to dopri5 within this penetration of jump-in */
    int nlaw;         /* the law's states, advanced by exp(A tau) (0: an elastic law) */
    double A[FL_NL][FL_NL]; /* their rate out of contact, dq/dt = A q */
    double vinv[FL_N][FL_N]; /* node values to monomial coefficients in theta */
    fl_cache lad[FL_RUNGS], scr; /* propagators per ladder rung, and a scratch one */
    /* the current flight step: q(theta) = sum b_k theta^k and the homogeneous part's
     * initial offset r0 and its time derivative */
    double b[FL_N], r0, r0d;
    double pen[FL_N + 2], vel[FL_N + 2]; /* penetration and its rate at 0, nodes, 1 */
};

/* Gauss-Legendre nodes on [0, 1] (the collocation points of the forcing and the
 * quadrature of the per-cycle integrals) and their weights. */
static const double FL_C[FL_N] = {
    0.5 - 0.4662347571015760, 0.5 - 0.3306046932331323, 0.5 - 0.1193095930415985,
    0.5 + 0.1193095930415985, 0.5 + 0.3306046932331323, 0.5 + 0.4662347571015760};
static const double FL_W[FL_N] = {0.0856622461895852, 0.1803807865240693, 0.2339569672863455,
                                  0.2339569672863455, 0.1803807865240693, 0.0856622461895852};

/* The node-value to monomial map: the inverse of the Vandermonde matrix V[j][k] = c_j^k,
 * by Gauss-Jordan (well conditioned at degree 5 on [0, 1]). */
static void flight_vandermonde(tt_flight *fl)
{
    double V[FL_N][2 * FL_N];
    for (int j = 0; j < FL_N; j++)
        for (int k = 0; k < FL_N; k++) {
            V[j][k] = pow(FL_C[j], k);
            V[j][FL_N + k] = j == k;
        }
    for (int col = 0; col < FL_N; col++) {
        int p = col;
        for (int r = col + 1; r < FL_N; r++)
            if (fabs(V[r][col]) > fabs(V[p][col]))
                p = r;
        for (int k = 0; k < 2 * FL_N; k++) {
            double t = V[col][k];
            V[col][k] = V[p][k];
            V[p][k] = t;
        }
        double piv = V[col][col];
        for (int k = 0; k < 2 * FL_N; k++)
            V[col][k] /= piv;
        for (int r = 0; r < FL_N; r++)
            if (r != col) {
                double f = V[r][col];
                for (int k = 0; k < 2 * FL_N; k++)
                    V[r][k] -= f * V[col][k];
            }
    }
    for (int k = 0; k < FL_N; k++)
        for (int j = 0; j < FL_N; j++)
            fl->vinv[k][j] = V[k][FL_N + j];
}

/* E = exp(A tau) for the law states' n x n rate matrix (FL_NL wide). */
static void fl_expm(int n, const double A[FL_NL][FL_NL], double tau, double *E)
{
    double P[FL_NL * FL_NL];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            P[i * n + j] = A[i][j];
    tt_shoot_expm(n, P, tau, E);
}

/* The law states' rate out of contact as a matrix, read off the law's rate at unit
 * states: a Maxwell sample's arms relax towards the free surface, tau_i dq_i/dt =
 * chi_f - q_i with chi_f = sum K_j q_j / K_g (src/physics/contact_sls.c), linear in q.
 * Returns 0 (the flight not taken) unless the rate is linear and the load out of contact
 * does not depend on the state, which the flight's force assumes. */
static int flight_law_setup(tt_flight *fl, const tt_sim *S)
{
    const tt_system *sys = &S->sys;
    int n = sys->nlaw;
    fl->nlaw = n;
    if (!n)
        return 1;
    if (n > FL_NL || sys->modes != 1 || !sys->law->rate || !sys->contact)
        return 0;
    const double sc = S->c.A0 > 0 ? S->c.A0 : 1e-9;
    double q[FL_NL] = {0}, r[FL_NL], p, sum[FL_NL] = {0};
    for (int j = 0; j < n; j++) {
        for (int i = 0; i < n; i++)
            q[i] = i == j ? sc : 0.0;
        sys->law->rate(sys->contact, -sc, 0.0, 0, q, r, &p);
        for (int i = 0; i < n; i++)
            fl->A[i][j] = r[i] / sc;
    }
    for (int i = 0; i < n; i++)
        q[i] = sc * (i + 1);
    sys->law->rate(sys->contact, -sc, 0.0, 0, q, r, &p);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            sum[i] += fl->A[i][j] * q[j];
    for (int i = 0; i < n; i++)
        if (!(fabs(r[i] - sum[i]) <= 1e-12 * (fabs(r[i]) + fabs(sum[i])) + 1e-300))
            return 0;
    double P0 = sys->force(sys->contact, sys->ci, -sc, 0.0, 0, NULL).conservative;
    return sys->force(sys->contact, sys->ci, -sc, 0.0, 0, q).conservative == P0;
}

/* The free flight's constants for the current cantilever. Out of contact Burnham et al.
 * eq. 2 is m d'' + c d' + k d = k z + c z' + F - P_vdw(d - s): its drive part has the
 * steady solution d_p = Re(D e^(i w t)), D = (k a + F0 + i c w a) / (k - m w^2 + i c w),
 * and x = d - d_p obeys a damped oscillator forced by -P / m alone. */
static void flight_setup(void *state, const tt_sim *S)
{
    tt_flight *fl = state;
    const tt_cantilever *c = &S->c;
    double zeta = 0.5 * c->c / (c->m * c->w0);
    /* the flight's steps are exact for the noiseless one-mode oscillator, and for the
     * law states of a sample whose surface recovers by a linear law (exp(A tau)) */
    fl->ok = S->solver.method == TT_METHOD_DOPRI5 && S->sys.modes == 1 && zeta < 0.8 &&
             !S->track_extremes && !S->sys.nz_f && flight_law_setup(fl, S);
    fl->sig = 0.5 * c->c / c->m;
    fl->w02 = c->k / c->m;
    fl->wdm = sqrt(fmax(fl->w02 - fl->sig * fl->sig, 0.0));
    double a = c->drive == TT_DRIVE_BASE ? c->a_d : 0.0, F0 = c->drive == TT_DRIVE_BASE ? 0.0 : c->F0;
    double nr = c->k * a + F0, ni = c->c * c->wd * a;
    double dr = c->k - c->m * c->wd * c->wd, di = c->c * c->wd, den = dr * dr + di * di;
    fl->Dr = (nr * dr + ni * di) / den;
    fl->Di = (ni * dr - nr * di) / den;
    /* at most one turning point of the drive or the free motion per step (T/8), which the
     * hand-over check relies on */
    fl->h0 = fmin(c->T, 2 * M_PI / c->w0) / 8;
    fl->nrung = 0;
    for (int r = 0; r < FL_RUNGS; r++) {
        fl->lad[r].ok = 0;
        fl->hr[r] = fl->h0 * pow(2.0, -0.25 * r);
        if (c->w0 * fl->hr[r] >= 0.1)
            fl->nrung = r + 1;
    }
    if (fl->nrung < 4)
        fl->ok = 0;
    fl->rung = 0;
    fl->skip = 0;
    fl->wait = 0;
    fl->scr.ok = 0;
    fl->margin = 0.05 * S->c.A0;
    flight_vandermonde(fl);
}

static void flight_reset(void *state, const tt_sim *S)
{
    tt_flight *fl = state;
    (void)S;
    fl->rung = 0;
    fl->skip = 0;
    fl->wait = 0;
    fl->rej = 0;
}

static void fl_fill(const tt_flight *fl, const tt_sim *S, fl_cache *F, double h)
{
    for (int j = 0; j <= FL_N; j++) {
        double tau = (j < FL_N ? FL_C[j] : 1.0) * h;
        F->e[j] = exp(-fl->sig * tau);
        F->cd[j] = cos(fl->wdm * tau);
        F->sd[j] = sin(fl->wdm * tau);
        F->cw[j] = cos(S->c.wd * tau);
        F->sw[j] = sin(S->c.wd * tau);
        if (fl->nlaw)
            fl_expm(fl->nlaw, fl->A, tau, F->E[j]);
    }
    F->h = h;
    F->ok = 1;
}

/* The flight's force term -P(d - s) / m on the out-of-contact branch. */
static inline double fl_force(const tt_sim *S, double delta)
{
    return S->sys.contact ? -S->sys.force(S->sys.contact, S->sys.ci, delta, 0.0, 0, NULL).conservative * S->sys.inv_m[0] : 0.0;
}

/* The polynomial particular solution of x_thth + 2 sig h x_th + w0^2 h^2 x = h^2 p(theta)
 * for p = sum a_k theta^k, by back substitution from the top degree; it loses about
 * (w0 h)^-10 of rounding relative to the forcing's displacement, which the ladder's
 * floor w0 h >= 0.1 keeps far below any tolerance. */
static void flight_particular(const tt_flight *fl, double h, const double *a, double *b)
{
    double h2 = h * h, s2 = 2 * fl->sig * h, iw = 1.0 / (fl->w02 * h2);
    double b1 = 0, b2 = 0;
    for (int k = FL_N - 1; k >= 0; k--) {
        double bk = (h2 * a[k] - (k + 1) * s2 * b1 - (k + 2) * (k + 1) * b2) * iw;
        b[k] = bk;
        b2 = b1;
        b1 = bk;
    }
}

/* x and x' at a node j of the cache F from the current step's q and r0. */
static inline void fl_node(const tt_flight *fl, const fl_cache *F, int j, double th, double h, double *x,
                           double *xd)
{
    const double *b = fl->b;
    double q = b[FL_N - 1], qd = 0;
    for (int k = FL_N - 2; k >= 0; k--) {
        qd = qd * th + q;
        q = q * th + b[k];
    }
    double A = fl->r0, B = (fl->r0d + fl->sig * A) / fl->wdm;
    double e = F->e[j], cs = F->cd[j], sn = F->sd[j];
    *x = q + e * (A * cs + B * sn);
    *xd = qd / h + e * (fl->r0d * cs - (fl->sig * B + fl->wdm * A) * sn);
}

/* The per-cycle integrals over the step by the nodes' Gauss-Legendre rule, from the
 * drive (cw, sw), the motion d = dp + x, v = dpd + x' and the forcing N at the nodes:
 * exact to about 1e-13 of a step's share for integrands up to twice the drive frequency
 * at h = T/8. */
static inline void flight_quadrature(tt_sim *S, double h, const double *cw, const double *sw,
                                     const double *dp, const double *dpd, const double *xj,
                                     const double *xdj, const double *N, const double *L)
{
    const tt_cantilever *c = &S->c;
    const double w = c->wd, *y0 = S->y;
    double *y1 = S->y1;
    double q[NY] = {0};
    for (int j = 0; j < FL_N; j++) {
        double d = dp[j] + xj[j], v = dpd[j] + xdj[j];
        double z, zd, Fd;
        if (c->drive == TT_DRIVE_BASE) {
            z = c->a_d * cw[j];
            zd = -c->a_d * w * sw[j];
            Fd = 0;
        } else {
            z = zd = 0;
            Fd = c->F0 * cw[j];
        }
        double y = d - z, spring = c->k * y, damp = c->c * (v - zd), W = FL_W[j];
        q[Y_WDRIVE] += W * (Fd * v - (spring + damp) * zd);
        q[Y_WDAMP] += W * damp * (v - zd);
        q[Y_WS] += W * (-N[j] * c->m) * S->sys.sdot;
        q[Y_IC] += W * y * cw[j];
        q[Y_IS] += W * y * sw[j];
        q[Y_IY] += W * y;
        if (L)
            q[Y_WVISC] += W * L[j];
    }
    /* the quadratures follow the law's states (sim.h's layout) */
    const int off = S->sys.n - 2;
    for (int i = Y_WDRIVE; i < NY; i++)
        y1[off + i] = y0[off + i] + h * q[i];
}

/* Keep the step for its dense output and the hand-over check: the penetration and its
 * rate at the start, the nodes and the end. */
static inline void flight_keep(tt_flight *fl, tt_sim *S, double h, const double *dp, const double *dpd,
                               const double *sj, const double *xj, const double *xdj)
{
    const double t0 = S->tau, *y0 = S->y, *y1 = S->y1;
    fl->pen[0] = y0[Y_D] - (S->sys.s0 + S->sys.sdot * t0);
    fl->vel[0] = y0[Y_V] - S->sys.sdot;
    for (int j = 0; j < FL_N; j++) {
        fl->pen[j + 1] = dp[j] + xj[j] - sj[j];
        fl->vel[j + 1] = dpd[j] + xdj[j] - S->sys.sdot;
    }
    fl->pen[FL_N + 1] = y1[Y_D] - sj[FL_N];
    fl->vel[FL_N + 1] = y1[Y_V] - S->sys.sdot;
    sim_copy(S, S->y0, y0);
    S->step_tau = t0;
    S->step_h = h;
    S->step_long = 1;
}

/* The drive's particular solution (its deflection dp and rate dpd, with the drive's
 * cos and sin) and the sample (sj) at the step's nodes and end (index FL_N), and the
 * homogeneous part's start (x0, x0d). */
static inline void flight_nodes(const tt_flight *fl, const tt_sim *S, double h, const fl_cache *F, double *cw,
                                double *sw, double *dp, double *dpd, double *sj, double *x0,
                                double *x0d)
{
    const double t0 = S->tau, w = S->c.wd, *y0 = S->y;
    const double Dr = fl->Dr, Di = fl->Di;
    double s0w, c0w;
    phase_sincos(w * t0, &s0w, &c0w);
    for (int j = 0; j <= FL_N; j++) {
        cw[j] = c0w * F->cw[j] - s0w * F->sw[j];
        sw[j] = s0w * F->cw[j] + c0w * F->sw[j];
        dp[j] = Dr * cw[j] - Di * sw[j];
        dpd[j] = -w * (Dr * sw[j] + Di * cw[j]);
        sj[j] = S->sys.s0 + S->sys.sdot * (t0 + (j < FL_N ? FL_C[j] : 1.0) * h);
    }
    *x0 = y0[Y_D] - (Dr * c0w - Di * s0w);
    *x0d = y0[Y_V] + w * (Dr * s0w + Di * c0w);
}

/* The law states over a flight step: exact, q(tau) = exp(A tau) q0, at the end into y1
 * and at the nodes for the power their dashpots take there (L), which the quadrature
 * books as the viscous loss. */
static void flight_law_step(const tt_flight *fl, tt_sim *S, const fl_cache *F, double *L)
{
    const int n = fl->nlaw;
    const double *q0 = S->y + 2;
    double q[FL_NL], dq[FL_NL];
    for (int j = 0; j <= FL_N; j++) {
        for (int i = 0; i < n; i++) {
            double acc = 0;
            for (int k = 0; k < n; k++)
                acc += F->E[j][i * n + k] * q0[k];
            q[i] = acc;
        }
        if (j == FL_N)
            memcpy(S->y1 + 2, q, sizeof(double) * (size_t)n);
        else
            S->sys.law->rate(S->sys.contact, -1.0, 0.0, 0, q, dq, &L[j]);
    }
}

/* One exponential step of length h from (tau, y) out of contact, into y1 with the
 * per-cycle integrals, filling the dense data. d = d_p + x with x advanced exactly for
 * the linear part (the damped oscillator's propagator) and the van der Waals force
 * interpolated at six Gauss-Legendre nodes by a degree-5 polynomial (collocation,
 * solved by Picard iteration, which contracts by about (dP/ddelta / k) (w0 h)^2, tiny
 * out of contact). The error estimate is the interpolation's miss at the step end,
 * mapped to the velocity it moves over the step (h |dN|), relative to the tolerance of
 * dopri5's estimate. Returns it (<= 1 accepts), or -1 if the iteration did not
 * converge. */
static double flight_step(tt_flight *fl, tt_sim *S, double h, const fl_cache *F)
{
    const double *y0 = S->y;
    const double sc = 1.0 / (S->solver.tolerance * S->c.A0 * S->c.wd);
    double cw[FL_N + 1], sw[FL_N + 1], dp[FL_N + 1], dpd[FL_N + 1], sj[FL_N + 1], x0, x0d;
    flight_nodes(fl, S, h, F, cw, sw, dp, dpd, sj, &x0, &x0d);
    double N[FL_N], a[FL_N], xj[FL_N], xdj[FL_N];
    double N0 = fl_force(S, y0[Y_D] - (S->sys.s0 + S->sys.sdot * S->tau));
    for (int j = 0; j < FL_N; j++)
        N[j] = N0;
    /* Picard iteration. After the first round the next change of the forcing is bounded
     * by its slope |dP/ddelta| / m at the node nearest the surface (the largest, the
     * force rising towards it) times the change of x, which spares the second round of
     * force evaluations when that is small enough. (Kept inline here: as a function of
     * its own it compiled to a fifth more instructions.) */
    int conv = 0;
    double L = -1, xprev[FL_N];
    for (int it = 0; it < 5 && !conv; it++) {
        for (int k = 0; k < FL_N; k++) {
            double acc = 0;
            for (int j = 0; j < FL_N; j++)
                acc += fl->vinv[k][j] * N[j];
            a[k] = acc;
        }
        flight_particular(fl, h, a, fl->b);
        fl->r0 = x0 - fl->b[0];
        fl->r0d = x0d - fl->b[1] / h;
        double dx = 0;
        for (int j = 0; j < FL_N; j++) {
            fl_node(fl, F, j, FL_C[j], h, &xj[j], &xdj[j]);
            if (it > 0)
                dx = fmax(dx, fabs(xj[j] - xprev[j]));
            xprev[j] = xj[j];
        }
        /* the last change moves the velocity by about h chg: converged when that is a
         * hundredth of the tolerance */
        if (it > 0 && L >= 0 && h * (2 * L * dx) * sc < 0.01)
        {
            conv = 1;
            break;
        }
        double chg = 0;
        int jn = 0;
        for (int j = 0; j < FL_N; j++) {
            double pen = dp[j] + xj[j] - sj[j];
            double Nn = fl_force(S, pen);
            chg = fmax(chg, fabs(Nn - N[j]));
            N[j] = Nn;
            if (pen > dp[jn] + xj[jn] - sj[jn])
                jn = j;
        }
        conv = h * chg * sc < 0.01;
        if (!conv && it == 0 && S->sys.contact) {
            double dPdd = 0;
            (void)tt_contact_load(S->sys.contact, dp[jn] + xj[jn] - sj[jn], 0, &dPdd, NULL);
            L = fabs(dPdd) * S->sys.inv_m[0];
        }
    }
    if (!conv)
        return -1;
    double xe, xed;
    fl_node(fl, F, FL_N, 1.0, h, &xe, &xed);
    double *y1 = S->y1;
    y1[Y_D] = dp[FL_N] + xe;
    y1[Y_V] = dpd[FL_N] + xed;
    double pe = 0;
    for (int k = 0; k < FL_N; k++)
        pe += a[k];
    double err = h * fabs(fl_force(S, y1[Y_D] - sj[FL_N]) - pe) * sc;
    double Lw[FL_N];
    if (fl->nlaw)
        flight_law_step(fl, S, F, Lw);
    flight_quadrature(S, h, cw, sw, dp, dpd, xj, xdj, N, fl->nlaw ? Lw : NULL);
    flight_keep(fl, S, h, dp, dpd, sj, xj, xdj);
    return isfinite(err) ? err : INFINITY;
}

/* Dense output of a flight step: the exact propagator at any fraction th. */
void tt_flight_dense(const tt_flight *fl, const tt_sim *S, double th, double *d, double *v)
{
    if (th == 0 || th == 1) {
        const double *y = th == 0 ? S->y0 : S->y1;
        *d = y[Y_D];
        *v = y[Y_V];
        return;
    }
    fl_cache F;
    double h = S->step_h, tau = th * h;
    F.e[0] = exp(-fl->sig * tau);
    /* the damped rotation's angle is below 2 pi (steps of at most 1/8 of a free period),
     * where the drive's own sine and cosine serve, at a third of the library's cost */
    phase_sincos(fl->wdm * tau, &F.sd[0], &F.cd[0]);
    double x, xd, sn, cs;
    fl_node(fl, &F, 0, th, h, &x, &xd);
    phase_sincos(S->c.wd * (S->step_tau + tau), &sn, &cs);
    *d = fl->Dr * cs - fl->Di * sn + x;
    *v = -S->c.wd * (fl->Dr * sn + fl->Di * cs) + xd;
}

void tt_flight_dense_x(const tt_flight *fl, const tt_sim *S, double th, double *x)
{
    const int n = S->sys.n;
    if (th == 0 || th == 1) {
        memcpy(x, th == 0 ? S->y0 : S->y1, sizeof(double) * (size_t)n);
        return;
    }
    tt_flight_dense(fl, S, th, &x[0], &x[1]);
    if (fl->nlaw) {
        double E[FL_NL * FL_NL];
        fl_expm(fl->nlaw, fl->A, th * S->step_h, E);
        for (int i = 0; i < fl->nlaw; i++) {
            double acc = 0;
            for (int k = 0; k < fl->nlaw; k++)
                acc += E[i * fl->nlaw + k] * S->y0[2 + k];
            x[2 + i] = acc;
        }
    }
}

/* Whether the current flight step comes within fl_margin of jump-in: at its start, nodes
 * or end, or at a maximum of the penetration between them (located on the exact dense
 * output), so that a brief approach between the step's points is not missed. */
static int flight_near(const tt_flight *fl, const tt_sim *S)
{
    if (!S->sys.contact || !isfinite(S->sys.jumpin))
        return 0;
    double thr = S->sys.jumpin - fl->margin;
    for (int j = 0; j < FL_N + 2; j++)
        if (fl->pen[j] >= thr)
            return 1;
    for (int j = 0; j < FL_N + 1; j++)
        if (fl->vel[j] > 0 && fl->vel[j + 1] < 0) {
            double a = j == 0 ? 0.0 : FL_C[j - 1], b = j == FL_N ? 1.0 : FL_C[j];
            double tm = tt_event_root(S, 1, 0, a, b, fl->vel[j], fl->vel[j + 1]);
            if (tt_event_delta(S, tm, thr) >= 0)
                return 1;
        }
    return 0;
}

/* The propagator for a step of length hf on rung r, or for the cycle's last (shorter)
 * step. */
static const fl_cache *flight_cache(tt_flight *fl, const tt_sim *S, int r, double hf, int lastf)
{
    if (lastf) {
        if (!(fl->scr.ok && fl->scr.h == hf))
            fl_fill(fl, S, &fl->scr, hf);
        return &fl->scr;
    }
    if (!fl->lad[r].ok)
        fl_fill(fl, S, &fl->lad[r], hf);
    return &fl->lad[r];
}

/* The rung after a flight step of rung r with error err. The estimate is O(h^7): one
 * rung (2^(1/4)) per factor 5. */
static int flight_next_rung(const tt_flight *fl, int r, double err, int lastf)
{
    int nr = r;
    if (err > 1)
        nr = r + 1 + (int)(log(err) * (4.0 / 7.0 / M_LN2));
    else if (!lastf && !fl->rej && err < 0.2)
        /* grow by 0.9 err^(-1/7), at most two rungs (a factor 1.41): an approaching tip's
         * error grows fast from step to step */
        nr = r - (err < 0.04 ? 2 : 1);
    return nr;
}

int tt_flight_advance(tt_flight *fl, tt_sim *S, double T)
{
    const double hmin = T * 1e-13;
    if (fl->wait && S->y[Y_V] - S->sys.sdot < 0)
        fl->wait = 0;
    if (fl->ok && !S->contact_state && fl->skip == 0 && !fl->wait &&
        S->y[Y_D] - (S->sys.s0 + S->sys.sdot * S->tau) < S->sys.jumpin - fl->margin) {
        int r = fl->rung;
        double hf = fl->hr[r];
        int lastf = 0;
        if (S->tau + hf >= T - hmin) {
            hf = T - S->tau;
            lastf = 1;
        }
        const fl_cache *F = flight_cache(fl, S, r, hf, lastf);
        if (S->c.w0 * hf >= 0.1) {
            double err = flight_step(fl, S, hf, F);
            if (err < 0 || flight_near(fl, S)) {
                fl->wait = 1; /* the approach: no more tries until it recedes */
            } else {
                int nr = flight_next_rung(fl, r, err, lastf);
                fl->rej = err > 1;
                if (nr < 0)
                    nr = 0;
                if (err > 1) {
                    S->rejected++;
                    if (nr >= fl->nrung) {
                        fl->rung = fl->nrung - 1;
                        fl->skip = 4; /* too short to pay: dopri5 for a while */
                    } else {
                        fl->rung = nr;
                    }
                    return TT_STEP_RETRY;
                }
                if (!lastf)
                    fl->rung = nr;
                return TT_STEP_TAKEN;
            }
        }
    }
    if (fl->skip > 0)
        fl->skip--;
    return TT_STEP_PASS;
}

static void *flight_alloc(const tt_sim *S)
{
    tt_flight *fl = calloc(1, sizeof *fl);
    if (fl)
        flight_setup(fl, S);
    return fl;
}

/* Dense output through the table: the step of dopri5's that was a flight. */
static void flight_dense_state(const void *state, const tt_sim *S, double th, double *d, double *v)
{
    tt_flight_dense(state, S, th, d, v);
}

static int flight_advance_state(void *state, tt_sim *S, double T, int *outcome)
{
    *outcome = tt_flight_advance(state, S, T);
    return TT_OK;
}

/* Not a method of its own: dopri5 takes its steps where it passes (TT_STEP_PASS). */
const tt_step_type tt_step_flight = {
    .name = "flight",
    .alloc = flight_alloc,
    .free = free,
    .reset = flight_reset,
    .setup = flight_setup,
    .advance = flight_advance_state,
    .dense = flight_dense_state,
};
