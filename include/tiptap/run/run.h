/* tiptap: whole runs from a scene into tables: what the tiptap commands compute, for a
 * caller that wants numbers rather than files (the Python package, docs/python.md).
 *
 * Each function reads and checks the scene through the configuration layer as the
 * command does (the same one-line refusals, before anything runs), runs, and returns a
 * tt_table (tiptap/util/table.h) in SI units: one column per quantity, named as the
 * command's CSV column without its unit ("amplitude", not "amplitude_nm"), with its
 * unit; the phase in degrees, as everywhere in tiptap's outputs. progress, if not NULL,
 * is called after each row (point, cycle, setting) with the rows done and the total.
 * Cancellation (tiptap/util/cancel.h) stops a run between rows, or within one, with
 * TT_EINTR; the rows finished are kept.
 *
 * Ownership: on TT_OK, and on a failure after the first row (TT_EINTR, a solver
 * failure), *out is a table the caller frees with tt_table_free, holding the rows
 * finished; on a refusal before the run *out is NULL. The scene is borrowed.
 */
#ifndef TIPTAP_RUN_H
#define TIPTAP_RUN_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/scene.h"
#include "tiptap/instrument/accuracy.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/table.h"

TT_BEGIN_DECLS

typedef void (*tt_progress_fn)(void *user, long done, long total);

/* tiptap approach: a row per point of [approach] (both branches): z (m), amplitude (m),
 * phase (deg), mean_deflection (m), peak_force (N), max_indentation (m),
 * contact_fraction, dissipated (J), branch (approach, retract), settled (1, 0), cycles,
 * drive_work (J), energy_residual, deflection_min, deflection_max (m), period (cycles:
 * steady mode, 1 a steady oscillation, n a period-n orbit whose row is the mean over its
 * n cycles, 0 none found, the mean over the last TT_SETTLE_WINDOW cycles; ramp mode 0).
 * The warnings of tt_approach_warn are raised on the calling thread. */
int tt_run_approach(const tt_scene *s, tt_table **out, tt_progress_fn progress, void *user);

/* tiptap trace: samples_per_cycle rows per recorded cycle: cycle, t (s), base, tip,
 * sample, deflection (m), force (N), contact_radius (m), pressure (Pa), contact (1, 0),
 * and the ramped key's value (its SI unit) when [trace] ramp is set; the warning of
 * tt_trace_warn_contact raised on the calling thread. */
int tt_run_trace(const tt_scene *s, tt_table **out, tt_progress_fn progress, void *user);

/* tiptap contact with a scene: the force law of the [material NAME] (NULL: the first),
 * its model replaced by model when not NULL, as the command builds it; *params and *Qi
 * (the material's interaction quality factor) as it read them. The caller frees the law
 * (tt_contact_free). */
int tt_run_contact_alloc(const tt_scene *s, const char *material, const char *model,
                         tt_contact **out, tt_contact_params *params, double *Qi);
/* The curve of `tiptap contact -o` in Burnham et al.'s normalised units (eq. 3): A,
 * Delta, P, stable, n points up to A = Amax (and the A -> 0 end first for an adhesive
 * law); the summary (tt_contact_summary, and with params the physical values) as the
 * table's metadata, numbers written to round-trip ("%.17g"). */
int tt_run_contact_table(const tt_contact *c, const tt_contact_params *params, double Qi,
                         size_t n, double Amax, tt_table **out);

/* tiptap accuracy: a row per solver setting (reference, floor, then the ladders):
 * method, tier, knob, value, run_time (s), cpu_time (s), steps_per_cycle, integrated,
 * the errors of the study's observables (their CSV names, SI), residual_rel, role,
 * is_default, status; p as tt_accuracy_params_default with the caller's choices. */
int tt_run_accuracy(const tt_scene *s, const tt_accuracy_params *p, tt_table **out,
                    tt_progress_fn progress, void *user);

TT_END_DECLS
#endif
