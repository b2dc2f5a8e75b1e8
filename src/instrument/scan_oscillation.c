/* Is the feedback loop oscillating: rings in a line's record, the loop's measured pole,
 * and a gain suggestion (see include/tiptap/instrument/scan_oscillation.h). */
#include "tiptap/instrument/scan_oscillation.h"
#include "scan_engine.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

enum { MIN_SWINGS = 6 };         /* three periods */
#define MIN_DECAY 0.5            /* per half period: a damping ratio of 0.215 or less */
#define SPACING 1.6              /* half periods within this factor of their median */
#define TARGET_MARGIN 60.0       /* deg */

void tt_scan_loop(const tt_scan *S, tt_loop *l)
{
    *l = (tt_loop){S->cantilever.Q / (M_PI * S->cantilever.f0), S->cantilever.fd, S->lockin.time_constant,
                   S->lockin.filter_order, S->lockin.periods_per_block, S->kp, S->ki, S->setpoint};
}

/* The loop's transfer function at s without the plant gain: C(s) G(s) / g. */
static double complex open_loop(const tt_loop *l, double ki, double complex s)
{
    const double d = l->periods_per_block / l->fd;
    double complex L = (l->kp + ki / s) * cexp(-s * d) / (1 + s * l->tau_a);
    for (int i = 0; i < l->filter_order && l->time_constant > 0; i++)
        L /= 1 + s * l->time_constant;
    return L;
}

/* The phase of L(i w) in degrees, continuous from 0 down (each factor's own lag). */
static double phase_deg(const tt_loop *l, double ki, double w)
{
    const double d = l->periods_per_block / l->fd;
    double ph = atan2(-ki / w, l->kp) - atan(w * l->tau_a) - w * d;
    if (l->time_constant > 0)
        ph -= l->filter_order * atan(w * l->time_constant);
    return ph * 180 / M_PI;
}

/* The crossover, |g L(i w)| = 1, by bisection in log w: |L| falls with w. */
static double crossover(const tt_loop *l, double g, double ki)
{
    double lo = 1e-3, hi = 1e10;
    if (g * cabs(open_loop(l, ki, I * hi)) >= 1)
        return NAN;
    for (int i = 0; i < 200 && hi / lo > 1 + 1e-12; i++) {
        double w = sqrt(lo * hi);
        if (g * cabs(open_loop(l, ki, I * w)) > 1)
            lo = w;
        else
            hi = w;
    }
    return sqrt(lo * hi);
}

double tt_loop_phase_margin(const tt_loop *l, double g, double ki)
{
    double w = crossover(l, g, ki);
    return isnan(w) ? NAN : 180 + phase_deg(l, ki, w);
}

