/* Maugis-Dugdale, DMT and JKR contact curves and their tables (Burnham et al. section
 * 2.2; see include/tiptap/physics/contact.h).
 *
 * Every adhesive model is a parametric curve (A, Delta, P)(p) in Burnham et al.'s normalised
 * units (eq. 3), with Delta increasing in p along the displacement-controlled stable
 * branch. That branch is tabulated once against s = sqrt(Delta - Delta_min), in which
 * the fold's square root is smooth: uniformly in s on [S_A, S1] (most contacts, no
 * transcendental function per look-up), uniformly in ln s on [S1, S_MAX] (a Hertz tail
 * continues it) and on [S_LO, S_A], and by one quadratic-exact cubic on [0, S_LO]. The
 * inner ln s grid is there because near the onset of the fold (lambda = 0.938) P goes
 * as (Delta - Delta0)^(2/3) down to a scale in s that shrinks to 0 there, which no
 * uniform s grid resolves. Cubic Hermite interpolation with exact derivatives makes
 * each look-up O(1). A negative s continues the end's tangent in s, so the branch stays
 * smooth a little below its end for the stages of a step that overshoot it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_private.h"
#include "tiptap/util/error.h"

/* ---------------------------------------------------------------- curves ---- */

/* Maugis-Dugdale eq. 7 at t = sqrt(m^2 - 1): for fixed m its first line is a quadratic
 * in A (docs/physics.md). A, Delta, P and their derivatives in t. */
static void maugis_t(double lam, double t, double *A, double *D, double *P, double *dA, double *dD,
                     double *dP)
{
    double at = atan(t), t2 = t * t, m = sqrt(1 + t2);
    double fa, fad;
    if (t < 1e-2) {
        /* t + (t^2 - 1) atan t cancels down to 4/3 t^3 for small t */
        fa = t2 * t * (4.0 / 3 + t2 * (-8.0 / 15 + t2 * (12.0 / 35 + t2 * (-16.0 / 63))));
        fad = t2 * (4.0 + t2 * (-8.0 / 3 + t2 * (12.0 / 5 + t2 * (-16.0 / 7))));
    } else {
        fa = t + (t2 - 1) * at;
        fad = 2 * t * at + 2 * t2 / (1 + t2);
    }
    double fb = -t2 / (1 + m) + t * at; /* 1 - m + t atan t without cancellation */
    double fbd = -t / m + at + t / (1 + t2);
    double a = 0.5 * lam * fa, b = 4.0 / 3.0 * lam * lam * fb;
    double ad = 0.5 * lam * fad, bd = 4.0 / 3.0 * lam * lam * fbd;
    double Av = 2.0 / (b + sqrt(b * b + 4 * a)); /* the positive root, no cancellation */
    double g = t + (1 + t2) * at, gd = 2 + 2 * t * at;
    *A = Av;
    *D = Av * Av - 4.0 / 3.0 * lam * Av * t;
    *P = Av * Av * Av - lam * Av * Av * g;
    if (dA) {
        double Ad = -(ad * Av * Av + bd * Av) / (2 * a * Av + b);
        *dA = Ad;
        *dD = 2 * Av * Ad - 4.0 / 3.0 * lam * (Ad * t + Av);
        *dP = 3 * Av * Av * Ad - lam * (2 * Av * Ad * g + Av * Av * gd);
    }
}

void tt_contact_maugis_point(double lambda, double m, double *A, double *Delta, double *P)
{
    maugis_t(lambda, sqrt(m * m - 1), A, Delta, P, NULL, NULL, NULL);
}

/* A point of the curve at parameter p with derivatives in p; Delta grows with p on the
 * stable branch. Maugis: p = -ln t (p -> -inf is the A -> 0 end); DMT, JKR: p = A. */
static void curve_at(curve_kind k, double lam, double p, double *A, double *D, double *P,
                     double *dA, double *dD, double *dP)
{
    if (k == CURVE_MAUGIS) {
        double t = exp(-p), a_, d_, p_;
        maugis_t(lam, t, A, D, P, &a_, &d_, &p_);
        *dA = -t * a_;
        *dD = -t * d_;
        *dP = -t * p_;
    } else if (k == CURVE_DMT) { /* eq. 5 */
        *A = p;
        *D = p * p;
        *P = p * p * p - 2;
        *dA = 1;
        *dD = 2 * p;
        *dP = 3 * p * p;
    } else { /* JKR, eq. 6 */
        double r = sqrt(6 * fmax(p, 0));
        *A = p;
        *D = p * p - 2.0 / 3.0 * r;
        *P = p * p * p - p * r;
        *dA = 1;
        *dD = 2 * p - (r > 0 ? 2.0 / r : -INFINITY);
        *dP = 3 * p * p - 1.5 * r;
    }
}

