/* tiptap: approach curves (Burnham et al.'s figures 1, 4): amplitude, phase and the rest against
 * the rest separation between the undeflected tip and the sample.
 *
 * steady mode: at each separation the steady oscillation is found by shooting, or the
 * cantilever runs until amplitude and phase settle, starting from the previous point's
 * state (so the branch followed depends on the history, as on an instrument), optionally
 * followed by the retract branch. Between points the sample moves continuously, at most
 * 0.1 nm per cycle, with the cantilever running (a jump would kick a captured tip loose).
 * With mode 2 driven (bimodal AM-AM) steady mode settles, watching a lock-in of each mode
 * whose low-pass filters out the other's incommensurate drive; ramp mode refuses it.
 * ramp mode: the sample moves continuously at a given speed, as in Burnham et al.'s figure 4;
 * each row is the cycle running at that moment, so there can be no more rows per
 * branch than the ramp has cycles plus one (TT_EINVAL "[approach] points" otherwise).
 *
 * Usage: tt_approach_alloc(&a, sim, &params); while (!tt_approach_done(a))
 * { tt_approach_iterate(a, &pt); ... }; tt_approach_free(a).
 * Ownership: the approach borrows sim (which must outlive it) and drives it.
 */
#ifndef TIPTAP_APPROACH_H
#define TIPTAP_APPROACH_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/solver/integrator.h"
#include "tiptap/solver/shooting.h"

TT_BEGIN_DECLS

typedef enum { TT_APPROACH_STEADY = 0, TT_APPROACH_RAMP = 1 } tt_approach_mode;
/* How steady mode finds a point's oscillation: the periodic orbit by shooting
 * (tiptap/solver/shooting.h, falling back to settling), or by settling alone. */
typedef enum { TT_STEADY_SHOOTING = 0, TT_STEADY_SETTLE = 1 } tt_approach_steady;

typedef struct {
    double from, to;       /* rest separations, m */
    long points;
    tt_approach_mode mode;
    int retract;
    double speed;          /* ramp mode, m/s */
    long max_cycles;       /* steady mode: per point */
    double settle_tolerance;
    tt_approach_steady steady; /* steady mode */
    /* the material under the tip, for tt_approach_warn's messages: its name (NULL:
     * none given, no contact warning) and the radius of its force law, m */
    const char *material;
    double tip_radius;
} tt_approach_params;

typedef struct {
    double z;        /* rest separation, m */
    int retract;     /* 0 approach branch, 1 retract branch */
    int settled;     /* steady mode: whether the point settled within max_cycles */
    long cycles;     /* cycles run for this row */
    tt_cycle cycle;  /* the point's observables: ramp mode, the cycle's; steady mode,
                      * the mean over its orbit's period, or over the last window cycles
                      * when none was found (tt_sim_settle_orbit, tt_cycle_mean) */
    tt_shoot_result shot; /* steady mode by shooting: how the point was found (else zero) */
    /* steady mode: the orbit's period in cycles (1 a steady oscillation, 2 to
     * TT_SETTLE_MAX_PERIOD a period-n orbit, settled too; 0 none found within
     * max_cycles, unsettled), the cycles cycle is the mean of (the period, or the last
     * TT_SETTLE_WINDOW), the amplitude's range over them, m, and its mean change per
     * cycle, m, over a whole period of an orbit; ramp mode: 0, 1 (one cycle per row) */
    int period, window;
    double amp_min, amp_max, amp_change;
    /* mode 2 driven ([cantilever] mode2_free_amplitude, steady mode): its lock-in's
     * amplitude (m) and lag behind its drive (rad) at the point, and cycle's amplitude and
     * phase are mode 1's lock-in's (tiptap/instrument/approach.c); NAN without */
    double amplitude2, phase2;
} tt_approach_point;

typedef struct tt_approach tt_approach;

int tt_approach_alloc(tt_approach **out, tt_sim *sim, const tt_approach_params *p);
void tt_approach_free(tt_approach *a);
size_t tt_approach_rows(const tt_approach *a);
int tt_approach_done(const tt_approach *a);
/* Compute the next row. TT_ENUM etc. on solver failure. */
int tt_approach_iterate(tt_approach *a, tt_approach_point *pt);

/* Raise the warnings (tiptap/util/warning.h) of the rows computed so far: TT_WARN_SETTLE
 * for the steady points that are period-n orbits (their rows are the means over the
 * period) and for those where no period up to TT_SETTLE_MAX_PERIOD was found (means
 * over the last TT_SETTLE_WINDOW cycles), each naming how many and which; and
 * TT_WARN_VALIDITY when the deepest contact of any row is beyond the force laws'
 * small-contact assumption (tt_contact_warn_validity; needs params' material). Once per
 * run, on the calling thread: a run's companion (its error estimate) does not call it. */
void tt_approach_warn(const tt_approach *a);

TT_END_DECLS
#endif
