/* The averaged tier's cycle for a force law with internal state (a sample's relaxation
 * arms, src/physics/contact_sls.c). Along the tip's harmonic motion delta(theta) = x - B +
 * B cos theta the law's state settles to a periodic cycle: out of contact it relaxes by
 * exp(A_out theta) (as the free flight advances it), in contact it follows
 * dq/dtheta = A_in q + b(delta) by exponential steps (exact for the relaxation, the
 * forcing b quadratic over a sub-step). The periodic state is solved for directly, by
 * Newton's method on the cycle map, whose derivative is the product of the steps'
 * exponentials (the state's rate is continuous where the contact switches, the load
 * being 0 there), so a relaxation time of many periods costs no more than a short one;
 * the force's harmonics are then taken on that cycle (docs/dynamics.md, Averaged). */
#include "averaged_private.h"

#include <string.h>

#include "tiptap/util/error.h"
#include "shooting_linalg.h"
#include "util/root.h"

enum {
    NS = 64,         /* exponential sub-steps over the contact's longest possible span */
    MB = 4 * AVG_NL, /* the block matrix of a sub-step's exponential and phi functions */
    NEWTON_MAX = 40
};
#define PER_TOL 1e-10 /* the cycle's state returns within this of its largest component */

/* y = M x (n x n, row-major, leading dimension ld). */
static void mv(int n, int ld, const double *M, const double *x, double *y)
{
    for (int i = 0; i < n; i++) {
        double acc = 0;
        for (int j = 0; j < n; j++)
            acc += M[i * ld + j] * x[j];
        y[i] = acc;
    }
}

/* Solve M z = r over the n components idx of the state (z into r); 0 if singular. */
static int solve(int n, const int *idx, const double *J, int nj, double *r, int minus_identity)
{
    double M[AVG_NL * AVG_NL], z[AVG_NL];
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            M[i * n + j] = J[idx[i] * nj + idx[j]] - (minus_identity && i == j);
    if (!tt_shoot_solve(n, M, r, z, 1))
        return 0;
    memcpy(r, z, sizeof(double) * (size_t)n);
    return 1;
}

/* exp(A_out dth), the flight's exact step of the state. */
static void flight_exp(const tt_averaged *a, double dth, double *E)
{
    const int n = a->nlaw;
    double A[AVG_NL * AVG_NL] = {0};
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            A[i * n + j] = a->Aout[i][j];
    tt_shoot_expm(n, A, dth, E);
}

/* A contact sub-step of h radians: exp(A_in h) and h phi_k(A_in h), k = 1, 2, 3, from
 * the exponential of [[A_in h, I, 0, 0], [0, 0, I, 0], [0, 0, 0, I], [0, 0, 0, 0]]. */
typedef struct {
    double E[AVG_NL * AVG_NL], F[3][AVG_NL * AVG_NL];
} substep;

static void substep_of(const tt_averaged *a, double h, substep *s)
{
    const int n = a->nlaw, m = 4 * n;
    double G[MB * MB] = {0}, X[MB * MB];
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++)
            G[i * m + j] = a->Ain[i][j] * h;
        for (int b = 0; b < 3; b++)
            G[(b * n + i) * m + (b + 1) * n + i] = 1;
    }
    tt_shoot_expm(m, G, 1.0, X);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            s->E[i * n + j] = X[i * m + j];
            for (int b = 0; b < 3; b++)
                s->F[b][i * n + j] = h * X[i * m + (b + 1) * n + j];
        }
}

/* The tip's motion and the law's forcing in contact, b = rate at a rested state, per
 * radian. */
typedef struct {
    const tt_averaged *a;
    double B, u;
} motion;

static double depth(const motion *m, double th) { return m->u + m->B * cos(th); }

static void forcing(const motion *m, double th, double *b)
{
    const tt_averaged *a = m->a;
    double q[AVG_NL] = {0}, p;
    a->law->rate(a->contact, depth(m, th), -m->B * a->c.wd * sin(th), 1, q, b, &p);
    for (int i = 0; i < a->nlaw; i++)
        b[i] /= a->c.wd;
}

