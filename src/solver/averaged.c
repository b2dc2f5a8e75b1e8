/* The averaged preview tier's model: the force's cycle harmonics tabulated over tip
 * amplitude and closest penetration, and the slow flow of the deflection's first
 * harmonic (see include/tiptap/solver/averaged.h, docs/dynamics.md). */
#include "averaged_private.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"
#include "tiptap/util/clock.h"

#define B_MAX 1.5 /* of the free amplitude: the driven amplitude exceeds A0 only off resonance */

/* The cycle's means at (B, x) by quadrature: the contact piece from jump-in (approach,
 * theta < 0) to pull-off (retract), the flight from pull-off through the far point; a
 * law with state on its periodic cycle (q0: its state's guess and result, or NULL).
 * Returns 1 when that periodic state missed its tolerance. */
static int direct(const tt_averaged *a, double B, double x, int stuck, double *v, double *q0)
{
    double sum[C_HARM + 2 * TT_AVG_HMAX] = {0}, peak = -INFINITY;
    const double u = x - B;
    int missed = 0;
    if (B <= 0) {
        int in = stuck || x >= a->jin;
        double P = a->nlaw ? tt_averaged_arms_static(a, x, in)
                           : tt_contact_load(a->contact, x, in, NULL, NULL);
        memset(v, 0, (size_t)a->ncol * sizeof *v);
        v[C_MEAN] = -P;
        v[C_PEAK] = P;
        return 0;
    }
    if (a->nlaw && (stuck || x >= a->jin)) {
        missed = tt_averaged_arms_cycle(a, B, x, stuck, sum, &peak, q0);
    } else if (stuck) {
        tt_averaged_piece(a, u, B, -M_PI, M_PI, 1, sum, &peak);
    } else if (x < a->jin) {
        tt_averaged_piece(a, u, B, -M_PI, 0, 0, sum, &peak);
        tt_averaged_piece(a, u, B, 0, M_PI, 0, sum, &peak);
    } else {
        double ca = fmax(-1, fmin(1, (a->jin - u) / B)), cr = fmax(-1, fmin(1, (a->jout - u) / B));
        double ta = -acos(ca), tr = acos(cr);
        tt_averaged_piece(a, u, B, ta, tr, 1, sum, &peak);
        tt_averaged_piece(a, u, B, tr, M_PI, 0, sum, &peak);
        tt_averaged_piece(a, u, B, -M_PI, ta, 0, sum, &peak);
        /* the deepest point: the load's peak without damping */
        double P0 = tt_contact_load(a->contact, x, 1, NULL, NULL);
        if (P0 > peak)
            peak = P0;
    }
    for (int i = 0; i < a->ncol; i++)
        v[i] = sum[i] / M_PI;
    v[C_MEAN] = sum[C_MEAN] / (2 * M_PI);
    v[C_PEAK] = peak;
    return missed;
}

/* The harmonics h >= 2 of the force move the tip's closest approach (theta = 0) by
 * sum_h Re[(gc_h - i gs_h) / (k - m h^2 w^2 + i c h w)] (each far from resonance,
 * quasi-steady): the force at theta contributes F(theta) kern(theta) d theta / pi. A
 * short contact's harmonics fall off slowly, and the first harmonic's motion alone
 * misses this cusp of the true motion (on the standard scene over a stiff material,
 * 0.02 nm of height). */
static void kernel(tt_averaged *a)
{
    const tt_cantilever *c = &a->c;
    for (int i = 0; i <= NK; i++) {
        double th = -M_PI + 2 * M_PI * i / NK, k = 0;
        for (int h = 2; h <= HK; h++) {
            double w = h * c->wd, re = c->k - c->m * w * w, im = c->c * w, n = re * re + im * im;
            /* Re[(cos - i sin)(re - i im)] / n */
            k += (cos(h * th) * re - sin(h * th) * im) / n;
        }
        a->kern[i] = k;
    }
}

double tt_averaged_build_seconds(const tt_averaged *a) { return a ? a->seconds : 0; }

long tt_averaged_build_misses(const tt_averaged *a) { return a ? a->unconverged : 0; }

/* The penetration of node j, and the node coordinate of a penetration. */
static double node_x(const tt_averaged *a, int j)
{
    double xi = (double)(j - NXH) / NXH;
    return a->jin + a->span * xi * fabs(xi);
}

