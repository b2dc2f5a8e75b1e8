/* tiptap bench's imaging figures (bench_imaging.c) and its noise figure (bench_noise.c).
 *
 * A figure scans a sample: a scene, assignments on top of it (section.key=value, as
 * --set takes them), and a function that makes the scan's parameters from the result
 * (two lines through the sample's features, height and phase, trace and retrace).
 * Each row of a figure adds its own assignments (a tier, a tolerance, noise), so a
 * value this build's scene layer does not know (a tier still to come) is refused by
 * the scene layer, not by the compiler, and an optional row says so and is skipped.
 *
 * Ownership: bench_params_make fills a bench_params that bench_params_free releases;
 * bench_run_scan fills a bench_run (its images) that bench_run_free releases.
 */
#ifndef TIPTAP_CLI_BENCH_H
#define TIPTAP_CLI_BENCH_H

#include <stddef.h>

#include "tiptap/config/scene.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/physics/material.h"

/* The lines a figure scans: 0 and 0 keep the sample's own. */
typedef struct {
    long pixels;
    double line_rate; /* Hz */
    int repeat;       /* time a run under a second again, up to five runs, keeping the best */
} bench_lines;

/* A scan's parameters; p.materials may point into mat (the edge sample's two). */
typedef struct {
    tt_scan_params p;
    const tt_material *own; /* what tt_config_scan allocated */
    tt_material mat[2];
} bench_params;

typedef struct bench_sample bench_sample;
struct bench_sample {
    const char *title;        /* the figure's heading, after "# " */
    const tt_scene *scene;
    const char *set[10];      /* the sample's assignments, NULL after the last */
    bench_lines lines;
    /* The sample's scan from the scene with every assignment applied. */
    int (*make)(const tt_scene *s, const bench_lines *l, bench_params *bp);
};

typedef struct {
    const char *label;
    const char *set[6]; /* the row's assignments, NULL after the last */
    int optional;       /* refused by the scene layer: printed as not available */
} bench_row;

/* One timed scan: wall and CPU seconds, instrument time, the share of cycles
 * integrated, the energy-balance check, the companion's estimate (when asked), and
 * the height (m) and phase (deg) images of trace and retrace. */
typedef struct {
    double wall, cpu, inst, err_est, integrated;
    long cycles, cycles_integrated;
    tt_scan_error est;
    double *img[2][2]; /* [height, phase][trace, retrace] */
    long pixels, lines;
} bench_run;

/* The scene with the sample's and the row's assignments, made into a scan's
 * parameters. On failure the library's message says why. */
int bench_params_make(const bench_sample *s, const char *const *row_set, bench_params *bp);
void bench_params_free(bench_params *bp);

/* A scan on threads threads, timed (again up to five runs under a second when
 * l->repeat, keeping the best times), its estimate when estimate is set. */
int bench_run_scan(const tt_scan_params *p, int threads, int estimate, int repeat, bench_run *out);
void bench_run_free(bench_run *r);

/* The imaging figure of a sample: rows[0] is the reference the others are judged
 * against; j1: time each row on one thread too. *ref (when not NULL) keeps the
 * reference's run for the caller, who frees it. */
int bench_imaging_figure(const bench_sample *s, const bench_row *rows, size_t n, int j1, bench_run *ref);

/* The samples: the edge sample of the first imaging figure (the standard scene's
 * polymer as a soft matrix around stiff disks on 1 nm steps), the README's main job
 * (scans/quick.ini and surfaces/polymer-blend.ini, two of its lines) and the standard
 * scene at Q 1e4 (examples/extreme/vacuum-q1e4.ini's quality factor) over 0.5 nm steps. */
int bench_edge_sample(const tt_scene *s, const bench_lines *l, bench_params *bp);
int bench_plain_sample(const tt_scene *s, const bench_lines *l, bench_params *bp);
/* The schema's default of [solver] tier ("envelope"): the tier of the bench's scenes,
 * which do not set it. */
const char *bench_default_tier(void);
/* The README main job's scene: scans/quick.ini followed by surfaces/polymer-blend.ini. */
const char *bench_blend_scene(void);

/* The largest and rms difference of channel c (0 height, 1 phase) between a and ref,
 * trace and retrace. */
void bench_image_error(const bench_run *a, const bench_run *ref, int c, double *max, double *rms);
/* The estimate tables (the run's own estimate against the measured error): the header,
 * its first column named first, and a row of est and meas, each [h rms, h max, ph rms,
 * ph max] (m, deg), printed in pm and deg; 1 where a max estimate lies below the
 * measured (its check says BELOW). */
void bench_estimate_header(const char *first);
int bench_estimate_row(const char *label, const double est[4], const double meas[4]);

/* The noise figure on a sample: each noise set on the every-cycle tier and on the
 * scene's default tier, seeds 1 to seeds, against the noise-free reference ref. */
int bench_noise_figure(const bench_sample *s, const bench_run *ref, int seeds);
/* The error estimate with noise on a sample: thermal and detector noise on the default
 * tier at tolerance 1e-8, seeds 1 to seeds (at most 3), its estimate against the same
 * lines at tolerance 1e-11 (the same tier and seed: the every-cycle tier draws its own
 * noise). */
int bench_noise_estimate(const bench_sample *s, int seeds);

/* The lesson figure: the teaching scene (bench_lesson_scene) at each of the lesson's
 * settings, lines 0 to lines - 1 stepped one at a time on the default tier and on the
 * every-cycle tier (quick: the last, 40 Hz lines, only; only > 0: that setting alone,
 * counted from 1). */
const char *bench_lesson_scene(void);
/* own_tier: the lesson's tier (envelope or averaged; NULL: the default), with the
 * tier's own error besides, both tiers again with the noise 1e9 times colder. */
int bench_lesson_figure(long lines, int quick, int only, const char *own_tier);

#endif