/* One cycle from the state q0 at the far point: the contact's sub-steps (angles, states
 * and their rates at the ends), entry and exit, the state at the end and the map's
 * derivative. */
typedef struct {
    double ta, tr;
    int k; /* sub-steps in contact, the last one ending at tr */
    double th[NS + 1], q[NS + 1][AVG_NL], dq[NS + 1][AVG_NL];
    double q1[AVG_NL], J[AVG_NL * AVG_NL];
} cycle;

/* The state at th in sub-step j (1..k) by cubic Hermite interpolation of its ends. */
static void hermite(const tt_averaged *a, const cycle *y, int j, double th, double *q)
{
    double h = y->th[j] - y->th[j - 1], s = h > 0 ? (th - y->th[j - 1]) / h : 0;
    double s2 = s * s, s3 = s2 * s;
    double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    for (int i = 0; i < a->nlaw; i++)
        q[i] = h00 * y->q[j - 1][i] + h10 * h * y->dq[j - 1][i] + h01 * y->q[j][i] +
               h11 * h * y->dq[j][i];
}

typedef struct {
    const motion *m;
    const cycle *y;
    const double *q0;
    int j;
} root_data;

/* Out of contact: the penetration past the surface, less jump-in, with the state
 * relaxed from the far point. */
static double entry_gap(double th, void *data)
{
    const root_data *r = data;
    const tt_averaged *a = r->m->a;
    double E[AVG_NL * AVG_NL], q[AVG_NL];
    flight_exp(a, th + M_PI, E);
    mv(a->nlaw, a->nlaw, E, r->q0, q);
    return depth(r->m, th) - a->law->surface(a->contact, q) - a->jin;
}

/* In contact: the penetration past the surface the state holds, less pull-off. */
static double exit_gap(double th, void *data)
{
    const root_data *r = data;
    const tt_averaged *a = r->m->a;
    double q[AVG_NL];
    hermite(a, r->y, r->j, th, q);
    return depth(r->m, th) - a->law->surface(a->contact, q) - a->jout;
}

/* The sub-step s from angle t0 at state q (its forcing b0) to t1, into q1, b1, dq1: the
 * forcing quadratic through t0, the middle and t1, q1 = E q + h (phi1 c0 + phi2 c1 +
 * 2 phi3 c2) for b = c0 + c1 r + c2 r^2 over the step's fraction r. */
static void contact_step(const motion *m, const substep *s, double t0, double t1, const double *q,
                         const double *b0, double *q1, double *b1, double *dq1)
{
    const tt_averaged *a = m->a;
    const int n = a->nlaw;
    double bm[AVG_NL], c[3][AVG_NL], e[AVG_NL];
    forcing(m, 0.5 * (t0 + t1), bm);
    forcing(m, t1, b1);
    for (int i = 0; i < n; i++) {
        c[0][i] = b0[i];
        c[1][i] = -3 * b0[i] + 4 * bm[i] - b1[i];
        c[2][i] = 2 * (2 * b0[i] - 4 * bm[i] + 2 * b1[i]); /* with phi3's factor 2 */
    }
    mv(n, n, s->E, q, q1);
    for (int b = 0; b < 3; b++) {
        mv(n, n, s->F[b], c[b], e);
        for (int i = 0; i < n; i++)
            q1[i] += e[i];
    }
    for (int i = 0; i < n; i++) {
        double acc = b1[i];
        for (int j = 0; j < n; j++)
            acc += a->Ain[i][j] * q1[j];
        dq1[i] = acc;
    }
}

/* The contact from y->ta with state qa (map derivative Ja so far) to its exit; stuck:
 * in contact to the cycle's end. Returns the derivative's product into Ja. */
