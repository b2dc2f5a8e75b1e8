/* The scan's private state, shared by its line loops: scan.c (every cycle) and
 * scan_envelope.c (the envelope tier), and the per-cycle steps they share
 * (scan_cycle.c). Private to libtiptap. */
#ifndef TIPTAP_SCAN_PRIVATE_H
#define TIPTAP_SCAN_PRIVATE_H

#include <stdint.h>

#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/solver/averaged.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/solver/graze.h"
#include "tiptap/solver/noise.h"

enum { NHARM = TT_CH_HARMONIC_MAX - 1 }; /* harmonic channels of each kind */
_Static_assert(TT_CH_COUNT <= 8 * sizeof(unsigned), "a channel mask holds every channel");

/* One thread's workspace: its own simulation, lock-in and sample buffer. */
typedef struct {
    tt_sim *sim;
    double tolerance; /* its solver's: the companion's is tighter than the scan's */
    double model_tol; /* the envelope tier's model's per cycle, relative to A0 */
    tt_lockin *lockin;
    tt_sample *samples;
    double *y; /* the lock-in block's periods: samples, or on the envelope tier each
                * period's components (tt_lockin_transform) */
    /* continuous lines: the feedback and the z piezo's ramp where the last line ended */
    int engaged;
    tt_feedback fb;
    double z_from, z_to;
    tt_piezo pz;
    double z_act;
    double zn; /* the z piezo's noise */
    /* the envelope tier (NULL: every cycle): its model, a snapshot of the lock-in and
     * of the block's periods (y) to roll back to, and two observable vectors */
    tt_envelope *env;
    tt_graze *graze; /* the touch branch of a grazing tip (the free one: env) */
    int env_shape;   /* the noise the model was made for (scan.c, model_shape) */
    tt_lockin *lockin_save;
    double *y_save, *obs;
    /* the greatest indentation of the trace and retrace cycles, per material */
    double *indent;
    /* the averaged tier (averaged: on): its slow state where the last line ended */
    int averaged;
    tt_averaged_state avg;
    /* the rest separation at z = 0 of the line's engage: continuous lines keep the
     * first engage's, so that a new setpoint does not move the sample */
    double s_ref;
    /* the scope the line under way records into (NULL: none) */
    tt_scan_scope *scope;
    /* the error estimate's companion line stops after this many cycles (0: never), so
     * that it costs a bounded share of the scan; budget_hit says it stopped there */
    long budget;
    int budget_hit;
    /* and engages and starts its trace at this cycle of the direction (0: the line's
     * start), so that its stretch lies where the image is hardest */
    long k0;
} worker;

/* A line stopped at its worker's cycle budget: its pixels so far are kept. */
enum { TT_SCAN_BUDGET = 100 };

struct tt_scan {
    tt_cantilever cantilever;
    tt_solver solver;
    size_t nmaterials;
    tt_contact **contacts; /* every material's force law, shared by the threads */
    double *Qi;
    double *contact_R;     /* each force law's radius, m */
    char (*names)[128];    /* each material's name, for messages */
    double *indent;        /* the greatest indentation recorded in each material, m */
    tt_raster raster;
    tt_surface *surface;
    tt_dilation *dilation; /* the surface as the tip's shape images it; NULL: the apex */
    tt_instrument_params inst;
    int plain;             /* a point tip on an ideal instrument: the heights as they are */
    int uniform, flat;
    unsigned channels;
    long settle_cycles;
    long profile_line;
    tt_scan_noise noise;
    double sd;           /* per-sample detector noise, m rms */
    tt_noise_ou zn;      /* the z piezo's noise, sampled at each drive cycle's start (sd 0: off) */
    int continuous;
    /* lock-in and feedback */
    tt_lockin_params lockin;
    double setpoint, kp, ki, z_range;
    double A0;
    /* results: [retrace][channel] -> lines * pixels */
    double *img[2][TT_CH_COUNT];
    char *line_done;
    long lines_done;
    long cycles;
    long integrated; /* cycles integrated (the envelope tier skips some) */
    double worst_residual;
    int clamped;
    /* the averaged tier: each material's table, and the pixels where the tip collapsed
     * onto the sample or left the table (first: the first such line and pixel) */
    tt_averaged **avg;
    double avg_seconds, avg_error;
    long collapsed, outside, collapse_line, collapse_px;
    /* the first failure of any thread */
    int status;
    char message[1024];
    /* tt_scan_step's workspace (NULL until the first stepped line), and the line
     * tt_scan_run records into a scope (watch_line -1: none) */
    worker *step;
    long watch_line;
    tt_scan_scope *watch;
};

