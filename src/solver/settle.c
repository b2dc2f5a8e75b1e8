/* Settling: cycles run until amplitude and phase stop changing, judged by extrapolating
 * the decay of their cycle-to-cycle changes. */
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

int tt_sim_settle(tt_sim *S, long max_cycles, double tol, tt_cycle *out, int *settled,
                  long *cycles)
{
    /* Amplitude and phase approach their steady values geometrically (rate about
     * exp(-pi/Q) per cycle near resonance); the change still to come is estimated
     * from the ratio of successive changes, so a slow approach is not taken for
     * convergence. Far off resonance the free mode's transient alternates from cycle
     * to cycle instead, and the adaptive step pattern may keep a tiny pattern of a few
     * cycles going for ever; see settle_estimate. */
    enum { H = 2 * SETTLE_PERIOD + 1 };
    double hA[H] = {0}, hP[H] = {0}; /* only the first nh are read */
    int nh = 0, ok_in_row = 0;
    *settled = 0;
    long n;
    for (n = 0; n < max_cycles; n++) {
        int rc = tt_sim_cycle(S, out);
        if (rc) {
            if (cycles)
                *cycles = n + 1;
            return rc;
        }
        memmove(hA + 1, hA, (H - 1) * sizeof hA[0]);
        memmove(hP + 1, hP, (H - 1) * sizeof hP[0]);
        hA[0] = out->amplitude / S->c.A0;
        hP[0] = out->phase;
        if (nh < H)
            nh++;
        if (nh >= 2) {
            if (settle_estimate(hA, nh, S->c.Q) < tol && settle_estimate(hP, nh, S->c.Q) < tol)
                ok_in_row++;
            else
                ok_in_row = 0;
            if (ok_in_row >= 3) {
                *settled = 1;
                n++;
                break;
            }
        }
    }
    if (cycles)
        *cycles = n;
    return TT_OK;
}
