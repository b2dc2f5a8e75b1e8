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
#include "tiptap/instrument/scan_scope.h"
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

/* tiptap scan's whole sequence, the one the program, the console and the Python package
 * run: the scan made (tt_run_scan_alloc: nothing runs on a refusal), the input warnings
 * (tt_run_scan_warn_inputs), the outputs asked for checked and their folder made, the
 * lines run (tt_scan_run: progress, cancellation), the result warnings
 * (tt_run_scan_warn_result), the finished lines written (also after a failure or a
 * cancel), the oscillation warning on the scope's line, the error estimate when asked
 * for after a scan that finished, its companion lines run on the same threads as the
 * files (a cancel in it: TT_EINTR, the images written), and its warning
 * (tt_run_scan_warn_error). The hooks let a caller add its own steps where the
 * program has them; each is optional (NULL). */
typedef struct tt_run_scan_result tt_run_scan_result;
typedef struct {
    int threads;              /* lines in parallel (0: all cores) */
    tt_progress_fn progress;  /* after each finished line (NULL: none) */
    void *user;               /* progress's and the hooks' */
    tt_scan_scope *scope;     /* records the profile line (NULL: none) */
    const char *scope_files;  /* where the caller writes the scope, named by the oscillation
                               * warning ("scope.csv, scope.png"; NULL: none) */
    const char *folder;       /* the outputs of `tiptap scan -o` (NULL: none): checked before
                               * the lines run (tt_run_scan_check_outputs), the folder made,
                               * written after (tt_run_scan_write_outputs) */
    int hdf5;                 /* with folder: FOLDER/scan.h5 too */
    const char *hdf5_file;    /* one HDF5 file (NULL: none), checked before the lines run */
    int estimate;             /* the error estimate (tt_scan_estimate_error) */
    /* the scan made, its cost known, before any warning (non-zero stops the run) */
    int (*made)(void *user, const tt_scan *scan, const tt_run_scan_cost *cost);
    /* the outputs checked and the folder made, before the lines run (non-zero stops) */
    int (*ready)(void *user, tt_scan *scan);
    /* the lines ran and the outputs were written (status: how that went; lines_done 0:
     * nothing written): the caller's own outputs; a failure it returns becomes the run's
     * when the run had none */
    int (*finished)(void *user, tt_scan *scan, int status);
    /* the estimate ran (or not: r->estimate_status): the caller's summary, which raises
     * the estimate's warning (tt_run_scan_warn_error) where it wants it among its lines;
     * without it tt_run_scan raises the warning */
    void (*summary)(void *user, const tt_scan *scan, const tt_run_scan_result *r);
    /* the caller's own files (the program's scope.csv and scope.png), written with the
     * folder's on the scan's threads once the lines ran, beside the estimate's companion
     * lines: files(user, scan, -1, NULL) says how many (0: none), then files(user, scan,
     * j, &written) writes file j of them (the longest first), on any thread, each j once,
     * counting what it wrote; also after another file failed, whose failure is the one
     * reported (the folder's before the caller's), before finished */
    int (*files)(void *user, const tt_scan *scan, int j, int *written);
} tt_run_scan_job;
struct tt_run_scan_result {
    tt_scan *scan;            /* the caller frees it (tt_scan_free); NULL when refused */
    tt_run_scan_cost cost;
    int written;              /* files written into the folder */
    int oscillating;          /* the oscillation warning was raised */
    double scan_seconds;      /* wall time to the outputs written, s (the estimate's
                               * companion lines run beside them: seconds - scan_seconds
                               * is what they took past the files) */
    double seconds;           /* the whole run's, the estimate included, s */
    int estimate_status;      /* TT_OK: est holds the estimate; -1: it did not run (not
                               * asked for, or the run failed); else why it failed */
    tt_scan_error est;
    double cpu_seconds;       /* the whole run's process CPU time, the estimate's included, s */
};
int tt_run_scan(const tt_scene *s, const tt_run_scan_job *job, tt_run_scan_result *r);

/* The scan a line at a time, for a caller that steps it on its own clock (tiptap live):
 * tt_run_scan's scan, checks and warnings, with the lines run one by one. begin makes
 * the scan (tt_run_scan_alloc, one thread: a refusal makes nothing) and raises no
 * warning, so that it may run on another thread than the steps; the first step raises
 * the input warnings of s (tt_run_scan_warn_inputs) and each runs line `line`
 * (tt_scan_step; scope NULL: none); end raises the result warnings of the lines run
 * since the begin or the last end (tt_run_scan_warn_result) and, with scope, the
 * oscillation warning on its line, and returns how many it raised. The scan stays the
 * caller's (r->scan: tt_scan_free). */
typedef struct {
    tt_scan *scan;
    tt_run_scan_cost cost;
    int warned;     /* the input warnings were raised */
    long lines_run; /* since the begin or the last end */
} tt_run_scan_lines;
int tt_run_scan_begin(const tt_scene *s, tt_run_scan_lines *r);
int tt_run_scan_step(tt_run_scan_lines *r, const tt_scene *s, long line, tt_scan_scope *scope);
int tt_run_scan_end(tt_run_scan_lines *r, const tt_scan_scope *scope, const char *files);

/* The outputs of `tiptap scan -o DIR` can be written: every file it writes (and every
 * channel's, which it may remove) is no input of the scene and no folder. */
int tt_run_scan_check_outputs(const char *dir, const tt_scan *scan, int hdf5);
/* Every channel, trace and retrace, with the run's parameters as metadata: GSF and PNG
 * files (CHANNEL_trace.gsf, ...), one .gwy holding them all (scan.gwy), profile.csv
 * (the profile line) and with hdf5 scan.h5 (docs/hdf5.md), each under a temporary name
 * and renamed, on up to threads threads (0: all cores; the same bytes on any number);
 * *written counts the files. After a failure the other files are still written, and the
 * first failing file in the order above is the one reported. */
int tt_run_scan_write_outputs(const tt_scan *scan, const tt_scene *scene, const char *dir,
                              int hdf5, int threads, int *written);
/* The scan as one HDF5 file at path, with the same metadata and the effective scene. */
int tt_run_scan_write_hdf5(const tt_scan *scan, const tt_scene *scene, const char *path);
/* The path of channel ch's image file in dir: retrace r, PNG (png) or GSF. */
void tt_run_scan_channel_file(char *buf, size_t len, const char *dir, int ch, int r, int png);

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
