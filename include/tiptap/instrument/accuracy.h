/* tiptap: the work-precision study of the solvers: how accurate each method is at
 * each setting of its accuracy knob, and what that costs in run time.
 *
 * The study judges one of two things, chosen from its subject:
 *  - a steady point (TT_ACCURACY_POINT): the cantilever starts in its free steady
 *    oscillation at one rest separation and runs a fixed number of cycles; the last
 *    cycle's amplitude, phase, mean deflection, peak force and tip-sample dissipation
 *    are the observables;
 *  - a scan line (TT_ACCURACY_LINE, subjects with a scan): a short segment of one
 *    line, with the scan's pixel size and time per pixel; the observables are the
 *    height and phase profiles (trace, and retrace if the scan records it).
 * Every setting of every ladder starts from the same state and runs the same cycles,
 * so the differences are integration errors alone. Errors are measured against a
 * reference run (dopri5 at ref_tolerance); the reference's own error is bounded by
 * comparing it with a second one at check_tolerance: the floor, below which no error
 * of the study can be told from zero.
 *
 * The ladders come from one table, one row per method and tier (tt_accuracy_ladders):
 * a new method joins the study with one row naming its [solver] knob and its values.
 * A scan line is also judged on the envelope tier (ladder "envelope": dopri5 cycles
 * between skipped ones, [solver] tier = envelope), against the same every-cycle
 * reference; a steady point has no tiers, and leaves that ladder out.
 *
 * Usage:
 *   tt_accuracy_params_default(&p);
 *   tt_accuracy_alloc(&a, &subject, &p);   (or tt_config_accuracy_alloc from a scene)
 *   while (!tt_accuracy_done(a)) { tt_accuracy_iterate(a, &row); ... }
 *   tt_accuracy_cheapest(a, -1, 1e-4); ...
 *   tt_accuracy_free(a);
 *
 * Ownership: tt_accuracy_alloc borrows nothing of the subject: it keeps its own copy
 * (the scan's materials included). The ladders given in the
 * parameters must outlive the study. Rows, observables and reference data belong to
 * the study and live until tt_accuracy_free.
 */
#ifndef TIPTAP_ACCURACY_H
#define TIPTAP_ACCURACY_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/physics/material.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

/* One method's ladder: the [solver] key it varies and its values, loosest first. */
typedef struct {
    tt_method method;
    const char *knob;      /* [solver] key: "tolerance", "steps_per_cycle" */
    const double *values;
    size_t nvalues;
    tt_tier tier;          /* TT_TIER_EVERY (0), or TT_TIER_ENVELOPE: scan lines only */
    const char *name;      /* what tables, plots and --methods call it; NULL: the
                            * method's name */
} tt_accuracy_ladder;

/* The ladder's name: its own, else its method's. */
const char *tt_accuracy_ladder_name(const tt_accuracy_ladder *l);

/* The built-in table (static storage). */
const tt_accuracy_ladder *tt_accuracy_ladders(size_t *count);
/* The ladders named in list ("dopri5, rk4", by tt_accuracy_ladder_name), in its order,
 * copied into out (at most max): TT_EINVAL with one line for an unknown name (listing
 * the known), too many names, or none. */
int tt_accuracy_pick(const char *list, tt_accuracy_ladder *out, size_t max, size_t *n);

typedef enum { TT_ACCURACY_AUTO = 0, TT_ACCURACY_POINT = 1, TT_ACCURACY_LINE = 2 } tt_accuracy_kind;

typedef struct {
    tt_accuracy_kind kind;  /* AUTO: a line when the subject has a scan, else a point */
    double point;           /* point: rest separation, m; NAN: the subject's approach
                             * point when it has one, else 0.8 times the free amplitude */
    long cycles;            /* point: cycles from the free state; 0: Q ln(1e8) / pi, when
                             * the free transient has decayed to 1e-8 */
    long line_pixels;       /* line: pixels of the segment (default 8) */
    int repeats;            /* timing passes over the ladders (default 3): a setting's time
                             * is the best of its runs, spread over the study so that a
                             * burst of load from other programs spoils few of them ... */
    double repeat_below;    /* ... and a run is repeated only if it took less than this, s (0.5) */
    int cpu_clock;          /* 1: "cheapest" compares CPU times (steadier on a shared
                             * machine), 0: wall-clock run times (default) */
    double ref_tolerance;   /* the reference: dopri5 at this tolerance (1e-13) */
    double check_tolerance; /* the second reference that bounds its error (1e-12) */
    const tt_accuracy_ladder *ladders; /* NULL: the built-in table */
    size_t nladders;
} tt_accuracy_params;

void tt_accuracy_params_default(tt_accuracy_params *p);

typedef enum {
    TT_ACCURACY_REFERENCE = 0, /* the reference itself (errors 0) */
    TT_ACCURACY_FLOOR = 1,     /* the check reference: its errors are the floor */
    TT_ACCURACY_SETTING = 2    /* a ladder setting */
} tt_accuracy_role;

/* The names the table gives a row's role ("reference", "floor", "setting") and tier
 * ("every", "envelope", "averaged"). */
const char *tt_accuracy_role_name(tt_accuracy_role r);
const char *tt_accuracy_tier_name(tt_tier t);

#define TT_ACCURACY_MAX_OBS 5