static void contact(const motion *m, cycle *y, const double *qa, int stuck, double *Ja)
{
    const tt_averaged *a = m->a;
    const int n = a->nlaw;
    double tmax = stuck ? M_PI : acos(fmax(-1, fmin(1, (a->jout - m->u) / m->B)));
    double h = (tmax - y->ta) / NS, b[AVG_NL], b1[AVG_NL];
    substep s;
    substep_of(a, h, &s);
    y->th[0] = y->ta;
    memcpy(y->q[0], qa, sizeof(double) * (size_t)n);
    forcing(m, y->ta, b);
    for (int i = 0; i < n; i++) {
        double acc = b[i];
        for (int j = 0; j < n; j++)
            acc += a->Ain[i][j] * qa[j];
        y->dq[0][i] = acc;
    }
    double gprev = depth(m, y->ta) - a->law->surface(a->contact, qa) - a->jout;
    double bprev[AVG_NL], Jprev[AVG_NL * AVG_NL];
    for (int k = 1; k <= NS; k++) {
        double t1 = k == NS ? tmax : y->ta + k * h;
        memcpy(bprev, b, sizeof bprev);
        memcpy(Jprev, Ja, sizeof Jprev);
        contact_step(m, &s, y->th[k - 1], t1, y->q[k - 1], b, y->q[k], b1, y->dq[k]);
        memcpy(b, b1, sizeof b);
        y->th[k] = t1;
        tt_shoot_matmul(n, s.E, Ja, Ja);
        y->k = k;
        double g = depth(m, t1) - a->law->surface(a->contact, y->q[k]) - a->jout;
        if (stuck || g > 0) {
            gprev = g;
            continue;
        }
        /* the exit in this sub-step: its root on the interpolated state, then the step
         * taken again to it exactly */
        root_data rd = {m, y, NULL, k};
        double lo = y->th[k - 1], glo = gprev;
        for (int p = 1; p < 8 && !(glo > 0); p++) { /* a graze that began on the threshold */
            lo = y->th[k - 1] + p * (t1 - y->th[k - 1]) / 8;
            glo = exit_gap(lo, &rd);
        }
        double tr = y->th[k - 1];
        if (glo > 0) {
            tt_root_bracket br = {lo, t1, glo, g};
            if (!tt_root_illinois(exit_gap, &rd, &br, 1e-14, 0, 60, &tr))
                tr = br.b;
        }
        double hp = tr - y->th[k - 1];
        substep_of(a, hp, &s);
        memcpy(Ja, Jprev, sizeof Jprev);
        contact_step(m, &s, y->th[k - 1], tr, y->q[k - 1], bprev, y->q[k], b1, y->dq[k]);
        tt_shoot_matmul(n, s.E, Ja, Ja);
        y->th[k] = tr;
        break;
    }
    y->tr = y->th[y->k];
}

/* The cycle from q0 at the far point (-pi) to the state y->q1 at pi. */
static void run_cycle(const motion *m, const double *q0, int stuck, cycle *y)
{
    const tt_averaged *a = m->a;
    const int n = a->nlaw;
    double E[AVG_NL * AVG_NL], qa[AVG_NL];
    y->k = 0;
    root_data rd = {m, y, q0, 0};
    double g0 = stuck ? 1 : entry_gap(-M_PI, &rd);
    if (g0 >= 0) {
        y->ta = -M_PI;
    } else {
        double gm = entry_gap(0, &rd);
        if (!(gm > 0)) { /* no contact: the flight all cycle */
            y->ta = y->tr = 0;
            flight_exp(a, 2 * M_PI, y->J);
            mv(n, n, y->J, q0, y->q1);
            return;
        }
        tt_root_bracket br = {-M_PI, 0, g0, gm};
        if (!tt_root_illinois(entry_gap, &rd, &br, 1e-14, 0, 80, &y->ta))
            y->ta = br.b;
    }
    flight_exp(a, y->ta + M_PI, y->J);
    mv(n, n, y->J, q0, qa);
    contact(m, y, qa, stuck, y->J);
    flight_exp(a, M_PI - y->tr, E);
    mv(n, n, E, y->q[y->k], y->q1);
    tt_shoot_matmul(n, E, y->J, y->J);
}

