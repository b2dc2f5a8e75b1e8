/* tiptap: force-distance curves (tiptap force): the undriven cantilever's base ramps
 * toward the sample and back at a constant speed, with an optional dwell at the turn,
 * integrated by the same solver as every other run (the equation of motion with zero
 * drive; docs/force-and-tune.md).
 *
 * The ramp is done by moving the sample at the speed instead of the base: with the base
 * at rest the equation of motion in the base's frame is the same (the lever's spring and
 * damping act on the tip's motion relative to the base either way), and "z" is the rest
 * separation, the gap between the undeflected tip and the surface.
 *
 * Ownership: tt_run_force returns a table the caller frees (tt_table_free); the scene
 * is borrowed.
 */
#ifndef TIPTAP_RUN_FORCE_H
#define TIPTAP_RUN_FORCE_H

#include "tiptap/export.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/config/scene.h"
#include "tiptap/run/run.h"
#include "tiptap/util/table.h"

TT_BEGIN_DECLS

/* What a force curve shows. Forces are the tip-sample force (N, repulsive positive);
 * z is the rest separation (m). NAN where there was none (no jump-in, no contact). */
typedef struct {
    double speed;             /* the ramp's speed as run (whole drive periods per leg), m/s */
    long cycles;              /* drive periods integrated */
    double jumpin_z;          /* where the tip snapped in: the approach's last point before
                               * its first contact at which the tip moved less than ten times
                               * the ramp speed (or the thermal speed) */
    double jumpin_force;      /* the force there: the largest attraction the lever held */
    double jumpin_gap;        /* the tip-sample gap there, m */
    double contact_z;         /* the approach's first contact event */
    double pulloff_z;         /* where the tip first leaves the surface on the retract */
    double pulloff_force;     /* the force at the last in-contact point before it */
    double adhesion;          /* the largest attraction on the retract, -min force, N */
    double max_force;         /* the largest force (at the turn, or the dwell), N */
    double slope;             /* the approach's contact part: -dF/dz, N/m, a straight line
                               * through the points above half the largest force */
    double slope_deflection;  /* the same in deflection per z, m/m (1: a rigid sample) */
    double slope_retract;     /* as slope on the retract */
    double k;                 /* the lever's spring constant, N/m */
    double indentation;       /* the largest indentation in contact, -separation, m */
} tt_force_summary;

/* [force] read by tt_config_force (refusals name the file and key, before anything
 * runs). A row per sample: t (s), z (m), deflection (m, tip - base, positive toward the sample),
 * separation (m, tip-sample gap z - deflection; negative: indentation), force (N,
 * tip-sample), lever_force (N, -k deflection: what the instrument reads), contact (1, 0),
 * leg (approach, dwell, retract). The summary as metadata, and in *sum when not NULL. */
int tt_run_force(const tt_scene *s, tt_table **out, tt_force_summary *sum, tt_progress_fn progress,
                 void *user);

TT_END_DECLS
#endif