/* Per-pixel sums of one scan direction. */
typedef struct {
    double sum[TT_CH_COUNT]; /* harmonic phases: the in-phase parts, X = A cos(phase) */
    double quad[NHARM];      /* harmonic phases: the quadrature parts, Y = A sin(phase) */
    long n;    /* cycles, for the per-cycle channels */
    long nblk; /* cycles of the lock-in blocks that ended in this pixel */
} pixel_acc;

/* Where a line's pixels go: the scan's images, or (packed) one line's worth per
 * channel and direction. */
typedef struct {
    double *img[2][TT_CH_COUNT];
    int packed;
} line_out;

/* The instrument's clock at the start of cycle k of phase 0 (settling), 1 (trace) or
 * 2 (retrace); the sample under raster position (x, y) at time t (scan.c). */
double tt_scan_clock_at(const tt_scan *S, long line, int phase, long nc, long k);
double tt_scan_sample_at(const tt_scan *S, double *x, double *y, double t, double *topo);

/* The surface at a cycle's start: the height the apex meets, the true height and the
 * material (k < 0: none found). */
typedef struct {
    long k;
    double h, topo;
    size_t mat;
} surf_pt;

/* What a line carries from cycle to cycle, and from line to line (continuous lines):
 * what the envelope tier's rollback restores. */
typedef struct {
    long k; /* the next cycle of this phase */
    tt_feedback fb;
    double z_from, z_to, z_act; /* the z piezo's command ramp and actual height */
    tt_piezo pz;
    double zn;        /* the z piezo's noise at cycle k's start, m (drawn in cycle_begin) */
    size_t current;   /* the material on the sim */
    double x[2];      /* the tip's state at cycle k's start: the sim's, or the model's */
    double x2[2];     /* the second-order part of a model's x (0 after an integration) */
    surf_pt ahead[2]; /* the surface at the next two cycles' starts */
    long cycles;      /* the line's cycles so far (the noise's cycle count) */
    double worst;
    int clamped;
} line_state;

/* One cycle's inputs: the surface at its start and end, the z piezo's command at its
 * start, and the sample's position (separation at rest) at its start and end. */
typedef struct {
    long k; /* the cycle of this phase */
    int j;  /* its place in the lock-in block */
    double ha, hb, topo, za, sa, sb;
    double zn; /* the z piezo's noise in sa, sb at the cycle's middle (0: none) */
    size_t mat, mat_next;
    int edge_next; /* the next cycle crosses an edge (edge heights or materials) */
} cycle_in;

/* A line's fixed quantities within a phase. */
typedef struct {
    tt_scan *S;
    worker *W;
    long line, nc, ncyc; /* cycles per direction; of this phase */
    long k0;             /* the trace's first cycle (worker k0) */
    int phase, dir, P, N, piezo;
    double s_ref;
    double tol, edge; /* the envelope tier's error per cycle and edge height */
    double rel;       /* and with noise on, its error per reach of the inputs from the anchor */
    double reach;     /* the largest reach of the second-order model's stretches, of A0 (0: any) */
    double retake;    /* the reach from where its derivatives were taken past which they are
                       * recalled or taken anew, of A0 (0: carried on) */
    uint64_t kd;      /* the every-cycle tier's detector noise key */
    uint64_t kz;      /* the z piezo noise's key (both tiers draw the same) */
    uint64_t ke;      /* the envelope tier's noise key (thermal and detector, per cycle) */
    pixel_acc *pix;   /* [direction][pixel] */
} line_ctx;