/* Newton's method on q -> cycle(q) - q over the moving components; 1 if it missed. */
static int periodic(const motion *m, double *q0, int stuck, cycle *y)
{
    const tt_averaged *a = m->a;
    const int n = a->nlaw;
    for (int it = 0; it < NEWTON_MAX; it++) {
        run_cycle(m, q0, stuck, y);
        double r[AVG_NL], big = 0, res = 0;
        int idx[AVG_NL], na = 0;
        for (int i = 0; i < n; i++) {
            big = fmax(big, fmax(fabs(q0[i]), fabs(y->q1[i])));
            res = fmax(res, fabs(y->q1[i] - q0[i]));
            if (a->active[i])
                idx[na++] = i;
        }
        if (res <= PER_TOL * big)
            return 0;
        for (int i = 0; i < na; i++)
            r[i] = q0[idx[i]] - y->q1[idx[i]];
        if (!solve(na, idx, y->J, n, r, 1))
            return 1;
        for (int i = 0; i < na; i++)
            q0[idx[i]] += r[i];
    }
    return 1;
}

int tt_averaged_arms_cycle(const tt_averaged *a, double B, double x, int stuck, double *sum,
                           double *peak, double *q0)
{
    motion m = {a, B, x - B};
    double rest[AVG_NL] = {0};
    double *q = q0 ? q0 : rest;
    cycle y;
    int missed = periodic(&m, q, stuck, &y);
    const double w = a->c.wd;
    if (y.k == 0) {
        tt_averaged_piece(a, m.u, B, -M_PI, 0, 0, sum, peak);
        tt_averaged_piece(a, m.u, B, 0, M_PI, 0, sum, peak);
        return missed;
    }
    tt_averaged_piece(a, m.u, B, -M_PI, y.ta, 0, sum, peak);
    tt_averaged_piece(a, m.u, B, y.tr, M_PI, 0, sum, peak);
    for (int j = 0; j <= y.k; j++) { /* the sub-steps' ends: the peak's nodes too */
        double th = y.th[j];
        tt_contact_forces f = a->force(a->contact, a->ci, depth(&m, th), -B * w * sin(th), 1, y.q[j]);
        *peak = fmax(*peak, f.conservative + f.dissipative);
    }
    for (int j = 1; j <= y.k; j++) {
        double half = 0.5 * (y.th[j] - y.th[j - 1]), mid = 0.5 * (y.th[j] + y.th[j - 1]);
        for (int g = 0; g < AVG_NG; g++) {
            double th = mid + half * a->sx[g], qs[AVG_NL], cs = cos(th), sn = sin(th);
            hermite(a, &y, j, th, qs);
            tt_contact_forces f = a->force(a->contact, a->ci, m.u + B * cs, -B * w * sn, 1, qs);
            double load = f.conservative + f.dissipative;
            *peak = fmax(*peak, load);
            tt_averaged_accumulate(a, th, cs, sn, half * a->sw[g], -load, sum);
        }
    }
    return missed;
}

double tt_averaged_arms_static(const tt_averaged *a, double x, int in)
{
    const int n = a->nlaw;
    double q[AVG_NL] = {0}, b[AVG_NL], A[AVG_NL * AVG_NL];
    int idx[AVG_NL], na = 0;
    if (in) { /* at rest: A_in q + b = 0 over the moving components */
        motion m = {a, 0, x};
        forcing(&m, 0, b);
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < n; j++)
                A[i * n + j] = a->Ain[i][j];
            if (a->active[i])
                idx[na++] = i;
        }
        double r[AVG_NL];
        for (int i = 0; i < na; i++)
            r[i] = -b[idx[i]];
        if (solve(na, idx, A, n, r, 0))
            for (int i = 0; i < na; i++)
                q[idx[i]] = r[i];
    }
    return a->force(a->contact, 0, x, 0, in, q).conservative;
}

