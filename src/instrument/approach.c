/* Approach curves: the outer loop over rest separations (see include/tiptap/instrument/approach.h). */
#include "tiptap/instrument/approach.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/instrument/lockin.h"
#include "tiptap/util/error.h"
#include "tiptap/util/warning.h"

/* The points a warning names, at most. */
#define WARN_LIST 8

struct tt_approach {
    tt_sim *sim;
    tt_approach_params p;
    size_t row, rows;
    /* ramp mode */
    long cycles_total, cycles_done;
    double dz_cycle;       /* sample travel per cycle, m (signed) */
    double z_last;         /* steady mode: the previous point's separation, m */
    /* for tt_approach_warn: the steady points that are period-n orbits and those with
     * no period found (how many, the first WARN_LIST of each: z, period) */
    size_t periodic, unsettled;
    double periodic_z[WARN_LIST], unsettled_z[WARN_LIST];
    int periodic_n[WARN_LIST];
    /* the deepest contact of any row (indentation, m; NAN: none) and its radius, m */
    double indent, radius;
    /* mode 2 driven: the lock-ins of both modes, fed every cycle, and the samples */
    tt_lockin *lockin;
    tt_sample *samples;
    double *y;
    int N; /* samples per cycle */
};

/* A bimodal approach's lock-in: its low-pass a cascade of TT_APPROACH_LOCKIN_ORDER
 * first-order sections of TT_APPROACH_LOCKIN_CYCLES drive cycles each, so that mode 2's
 * leak into mode 1's cycles (a fraction of A2, beating at frac(f2 / f) per cycle) and
 * mode 1's into mode 2's mixing fall below a settling tolerance of 1e-9 of A0 at the
 * defaults (docs/physics.md, "Bimodal imaging"). */
#define TT_APPROACH_LOCKIN_CYCLES 64
#define TT_APPROACH_LOCKIN_ORDER 4

/* Steady mode moves the sample from one point to the next at this much per cycle at
 * most (5 um/s at 52 kHz, the slow end of an instrument's approach): a jump would keep
 * the tip's state against a surface that moved by the step, far beyond the contact's
 * length scale a0, and kick a tip captured by adhesion loose (Burnham et al. fig. 4a). */
#define TT_APPROACH_MOVE_PER_CYCLE 0.1e-9

/* With mode 2 driven, the lock-in that reads both modes every cycle (mode 1 from the
 * cycle's own fundamental, mode 2 by mixing the deflection's samples on its drive's
 * clock, as the scan's second lock-in does) and the samples it mixes. */
static int bimodal_alloc(tt_approach *a)
{
    const tt_cantilever *c = tt_sim_cantilever(a->sim);
    if (!(c->A2 > 0))
        return TT_OK;
    /* the mixing's sum frequency 2 f2 below the samples' Nyquist frequency */
    int N = 8 * (int)ceil(c->ratio2);
    a->N = N = N < 16 ? 16 : N;
    tt_lockin_params lp = {c->fd, N, 1, 1, TT_APPROACH_LOCKIN_CYCLES * c->T, TT_APPROACH_LOCKIN_ORDER,
                           c->ratio2};
    int rc = tt_lockin_alloc(&a->lockin, &lp);
    if (rc)
        return rc;
    a->samples = calloc((size_t)N, sizeof *a->samples);
    a->y = calloc((size_t)N, sizeof *a->y);
    if (!a->samples || !a->y)
        return tt_error_nomem("the approach's lock-in samples");
    tt_sim_set_sampling(a->sim, N, a->samples);
    return TT_OK;
}

/* The free oscillation of both modes, the lock-in's filters started from it. */
static void reset_free(tt_approach *a)
{
    tt_sim_reset_free(a->sim);
    if (!a->lockin)
        return;
    const tt_cantilever *c = tt_sim_cantilever(a->sim);
    tt_lockin_reset(a->lockin, c->A0, c->phi0);
    tt_lockin_reset_second(a->lockin, c->A2, c->phi2);
}

/* A cycle's deflection into the lock-in; the settling observer's values: mode 1's
 * amplitude / A0 and phase, mode 2's in-phase and quadrature parts / A0 (so that a mode
 * 2 of any amplitude settles to the tolerance of mode 1's). */
static int observe(void *user, const tt_cycle *cy, double *v)
{
    tt_approach *a = user;
    const tt_cantilever *c = tt_sim_cantilever(a->sim);
    for (int q = 0; q < a->N; q++)
        a->y[q] = a->samples[q].d - a->samples[q].z;
    tt_lockin_second_period(a->lockin, a->y, tt_cantilever_drive2_turns(c, tt_sim_cycles(a->sim) - 1));
    const double comp[3] = {cy->mean, cy->amplitude * cos(cy->phase), cy->amplitude * sin(cy->phase)};
    int rc = tt_lockin_push_components(a->lockin, comp);
    double A2 = tt_lockin_second_amplitude(a->lockin), ph2 = tt_lockin_second_phase(a->lockin);
    v[0] = tt_lockin_amplitude(a->lockin, 1) / c->A0;
    v[1] = tt_lockin_phase(a->lockin, 1);
    v[2] = A2 * cos(ph2) / c->A0;
    v[3] = A2 * sin(ph2) / c->A0;
    return rc;
}

