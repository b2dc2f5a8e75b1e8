/* Settling: cycles run until amplitude and phase stop changing, judged by extrapolating
 * the decay of their cycle-to-cycle changes; or until they repeat with a period of a
 * few cycles (a period-n orbit), whose observables are then the means over its period. */
#include <math.h>
#include <string.h>

#include "sim.h"
#include "tiptap/util/error.h"

/* What is left of a settling sequence, from its last two signed changes d and prevd
 * (NAN: none yet), r = d / prevd. Changes of one sign that shrink are a geometric tail
 * summing to d / (1 - r), and ones that do not shrink a drift of Q cycles. Changes that
 * alternate in sign are an oscillation about the limit, which every value lies within
 * |d| of while it does not grow; its growth is extrapolated over Q cycles, so that a
 * steady alternation (|r| = 1 up to rounding) passes and a growing one does not. */
static double remaining(double d, double prevd, double Q)
{
    if (!isfinite(prevd))
        return fabs(d);
    double r = prevd != 0 ? d / prevd : (d == 0 ? 0 : INFINITY);
    if (r < 0)
        return fabs(d) * pow(fmax(1.0, -r), Q);
    if (r < 1)
        return fabs(d) / (1 - r);
    return fabs(d) * Q;
}

/* The longest cycle-to-cycle pattern the settling test sees through. */
#define SETTLE_PERIOD 4

/* What is left to settle of a sequence x (x[0] the newest of n values), the least over
 * periods p of: its drift over p cycles, extrapolated by remaining() with a memory of
 * Q / p periods, plus the spread of its last p values, which a steady pattern of period
 * p keeps for ever. p = 1 is the plain geometric extrapolation; longer periods let a
 * jitter far below the tolerance (the adaptive step pattern can sustain one, with
 * period 2 or 3) count as steady, while a real period-doubled orbit, whose spread is
 * large, does not. */
static double settle_estimate(const double *x, int n, double Q)
{
    double best = n >= 2 ? remaining(x[0] - x[1], n >= 3 ? x[1] - x[2] : NAN, Q) : INFINITY;
    for (int p = 2; p <= SETTLE_PERIOD && 2 * p < n; p++) {
        double spread = 0;
        for (int j = 1; j < p; j++)
            spread = fmax(spread, fabs(x[0] - x[j]));
        double est = remaining(x[0] - x[p], x[p] - x[2 * p], Q / p) + spread;
        if (est < best)
            best = est;
    }
    return best;
}

/* What is left of the drift over p cycles of x (n values, newest first; remaining(),
 * memory Q / p periods), and in *spread the spread of its last p values. */
static double orbit_drift(const double *x, int n, int p, double Q, double *spread)
{
    *spread = 0;
    if (2 * p >= n)
        return INFINITY;
    for (int j = 1; j < p; j++)
        *spread = fmax(*spread, fabs(x[0] - x[j]));
    return remaining(x[0] - x[p], x[p] - x[2 * p], Q / p);
}

/* The observables of the n cycles c[0..n) taken together, as over one period of an
 * orbit: amplitude and phase of the mean fundamental (what a lock-in reads over the n
 * cycles), the means of the mean deflection, peak force, indentation, contact fraction
 * and energies (so that the energy balance holds for the means), the extremes of the
 * deflection, the largest residual_rel, the first contact and last release among them
 * (NAN: none), and the mean step counts. */
void tt_cycle_mean(const tt_cycle *c, int n, tt_cycle *out)
{
    if (n == 1) {
        *out = c[0];
        return;
    }
    double X = 0, Y = 0;
    tt_cycle m;
    memset(&m, 0, sizeof m);
    m.y_min = INFINITY;
    m.y_max = -INFINITY;
    m.t_contact = m.t_release = NAN;
    double steps = 0, rejected = 0, events = 0;
    for (int k = 0; k < n; k++) {
        X += c[k].amplitude * cos(c[k].phase);
        Y += c[k].amplitude * sin(c[k].phase);
        m.mean += c[k].mean;
        m.y_min = fmin(m.y_min, c[k].y_min);
        m.y_max = fmax(m.y_max, c[k].y_max);
        m.peak_force += c[k].peak_force;
        m.max_indentation += c[k].max_indentation;
        m.contact_fraction += c[k].contact_fraction;
        m.e_drive += c[k].e_drive;
        m.e_damp += c[k].e_damp;
        m.e_ts += c[k].e_ts;
        m.e_hyst += c[k].e_hyst;
        m.e_ci += c[k].e_ci;
        m.e_visc += c[k].e_visc;
        m.e_sample += c[k].e_sample;
        m.residual += c[k].residual;
        m.residual_rel = fmax(m.residual_rel, c[k].residual_rel);
        if (isnan(m.t_contact))
            m.t_contact = c[k].t_contact;
        if (!isnan(c[k].t_release))
            m.t_release = c[k].t_release;
        steps += (double)c[k].steps;
        rejected += (double)c[k].rejected;
        events += (double)c[k].events;
    }
    m.amplitude = hypot(X, Y) / n;
    double ph = atan2(Y, X);
    if (ph < -M_PI / 2)
        ph += 2 * M_PI; /* as each cycle's (cycle.c) */
    m.phase = ph;
    m.mean /= n;
    m.peak_force /= n;
    m.max_indentation /= n;
    m.contact_fraction /= n;
    m.e_drive /= n;
    m.e_damp /= n;
    m.e_ts /= n;
    m.e_hyst /= n;
    m.e_ci /= n;
    m.e_visc /= n;
    m.e_sample /= n;
    m.residual /= n;
    m.steps = lround(steps / n);
    m.rejected = lround(rejected / n);
    m.events = lround(events / n);
    *out = m;
}

