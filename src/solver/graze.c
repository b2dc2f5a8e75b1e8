/* Grazing touches on the envelope tier (see include/tiptap/solver/graze.h). */
#include "tiptap/solver/graze.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "util/root.h"

enum {
    NP = TT_GRAZE_PROBES,
    HIST = 32,     /* touch cycles held */
    PAIR_MAX = 2 * (TT_SIM_DIM_MAX + 1), /* and the star: the deepest moved in each
                                          * state component and the sample, 2 (nx + 1) */
    NMIN = 8,      /* held (besides the star) before a fit is tried */
    NF_MAX = TT_SIM_DIM_MAX + 5, /* fit features: 1, the state's nx, s, the cubic in t_c */
    STAR = 5       /* the star's reach in the sample, in the touches' */
};

/* A fit of the touch branch: outputs = coef^T phi(inputs), phi the features scaled
 * about a centre; the ranges of the samples and the jump-in times of the cycles fitted. */
typedef struct {
    double centre[TT_SIM_DIM_MAX + 2], scale[TT_SIM_DIM_MAX + 2], smin, smax, tmin, tmax;
    double lo[TT_SIM_DIM_MAX], hi[TT_SIM_DIM_MAX]; /* and of the states they started from */
    double *coef; /* NF x no, by feature */
} fit_t;

typedef struct {
    double f[NF_MAX]; /* 1, then the inputs: the state (at the start), s (mid-cycle), t_c */
    double *out;      /* end state, then the m reduced observables */
} point;

struct tt_graze {
    int nx, nf, npair;   /* the state's components; fit features (nx + 5); star cycles */
    int m, no;           /* reduced observables; outputs nx + m */
    double T, L, V;      /* period, free amplitude, w A0 */
    double jumpin;       /* the material's jump-in penetration, m */
    double margin;       /* a reach within this of jump-in is too close to call, m */
    double reach;        /* the sample's reach of a fit, m */
    double *oscale;      /* the outputs' scales */
    double *otol;        /* and the least tolerance each is held to (in its scale) */
    double tau[NP];      /* probe times from the cycle's start, s */
    tt_sample buf[NP];
    point hist[HIST + PAIR_MAX];
    double *work;        /* the fit's Q and R */
    int nh, head, nstar;
    int fitted;          /* fit holds one; trial: the next one, until it proves good */
    fit_t fit, trial;
};

int tt_graze_alloc(tt_graze **out, const tt_sim *sim, int m, const double *scale,
                   const double *floor)
{
    *out = NULL;
    tt_graze *g = calloc(1, sizeof *g);
    if (!g)
        return tt_error_nomem("the envelope tier's grazing model");
    const tt_cantilever *c = tt_sim_cantilever(sim);
    g->nx = tt_sim_dim(sim);
    g->nf = g->nx + 5;
    g->npair = 2 * (g->nx + 1);
    g->m = m;
    g->no = g->nx + m;
    g->T = c->T;
    g->L = c->A0;
    g->V = c->wd * c->A0;
    /* fifty times the sim's event margin: no touch the model calls is one the
     * integration would miss, or the reverse */
    g->margin = 2e-6 * c->A0;
    g->reach = 1e-3 * c->A0;
    g->jumpin = NAN;
    const size_t nf = (size_t)g->nf, npts = HIST + PAIR_MAX;
    g->fit.coef = calloc(nf * (size_t)g->no, sizeof *g->fit.coef);
    g->trial.coef = calloc(nf * (size_t)g->no, sizeof *g->trial.coef);
    g->oscale = malloc(2 * (size_t)g->no * sizeof *g->oscale);
    g->otol = g->oscale ? g->oscale + g->no : NULL;
    g->work = malloc((npts * nf + nf * nf) * sizeof *g->work);
    int ok = g->fit.coef && g->trial.coef && g->oscale && g->work;
    for (int i = 0; i < g->no && ok; i++) {
        g->oscale[i] = i < g->nx ? (i % 2 ? g->V : g->L) : scale[i - g->nx];
        g->otol[i] = i < g->nx ? 0 : floor[i - g->nx];
    }
    for (int i = 0; i < HIST + g->npair && ok; i++)
        ok = (g->hist[i].out = malloc((size_t)g->no * sizeof *g->hist[i].out)) != NULL;
    if (!ok) {
        tt_graze_free(g);
        return tt_error_nomem("the envelope tier's grazing model");
    }
    *out = g;
    return TT_OK;
}