/* The A -> 0 end of the curve (P0, Delta0): eq. 8 for Maugis, in docs/physics.md's exact form. */
static void curve_end(curve_kind k, double lam, double *P0, double *D0)
{
    if (k == CURVE_MAUGIS) {
        double qa = M_PI * lam / 4, qb = 4.0 / 3.0 * lam * lam * (M_PI / 2 - 1);
        double u = 2.0 / (qb + sqrt(qb * qb + 4 * qa));
        *P0 = -M_PI * lam / 2 * u * u;
        *D0 = -4.0 / 3.0 * lam * u;
    } else if (k == CURVE_DMT) {
        *P0 = -2;
        *D0 = 0;
    } else {
        *P0 = 0;
        *D0 = 0;
    }
}

/* Search range of p: from near the A -> 0 end to far into the Hertz regime. */
static void curve_range(curve_kind k, double *lo, double *hi)
{
    if (k == CURVE_MAUGIS) {
        *lo = -log(1e8); /* t = 1e8: A about 1e-8 */
        *hi = 25;
    } else {
        *lo = 0;
        *hi = 2e4;
    }
}

static double dDelta_dp(curve_kind k, double lam, double p)
{
    double A, D, P, dA, dD, dP;
    curve_at(k, lam, p, &A, &D, &P, &dA, &dD, &dP);
    return dD;
}

static double dP_dp(curve_kind k, double lam, double p)
{
    double A, D, P, dA, dD, dP;
    curve_at(k, lam, p, &A, &D, &P, &dA, &dD, &dP);
    return dP;
}

/* Bisection for a sign change of f between a and b (f(a) < 0 < f(b) or reverse). */
static double bisect(double (*f)(curve_kind, double, double), curve_kind k, double lam, double a,
                     double b)
{
    double fa = f(k, lam, a);
    for (int i = 0; i < 200 && b - a > 1e-15 * (1 + fabs(a)); i++) {
        double m = 0.5 * (a + b), fm = f(k, lam, m);
        if ((fm < 0) == (fa < 0)) {
            a = m;
            fa = fm;
        } else {
            b = m;
        }
    }
    return 0.5 * (a + b);
}

#define GRID 3000

/* The fold (least Delta; displacement-controlled pull-off) and the least load
 * (load-controlled pull-off) by a scan over p refined by bisection. *pf is -INFINITY
 * when Delta rises all along the curve from its A -> 0 end (no fold). */
static void find_extrema(curve_kind k, double lam, double *pf, double *pmin_load, double *Pmin)
{
    double lo, hi, A, D, P, dA, dD, dP;
    curve_range(k, &lo, &hi);
    double scan_hi = k == CURVE_MAUGIS ? 12 : 10;
    double h = (scan_hi - lo) / (GRID - 1);
    /* the least Delta and the least load on a grid (signs of the derivatives are mere
     * round-off near the A -> 0 end), each refined by bisection on its derivative */
    int iD = 0, iP = 0;
    double bestD = INFINITY, bestP = INFINITY;
    for (int i = 0; i < GRID; i++) {
        curve_at(k, lam, lo + h * i, &A, &D, &P, &dA, &dD, &dP);
        if (D < bestD) {
            bestD = D;
            iD = i;
        }
        if (P < bestP) {
            bestP = P;
            iP = i;
        }
    }
    double P0, D0;
    curve_end(k, lam, &P0, &D0);
    *pf = -INFINITY;
    if (iD > 0 && iD < GRID - 1 && bestD < D0 - 1e-12 * (1 + fabs(D0)))
        *pf = bisect(dDelta_dp, k, lam, lo + h * (iD - 1), lo + h * (iD + 1));
    *pmin_load = -INFINITY;
    *Pmin = P0;
    if (iP > 0 && iP < GRID - 1) {
        double pm = bisect(dP_dp, k, lam, lo + h * (iP - 1), lo + h * (iP + 1));
        curve_at(k, lam, pm, &A, &D, &P, &dA, &dD, &dP);
        if (P < P0) {
            *pmin_load = pm;
            *Pmin = P;
        }
    }
}

