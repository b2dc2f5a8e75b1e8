/* Approach curves: the outer loop over rest separations (see include/tiptap/instrument/approach.h). */
#include "tiptap/instrument/approach.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

struct tt_approach {
    tt_sim *sim;
    tt_approach_params p;
    size_t row, rows;
    /* ramp mode */
    long cycles_total, cycles_done;
    double dz_cycle;       /* sample travel per cycle, m (signed) */
    double z_last;         /* steady mode: the previous point's separation, m */
};

/* Steady mode moves the sample from one point to the next at this much per cycle at
 * most (5 um/s at 52 kHz, the slow end of an instrument's approach): a jump would keep
 * the tip's state against a surface that moved by the step, far beyond the contact's
 * length scale a0, and kick a tip captured by adhesion loose (Burnham et al. fig. 4a). */
#define TT_APPROACH_MOVE_PER_CYCLE 0.1e-9

int tt_approach_alloc(tt_approach **out, tt_sim *sim, const tt_approach_params *p)
{
    *out = NULL;
    if (p->points < 1)
        return tt_error(TT_EINVAL, "[approach] points: must be at least 1");
    if (!isfinite(p->from) || !isfinite(p->to))
        return tt_error(TT_EINVAL, "[approach] from/to: must be finite");
    tt_approach *a = calloc(1, sizeof *a);
    if (!a)
        return tt_error_nomem("the approach");
    a->sim = sim;
    a->p = *p;
    a->rows = (size_t)p->points * (p->retract ? 2 : 1);
    if (p->mode == TT_APPROACH_RAMP) {
        double T = tt_sim_cantilever(sim)->T;
        if (!(p->speed > 0)) {
            free(a);
            return tt_error(TT_EINVAL, "[approach] speed: must be positive in ramp mode");
        }
        double dist = fabs(p->to - p->from);
        a->cycles_total = (long)ceil(dist / (p->speed * T));
        if (a->cycles_total < 1)
            a->cycles_total = 1;
        if (a->cycles_total > 2000000000L) {
            free(a);
            return tt_error(TT_EINVAL, "[approach] speed: the ramp would take more than 2e9 cycles");
        }
        /* Each row is a cycle of the ramp: more rows than cycles would run the sample
         * past `to` (it moves on through every cycle). */
        if (p->points > a->cycles_total + 1) {
            long most = a->cycles_total + 1;
            free(a);
            return tt_error(TT_EINVAL,
                            "[approach] points: %ld rows but the ramp takes %ld cycles at this "
                            "speed (at most %ld points, or a lower speed)",
                            p->points, most - 1, most);
        }
        a->dz_cycle = (p->to - p->from) / (double)a->cycles_total;
        tt_sim_track_extremes(sim, 1);
    } else {
        /* the sample moves between points at TT_APPROACH_MOVE_PER_CYCLE at most */
        double step = fabs(p->to - p->from) / (double)(p->points > 1 ? p->points - 1 : 1);
        if (!(step / TT_APPROACH_MOVE_PER_CYCLE <= 2e9)) {
            free(a);
            return tt_error(TT_EINVAL, "[approach] points: %ld points from %g to %g m move the "
                                       "sample more than 2e9 cycles between two of them",
                            p->points, p->from, p->to);
        }
    }
    *out = a;
    return TT_OK;
}

void tt_approach_free(tt_approach *a) { free(a); }
size_t tt_approach_rows(const tt_approach *a) { return a->rows; }
int tt_approach_done(const tt_approach *a) { return a->row >= a->rows; }

/* Separation of row i of a branch of n points, from -> to (or back). */
static double branch_z(const tt_approach_params *p, size_t i, int retract)
{
    if (p->points == 1)
        return p->from;
    double f = (double)i / (double)(p->points - 1);
    return retract ? p->to + f * (p->from - p->to) : p->from + f * (p->to - p->from);
}

static int move_sample(tt_approach *a, double from, double to, long *cycles)
{
    double dist = fabs(to - from);
    long m = (long)ceil(dist / TT_APPROACH_MOVE_PER_CYCLE - 1e-9);
    double T = tt_sim_cantilever(a->sim)->T;
    tt_cycle c;
    for (long k = 0; k < m; k++) {
        tt_sim_set_sample(a->sim, from + (to - from) * (double)k / (double)m,
                          (to - from) / ((double)m * T));
        int rc = tt_sim_cycle(a->sim, &c);
        if (rc)
            return rc;
    }
    *cycles = m;
    return TT_OK;
}

/* Cycles run after an unsettled point to say why it did not settle. */
#define TT_APPROACH_DIAG_CYCLES 48
#define TT_APPROACH_MAX_PERIOD 8

/* Why a point did not settle: a period-n orbit (amplitude and phase repeat every n
 * cycles but not every cycle), or the change the last cycles still show. */
