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
#include "tiptap/instrument/scan.h"
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

/* Warnings (tiptap/util/warning.h): what every surface of tiptap says about a run whose
 * numbers may mislead. The commands and the Python package call the same functions, so
 * that they hear the same warnings with the same words; each raises at most the lines
 * named, on the calling thread, and returns how many it raised. */

/* tiptap scan's checks and cost before anything runs: the scene read (tt_config_scan),
 * rk4's steps checked (tt_config_check_rk4), the cost estimated (tt_config_scan_estimate)
 * and a scan needing more memory than this process can allocate refused (TT_ENOMEM: "W x
 * H pixels need about 6.5 GB of memory (...), more than the 1.0 GB available; ..."),
 * then the scan made (tt_scan_alloc). Raises no warning: tt_run_scan_warn_inputs does,
 * once the caller has shown the estimate. threads: lines in parallel (0: all cores). */
typedef struct {
    long pixels, lines;    /* the raster */
    int threads;           /* lines in parallel: as asked, else the cores; at most lines */
    int upper_bound;       /* cycles and seconds are the most the run can take */
    int envelope;          /* the envelope tier: seconds_low to seconds */
    int averaged;          /* the scan runs on the averaged tier */
    double cycles;         /* drive cycles to simulate */
    double seconds;        /* run time on one thread, by estimate */
    double seconds_low;    /* the least (the envelope tier); seconds otherwise */
    double integrated_low, integrated_high; /* the envelope tier's fractions integrated */
    double bytes;          /* memory the run holds on its threads */
    double available;      /* memory this process can allocate (tt_run_memory_available) */
    double f0, fd;         /* resonance and drive frequency, Hz */
} tt_run_scan_cost;
int tt_run_scan_alloc(const tt_scene *s, int threads, tt_scan **out, tt_run_scan_cost *cost);

/* Before a scan runs: a run longer than a minute by estimate (TT_WARN_RUN), each
 * material the surface map never puts under the tip (TT_WARN_INPUT, at most 8 and a
 * count), and [noise] on the averaged tier, which does not model it (TT_WARN_INPUT). */
int tt_run_scan_warn_inputs(const tt_scene *s, const tt_run_scan_cost *cost);

/* After a scan ran: each material whose contact went past the force laws' small
 * contact (TT_WARN_VALIDITY), pixels where the averaged tier's oscillation collapsed
 * (TT_WARN_VALIDITY), the z piezo at the end of its range (TT_WARN_SETPOINT). */
int tt_run_scan_warn_result(const tt_scan *scan);

/* The feedback loop oscillating on the scope's line (tt_scan_oscillation;
 * TT_WARN_OSCILLATION); files names where the record was written ("scope.csv,
 * scope.png"; NULL: none). */
int tt_run_scan_warn_oscillation(const tt_scan *scan, const tt_scan_scope *scope,
                                 const char *files);

/* A scan's error estimate (tt_scan_estimate_error) past tt_run_warn_estimate's limits,
 * in height and lock-in amplitude; none on the averaged tier (cost->averaged), whose
 * error is its model's, which no tolerance moves. */
int tt_run_scan_warn_error(const tt_scan *scan, const tt_run_scan_cost *cost,
                           const tt_scan_error *e);

/* The run's own error estimate above TT_RUN_WARN_AMPLITUDE_REL of the free amplitude
 * A0 in height (m; NAN: none) or in what ("amplitude", "deflection"), or above
 * TT_RUN_WARN_PHASE_DEG in phase, naming the key that tightens solver s
 * (TT_WARN_ESTIMATE). */
#define TT_RUN_WARN_AMPLITUDE_REL 1e-3
#define TT_RUN_WARN_PHASE_DEG 0.1
int tt_run_warn_estimate(const tt_solver *s, double A0, double height_m, const char *what,
                         double amplitude_rel, double phase_deg);

/* A run longer than a minute (wall, s) by estimate, naming the drive's distance below the
 * resonance f0 when the drive fd is less than half of it (TT_WARN_RUN). */
int tt_run_warn_duration(double wall, int upper_bound, double f0, double fd);

/* The rows of a setpoint sweep's table (tt_run_sweep) whose found column says
 * TT_SWEEP_UNREACHABLE, naming up to 10 combinations (TT_WARN_SETPOINT). */
int tt_run_warn_unreached(const tt_table *t);

/* Bytes this process can still allocate: the smaller of the memory available
 * (/proc/meminfo MemAvailable, else the physical memory) and its address-space and data
 * limits (ulimit -v, -d). */
double tt_run_memory_available(void);

/* A duration and a size for people ("40 s", "12 min", "3.1 h", "2.5 days"; "80 MB"),
 * written into buf, which is returned. */
const char *tt_run_duration(double seconds, char *buf, size_t len);
const char *tt_run_bytes(double bytes, char *buf, size_t len);

TT_END_DECLS
#endif
