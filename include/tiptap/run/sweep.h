/* tiptap: sweeps run: what `tiptap sweep` computes for each combination of a grid
 * (tiptap/config/sweep.h), as rows of a table (tiptap/util/table.h), and the whole sweep
 * in memory for callers that want its table (the Python package) or an HDF5 file.
 *
 * A combination's rows: steady, its steady point at [approach] from; setpoint, the
 * steady point whose amplitude is the [feedback] setpoint; approach, its approach
 * curve's points; scan, a summary row of its scan for all pixels and for each material
 * (the one at each pixel's centre). Each begins with the combination's number (from 1)
 * and the varied keys' values (in SI, or the text for keys whose values are text).
 * Each combination is computed from its own fresh scene, setup and simulation, so its
 * rows depend on nothing but the combination.
 *
 * Ownership: the grid and tables are the caller's; a table made by tt_run_sweep or
 * tt_run_sweep_columns is freed with tt_table_free.
 */
#ifndef TIPTAP_RUN_SWEEP_H
#define TIPTAP_RUN_SWEEP_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/sweep.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/run/run.h"
#include "tiptap/util/table.h"

TT_BEGIN_DECLS

typedef enum { TT_SWEEP_STEADY, TT_SWEEP_SETPOINT, TT_SWEEP_APPROACH, TT_SWEEP_SCAN } tt_sweep_kind;

/* "steady", "setpoint", "approach", "scan"; -1 when unknown. */
int tt_sweep_kind_parse(const char *name, tt_sweep_kind *kind);
const char *tt_sweep_kind_name(tt_sweep_kind kind);

/* The found column of a setpoint row whose setpoint was not reached (the row holds the
 * closest point the search found). */
#define TT_SWEEP_UNREACHABLE "unreachable"
/* The found column of a point that settled into a periodic orbit of n > 1 cycles (its
 * row: the means over the orbit's period, which the period column gives), and of one
 * where no period up to TT_SETTLE_MAX_PERIOD was found within [approach] max_cycles
 * (the means over its last TT_SETTLE_WINDOW cycles; period 0). */
#define TT_SWEEP_PERIODIC "periodic"
#define TT_SWEEP_UNSETTLED "unsettled"
/* The found column of an approach sweep's rows in ramp mode: one cycle each of the
 * moving sample (period 0). */
#define TT_SWEEP_RAMP "ramp"

/* An empty table with the columns of kind's rows: combination; each varied key (unit
 * tt_sweep_unit; a text column for keys whose values are text); setpoint (m) for
 * setpoint sweeps; then z (m), amplitude (m), phase (deg), mean_deflection (m),
 * peak_force (N), max_indentation (m), contact_fraction, dissipated (J), drive_work (J),
 * energy_residual, regime (free, attractive, repulsive, failed), direction, settled,
 * cycles, period (cycles; 1 steady, n > 1 a period-n orbit, 0 none found), found
 * (newton, settled, periodic, unsettled, unreachable, ramp, failed); or for scans folder (the
 * combination's folder name, "0001"), lines_done, error_estimate, material, pixels,
 * height_mean, height_std (m), phase_mean, phase_std (deg), height_contrast (m),
 * phase_contrast (deg): against the first material. */
int tt_run_sweep_columns(const tt_sweep *grid, tt_sweep_kind kind, tt_table **out);

/* Check combination i before anything runs: its scene and every configuration the run
 * reads (without building force tables). One line naming the combination on failure. */
int tt_run_sweep_check(const tt_sweep *grid, tt_sweep_kind kind, size_t i);

/* Append combination i's rows (steady, setpoint, approach) to t. A combination whose
 * solver fails gives a row saying so (regime failed), not an error; TT_EINTR when
 * cancelled part way (its rows are then incomplete: drop them). */
int tt_run_sweep_points(const tt_sweep *grid, tt_sweep_kind kind, size_t i, tt_table *t);

/* Append the summary rows of combination i's finished scan (its scene) to t: the
 * energy balance (tt_scan_error_estimate: a check), the error estimate's height and
 * phase (est's largest, tt_scan_estimate_error; NaN where est is NULL). */
int tt_run_sweep_scan_rows(const tt_sweep *grid, size_t i, const tt_scene *scene,
                           const tt_scan *scan, const tt_scan_error *est, tt_table *t);

/* Raise the TT_WARN_SETTLE warnings (tiptap/util/warning.h) of a steady, setpoint or
 * approach sweep's table: how many rows are found=periodic and found=unsettled, and in
 * which combinations. tt_run_sweep raises them itself. */
void tt_run_sweep_warn(const tt_table *t);

/* The whole sweep: every combination checked, then computed (points on threads
 * threads, 0: all cores; scans one at a time, their lines on threads threads), the rows
 * in combination order. progress after each combination. TT_EINTR keeps the
 * combinations finished before the first one unfinished in *out. */
int tt_run_sweep(const tt_sweep *grid, tt_sweep_kind kind, int threads, tt_table **out,
                 tt_progress_fn progress, void *user);

/* The sweep's table as an HDF5 file (docs/hdf5.md): each column a dataset over the
 * grid, one dimension per varied key with its values as a dimension scale (plus a
 * row dimension for approach curves and scans), the base scene's keys as attributes
 * and its effective scene as text. */
int tt_run_sweep_hdf5(const char *path, const tt_sweep *grid, tt_sweep_kind kind,
                      const tt_scene *base, const tt_table *t);

TT_END_DECLS
#endif