/* The spread (of the free amplitude, and rad) below which a repeating pattern of a few
 * cycles is the integrator's jitter about a steady oscillation, not an orbit: dopri5 at
 * 1e-8 keeps a period-2 alternation of 1.2e-7 rad on the standard scene at 2 nm, gone
 * at 1e-10 (docs/dynamics.md, Settling); real orbits spread by 1e-3 and more. */
#define SETTLE_JITTER 1e-5

/* The ring of the last cycles: a period's and one more, or the window's. */
enum { RING = (TT_SETTLE_WINDOW > TT_SETTLE_MAX_PERIOD ? TT_SETTLE_WINDOW : TT_SETTLE_MAX_PERIOD) + 1 };

/* The orbit's period, or the window of the last cycles when none was found (or
 * always, with whole_window), from the ring of the last of n cycles: res's window,
 * the amplitude's range and change, and out their means (tt_cycle_mean). window: the
 * jitter pattern's length a period-1 point is the mean of (0: none). */
static int settle_means(const tt_cycle *ring, long n, int window, int whole_window, tt_cycle *out,
                        tt_settle_result *res)
{
    int all = (int)(n < TT_SETTLE_WINDOW ? n : TT_SETTLE_WINDOW);
    int w = whole_window ? all : window ? window : res->period ? res->period : all;
    tt_cycle last[RING];
    for (int k = 0; k < w; k++) /* oldest first */
        last[k] = ring[(n - w + k) % RING];
    res->window = w;
    if (w == 0)
        return TT_OK;
    res->amp_min = INFINITY;
    res->amp_max = res->max_indentation = -INFINITY;
    for (int k = 0; k < w; k++) {
        res->amp_min = fmin(res->amp_min, last[k].amplitude);
        res->amp_max = fmax(res->amp_max, last[k].amplitude);
        res->max_indentation = fmax(res->max_indentation, last[k].max_indentation);
    }
    /* an orbit's change over one whole period, so that its phases do not pass for a drift */
    if (w > 1 && !whole_window && (res->period > 1 || window))
        res->amp_change = (ring[(n - 1) % RING].amplitude - ring[(n - 1 - w) % RING].amplitude) / w;
    else
        res->amp_change = w > 1 ? (last[w - 1].amplitude - last[0].amplitude) / (w - 1) : 0;
    tt_cycle_mean(last, w, out); /* w = 1: out itself, unchanged */
    return TT_OK;
}

/* The sequences settling watches: amplitude (relative to the free amplitude) and phase
 * of each cycle, or an observer's (TT_SETTLE_OBSERVED at most). */
enum { SEQ = TT_SETTLE_OBSERVED > 2 ? TT_SETTLE_OBSERVED : 2 };

/* Settling, and with orbits set the search for a period-n orbit and the means (see
 * integrator.h); with an observer its values are the sequences and the means are over
 * the window whatever the period. */