void tt_graze_free(tt_graze *g)
{
    if (!g)
        return;
    for (int i = 0; i < HIST + PAIR_MAX; i++)
        free(g->hist[i].out);
    free(g->fit.coef);
    free(g->trial.coef);
    free(g->oscale);
    free(g->work);
    free(g);
}

void tt_graze_reset(tt_graze *g, double jumpin)
{
    g->jumpin = jumpin;
    g->nh = g->head = g->nstar = 0;
    g->fitted = 0;
}

/* The closest approach among n gaps at times t: the greatest, refined by the parabola
 * through it and its neighbours (i0 - 1, i0 + 1 within [0, n)); -1 at an end. */
static int closest(const double *gap, const double *t, int n, double *tm, double *gm)
{
    int k = 0;
    for (int i = 1; i < n; i++)
        if (gap[i] > gap[k])
            k = i;
    if (k == 0 || k == n - 1)
        return -1;
    const double a = gap[k - 1], b = gap[k], c = gap[k + 1], den = a - 2 * b + c;
    const double off = den < 0 ? 0.5 * (a - c) / den : 0; /* in steps, within +-1/2 */
    *tm = t[k] + off * 0.5 * (t[k + 1] - t[k - 1]);
    *gm = b - 0.25 * (a - c) * off;
    return k;
}

int tt_graze_aim(tt_graze *g, tt_sim *sim, const tt_sample *smp, int n)
{
    tt_graze_disarm(g, sim);
    double gap[3], t[3], tm, gm;
    int k = 0;
    for (int q = 1; q < n; q++)
        if (smp[q].d - smp[q].s > smp[k].d - smp[k].s)
            k = q;
    if (k == 0 || k == n - 1)
        return 0;
    for (int i = 0; i < 3; i++) {
        gap[i] = smp[k - 1 + i].d - smp[k - 1 + i].s;
        t[i] = g->T * (k - 1 + i) / n;
    }
    if (closest(gap, t, 3, &tm, &gm) < 0)
        return 0;
    /* the touch starts before the closest approach, by sqrt(2 e / a) for a reach e past
     * jump-in (a = w^2 A): 0.06 T covers reaches up to a tenth of the amplitude */
    const double t0 = tm - 0.06 * g->T, t1 = tm + 0.015 * g->T;
    if (t0 <= 0 || t1 >= g->T)
        return 0;
    for (int i = 0; i < NP; i++)
        g->tau[i] = t0 + (t1 - t0) * i / (NP - 1);
    tt_sim_set_probes(sim, NP, g->tau, g->buf);
    return 1;
}

double tt_graze_probe_time(const tt_graze *g, int i) { return g->tau[i]; }

void tt_graze_disarm(tt_graze *g, tt_sim *sim)
{
    (void)g;
    tt_sim_set_probes(sim, 0, NULL, NULL);
}

/* The cubic through the gaps at the equally spaced probes i0 .. i0 + 3 at time t,
 * minus jump-in (Lagrange's weights in the probe index u). */
static double cubic(const tt_graze *g, const double *gap, int i0, double t)
{
    const double u = (t - g->tau[i0]) / (g->tau[1] - g->tau[0]);
    const double a = u * (u - 1), b = (u - 2) * (u - 3);
    const double *y = gap + i0;
    return -(u - 1) * b / 6 * y[0] + u * b / 2 * y[1] - a * (u - 3) / 2 * y[2] +
           a * (u - 2) / 6 * y[3] - g->jumpin;
}

typedef struct {
    const tt_graze *g;
    const double *gap;
    int i0;
} crossing_fn;

static double crossing_value(double t, void *data)
{
    const crossing_fn *c = data;
    return cubic(c->g, c->gap, c->i0, t);
}

/* Where the path, rising from probe k - 1 (below jump-in) to time b (at or past it,
 * gb), meets jump-in (Illinois on the cubic through the probes about k), to 1e-10 of
 * the period: the touch branch moves by about 0.1 A0 per period of t_c, so this is
 * 1e-11 of A0. */
static double crossing(const tt_graze *g, const double *gap, int k, double b, double gb)
{
    int i0 = k - 2 < 0 ? 0 : k - 2;
    if (i0 + 3 >= NP)
        i0 = NP - 4;
    crossing_fn c = {g, gap, i0};
    tt_root_bracket br = {g->tau[k - 1], b, gap[k - 1] - g->jumpin, gb - g->jumpin};
    double t;
    if (tt_root_illinois(crossing_value, &c, &br, 1e-10 * g->T, 1e-9 * g->L, 60, &t))
        return t;
    return 0.5 * (br.a + br.b);
}

