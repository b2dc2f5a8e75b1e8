/* tiptap: the full-rate record of one scan line, the instrument's scope (docs/imaging.md,
 * "The scope").
 *
 * A pixel is a mean; the scope is what the loop saw. It holds one point per lock-in
 * block, the rate at which the feedback runs (the loop's own rate: drive frequency /
 * [lockin] periods_per_block, 75 kHz on the standard scene), for the trace and the
 * retrace of the line it recorded, each point at the block's end:
 *
 *   time       the instrument's clock (s): line n starts at n / line_rate, its trace
 *              takes the first half of the line's period, its retrace the second
 *   position   the tip along the fast axis (m), 0 at the trace's start
 *   z          the z piezo's command (m), the height channel's signal: it ramps
 *              linearly from one point to the next, and a pixel's height is the mean of
 *              that ramp over the pixel's cycles
 *   error      the filtered lock-in amplitude minus the setpoint (m), what the PI loop
 *              integrates; a pixel's error is the mean of its points (those whose block
 *              ends in it), exactly
 *   amplitude  the filtered lock-in amplitude (m); a pixel's amplitude: the same mean
 *   phase      the filtered lag of the deflection behind the drive (deg); the same mean
 *   surface    the true surface height under the tip's axis (m), the topography channel's
 *              signal (no dilation, tilt or drift)
 *   pixel      the pixel (0 .. pixels - 1, counted along the trace) whose lock-in
 *              channels the point goes into: that of the block's last cycle
 *   material   the material under the tip (its index in the scan's materials)
 *   followed   the height the apex meets (m): the surface as the tip's shape images it
 *              (its dilation), with the tilt and the z drift; what z can follow, and
 *              what the oscillation check measures z against (the surface itself for a
 *              point tip on an untilted, undrifting sample)
 *
 * It costs nothing unless asked for: a scope passed to tt_scan_step, or attached to a
 * line of tt_scan_run, is filled; without one the line loops do not look.
 *
 * Ownership: the caller allocates a scope (tt_scan_scope_alloc) and frees it
 * (tt_scan_scope_free); the scan only writes into it while a line runs, and keeps no
 * reference after tt_scan_step returns. An attached scope (tt_scan_scope_attach) must
 * outlive the runs it is attached for, or be detached. The series belong to the scope
 * and stay valid until its next line or its free; a scope may be filled from any scan
 * (it grows to the longest line). Not for two threads at once.
 */
#ifndef TIPTAP_SCAN_SCOPE_H
#define TIPTAP_SCAN_SCOPE_H

#include "tiptap/export.h"
#include "tiptap/instrument/scan.h"

TT_BEGIN_DECLS

enum {
    TT_SCOPE_TIME,
    TT_SCOPE_POSITION,
    TT_SCOPE_Z,
    TT_SCOPE_ERROR,
    TT_SCOPE_AMPLITUDE,
    TT_SCOPE_PHASE,
    TT_SCOPE_SURFACE,
    TT_SCOPE_PIXEL,
    TT_SCOPE_MATERIAL,
    TT_SCOPE_FOLLOWED,
    TT_SCOPE_COUNT
};

/* Name ("time", "z", ...) and SI unit ("s", "m", "deg"; "" for the pixel and the material) of a quantity. */
const char *tt_scan_scope_name(int quantity);
const char *tt_scan_scope_unit(int quantity);

int tt_scan_scope_alloc(tt_scan_scope **out);
void tt_scan_scope_free(tt_scan_scope *sc);

/* The line it holds (-1: none yet, or the last one failed). */
long tt_scan_scope_line(const tt_scan_scope *sc);
/* Points of the trace (retrace 0) or the retrace (1); 0 when that direction did not run
 * (a scan without retrace, unless its lines are continuous, which run the retrace). */
long tt_scan_scope_points(const tt_scan_scope *sc, int retrace);
/* One quantity's series (tt_scan_scope_points values), or NULL. */
const double *tt_scan_scope_series(const tt_scan_scope *sc, int retrace, int quantity);
/* Lock-in blocks per second: the rate of the points. */
double tt_scan_scope_rate(const tt_scan_scope *sc);

/* tt_scan_run records line `line` into sc (NULL: none), whichever thread runs it. */
void tt_scan_scope_attach(tt_scan *s, long line, tt_scan_scope *sc);

TT_END_DECLS
#endif