int tt_averaged_alloc(tt_averaged **out, const tt_cantilever *c, const tt_contact *contact,
                      double Qi, int harmonics)
{
    *out = NULL;
    if (harmonics < 1 || harmonics > TT_AVG_HMAX)
        return tt_error(TT_EINVAL, "averaged tier: %d harmonics (1 to %d)", harmonics, TT_AVG_HMAX);
    double t0 = tt_clock(TT_CLOCK_THREAD);
    tt_averaged *a = calloc(1, sizeof *a);
    if (!a)
        return tt_error_nomem("the averaged tier's table");
    a->c = *c;
    a->contact = contact;
    a->ci = Qi > 0 ? c->m * c->w0 / Qi : 0;
    a->law = tt_contact_law_of(contact);
    a->force = a->law->force;
    a->nlaw = (int)a->law->state_size;
    a->H = harmonics;
    a->ncol = C_HARM + 2 * (harmonics - 1);
    a->jin = tt_contact_jumpin(contact);
    a->jout = tt_contact_jumpout(contact);
    a->db = B_MAX * c->A0 / (NB - 1);
    a->span = c->A0;
    tt_averaged_gauss_legendre(NQ, a->gx, a->gw);
    kernel(a);
    int rc = a->nlaw ? tt_averaged_arms_setup(a) : TT_OK;
    if (rc) {
        free(a);
        return rc;
    }
    a->t = malloc((size_t)NB * NX * (size_t)a->ncol * sizeof *a->t);
    if (!a->t) {
        free(a);
        return tt_error_nomem("the averaged tier's table");
    }
    for (int i = 0; i < NB; i++) {
        double q0[AVG_NL] = {0}; /* each node's periodic state the next one's guess */
        for (int j = 0; j < NX; j++)
            a->unconverged += direct(a, i * a->db, node_x(a, j), 0,
                                     a->t + ((size_t)i * NX + (size_t)j) * (size_t)a->ncol, q0);
    }
    a->seconds = tt_clock(TT_CLOCK_THREAD) - t0;
    *out = a;
    return TT_OK;
}

void tt_averaged_free(tt_averaged *a)
{
    if (!a)
        return;
    free(a->t);
    free(a);
}

/* Catmull-Rom weights of a cell at t in [0, 1] and their derivatives. */
static void cr_weights(double t, double *w, double *d)
{
    double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t + 2 * t2 - t3);
    w[1] = 0.5 * (2 - 5 * t2 + 3 * t3);
    w[2] = 0.5 * (t + 4 * t2 - 3 * t3);
    w[3] = 0.5 * (-t2 + t3);
    d[0] = 0.5 * (-1 + 4 * t - 3 * t2);
    d[1] = 0.5 * (-10 * t + 9 * t2);
    d[2] = 0.5 * (1 + 8 * t - 9 * t2);
    d[3] = 0.5 * (-2 * t + 3 * t2);
}

/* A cell's index and position in it, clamped to the table. */
static int cell(double u, int n, double *t)
{
    int i = (int)floor(u);
    if (i < 0) {
        i = 0;
        u = 0;
    }
    if (i > n - 2) {
        i = n - 2;
        u = n - 1;
    }
    *t = u - i;
    return i;
}

/* The force's harmonics, mean, peak and shift from one row of the table's columns (a
 * looked-up or a directly integrated one). */
static void from_columns(const tt_averaged *a, const double *v, tt_averaged_force *f)
{
    for (int h = 0; h < a->H; h++) {
        f->gc[h] = v[h ? C_HARM + 2 * (h - 1) : C_GC];
        f->gs[h] = v[h ? C_HARM + 2 * (h - 1) + 1 : C_GS];
    }
    f->mean = v[C_MEAN];
    f->peak = v[C_PEAK];
    f->shift = v[C_SHIFT];
}

/* The 4 x 4 nodes' weighted sums of a cell: the columns (v) and the first three's
 * derivatives along B (vb) and x (vx). Inline with nc a constant where the table has
 * the fundamental alone (nc 5, the common case: the compiler then unrolls the columns),
 * the same sums in the same order either way. */