int tt_graze_branch(const tt_graze *g, const double *d, double s0, double sdot, double *tc,
                    double *reach)
{
    double gap[NP], tm, gm;
    for (int i = 0; i < NP; i++)
        gap[i] = d[i] - (s0 + sdot * g->tau[i]);
    const int km = closest(gap, g->tau, NP, &tm, &gm);
    if (km < 0 || !(gap[0] < g->jumpin)) {
        *tc = *reach = NAN;
        return TT_GRAZE_UNSURE; /* the probes miss the closest approach or the touch */
    }
    *tc = tm;
    *reach = gm;
    if (gm < g->jumpin)
        return gm < g->jumpin - g->margin ? TT_GRAZE_FREE : TT_GRAZE_UNSURE;
    int k = 1;
    while (k < NP && gap[k] < g->jumpin)
        k++;
    if (k < NP)
        *tc = crossing(g, gap, k, g->tau[k], gap[k]);
    else /* the probes fall short of jump-in, the closest approach between them not */
        *tc = crossing(g, gap, km, tm, gm);
    return gm > g->jumpin + g->margin ? TT_GRAZE_TOUCH : TT_GRAZE_UNSURE;
}

static void store(tt_graze *g, point *p, const double *x0, double s_mid, double tc,
                  const double *x1, const double *red)
{
    const int nx = g->nx;
    p->f[0] = 1;
    for (int i = 0; i < nx; i++)
        p->f[1 + i] = x0[i];
    p->f[1 + nx] = s_mid;
    p->f[2 + nx] = tc;
    memcpy(p->out, x1, (size_t)nx * sizeof *x1);
    memcpy(p->out + nx, red, (size_t)g->m * sizeof *red);
}

void tt_graze_add(tt_graze *g, const double *x0, double s_mid, double tc, const double *x1,
                  const double *red)
{
    store(g, &g->hist[g->head], x0, s_mid, tc, x1, red);
    g->head = (g->head + 1) % HIST;
    if (g->nh < HIST)
        g->nh++;
}

int tt_graze_count(const tt_graze *g) { return g->nh; }
int tt_graze_fitted(const tt_graze *g) { return g->fitted; }
int tt_graze_star_size(const tt_graze *g) { return g->npair; }

/* A point's sample (mid-cycle) and jump-in time. */
static double s_of(const tt_graze *g, const point *p) { return p->f[1 + g->nx]; }
static double tc_of(const tt_graze *g, const point *p) { return p->f[2 + g->nx]; }

/* The latest touch's sample (mid-cycle). */
static double latest_s(const tt_graze *g)
{
    return s_of(g, &g->hist[(g->head + HIST - 1) % HIST]);
}

int tt_graze_star_due(const tt_graze *g, int fresh)
{
    if (g->nstar < g->npair || g->nh == 0)
        return 1;
    const double s = latest_s(g), far = (fresh ? 0.5 : STAR) * g->reach;
    for (int i = 0; i < g->npair; i++)
        if (fabs(s_of(g, &g->hist[HIST + i]) - s) > far)
            return 1;
    return 0;
}

int tt_graze_near(const tt_graze *g)
{
    int n = 0;
    const double s = g->nh ? latest_s(g) : 0;
    for (int i = 0; i < g->nh; i++)
        n += fabs(s_of(g, &g->hist[i]) - s) <= g->reach;
    return n;
}

int tt_graze_outputs(const tt_graze *g) { return g->no; }

int tt_graze_deepest(const tt_graze *g, double *x0, double *s_mid)
{
    if (g->nh == 0)
        return 0;
    const point *deep = &g->hist[0];
    for (int i = 1; i < g->nh; i++)
        if (tc_of(g, &g->hist[i]) < tc_of(g, deep))
            deep = &g->hist[i];
    memcpy(x0, deep->f + 1, (size_t)g->nx * sizeof *x0);
    *s_mid = s_of(g, deep);
    return 1;
}

void tt_graze_add_pair(tt_graze *g, int i, const double *x0, double s_mid, double tc,
                       const double *x1, const double *red)
{
    store(g, &g->hist[HIST + i], x0, s_mid, tc, x1, red);
    g->nstar = i + 1;
}

/* The fit's kernels take the state's size as an argument and are inlined into callers
 * that pass it as a constant for one mode (nx 2, nf 7), so that one mode's loops unroll
 * as they did when that size was fixed, and the generic size otherwise. */
#define KERNEL __attribute__((always_inline)) static inline