static int diagnose(tt_approach *a, tt_approach_point *pt)
{
    double amp[TT_APPROACH_DIAG_CYCLES], ph[TT_APPROACH_DIAG_CYCLES];
    for (int k = 0; k < TT_APPROACH_DIAG_CYCLES; k++) {
        int rc = tt_sim_cycle(a->sim, &pt->cycle);
        if (rc)
            return rc;
        amp[k] = pt->cycle.amplitude;
        ph[k] = pt->cycle.phase;
    }
    pt->cycles += TT_APPROACH_DIAG_CYCLES;
    double A0 = tt_sim_cantilever(a->sim)->A0;
    /* repeat within 1e-4 of the free amplitude and 1e-4 rad: tighter than any figure
     * shows, looser than the orbit's own wander after thousands of cycles */
    double ta = 1e-4 * A0, tp = 1e-4;
    int h = TT_APPROACH_DIAG_CYCLES / 2; /* compare over the second half */
    for (int n = 1; n <= TT_APPROACH_MAX_PERIOD; n++) {
        double da = 0, dp = 0;
        for (int k = h; k < TT_APPROACH_DIAG_CYCLES; k++) {
            da = fmax(da, fabs(amp[k] - amp[k - n]));
            dp = fmax(dp, fabs(ph[k] - ph[k - n]));
        }
        if (da < ta && dp < tp) {
            pt->period = n;
            break;
        }
    }
    double lo = INFINITY, hi = -INFINITY;
    for (int k = h; k < TT_APPROACH_DIAG_CYCLES; k++) {
        lo = fmin(lo, amp[k]);
        hi = fmax(hi, amp[k]);
    }
    pt->amp_min = lo;
    pt->amp_max = hi;
    /* over whole periods of an orbit, so that its phases do not pass for a drift */
    int span = TT_APPROACH_DIAG_CYCLES - 1 - h;
    if (pt->period > 1)
        span -= span % pt->period;
    pt->amp_change = (amp[h + span] - amp[h]) / (double)span;
    return TT_OK;
}

static int iterate_steady(tt_approach *a, tt_approach_point *pt)
{
    size_t n = (size_t)a->p.points;
    int retract = a->row >= n;
    size_t i = retract ? a->row - n : a->row;
    double z = branch_z(&a->p, i, retract);
    int rc;
    long moved = 0;
    memset(pt, 0, sizeof *pt);
    if (a->row == 0)
        tt_sim_reset_free(a->sim);
    else if ((rc = move_sample(a, a->z_last, z, &moved)))
        return rc;
    a->z_last = z;
    tt_sim_set_sample(a->sim, z, 0);
    pt->z = z;
    pt->retract = retract;
    if (a->p.steady == TT_STEADY_SHOOTING) {
        tt_shoot_params sp;
        tt_shoot_default(&sp);
        rc = tt_shoot_steady(a->sim, &sp, a->p.max_cycles, a->p.settle_tolerance, &pt->cycle,
                             &pt->settled, &pt->shot);
        pt->cycles = pt->shot.cycles;
    } else {
        rc = tt_sim_settle(a->sim, a->p.max_cycles, a->p.settle_tolerance, &pt->cycle,
                           &pt->settled, &pt->cycles);
    }
    pt->cycles += moved;
    if (rc == TT_OK && !pt->settled)
        rc = diagnose(a, pt);
    a->row++;
    return rc;
}

static int iterate_ramp(tt_approach *a, tt_approach_point *pt)
{
    size_t n = (size_t)a->p.points;
    int retract = a->row >= n;
    size_t i = retract ? a->row - n : a->row;
    int rc;
    memset(pt, 0, sizeof *pt);
    if (a->row == 0) {
        /* Start in the free steady state far away, as an instrument does. */
        tt_sim_reset_free(a->sim);
        tt_sim_set_sample(a->sim, a->p.from, 0);
        int settled;
        long cyc;
        if ((rc = tt_sim_settle(a->sim, a->p.max_cycles, a->p.settle_tolerance, &pt->cycle,
                                &settled, &cyc)))
            return rc;
        a->cycles_done = 0;
    }
    /* The cycle at which this row is taken along the branch. */
    long target = n == 1 ? 0 : (long)llround((double)i * (double)a->cycles_total / (double)(n - 1));
    long base = retract ? a->cycles_total : 0;
    double sdot = (retract ? -a->dz_cycle : a->dz_cycle) / tt_sim_cantilever(a->sim)->T;
    long ran = 0;
    double z = retract ? a->p.to : a->p.from;
    do {
        long k = a->cycles_done - base; /* cycles into this branch */
        z = retract ? a->p.to - (double)k * a->dz_cycle : a->p.from + (double)k * a->dz_cycle;
        tt_sim_set_sample(a->sim, z, (k < a->cycles_total) ? sdot : 0.0);
        if ((rc = tt_sim_cycle(a->sim, &pt->cycle)))
            return rc;
        a->cycles_done++;
        ran++;
    } while (a->cycles_done - base <= target);
    pt->z = z;
    pt->retract = retract;
    pt->settled = 0;
    pt->cycles = ran;
    a->row++;
    return TT_OK;
}

int tt_approach_iterate(tt_approach *a, tt_approach_point *pt)
{
    if (tt_approach_done(a))
        return tt_error(TT_EINVAL, "approach already finished");
    return a->p.mode == TT_APPROACH_RAMP ? iterate_ramp(a, pt) : iterate_steady(a, pt);
}