static inline __attribute__((always_inline)) void lookup_sums(const tt_averaged *a, int nc, int ib,
                                                              int ix, const double *wb,
                                                              const double *db, const double *wx,
                                                              const double *dx, double *v,
                                                              double *vb, double *vx)
{
    for (int p = 0; p < 4; p++) {
        int i = ib - 1 + p;
        i = i < 0 ? 0 : i > NB - 1 ? NB - 1 : i;
        for (int q = 0; q < 4; q++) {
            int j = ix - 1 + q;
            j = j < 0 ? 0 : j > NX - 1 ? NX - 1 : j;
            const double *e = a->t + ((size_t)i * NX + (size_t)j) * (size_t)nc;
            double w = wb[p] * wx[q], wdb = db[p] * wx[q], wdx = wb[p] * dx[q];
            for (int k = 0; k < nc; k++)
                v[k] += w * e[k];
            for (int k = 0; k < 3; k++) {
                vb[k] += wdb * e[k];
                vx[k] += wdx * e[k];
            }
        }
    }
}

static void lookup(const tt_averaged *a, double B, double x, tt_averaged_force *f)
{
    double ub = B / a->db, r = (x - a->jin) / a->span;
    double xi = copysign(sqrt(fabs(r)), r);
    f->outside = ub > NB - 1 || xi > 1;
    double tb, tx;
    int ib = cell(ub, NB, &tb), ix = cell(xi * NXH + NXH, NX, &tx);
    double wb[4], db[4], wx[4], dx[4];
    cr_weights(tb, wb, db);
    cr_weights(tx, wx, dx);
    double v[C_HARM + 2 * TT_AVG_HMAX] = {0}, vb[3] = {0}, vx[3] = {0};
    if (a->ncol == C_HARM)
        lookup_sums(a, C_HARM, ib, ix, wb, db, wx, dx, v, vb, vx);
    else
        lookup_sums(a, a->ncol, ib, ix, wb, db, wx, dx, v, vb, vx);
    /* d xi / dx, finite at jump-in: the contact's onset there is a square root in x,
     * which the node spacing (quadratic in xi) resolves */
    double dxi = NXH / (2 * a->span * fmax(fabs(xi), 0.5 / NXH));
    for (int k = 0; k < 3; k++) {
        f->d_b[k] = vb[k] / a->db;
        f->d_x[k] = vx[k] * dxi;
    }
    from_columns(a, v, f);
}

/* Direct quadrature with central differences for the derivatives (the stuck branch,
 * which the table does not hold, and checks). */
static void direct_force(const tt_averaged *a, double B, double x, int stuck, tt_averaged_force *f)
{
    double v[C_HARM + 2 * TT_AVG_HMAX], p[C_HARM + 2 * TT_AVG_HMAX], m[C_HARM + 2 * TT_AVG_HMAX];
    double q[AVG_NL] = {0}, g[AVG_NL]; /* the periodic state at (B, x): the others' guess */
    direct(a, B, x, stuck, v, q);
    const double e = 1e-4 * a->c.A0;
    memcpy(g, q, sizeof g);
    direct(a, B + e, x, stuck, p, g);
    memcpy(g, q, sizeof g);
    direct(a, fmax(B - e, 0), x, stuck, m, g);
    for (int k = 0; k < 3; k++)
        f->d_b[k] = (p[k] - m[k]) / (B + e - fmax(B - e, 0));
    memcpy(g, q, sizeof g);
    direct(a, B, x + e, stuck, p, g);
    memcpy(g, q, sizeof g);
    direct(a, B, x - e, stuck, m, g);
    for (int k = 0; k < 3; k++)
        f->d_x[k] = (p[k] - m[k]) / (2 * e);
    from_columns(a, v, f);
    f->outside = 0;
}

void tt_averaged_force_at(const tt_averaged *a, double B, double x, int stuck, int use_direct,
                          tt_averaged_force *f)
{
    if (stuck || use_direct) {
        direct_force(a, B, x, stuck, f);
        return;
    }
    if (x < a->jin - a->span) { /* the far van der Waals force, under 1e-6 k A0: none */
        memset(f, 0, sizeof *f);
        f->peak = tt_contact_load(a->contact, x, 0, NULL, NULL);
        return;
    }
    lookup(a, B, x, f);
    if (f->outside) { /* past the table (a tip pressed into a wall): its forces still */
        direct_force(a, B, x, 0, f);
        f->outside = 1;
    }
}