/* The scaled features of a cycle's inputs about the fit's centre. */
KERNEL void features(int nx, const fit_t *F, const double *f, double *phi)
{
    phi[0] = 1;
    for (int i = 0; i <= nx; i++)
        phi[1 + i] = (f[1 + i] - F->centre[i]) / F->scale[i];
    const double tau = (f[2 + nx] - F->centre[1 + nx]) / F->scale[1 + nx];
    phi[2 + nx] = tau;
    phi[3 + nx] = tau * tau;
    phi[4 + nx] = tau * tau * tau;
}

/* Least squares by modified Gram-Schmidt (twice, for orthogonality), a column that the
 * ones before it nearly span dropped (its coefficient 0): Q (n x nf, by columns) and R
 * (nf x nf); keep[j] tells the columns kept. */
KERNEL void orthogonalise(int n, int nf, double *Q, double *R, int *keep)
{
    for (int j = 0; j < nf; j++) {
        double *v = Q + (size_t)j * (size_t)n, norm0 = 0, norm = 0;
        for (int r = 0; r < n; r++)
            norm0 += v[r] * v[r];
        for (int i = 0; i < nf; i++)
            R[i * nf + j] = 0;
        for (int pass = 0; pass < 2; pass++)
            for (int i = 0; i < j; i++) {
                if (!keep[i])
                    continue;
                const double *q = Q + (size_t)i * (size_t)n;
                double dot = 0;
                for (int r = 0; r < n; r++)
                    dot += q[r] * v[r];
                R[i * nf + j] += dot;
                for (int r = 0; r < n; r++)
                    v[r] -= dot * q[r];
            }
        for (int r = 0; r < n; r++)
            norm += v[r] * v[r];
        keep[j] = norm0 > 0 && norm > 1e-18 * norm0;
        norm = sqrt(norm);
        R[j * nf + j] = keep[j] ? norm : 0;
        for (int r = 0; r < n && keep[j]; r++)
            v[r] /= norm;
    }
}

/* The cycles held whose sample is within the fit's reach of the latest's, into pts:
 * over a transient (engaging) the sample moves by several thousandths of A0 among the
 * cycles held, and the map is not linear in it that far; the star's within its wider
 * reach. Sets the trial fit's centre (the latest cycle), scales and the ranges the
 * touches among them span. */
static int select_points(tt_graze *g, const point **pts)
{
    const int nx = g->nx;
    fit_t *F = &g->trial;
    const point *last = &g->hist[(g->head + HIST - 1) % HIST];
    for (int i = 0; i < nx + 2; i++)
        F->centre[i] = last->f[1 + i];
    for (int i = 0; i < nx; i++)
        F->scale[i] = i % 2 ? g->V : g->L;
    F->scale[nx] = g->L;
    F->scale[nx + 1] = 0.01 * g->T;
    F->smin = F->tmin = INFINITY;
    F->smax = F->tmax = -INFINITY;
    for (int j = 0; j < nx; j++) {
        F->lo[j] = INFINITY;
        F->hi[j] = -INFINITY;
    }
    int n = 0;
    for (int i = 0; i < g->nh + g->nstar; i++) {
        const point *p = i < g->nh ? &g->hist[i] : &g->hist[HIST + i - g->nh];
        if (fabs(s_of(g, p) - F->centre[nx]) > (i < g->nh ? 1 : STAR) * g->reach)
            continue;
        pts[n++] = p;
        if (i < g->nh) { /* the ranges the fit covers are the touches' */
            F->smin = fmin(F->smin, s_of(g, p));
            F->smax = fmax(F->smax, s_of(g, p));
            F->tmin = fmin(F->tmin, tc_of(g, p));
            F->tmax = fmax(F->tmax, tc_of(g, p));
            for (int j = 0; j < nx; j++) {
                F->lo[j] = fmin(F->lo[j], p->f[1 + j]);
                F->hi[j] = fmax(F->hi[j], p->f[1 + j]);
            }
        }
    }
    return n;
}

/* Output o's coefficients from Q and R, and whether they reproduce every point within
 * tol of its scale (an output not tracked is NAN throughout and passes). */