/* A line's observables, by their index in err (a point's: amplitude, phase, mean, peak
 * force, dissipation, in tt_accuracy_observables' order). */
enum {
    TT_ACCURACY_HEIGHT_MAX = 0,
    TT_ACCURACY_HEIGHT_RMS = 1,
    TT_ACCURACY_PHASE_MAX = 2,
    TT_ACCURACY_PHASE_RMS = 3
};

typedef struct {
    tt_accuracy_role role;
    int is_default;          /* the subject's own solver setting (added if not on a ladder) */
    const char *name;        /* its ladder's name (static or the ladder's): one curve each */
    tt_method method;
    tt_tier tier;            /* the tier it ran on (a line; TT_TIER_EVERY for a point) */
    const char *knob;        /* static or the ladder's */
    double value;
    int status;              /* TT_OK, or why this setting failed (then errors are NAN) */
    char message[256];
    double run_time;         /* s, wall clock of the integration, best of the repeats */
    double cpu_time;         /* s, CPU time of the same, best of the repeats */
    int runs;                /* how many runs the times are the best of */
    double steps_per_cycle;  /* accepted steps per cycle (NAN for a line: not counted) */
    double integrated;       /* line: the fraction of cycles integrated (1 on the every-
                              * cycle tier, and where the envelope tier fell back); NAN
                              * for a point */
    double residual_rel;     /* the run's own error estimate: largest energy-balance
                              * residual of a cycle / free drive work per cycle */
    double err[TT_ACCURACY_MAX_OBS]; /* per observable, against the reference */
    double primary;          /* err[0] as a fraction: relative amplitude error (point);
                              * largest height error / free amplitude (line) */
} tt_accuracy_row;

typedef struct {
    const char *column;      /* CSV column, SI: "amplitude_err_rel", "height_err_max_m" */
    const char *label;       /* axis label */
} tt_accuracy_observable;

/* What the study judges: a cantilever with its own solver setting (the default row),
 * one material under the tip for a point, and the scan whose segment is a line. */
typedef struct {
    tt_cantilever cantilever;
    tt_solver solver;
    tt_material material;    /* point: the sample under the tip */
    int has_scan;            /* whether scan is given (AUTO then judges a line) */
    tt_scan_params scan;     /* line: its materials are copied by tt_accuracy_alloc */
    double approach_point;   /* the rest separation of a one-point approach, m; NAN: none */
} tt_accuracy_subject;

typedef struct tt_accuracy tt_accuracy;

/* TT_EINVAL with a message for a bad subject (a material whose force law cannot be
 * made, a ladder with an unknown knob). */
int tt_accuracy_alloc(tt_accuracy **out, const tt_accuracy_subject *subject,
                      const tt_accuracy_params *p);
void tt_accuracy_free(tt_accuracy *a);

tt_accuracy_kind tt_accuracy_kind_of(const tt_accuracy *a);
/* Observables of this kind of study; index 0 is the primary one. */
size_t tt_accuracy_observables(const tt_accuracy *a, const tt_accuracy_observable **obs);

/* Rows in order: reference, floor, then each ladder loosest first. */
size_t tt_accuracy_rows(const tt_accuracy *a);
int tt_accuracy_done(const tt_accuracy *a);
/* Do the next unit of work; *row points to the row it concerns. In the first pass
 * that is a new row. A setting that fails (rk4 too coarse for the contact, NaN) is a
 * row with its status and message, and TT_OK is returned; a failing reference or
 * TT_EINTR (cancel.h) ends the study. The later passes time cheap rows again
 * (row->runs counts the runs its times are the best of). */
int tt_accuracy_iterate(tt_accuracy *a, const tt_accuracy_row **row);
/* The pass under way: 1 while rows are computed, then 2 .. repeats. */
int tt_accuracy_pass(const tt_accuracy *a);
const tt_accuracy_row *tt_accuracy_row_at(const tt_accuracy *a, size_t i);

/* The setting to recommend for a target accuracy of the primary observable: for one
 * ladder (by name, "dopri5", "envelope"), its loosest setting from which on every
 * tighter finished setting of that ladder meets the target (one lucky setting does not
 * count); for name NULL, the fastest of the ladders' choices (by the clock of the
 * parameters). NULL if none. */
const tt_accuracy_row *tt_accuracy_cheapest(const tt_accuracy *a, const char *name, double target);
/* The subject's own setting. */
const tt_accuracy_row *tt_accuracy_default_row(const tt_accuracy *a);

/* What was judged. */
double tt_accuracy_point(const tt_accuracy *a);          /* rest separation, m (point) */
long tt_accuracy_cycles(const tt_accuracy *a);           /* cycles per run (point) */
long tt_accuracy_line_pixels(const tt_accuracy *a);      /* pixels (line) */
double tt_accuracy_free_amplitude(const tt_accuracy *a); /* m */
/* The reference's last cycle (point; NULL before the reference ran or for a line). */
const tt_cycle *tt_accuracy_reference_cycle(const tt_accuracy *a);
/* The reference's amplitude change over its last cycle relative to the free amplitude:
 * how far from steady the judged cycle still is (point). */
double tt_accuracy_reference_drift(const tt_accuracy *a);
/* The reference profiles (line): height trace then retrace (m), then phase trace then
 * retrace (deg); n values in all. */
const double *tt_accuracy_reference_profile(const tt_accuracy *a, size_t *n);

TT_END_DECLS
#endif