double tt_averaged_table_error(const tt_averaged *a)
{
    double worst = 0, scale = a->c.k * a->c.A0;
    for (int i = NB / 6; i < (NB - 1) * 2 / 3; i += 3)
        for (int j = NXH; j < NX - 1; j += 2) {
            double B = (i + 0.5) * a->db, x = 0.5 * (node_x(a, j) + node_x(a, j + 1));
            if (x > a->jin + 5e-9)
                break;
            tt_averaged_force t, d;
            lookup(a, B, x, &t);
            direct_force(a, B, x, 0, &d);
            double e = fmax(fabs(t.gc[0] - d.gc[0]), fmax(fabs(t.gs[0] - d.gs[0]), fabs(t.mean - d.mean)));
            if (e > worst)
                worst = e;
        }
    return worst / scale;
}

void tt_averaged_state_free(const tt_cantilever *c, tt_averaged_state *st)
{
    st->X = c->A0 * cos(c->phi0);
    st->Y = c->A0 * sin(c->phi0);
    st->m0 = 0;
    st->stuck = 0;
}

/* The slow flow's right-hand side at the state, its Jacobian in (X, Y), and what the
 * step reports of the force there. */
typedef struct {
    double f[2], J[2][2];
    double B, cp, sp, x, m0;
    int bad; /* forces beyond the averaging's premise: the model is wrong here */
    tt_averaged_force F;
} slow;

/* The mean deflection, quasi-static: one Newton step of k m0 = mean(B, m0 + B - s)
 * from the last, the force's values (looked up at the last m0, in o->F) carried to
 * it and to the higher harmonics' shift of the closest approach along their
 * derivatives. Returns d x / d B through m0. */
static double mean_deflection(const tt_averaged *a, const tt_averaged_state *st, double x0,
                              slow *o)
{
    const double k = a->c.k, B = o->B;
    tt_averaged_force *F = &o->F;
    double gx = fmin(F->d_x[2], 0.5 * k);
    /* Averaging takes the tip-sample force as a perturbation of the cantilever's: where
     * its mean would bend the lever by a tenth of A0, or its harmonics move the closest
     * approach by a tenth of B, the premise fails (a soft lever on a stiff sample, a
     * tip captured by adhesion); the shift and the mean deflection's change per step
     * are then bounded (the state stays finite) and the step is marked. */
    const double lim = 0.1 * a->c.A0;
    o->bad = !(fabs(F->mean) <= lim * k) || !(fabs(F->shift) <= 0.1 * B);
    if (!(fabs(F->shift) <= 0.1 * B))
        F->shift = F->shift > 0 ? 0.1 * B : -0.1 * B;
    double m0 = (F->mean - gx * (st->m0 - F->shift)) / (k - gx);
    if (!(fabs(m0 - st->m0) <= lim))
        m0 = m0 > st->m0 ? st->m0 + lim : st->m0 - lim;
    /* and the closest approach moved by the higher harmonics' cusp */
    double dx = m0 - st->m0 + F->shift;
    F->gc[0] += F->d_x[0] * dx;
    F->gs[0] += F->d_x[1] * dx;
    F->mean += F->d_x[2] * dx;
    o->m0 = m0;
    o->x = x0 + dx;
    if (o->x >= a->jin && !a->nlaw) /* the peak load moves with the deepest point */
        F->peak = fmax(F->peak, tt_contact_load(a->contact, o->x, 1, NULL, NULL));
    return (1 + F->d_b[2] / k) / (1 - gx / k);
}