double tt_loop_ki_for_margin(const tt_loop *l, double g, double pm)
{
    /* the margin falls as ki grows (the crossover moves up into the lags) */
    double lo = 1e-3, hi = 1e10;
    if (!(tt_loop_phase_margin(l, g, lo) > pm) || tt_loop_phase_margin(l, g, hi) > pm)
        return NAN;
    for (int i = 0; i < 200 && hi / lo > 1 + 1e-9; i++) {
        double k = sqrt(lo * hi);
        if (tt_loop_phase_margin(l, g, k) > pm)
            lo = k;
        else
            hi = k;
    }
    return sqrt(lo * hi);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, long n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The error's noise: the rms of what a straight line through each point's neighbours
 * leaves (robust: 1.4826 times the median of its magnitude; a smooth ring leaves
 * little), scaled to one point's own noise. */
static double noise_of(const double *e, long n, double *work)
{
    long m = 0;
    for (long i = 1; i + 1 < n; i++)
        work[m++] = fabs(e[i] - 0.5 * (e[i - 1] + e[i + 1]));
    return m ? 1.4826 * median(work, m) / sqrt(1.5) : 0;
}

/* One swing: the error's extreme between crossing one threshold and the other's. */
typedef struct {
    long i;   /* its peak's point */
    double v; /* the error there */
} swing;

/* The swings of e beyond +-h, alternating in sign by construction. */
static long swings_of(const double *e, long n, double h, swing *sw)
{
    long m = 0;
    int side = 0;
    for (long i = 0; i < n; i++) {
        int s = e[i] > h ? 1 : e[i] < -h ? -1 : 0;
        if (s && s != side) {
            side = s;
            sw[m++] = (swing){i, e[i]};
        } else if (side && s == side && fabs(e[i]) > fabs(sw[m - 1].v)) {
            sw[m - 1] = (swing){i, e[i]};
        }
    }
    return m;
}

/* The longest run of evenly spaced swings: its first and count. Periods are measured
 * between swings of one sign (two apart): a ring that has run into the surface is
 * lopsided, its swings toward the surface shorter than those away. A swing after the
 * surface moved (its range since the last swing above thr) or the material changed is
 * the sample's doing, not the loop's: it may start a ring (the edge that excites it),
 * not continue one, or a loop would ring at the rate of a staircase's edges or of a
 * blend's disks. h is the surface the tip follows (its dilation): a blunt tip's error
 * swings on the slopes it makes of a grating's walls, where the true surface is flat. */
static long longest_ring(const swing *sw, long m, const double *t, const double *h,
                         const double *mat, double thr, long *first, double *work)
{
    long best = m < 2 ? m : 2, a = 0;
    *first = 0;
    for (long b = 1; b < m; b++) {
        double lo = h[sw[b - 1].i], hi = lo;
        int moved = 0;
        for (long i = sw[b - 1].i; i < sw[b].i && !moved; i++) {
            lo = fmin(lo, h[i + 1]);
            hi = fmax(hi, h[i + 1]);
            moved = mat[i + 1] != mat[i] || hi - lo > thr;
        }
        if (moved) {
            a = b;
            continue;
        }
        if (b < a + 2)
            continue;
        /* extend [a, b] while every period stays within SPACING of their median */
        long k = 0;
        for (long i = a + 2; i <= b; i++)
            work[k++] = t[sw[i].i] - t[sw[i - 2].i];
        double med = median(work, k), last = t[sw[b].i] - t[sw[b - 2].i];
        if (!(last <= SPACING * med && last >= med / SPACING))
            a = b - 2;
        if (b - a + 1 > best) {
            best = b - a + 1;
            *first = a;
        }
    }
    return best;
}

/* The model's phase at the pole p (deg), unwrapped: each factor's own angle, the
 * lags' from 0 (the pole lies in the upper half plane). */
static double pole_phase(const tt_loop *l, double complex p)
{
    const double s = -creal(p), w = cimag(p), d = l->periods_per_block / l->fd;
    double ph = carg(l->kp + l->ki / p) - w * d - atan2(w * l->tau_a, 1 - s * l->tau_a);
    if (l->time_constant > 0)
        ph -= l->filter_order * atan2(w * l->time_constant, 1 - s * l->time_constant);
    return ph * 180 / M_PI;
}

/* The amplitude's time constant that puts the pole on the model (phase -180 deg): the
 * phase falls as tau_A grows, by bisection; 0 when the rest lags too much already. */
static double fit_tau(const tt_loop *l, double complex p)
{
    tt_loop m = *l;
    m.tau_a = 0;
    if (pole_phase(&m, p) <= -180)
        return 0;
    double lo = 0, hi = 1;
    for (int i = 0; i < 200 && hi - lo > 1e-15; i++) {
        m.tau_a = 0.5 * (lo + hi);
        if (pole_phase(&m, p) > -180)
            lo = m.tau_a;
        else
            hi = m.tau_a;
    }
    return 0.5 * (lo + hi);
}

/* The ring's frequency, decay and extent into o; the pole's model figures. */
static void measure(const tt_loop *l, const double *t, const double *z, const double *h,
                    const swing *sw, long a, long m, double *work, tt_oscillation *o)
{
    const long last = a + m - 1;
    o->t_start = t[sw[a].i];
    o->t_end = t[sw[last].i];
    o->frequency = (double)(m - 1) / (2 * (o->t_end - o->t_start));
    o->periods = (double)(m - 1) / 2;
    /* the decay over each period (a lopsided ring's swings alternate in size), per half */
    for (long i = a + 2; i <= last; i++)
        work[i - a - 2] = fabs(sw[i].v / sw[i - 2].v);
    o->decay = sqrt(median(work, m - 2));
    double lr = log(o->decay);
    o->damping = -lr / sqrt(M_PI * M_PI + lr * lr);
    o->error_peak = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (long i = sw[a].i; i <= sw[last].i; i++) {
        lo = fmin(lo, z[i] - h[i]);
        hi = fmax(hi, z[i] - h[i]);
    }
    for (long i = a; i <= last; i++)
        o->error_peak = fmax(o->error_peak, fabs(sw[i].v));
    o->z_peak_to_peak = hi - lo;
    /* the pole: decays by r each half period 1 / (2 f) */
    const double complex p = 2 * o->frequency * lr + I * 2 * M_PI * o->frequency;
    tt_loop fit = *l;
    fit.tau_a = fit_tau(l, p);
    const double complex L = open_loop(&fit, l->ki, p);
    o->amplitude_time = fit.tau_a;
    o->plant_gain = 1 / cabs(L);
    o->model_phase = pole_phase(&fit, p);
    o->phase_margin = tt_loop_phase_margin(&fit, o->plant_gain, l->ki);
    o->ki_suggested = tt_loop_ki_for_margin(&fit, o->plant_gain, TARGET_MARGIN);
}

int tt_scan_oscillation(const tt_scan_scope *sc, const tt_loop *l, tt_oscillation *o)
{
    memset(o, 0, sizeof *o);
    o->plant_gain = o->model_phase = o->phase_margin = o->ki_suggested = NAN;
    o->frequency = o->decay = o->damping = NAN;
    long n0 = tt_scan_scope_points(sc, 0), n1 = tt_scan_scope_points(sc, 1);
    long nmax = n0 > n1 ? n0 : n1;
    if (nmax < 3)
        return tt_error(TT_EINVAL, "the scope holds no line to check");
    double *work = malloc((size_t)nmax * sizeof *work);
    swing *sw = malloc((size_t)nmax * sizeof *sw);
    if (!work || !sw) {
        free(work);
        free(sw);
        return tt_error_nomem("the oscillation check of %ld points", nmax);
    }
    long best = 0;
    for (int dir = 0; dir < 2; dir++) {
        long n = tt_scan_scope_points(sc, dir);
        if (n < 3)
            continue;
        const double *e = tt_scan_scope_series(sc, dir, TT_SCOPE_ERROR),
                     *t = tt_scan_scope_series(sc, dir, TT_SCOPE_TIME),
                     *z = tt_scan_scope_series(sc, dir, TT_SCOPE_Z),
                     *h = tt_scan_scope_series(sc, dir, TT_SCOPE_FOLLOWED),
                     *mat = tt_scan_scope_series(sc, dir, TT_SCOPE_MATERIAL);
        double noise = noise_of(e, n, work), thr = fmax(5 * noise, 0.01 * l->setpoint);
        if (noise > o->noise)
            o->noise = noise;
        long m = swings_of(e, n, thr, sw), first;
        long len = longest_ring(sw, m, t, h, mat, thr, &first, work);
        if (len > best && len >= 4) {
            best = len;
            o->retrace = dir;
            o->threshold = thr;
            measure(l, t, z, h, sw, first, len, work, o);
        }
    }
    o->rings = best >= MIN_SWINGS && o->decay >= MIN_DECAY;
    free(work);
    free(sw);
    return TT_OK;
}