/* The cycles after which the lock-in's filters remember less than tol of their state
 * (a step's share left after x time constants is exp(-x) sum_{k < order} x^k / k!):
 * 1660 at tol 1e-7. Sooner its output barely moves from where it was, and would pass
 * for settled. */
static long lockin_memory(double tol)
{
    double x = 0, left = 1;
    while (left >= tol && x < 1e3) {
        x += 0.25;
        double term = 1, sum = 1;
        for (int k = 1; k < TT_APPROACH_LOCKIN_ORDER; k++)
            sum += term *= x / k;
        left = exp(-x) * sum;
    }
    return (long)ceil(x * TT_APPROACH_LOCKIN_CYCLES);
}

/* One cycle, the lock-in fed. */
static int approach_cycle(tt_approach *a, tt_cycle *c)
{
    double v[4];
    int rc = tt_sim_cycle(a->sim, c);
    return rc || !a->lockin ? rc : observe(a, c, v);
}

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
    a->indent = a->radius = NAN;
    a->rows = (size_t)p->points * (p->retract ? 2 : 1);
    int rc = bimodal_alloc(a);
    if (rc) {
        tt_approach_free(a);
        return rc;
    }
    if (p->mode == TT_APPROACH_RAMP) {
        double T = tt_sim_cantilever(sim)->T;
        if (a->lockin) {
            tt_approach_free(a);
            return tt_error(TT_EINVAL, "[approach] mode: ramp does not serve mode 2's drive "
                                       "([cantilever] mode2_free_amplitude): use steady");
        }
        if (!(p->speed > 0)) {
            tt_approach_free(a);
            return tt_error(TT_EINVAL, "[approach] speed: must be positive in ramp mode");
        }
        double dist = fabs(p->to - p->from);
        a->cycles_total = (long)ceil(dist / (p->speed * T));
        if (a->cycles_total < 1)
            a->cycles_total = 1;
        if (a->cycles_total > 2000000000L) {
            tt_approach_free(a);
            return tt_error(TT_EINVAL, "[approach] speed: the ramp would take more than 2e9 cycles");
        }
        /* Each row is a cycle of the ramp: more rows than cycles would run the sample
         * past `to` (it moves on through every cycle). */
        if (p->points > a->cycles_total + 1) {
            long most = a->cycles_total + 1;
            tt_approach_free(a);
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
            tt_approach_free(a);
            return tt_error(TT_EINVAL, "[approach] points: %ld points from %g to %g m move the "
                                       "sample more than 2e9 cycles between two of them",
                            p->points, p->from, p->to);
        }
    }
    *out = a;
    return TT_OK;
}

void tt_approach_free(tt_approach *a)
{
    if (!a)
        return;
    if (a->samples) /* the sim outlives the approach: no pointer left to its samples */
        tt_sim_set_sampling(a->sim, 0, NULL);
    tt_lockin_free(a->lockin);
    free(a->samples);
    free(a->y);
    free(a);
}
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
        int rc = approach_cycle(a, &c);
        if (rc)
            return rc;
    }
    *cycles = m;
    return TT_OK;
}