static void slow_eval(const tt_averaged *a, const tt_averaged_state *st, double s, slow *o)
{
    const tt_cantilever *c = &a->c;
    const double k = c->k, w = c->wd, M = 2 * c->m * w, kap = k - c->m * w * w, cw = c->c * w;
    const double ad = c->drive == TT_DRIVE_BASE ? c->a_d : 0;
    const double fdrv = c->drive == TT_DRIVE_BASE ? c->m * w * w * c->a_d : c->F0;
    /* the tip's first harmonic: the deflection's plus the base's */
    double Xd = st->X + ad, Yd = st->Y, B = hypot(Xd, Yd);
    double Bs = fmax(B, 1e-9 * c->A0);
    o->cp = B > 0 ? Xd / B : 1;
    o->sp = B > 0 ? Yd / B : 0;
    o->B = B;
    double x0 = st->m0 + B - s;
    tt_averaged_force *F = &o->F;
    tt_averaged_force_at(a, B, x0, st->stuck, 0, F);
    double dxdb = mean_deflection(a, st, x0, o);
    /* the force in the drive's frame, (Fx, Fy) = (Gc, Gs) turned by psi, and its
     * derivatives in (X, Y) through B (at fixed psi) and psi (at fixed B) */
    double Gc = F->gc[0], Gs = F->gs[0];
    double Gcb = F->d_b[0] + F->d_x[0] * dxdb, Gsb = F->d_b[1] + F->d_x[1] * dxdb;
    double cp = o->cp, sp = o->sp;
    double Fx = Gc * cp - Gs * sp, Fy = Gc * sp + Gs * cp;
    double Dr = Gcb * cp - Gsb * sp, Di = Gcb * sp + Gsb * cp;
    double FxX = cp * Dr + sp * Fy / Bs, FyX = cp * Di - sp * Fx / Bs;
    double FxY = sp * Dr - cp * Fy / Bs, FyY = sp * Di + cp * Fx / Bs;
    o->f[0] = (kap * st->Y - cw * st->X - Fy) / M;
    o->f[1] = (fdrv - kap * st->X - cw * st->Y + Fx) / M;
    o->J[0][0] = (-cw - FyX) / M;
    o->J[0][1] = (kap - FyY) / M;
    o->J[1][0] = (-kap + FxX) / M;
    o->J[1][1] = (-cw + FxY) / M;
}

/* The deflection's harmonic h >= 2: the force's, through the cantilever's response
 * there (far from resonance, so quasi-steady). */
static void harmonic(const tt_averaged *a, const slow *o, int h, double *X, double *Y)
{
    const tt_cantilever *c = &a->c;
    double gc = o->F.gc[h - 1], gs = o->F.gs[h - 1];
    /* rotate by h psi: the table's phase is the tip's own */
    double ch = 1, sh = 0;
    for (int i = 0; i < h; i++) {
        double c2 = ch * o->cp - sh * o->sp;
        sh = sh * o->cp + ch * o->sp;
        ch = c2;
    }
    double Fx = gc * ch - gs * sh, Fy = gc * sh + gs * ch;
    double w = h * c->wd, re = c->k - c->m * w * w, im = c->c * w, n = re * re + im * im;
    /* y = Re[(Fx - i Fy) e^{i h w t} / (re + i im)] = X cos + Y sin */
    double yr = (Fx * re - Fy * im) / n, yi = (-Fy * re - Fx * im) / n;
    *X = yr;
    *Y = -yi;
}

/* One linearly implicit step: (I - gamma h J) dx = h f; gamma 1/2 (second order, A-
 * stable) or 1 (first order, L-stable: the halved steps of an impact). */