/* Solve Delta(p) = target on the stable branch, p in [pl, range end]. */
static double solve_p(curve_kind k, double lam, double target, double pl, double hi_lim)
{
    double A, D, P, dA, dD, dP;
    double ph = pl + 0.5;
    for (;;) {
        curve_at(k, lam, ph, &A, &D, &P, &dA, &dD, &dP);
        if (D >= target || ph >= hi_lim)
            break;
        ph = pl + 2 * (ph - pl);
        if (ph > hi_lim)
            ph = hi_lim;
    }
    double p = 0.5 * (pl + ph);
    for (int it = 0; it < 200; it++) {
        curve_at(k, lam, p, &A, &D, &P, &dA, &dD, &dP);
        double f = D - target;
        if (f > 0)
            ph = p;
        else
            pl = p;
        /* done when the Newton step is below round-off too: far into the Hertz regime
         * Delta's round-off exceeds 1e-15 Delta, and creeping by ulps would run out of
         * iterations midway through a bisection */
        double step = dD > 0 ? f / dD : INFINITY;
        if (fabs(f) <= 1e-15 * fmax(1.0, fabs(target)) || ph - pl < 1e-15 * (1 + fabs(p)) ||
            fabs(step) <= 1e-15 * (1 + fabs(p)))
            break;
        double pn = p - step;
        p = (pn > pl && pn < ph) ? pn : 0.5 * (pl + ph);
    }
    return p;
}

/* Cubic Hermite on a segment: value and derivative in the segment's variable. */
static inline double herm(const segment *g, const double *y, const double *dy, double x, double *d)
{
    double u = (x - g->x0) * g->inv_h;
    int i = (int)floor(u);
    if (i < 0)
        i = 0;
    if (i > g->n - 2)
        i = g->n - 2;
    double t = u - i, t2 = t * t, t3 = t2 * t, h = g->h;
    double v = (2 * t3 - 3 * t2 + 1) * y[i] + (t3 - 2 * t2 + t) * h * dy[i] + (-2 * t3 + 3 * t2) * y[i + 1] +
               (t3 - t2) * h * dy[i + 1];
    if (d)
        *d = ((6 * t2 - 6 * t) * y[i] + (3 * t2 - 4 * t + 1) * h * dy[i] + (-6 * t2 + 6 * t) * y[i + 1] +
              (3 * t2 - 2 * t) * h * dy[i + 1]) *
             g->inv_h;
    return v;
}

/* Normalised contact branch at Delta: load, dP/dDelta, A and U = I(s), the integral
 * of P dDelta from the branch's end. dPdD, A and U may be NULL: the time loop needs
 * none of them, and each costs work of its own (a division, a table look-up). */
static void branch(const struct tt_contact *c, double D, double *P, double *dPdD, double *A,
                   double *U)
{
    if (D > c->Dend) {
        /* Hertz tail (eq. 4), continuous with the table at its end */
        double r = sqrt(D), re = sqrt(c->Dend);
        *P = c->Pend + D * r - c->Dend * re;
        if (dPdD)
            *dPdD = 1.5 * r;
        if (A)
            *A = c->Aend + r - re;
        if (U)
            *U = c->Uend + (c->Pend - c->Dend * re) * (D - c->Dend) +
                 0.4 * (D * D * r - c->Dend * c->Dend * re);
        return;
    }
    double x = D - c->dmin;
    double s = x >= 0 ? sqrt(x) : -sqrt(-x);
    const segment *g;
    double r, dPr = 0;
    if (s >= S_A && s <= S1) {
        g = &c->seg[2]; /* most contacts: uniform in s, no log */
        r = s;
    } else if (s > S_LO) {
        g = s < S_A ? &c->seg[1] : &c->seg[3];
        r = log(s);
    } else if (s >= 0) {
        g = &c->seg[0];
        r = s;
    } else {
        /* below the end: the end's tangent in s, which stays bounded however far a
         * stage overshoots (the first cubic spans only S_LO) */
        g = &c->seg[0];
        *P = g->P[0] + g->dP[0] * s;
        if (A)
            *A = g->A[0] + g->dA[0] * s < 0 ? 0.0 : g->A[0] + g->dA[0] * s;
        if (dPdD)
            *dPdD = g->dP[0] / (2 * fmax(-s, 1e-9));
        if (U)
            *U = g->U[0] + g->dU[0] * s;
        return;
    }
    *P = herm(g, g->P, g->dP, r, dPdD ? &dPr : NULL);
    if (A) {
        double Av = herm(g, g->A, g->dA, r, NULL);
        *A = Av < 0 ? 0 : Av;
    }
    /* dP/dDelta = (dP/ds) / (2 s) = (dP/d ln s) / (2 s^2) */
    if (dPdD)
        *dPdD = g->log ? dPr / (2 * s * s) : dPr / (2 * fmax(s, 1e-9));
    if (U)
        *U = herm(g, g->U, g->dU, r, NULL);
}