static int settle(tt_sim *S, long max_cycles, double tol, int orbits, const tt_settle_observer *obs,
                  tt_cycle *out, tt_settle_result *res)
{
    /* Amplitude and phase approach their steady values geometrically (rate about
     * exp(-pi/Q) per cycle near resonance); the change still to come is estimated
     * from the ratio of successive changes, so a slow approach is not taken for
     * convergence. Far off resonance the free mode's transient alternates from cycle
     * to cycle instead, and the adaptive step pattern may keep a tiny pattern of a few
     * cycles going for ever; see settle_estimate. */
    enum { H1 = 2 * SETTLE_PERIOD + 1, H = 2 * TT_SETTLE_MAX_PERIOD + 1 };
    double h[SEQ][H] = {{0}};        /* only the first nh of each are read */
    tt_cycle ring[RING];             /* the last cycles, the newest at (n % RING) */
    const int K = obs ? obs->n : 2;
    int nh = 0, ok_in_row = 0, orbit_in_row[TT_SETTLE_MAX_PERIOD + 1] = {0}, window = 0;
    memset(res, 0, sizeof *res);
    long n;
    for (n = 0; n < max_cycles; n++) {
        double v[SEQ];
        int rc = tt_sim_cycle(S, out);
        if (rc == TT_OK && obs)
            rc = obs->fn(obs->user, out, v);
        if (rc) {
            res->cycles = n + 1;
            return rc;
        }
        if (!obs) {
            v[0] = out->amplitude / S->c.A0;
            v[1] = out->phase;
        }
        if (orbits)
            ring[n % RING] = *out;
        for (int k = 0; k < K; k++) {
            memmove(h[k] + 1, h[k], (H - 1) * sizeof h[k][0]);
            h[k][0] = v[k];
        }
        if (nh < H)
            nh++;
        if (nh < 2 || (obs && n + 1 < obs->min_cycles))
            continue;
        int n1 = nh < H1 ? nh : H1, steady = 1; /* the steady test sees what it always saw */
        for (int k = 0; k < K && steady; k++)
            steady = settle_estimate(h[k], n1, S->c.Q) < tol;
        ok_in_row = steady ? ok_in_row + 1 : 0;
        if (ok_in_row >= 3) {
            res->settled = 1;
            res->period = 1;
            n++;
            break;
        }
        /* A period-p orbit: amplitude and phase drift over p cycles by less than tol
         * (what is left of it, extrapolated), their spread over p cycles is above tol
         * and ten times that drift, for every one of its p phases and two cycles more.
         * A transient decaying onto a steady oscillation spreads by at most about twice
         * what is left of it (an alternation about the limit), so it is not taken for an
         * orbit, and a jitter below tol is settle_estimate's. */
        double spread = 0;
        for (int p = 2; orbits && p <= TT_SETTLE_MAX_PERIOD && !res->period; p++) {
            double drift = 0, sk;
            spread = 0;
            for (int k = 0; k < K; k++) {
                drift = fmax(drift, orbit_drift(h[k], nh, p, S->c.Q, &sk));
                spread = fmax(spread, sk);
            }
            if (drift < tol && spread > tol && spread > 10 * drift)
                orbit_in_row[p]++;
            else
                orbit_in_row[p] = 0;
            if (orbit_in_row[p] >= p + 2)
                res->period = p;
        }
        /* the least period: a divisor of p over which the last p values repeat to tol
         * (a longer multiple may pass first where the shorter one's test flickered) */
        for (int m = 2; res->period > 2 && m < res->period; m++) {
            int p = res->period, same = p % m == 0;
            for (int j = 0; same && j + m < p; j++)
                for (int k = 0; k < K && same; k++)
                    same = fabs(h[k][j] - h[k][j + m]) < tol;
            if (same) {
                res->period = m;
                break;
            }
        }
        if (res->period) {
            res->settled = 1;
            /* a pattern below SETTLE_JITTER is the steady oscillation seen through the
             * integrator's jitter: period 1, its row the mean over the pattern */
            if (spread <= SETTLE_JITTER) {
                window = res->period;
                res->period = 1;
            }
            n++;
            break;
        }
    }
    res->cycles = n;
    if (!orbits) {
        res->window = 1;
        return TT_OK;
    }
    return settle_means(ring, n, obs ? 0 : window, obs != NULL, out, res);
}

int tt_sim_settle(tt_sim *S, long max_cycles, double tol, tt_cycle *out, int *settled,
                  long *cycles)
{
    tt_settle_result r;
    int rc = settle(S, max_cycles, tol, 0, NULL, out, &r);
    *settled = r.settled;
    if (cycles)
        *cycles = r.cycles;
    return rc;
}

int tt_sim_settle_orbit(tt_sim *S, long max_cycles, double tol, tt_cycle *out,
                        tt_settle_result *res)
{
    return settle(S, max_cycles, tol, 1, NULL, out, res);
}

int tt_sim_settle_observed(tt_sim *S, long max_cycles, double tol, const tt_settle_observer *obs,
                           tt_cycle *out, tt_settle_result *res)
{
    if (obs->n < 1 || obs->n > TT_SETTLE_OBSERVED)
        return tt_error(TT_EINVAL, "settling: %d observed values (1 to %d)", obs->n, TT_SETTLE_OBSERVED);
    return settle(S, max_cycles, tol, 1, obs, out, res);
}