static void one_step(const tt_averaged *a, tt_averaged_state *st, double s, double h, double gamma,
                     double cap, const double *kick, tt_averaged_out *o)
{
    slow e;
    /* the branch: a touching tip whose far point stays past pull-off cannot leave */
    double B = hypot(st->X + (a->c.drive == TT_DRIVE_BASE ? a->c.a_d : 0), st->Y);
    double x = st->m0 + B - s;
    if (!st->stuck && x >= a->jin && x - 2 * B > a->jout)
        st->stuck = 1;
    else if (st->stuck && x - 2 * B <= a->jout)
        st->stuck = 0;
    slow_eval(a, st, s, &e);
    double g = gamma * h;
    double m00 = 1 - g * e.J[0][0], m01 = -g * e.J[0][1], m10 = -g * e.J[1][0], m11 = 1 - g * e.J[1][1];
    double det = m00 * m11 - m01 * m10;
    double r0 = h * e.f[0], r1 = h * e.f[1];
    double dX = (m11 * r0 - m01 * r1) / det, dY = (m00 * r1 - m10 * r0) / det;
    /* the last halving of an impact moves the state by at most cap of A0 */
    double big = fmax(fabs(dX), fabs(dY)) / a->c.A0;
    if (!(big <= cap)) {
        double r = big < INFINITY ? cap / big : 0;
        dX = r > 0 ? dX * r : 0;
        dY = r > 0 ? dY * r : 0;
        e.bad = 1;
    }
    o->change = fmax(fabs(dX), fabs(dY)) / a->c.A0; /* the flow's own move, not the noise's */
    if (!(o->change < INFINITY))
        o->change = INFINITY;
    if (kick) { /* through the same solve: the linearised flow's stationary covariance exactly */
        dX += (m11 * kick[0] - m01 * kick[1]) / det;
        dY += (m00 * kick[1] - m10 * kick[0]) / det;
    }
    o->comp[0] = 0.5 * (st->m0 + e.m0);
    o->comp[1] = st->X + 0.5 * dX;
    o->comp[2] = st->Y + 0.5 * dY;
    for (int hh = 2; hh <= a->H; hh++)
        harmonic(a, &e, hh, &o->comp[2 * hh - 1], &o->comp[2 * hh]);
    st->X += dX;
    st->Y += dY;
    /* nor does the amplitude pass twice the free one, which no drive near resonance
     * reaches: only a model gone wrong does */
    double Bn = hypot(st->X, st->Y);
    if (Bn > 2 * a->c.A0) {
        st->X *= 2 * a->c.A0 / Bn;
        st->Y *= 2 * a->c.A0 / Bn;
        e.bad = 1;
    }
    st->m0 = e.m0;
    o->peak = e.F.peak;
    o->indent = e.x;
    o->ets = M_PI * e.B * e.F.gs[0];
    o->outside = e.F.outside;
    o->collapsed = st->stuck || e.B < 0.25 * a->c.A0 || e.bad;
}

/* A step whose linearisation moved the state by more than a tenth of the free amplitude
 * (an impact: the sample rose by more than the oscillation can take in a cycle) is
 * taken again as two halves, L-stable, down to DEPTH halvings: the model is wrong
 * there (collapse), but its state stays bounded for the feedback to recover. */
#define BIG 0.1
#define DEPTH 8
static void advance(const tt_averaged *a, tt_averaged_state *st, double s, double h, int depth,
                    const double *kick, tt_averaged_out *o)
{
    tt_averaged_state start = *st;
    one_step(a, st, s, h, depth ? 1 : 0.5, depth >= DEPTH ? BIG : INFINITY, kick, o);
    if (o->change <= BIG || depth >= DEPTH)
        return;
    *st = start;
    tt_averaged_out p, q;
    /* the impulse split evenly: its sum kept (the model is wrong here anyway) */
    const double half[2] = {kick ? 0.5 * kick[0] : 0, kick ? 0.5 * kick[1] : 0};
    advance(a, st, s, 0.5 * h, depth + 1, kick ? half : NULL, &p);
    advance(a, st, s, 0.5 * h, depth + 1, kick ? half : NULL, &q);
    for (int i = 0; i < 1 + 2 * a->H; i++)
        o->comp[i] = 0.5 * (p.comp[i] + q.comp[i]);
    o->peak = fmax(p.peak, q.peak);
    o->indent = fmax(p.indent, q.indent);
    o->ets = 0.5 * (p.ets + q.ets);
    o->collapsed = 1; /* an impact the averaged model cannot follow */
    o->outside = p.outside | q.outside;
    o->change = BIG; /* the caller's measure: the step was resolved */
}

void tt_averaged_step(const tt_averaged *a, tt_averaged_state *st, double s, double h,
                      tt_averaged_out *o)
{
    advance(a, st, s, h, 0, NULL, o);
}

void tt_averaged_step_noisy(const tt_averaged *a, tt_averaged_state *st, double s, double h,
                            const double kick[2], tt_averaged_out *o)
{
    advance(a, st, s, h, 0, kick, o);
}

double tt_averaged_thermal_density(const tt_cantilever *c, double temperature)
{
    /* the force's 2 c kB T projected by -sin(w t) / (m w) and cos(w t) / (m w): a half each */
    return temperature > 0 ? sqrt(c->c * TT_BOLTZMANN * temperature) / (c->m * c->wd) : 0;
}