/* Van der Waals branch (eq. 10 with docs/physics.md's sign): P = P0 (Delta0 - xi)^2 /
 * (Delta - xi)^2, U = -P0 (Delta0 - xi)^2 / (Delta - xi) (zero far away); continued
 * linearly past a cap halfway to its pole, which only overshooting stages reach. */
static void vdw(const struct tt_contact *c, double D, double *P, double *dPdD, double *U)
{
    if (c->P0 == 0) {
        *P = 0;
        if (dPdD)
            *dPdD = 0;
        if (U)
            *U = 0;
        return;
    }
    double k2 = c->vdw_k2;
    double Dc = D < c->vdw_cap ? D : c->vdw_cap;
    double ir = 1.0 / (Dc - c->xi); /* one division for all three */
    double Uc = -k2 * ir, Pc = -Uc * ir, dPc = -2 * Pc * ir;
    if (D <= c->vdw_cap) {
        *P = Pc;
        if (dPdD)
            *dPdD = dPc;
        if (U)
            *U = Uc;
        return;
    }
    double e = D - c->vdw_cap;
    *P = Pc + dPc * e;
    if (dPdD)
        *dPdD = dPc;
    if (U)
        *U = Uc + Pc * e + 0.5 * dPc * e * e;
}

/* Tabulate the stable branch of a curve from its end (fold or A -> 0) outwards. */
static void build_table(struct tt_contact *c, double pf)
{
    curve_kind k = c->kind;
    double lam = c->lambda, lo, hi, A, D, P, dA, dD, dP;
    curve_range(k, &lo, &hi);
    int end_closed = !isfinite(pf) && k == CURVE_MAUGIS; /* the A -> 0 end, closed form */
    double p_start = isfinite(pf) ? pf : lo;
    /* node 0 */
    double P0n, A0n, D0n;
    if (end_closed) {
        P0n = c->P0;
        A0n = 0;
        D0n = c->D0;
    } else {
        curve_at(k, lam, p_start, &A0n, &D0n, &P0n, &dA, &dD, &dP);
    }
    c->dmin = D0n;
    static const int nodes[NSEG] = {2, N0, N1, N2};
    const double lo_s[NSEG] = {0, log(S_LO), S_A, log(S1)};
    const double hi_s[NSEG] = {S_LO, log(S_A), S1, log(S_MAX)};
    double pl = p_start;
    for (int gi = 0; gi < NSEG; gi++) {
        segment *g = &c->seg[gi];
        g->log = gi % 2;
        g->n = nodes[gi];
        g->x0 = lo_s[gi];
        g->h = (hi_s[gi] - lo_s[gi]) / (g->n - 1);
        g->inv_h = 1.0 / g->h;
        for (int i = 0; i < g->n; i++) {
            double x = g->x0 + g->h * i;
            double s = g->log ? exp(x) : x;
            if (gi == 0 && i == 0) {
                g->P[0] = P0n;
                g->A[0] = A0n;
                continue;
            }
            double p = solve_p(k, lam, c->dmin + s * s, pl, hi);
            pl = p;
            curve_at(k, lam, p, &A, &D, &P, &dA, &dD, &dP);
            g->P[i] = P;
            g->A[i] = A;
            /* d/ds = (d/dp) 2 s / (dDelta/dp); d/d ln s = s d/ds */
            double ds = 2 * s / dD * (g->log ? s : 1.0);
            g->dP[i] = dP * ds;
            g->dA[i] = dA * ds;
        }
    }
    /* the end node's slope in s (the chain rule is 0/0 there): the one that makes the
     * first cubic exact for quadratics, which holds both at a fold (P linear in s) and
     * at the A -> 0 end (P - P0 quadratic in s) */
    segment *g0 = &c->seg[0];
    g0->dP[0] = 2 * (g0->P[1] - g0->P[0]) / g0->h - g0->dP[1];
    g0->dA[0] = 2 * (g0->A[1] - g0->A[0]) / g0->h - g0->dA[1];
    /* U = integral of P dDelta = integral of 2 s P ds, by 3-point Gauss per interval
     * on the Hermite interpolant of P */
    static const double gx[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
    static const double gw[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
    double Ucum = 0;
    for (int gi = 0; gi < NSEG; gi++) {
        segment *g = &c->seg[gi];
        for (int i = 0; i < g->n; i++) {
            double x = g->x0 + g->h * i;
            double s = g->log ? exp(x) : x;
            if (i > 0) {
                double sum = 0;
                for (int q = 0; q < 3; q++) {
                    double xm = g->x0 + g->h * (i - 0.5 + 0.5 * gx[q]);
                    double sm = g->log ? exp(xm) : xm;
                    double Pm = herm(g, g->P, g->dP, xm, NULL);
                    sum += gw[q] * 2 * sm * Pm * (g->log ? sm : 1.0);
                }
                Ucum += 0.5 * g->h * sum;
            }
            g->U[i] = Ucum;
            g->dU[i] = 2 * s * g->P[i] * (g->log ? s : 1.0);
        }
    }
    const segment *gl = &c->seg[NSEG - 1];
    c->Pend = gl->P[N2 - 1];
    c->Aend = gl->A[N2 - 1];
    c->Uend = gl->U[N2 - 1];
    c->Dend = c->dmin + S_MAX * S_MAX;
}

/* ----------------------------------------------------------- the table laws ---- */

/* The tabulated laws (Maugis-Dugdale, DMT, JKR): the stable branch in contact, van der
 * Waals out of it, in normalised units scaled back. */
static inline double table_load(const struct tt_contact *c, double delta, int in_contact,
                                double *dPdd, double *a)
{
    double D = delta * c->inv_d, P, dP, A = 0;
    if (in_contact) {
        branch(c, D, &P, dPdd ? &dP : NULL, a ? &A : NULL, NULL);
        if (a)
            *a = A * c->a;
    } else {
        vdw(c, D, &P, dPdd ? &dP : NULL, NULL);
        if (a)
            *a = 0;
    }
    if (dPdd)
        *dPdd = dP * c->F_per_d;
    return P * c->F;
}

double tt_contact_table_energy(const struct tt_contact *c, double delta, int in_contact, const double *q)
{
    (void)q;
    double D = delta * c->inv_d, P, U;
    if (in_contact) {
        branch(c, D, &P, NULL, NULL, &U);
        U += c->Uc_shift;
    } else {
        vdw(c, D, &P, NULL, &U);
    }
    return U * c->F * c->d;
}

double tt_contact_table_load(const struct tt_contact *c, double delta, int in_contact,
                             double *dPdd, double *a)
{
    return table_load(c, delta, in_contact, dPdd, a);
}

ELASTIC_ROW_FUNCTIONS(, table, tt_contact_table)

/* Build the normalised curve, table, summary; scales already set. */
int tt_contact_md_build(struct tt_contact *c)
{
    tt_contact_summary *S = &c->sum;
    double pf, pmin, Pmin;
    curve_end(c->kind, c->lambda, &c->P0, &c->D0);
    c->vdw_k2 = (c->D0 - c->xi) * (c->D0 - c->xi) * c->P0;
    c->inv_d = 1.0 / c->d;
    c->F_per_d = c->F / c->d;
    find_extrema(c->kind, c->lambda, &pf, &pmin, &Pmin);
    if (c->kind == CURVE_DMT)
        pf = 0; /* Delta rises from A = 0, its own end */
    build_table(c, pf);
    if (c->kind == CURVE_DMT || !isfinite(pf))
        c->dmin = c->D0;
    c->s_in = sqrt(fmax(c->D0 - c->dmin, 0));
    c->vdw_cap = c->D0 + 0.5 * (c->xi - c->D0);
    double P, dP, A, Uin, Uvin;
    branch(c, c->D0, &P, &dP, &A, &Uin);
    vdw(c, c->D0, &P, &dP, &Uvin);
    c->Uc_shift = Uvin - Uin;
    S->adhesive = 1;
    S->lambda = c->kind == CURVE_MAUGIS ? c->lambda : c->kind == CURVE_DMT ? 0 : INFINITY;
    S->force_scale = c->F;
    S->depth_scale = c->d;
    S->radius_scale = c->a;
    S->xi0 = c->xi * c->d;
    S->P0 = c->P0;
    S->Delta0 = c->D0;
    S->pulloff_load = Pmin;
    if (isfinite(pmin)) {
        double Ax, Dx, Px, a_, d_, p_;
        curve_at(c->kind, c->lambda, pmin, &Ax, &Dx, &Px, &a_, &d_, &p_);
        S->pulloff_delta = Dx;
    } else {
        S->pulloff_delta = c->D0;
    }
    S->jumpout_delta = c->dmin;
    S->jumpout_load = c->seg[0].P[0];
    S->jumpin_delta = c->D0;
    branch(c, c->D0, &S->jumpin_load, &dP, &A, NULL);
    S->hysteresis = c->D0 - c->dmin > 1e-12;
    S->hamaker = 6 * fabs(c->P0) * c->F * pow(fabs(c->D0) + c->xi, 2) * c->d * c->d / c->p.R;
    /* the loop: the contact branch's energy from jump-in down to jump-out, and the van
     * der Waals branch's back up, -P0 (dmin - D0) (D0 - xi) / (dmin - xi), written so
     * that no potential of size P0 xi enters (a difference of two of them loses the
     * loop to rounding when xi is large: 1e-5 of it at xi = 1e6, all of it at 1e160) */
    double Uc;
    branch(c, c->dmin, &P, &dP, &A, &Uc);
    double dUv = -c->P0 * (c->dmin - c->D0) * ((c->D0 - c->xi) / (c->dmin - c->xi));
    S->loop_energy = S->hysteresis ? (Uc - Uin + dUv) * c->F * c->d : 0.0;
    return TT_OK;
}

double tt_contact_table_error(const tt_contact *c, size_t n)
{
    if (c->hertz || c->custom || n < 2)
        return 0; /* closed forms: nothing tabulated */
    double lo, hi, worst = 0;
    curve_range(c->kind, &lo, &hi);
    hi = c->kind == CURVE_MAUGIS ? 12 : 50; /* A up to about 1e5, then the exact Hertz tail */
    /* the stable branch begins past the least Delta (the fold, or the A -> 0 end):
     * before it the curve is the unstable branch, tabulated by no one */
    size_t first = 0;
    double Dleast = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double p = lo + (hi - lo) * (double)i / (double)(n - 1), A, D, P, dA, dD, dP;
        curve_at(c->kind, c->lambda, p, &A, &D, &P, &dA, &dD, &dP);
        if (D < Dleast) {
            Dleast = D;
            first = i + 1;
        }
    }
    for (size_t i = first; i < n; i++) {
        double p = lo + (hi - lo) * (double)i / (double)(n - 1), A, D, P, dA, dD, dP;
        curve_at(c->kind, c->lambda, p, &A, &D, &P, &dA, &dD, &dP);
        /* its first 1e-9 is the fold's own scale; past Dend the tail is exact Hertz */
        if (D < c->dmin + 1e-9 || D > c->Dend)
            continue;
        double Pt = tt_contact_load(c, D * c->d, 1, NULL, NULL) / c->F;
        double e = fabs(Pt - P) / fmax(1, fabs(P));
        if (e > worst)
            worst = e;
    }
    return worst;
}

int tt_contact_curve(const tt_contact *c, size_t n, double A_max, double *A, double *Delta,
                     double *P, int *stable)
{
    if (n < 2 || !(A_max > 0))
        return tt_error(TT_EINVAL, "contact curve: needs n >= 2 and A_max > 0");
    for (size_t i = 0; i < n; i++) {
        double Ai = A_max * (double)(i + 1) / (double)n;
        if (c->hertz || c->custom) {
            A[i] = Ai;
            Delta[i] = Ai * Ai;
            P[i] = Ai * Ai * Ai;
            stable[i] = 1;
            continue;
        }
        double p, Av, Dv, Pv, dA, dD, dP;
        if (c->kind == CURVE_MAUGIS) {
            /* A grows with p: bisect for the parameter of this A */
            double lo = -40, hi = 40;
            for (int it = 0; it < 200; it++) {
                double m = 0.5 * (lo + hi);
                curve_at(c->kind, c->lambda, m, &Av, &Dv, &Pv, &dA, &dD, &dP);
                if (Av < Ai)
                    lo = m;
                else
                    hi = m;
            }
            p = 0.5 * (lo + hi);
        } else {
            p = Ai;
        }
        curve_at(c->kind, c->lambda, p, &Av, &Dv, &Pv, &dA, &dD, &dP);
        A[i] = Av;
        Delta[i] = Dv;
        P[i] = Pv;
        stable[i] = dD > 0;
    }
    return TT_OK;
}