/* The state's rate per radian on one branch as a matrix, read off the law's rate at unit
 * states: 0 unless it is linear in the state (affine in contact, with a forcing of the
 * penetration alone; none out of contact, where the surface rests at a rested state). */
static int rate_matrix(tt_averaged *a, int in, double A[AVG_NL][AVG_NL])
{
    const int n = a->nlaw;
    const double sc = a->c.A0 > 0 ? a->c.A0 : 1e-9, w = a->c.wd;
    for (int pass = 1; pass <= 2; pass++) {
        double d = in ? pass * sc : -pass * sc, q[AVG_NL] = {0}, r0[AVG_NL], r[AVG_NL], p;
        a->law->rate(a->contact, d, 0.0, in, q, r0, &p);
        if (!in)
            for (int i = 0; i < n; i++)
                if (r0[i] != 0)
                    return 0;
        for (int j = 0; j < n; j++) {
            for (int i = 0; i < n; i++)
                q[i] = i == j ? sc : 0.0;
            a->law->rate(a->contact, d, 0.0, in, q, r, &p);
            for (int i = 0; i < n; i++) {
                double v = (r[i] - r0[i]) / sc / w;
                if (pass == 1)
                    A[i][j] = v;
                else if (!(fabs(v - A[i][j]) <= 1e-12 * fabs(A[i][j]) + 1e-300))
                    return 0;
            }
        }
        for (int i = 0; i < n; i++)
            q[i] = sc * (i + 1);
        a->law->rate(a->contact, d, 0.0, in, q, r, &p);
        for (int i = 0; i < n; i++) {
            double s = r0[i];
            for (int j = 0; j < n; j++)
                s += A[i][j] * w * q[j];
            if (!(fabs(r[i] - s) <= 1e-12 * (fabs(r[i]) + fabs(s)) + 1e-300))
                return 0;
        }
    }
    return 1;
}

int tt_averaged_arms_setup(tt_averaged *a)
{
    const int n = a->nlaw;
    if (n > AVG_NL || !a->law->rate || !a->law->surface)
        return tt_error(TT_EINVAL,
                        "averaged tier: the contact law %s carries %d states (at most %d, with "
                        "a rate and a surface)",
                        a->law->name, n, AVG_NL);
    const double sc = a->c.A0 > 0 ? a->c.A0 : 1e-9;
    double q[AVG_NL];
    for (int i = 0; i < n; i++)
        q[i] = sc * (i + 1);
    if (!rate_matrix(a, 0, a->Aout) || !rate_matrix(a, 1, a->Ain) ||
        a->force(a->contact, 0, -sc, 0, 0, q).conservative !=
            a->force(a->contact, 0, -sc, 0, 0, NULL).conservative)
        return tt_error(TT_EINVAL,
                        "averaged tier: the contact law %s's state does not move linearly (its "
                        "cycle is solved as a linear one's)",
                        a->law->name);
    for (int i = 0; i < n; i++) {
        a->active[i] = 0;
        for (int j = 0; j < n; j++)
            a->active[i] |= a->Ain[i][j] != 0 || a->Aout[i][j] != 0;
    }
    tt_averaged_gauss_legendre(AVG_NG, a->sx, a->sw);
    /* a state that never moves from rest (infinite relaxation times) or never acts on
     * the force (arms of zero modulus) leaves the law elastic: its table is the
     * elastic one, of the force at the rested state */
    int moves = 0, acts = 0;
    double zero[AVG_NL] = {0};
    for (int i = 0; i < n; i++)
        moves |= a->active[i];
    for (int j = 0; j < n; j++) {
        double e[AVG_NL] = {0};
        e[j] = sc;
        acts |= a->force(a->contact, 0, sc, 0, 1, e).conservative !=
                    a->force(a->contact, 0, sc, 0, 1, zero).conservative ||
                a->law->surface(a->contact, e) != a->law->surface(a->contact, zero);
    }
    if (!moves || !acts)
        a->nlaw = 0;
    return TT_OK;
}