/* A tier's cycles of one phase (L->phase), from st (k = 0). */
typedef int (*scan_phase_fn)(const line_ctx *L, line_state *st, void *tier);

/* One line (scan.c): engage at its first pixel, settle, trace and retrace, each phase's
 * cycles run by the tier's run; the pixels' means into out. */
int tt_scan_line_run(tt_scan *S, worker *W, long line, const line_out *out, scan_phase_fn run,
                     void *tier, long *cycles, double *worst, int *clamped);

/* The per-cycle steps both tiers share (scan_cycle.c). */
/* A cycle starts: the inputs of cycle st->k, or TT_EINTR when the run is cancelled;
 * advances the piezo. The surface is found one cycle further ahead than the cycle
 * needs (edge_next) and kept in st->ahead for the next cycles. */
int tt_scan_cycle_begin(const line_ctx *L, line_state *st, cycle_in *in);
/* Integrate the cycle from the sim's state, its material set on the sim first. */
int tt_scan_integrate(const line_ctx *L, line_state *st, const cycle_in *in, tt_cycle *cy);
/* A cycle ends (its deflection samples in W->y): its per-cycle channels into its
 * pixel's sums (trace, retrace), and at the end of a lock-in block, the lock-in, the
 * feedback and the block's outputs into the pixel of its last cycle; on to the next. */
int tt_scan_cycle_end(const line_ctx *L, line_state *st, const cycle_in *in, double peak,
                      double indent, double ets);

/* The surface at the start of cycle k of the phase (scan_cycle.c). */
surf_pt tt_scan_surface_at(const line_ctx *L, long k);
/* The end of lock-in block b (its periods in W->y: samples, or components on the
 * envelope and averaged tiers): demodulate, update the feedback, and (trace, retrace)
 * add the lock-in's outputs to the pixel of the block's last cycle (scan_cycle.c). */
int tt_scan_block_end(const line_ctx *L, line_state *st, long b);

/* A worker's buffers freed (scan.c). */
void tt_scan_worker_free(worker *W);
/* A worker made to fit the scan's noise after a change (scan.c): the thermal force on
 * its sim, the envelope tier's model made anew where the noise changes its inputs or
 * order (z piezo noise: the travel; thermal or z piezo: second order) and its noise. */
int tt_scan_worker_retune(tt_scan *S, worker *W);
/* The z piezo's noise of n for the cantilever's drive period (sd 0: off); TT_EINVAL naming
 * [noise] z_piezo_bandwidth when its band is not within (0, fd / 2]. */
int tt_scan_piezo_noise(const tt_scan_noise *n, const tt_cantilever *c, tt_noise_ou *zn);

/* The scope (scan_scope.c): made ready for line `line` before it runs (its points NaN),
 * block b's point written at the block's end from the lock-in's filtered amplitude A
 * and phase ph (rad) after the feedback's update, and closed after the line (ok: the
 * line finished; else the scope holds none). */
int tt_scan_scope_begin(tt_scan_scope *sc, const tt_scan *S, long line);
void tt_scan_scope_put(const line_ctx *L, const line_state *st, long b, double A, double ph);
void tt_scan_scope_end(tt_scan_scope *sc, int ok);

/* One line on the averaged tier (scan_averaged.c), through tt_scan_line_run; it
 * integrates no cycle. */
int tt_scan_line_averaged(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          double *worst, int *clamped);

/* One line on the envelope tier (scan_envelope.c), through tt_scan_line_run;
 * *integrated counts the cycles integrated, the rest followed the model. */
int tt_scan_line_envelope(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          long *integrated, double *worst, int *clamped);

#endif