/* Keep the deepest contact, a greatest penetration d (m) of a cycle, and its radius. */
static void deepest(tt_approach *a, double d)
{
    if (d > 0 && !(d <= a->indent)) {
        tt_sample s = {.d = d, .contact = 1};
        a->indent = d;
        tt_sim_force(a->sim, &s, &a->radius);
    }
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
    pt->amplitude2 = pt->phase2 = NAN;
    if (a->row == 0)
        reset_free(a);
    else if ((rc = move_sample(a, a->z_last, z, &moved)))
        return rc;
    a->z_last = z;
    tt_sim_set_sample(a->sim, z, 0);
    pt->z = z;
    pt->retract = retract;
    tt_settle_result sr;
    if (a->p.steady == TT_STEADY_SHOOTING && !a->lockin) {
        tt_shoot_params sp;
        tt_shoot_default(&sp);
        rc = tt_shoot_steady(a->sim, &sp, a->p.max_cycles, a->p.settle_tolerance, &pt->cycle,
                             &pt->settled, &pt->shot);
        pt->cycles = pt->shot.cycles;
        sr = pt->shot.settle;
        if (pt->shot.how == TT_SHOOT_NEWTON)
            sr.period = sr.window = 1;
    } else if (a->lockin) {
        tt_settle_observer obs = {observe, a, 4, lockin_memory(a->p.settle_tolerance)};
        rc = tt_sim_settle_observed(a->sim, a->p.max_cycles, a->p.settle_tolerance, &obs, &pt->cycle, &sr);
        pt->settled = sr.settled;
        pt->cycles = sr.cycles;
        /* the lock-ins' outputs, not the last cycles' mean, in which mode 2 leaks */
        pt->cycle.amplitude = tt_lockin_amplitude(a->lockin, 1);
        pt->cycle.phase = tt_lockin_phase(a->lockin, 1);
        pt->amplitude2 = tt_lockin_second_amplitude(a->lockin);
        pt->phase2 = tt_lockin_second_phase(a->lockin);
    } else {
        rc = tt_sim_settle_orbit(a->sim, a->p.max_cycles, a->p.settle_tolerance, &pt->cycle, &sr);
        pt->settled = sr.settled;
        pt->cycles = sr.cycles;
    }
    if (a->p.steady != TT_STEADY_SHOOTING || a->lockin)
        pt->shot.how = TT_SHOOT_SETTLED; /* no Newton tried: not Newton's point */
    pt->cycles += moved;
    pt->period = sr.period;
    pt->window = sr.window;
    pt->amp_min = sr.window > 1 ? sr.amp_min : pt->cycle.amplitude;
    pt->amp_max = sr.window > 1 ? sr.amp_max : pt->cycle.amplitude;
    pt->amp_change = sr.window > 1 ? sr.amp_change : 0;
    if (rc == TT_OK)
        deepest(a, sr.window > 1 ? sr.max_indentation : pt->cycle.max_indentation);
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
    pt->amplitude2 = pt->phase2 = NAN;
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
        deepest(a, pt->cycle.max_indentation);
        a->cycles_done++;
        ran++;
    } while (a->cycles_done - base <= target);
    pt->z = z;
    pt->retract = retract;
    pt->settled = 0;
    pt->cycles = ran;
    pt->window = 1;
    pt->amp_min = pt->amp_max = pt->cycle.amplitude;
    a->row++;
    return TT_OK;
}

/* Keep what tt_approach_warn says of a steady row: its orbit. */
static void note(tt_approach *a, const tt_approach_point *pt)
{
    if (a->p.mode == TT_APPROACH_STEADY && pt->period != 1) {
        size_t *k = pt->period ? &a->periodic : &a->unsettled;
        if (*k < WARN_LIST) {
            (pt->period ? a->periodic_z : a->unsettled_z)[*k] = pt->z;
            if (pt->period)
                a->periodic_n[*k] = pt->period;
        }
        (*k)++;
    }
}

int tt_approach_iterate(tt_approach *a, tt_approach_point *pt)
{
    if (tt_approach_done(a))
        return tt_error(TT_EINVAL, "approach already finished");
    int rc = a->p.mode == TT_APPROACH_RAMP ? iterate_ramp(a, pt) : iterate_steady(a, pt);
    if (rc == TT_OK)
        note(a, pt);
    return rc;
}

/* "z1, z2 nm" of the first min(n, WARN_LIST) of z (with " (period p)" when per), and
 * ", ..." when there were more. */
static void z_list(char *buf, size_t len, const double *z, const int *per, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < n && i < WARN_LIST && used < len; i++) {
        used += (size_t)snprintf(buf + used, len - used, "%s%.6g", i ? ", " : "", z[i] * 1e9);
        if (per && used < len)
            used += (size_t)snprintf(buf + used, len - used, " (period %d)", per[i]);
    }
    if (used < len)
        snprintf(buf + used, len - used, " nm%s", n > WARN_LIST ? ", ..." : "");
}

void tt_approach_warn(const tt_approach *a)
{
    char list[512];
    size_t n = a->row;
    if (a->periodic) {
        z_list(list, sizeof list, a->periodic_z, a->periodic_n, a->periodic);
        tt_warn(TT_WARN_SETTLE,
                "%zu of %zu points are periodic orbits of more than one cycle, not "
                "steady oscillations (z = %s): their rows are the means over the period, which "
                "the period column gives in cycles", a->periodic, n, list);
    }
    if (a->unsettled) {
        z_list(list, sizeof list, a->unsettled_z, NULL, a->unsettled);
        tt_warn(TT_WARN_SETTLE,
                "%zu of %zu points found no period up to %d cycles within max_cycles = "
                "%ld (z = %s): their rows are the means over their last %d cycles (period 0); "
                "chaos, or raise [approach] max_cycles", a->unsettled, n, TT_SETTLE_MAX_PERIOD,
                a->p.max_cycles, list, TT_SETTLE_WINDOW);
    }
    if (a->p.material && a->indent > 0)
        tt_contact_warn_validity(a->p.material, a->radius, a->indent, a->p.tip_radius,
                                 "a larger [tip] radius, a larger [approach] to or a smaller "
                                 "[cantilever] free_amplitude");
}