KERNEL int solve_output(tt_graze *g, int nx, int nf, int o, int n, const point **pts,
                        const double *Q, const double *R, const int *keep, double tol)
{
    fit_t *F = &g->trial;
    double b[NF_MAX], *c = F->coef, phi[NF_MAX];
    for (int j = 0; j < nf; j++) {
        b[j] = 0;
        for (int r = 0; r < n && keep[j]; r++)
            b[j] += Q[(size_t)j * (size_t)n + (size_t)r] * pts[r]->out[o];
    }
    for (int j = nf - 1; j >= 0; j--) {
        double v = 0;
        if (keep[j]) {
            v = b[j];
            for (int i = j + 1; i < nf; i++)
                v -= R[j * nf + i] * c[i * g->no + o];
            v /= R[j * nf + j];
        }
        c[j * g->no + o] = v;
    }
    const double sc = g->oscale[o] * fmax(tol, g->otol[o]);
    for (int r = 0; r < n; r++) {
        features(nx, F, pts[r]->f, phi);
        double y = 0;
        for (int j = 0; j < nf; j++)
            y += phi[j] * c[j * g->no + o];
        if (fabs(y - pts[r]->out[o]) > sc)
            return 0;
    }
    return 1;
}

KERNEL int fit_n(tt_graze *g, double tol, int nx, int nf)
{
    if (g->nh < NMIN || g->nstar < g->npair)
        return 0;
    const point *pts[HIST + PAIR_MAX];
    const int n = select_points(g, pts);
    if (n < NMIN + g->npair)
        return 0;
    double *Q = g->work, *R = Q + (size_t)n * (size_t)nf;
    int keep[NF_MAX];
    for (int r = 0; r < n; r++) {
        double ph[NF_MAX];
        features(nx, &g->trial, pts[r]->f, ph);
        for (int j = 0; j < nf; j++)
            Q[(size_t)j * (size_t)n + (size_t)r] = ph[j];
    }
    orthogonalise(n, nf, Q, R, keep);
    /* the state and the sample must be resolved; the cubic in t_c may drop terms */
    int ok = 1;
    for (int j = 0; j < nx + 2; j++)
        ok = ok && keep[j];
    for (int o = 0; o < g->no && ok; o++)
        ok = solve_output(g, nx, nf, o, n, pts, Q, R, keep, tol);
    if (ok) { /* the trial becomes the fit; a failed one leaves the last fit in use */
        fit_t t = g->fit;
        g->fit = g->trial;
        g->trial = t;
        g->fitted = 1;
    }
    return ok;
}

int tt_graze_fit(tt_graze *g, double tol)
{
    return g->nx == 2 ? fit_n(g, tol, 2, 7) : fit_n(g, tol, g->nx, g->nf);
}

KERNEL void predict_n(const tt_graze *g, const double *x, double s_mid, double tc, double *x1,
                      double *red, int nx, int nf)
{
    double f[NF_MAX], phi[NF_MAX];
    f[0] = 1;
    for (int i = 0; i < nx; i++)
        f[1 + i] = x[i];
    f[1 + nx] = s_mid;
    f[2 + nx] = tc;
    features(nx, &g->fit, f, phi);
    const double *c = g->fit.coef;
    for (int o = 0; o < g->no; o++) {
        double y = 0;
        for (int j = 0; j < nf; j++)
            y += phi[j] * c[j * g->no + o];
        if (o < nx)
            x1[o] = y;
        else
            red[o - nx] = y;
    }
}

void tt_graze_predict(const tt_graze *g, const double *x, double s_mid, double tc, double *x1,
                      double *red)
{
    if (g->nx == 2)
        predict_n(g, x, s_mid, tc, x1, red, 2, 7);
    else
        predict_n(g, x, s_mid, tc, x1, red, g->nx, g->nf);
}

double tt_graze_error(const tt_graze *g, const double *xa, const double *ra, const double *xb,
                      const double *rb, double tol)
{
    double err = fabs(xa[0] - xb[0]) / (g->oscale[0] * tol);
    for (int i = 1; i < g->nx; i++)
        err = fmax(err, fabs(xa[i] - xb[i]) / (g->oscale[i] * tol));
    for (int o = g->nx; o < g->no; o++) {
        double d = fabs(ra[o - g->nx] - rb[o - g->nx]) / (g->oscale[o] * fmax(tol, g->otol[o]));
        if (d > err)
            err = d; /* NAN (not tracked) is skipped */
    }
    return err;
}

/* Whether v lies within [lo, hi] widened by a twentieth of its span on each side. */
static int within(double v, double lo, double hi)
{
    const double w = 0.05 * (hi - lo);
    return v >= lo - w && v <= hi + w;
}

int tt_graze_covers(const tt_graze *g, const double *x, double s_mid, double tc)
{
    const fit_t *F = &g->fit;
    int in = g->fitted && s_mid >= F->smin - g->reach && s_mid <= F->smax + g->reach &&
             within(tc, F->tmin, F->tmax);
    for (int i = 0; i < g->nx && in; i++)
        in = within(x[i], F->lo[i], F->hi[i]);
    return in;
}
