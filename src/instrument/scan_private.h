/* The line engine's own machinery, shared by its files: one line's context, state and
 * cycles (scan_line.c), the per-cycle steps the tiers share (scan_cycle.c), where the
 * sample is (scan_sample.c), the scope's record (scan_scope.c) and the tiers' lines
 * (scan_line.c every cycle, scan_envelope.c, scan_averaged.c). The scan's drivers see
 * only scan_engine.h. Private to libtiptap. */
#ifndef TIPTAP_SCAN_PRIVATE_H
#define TIPTAP_SCAN_PRIVATE_H

#include "scan_engine.h"

enum { NHARM = TT_CH_HARMONIC_MAX - 1 }; /* harmonic channels of each kind */

/* Per-pixel sums of one scan direction. */
typedef struct {
    double sum[TT_CH_COUNT]; /* harmonic phases: the in-phase parts, X = A cos(phase) */
    double quad[NHARM];      /* harmonic phases: the quadrature parts, Y = A sin(phase) */
    long n;    /* cycles, for the per-cycle channels */
    long nblk; /* cycles of the lock-in blocks that ended in this pixel */
} pixel_acc;

/* The instrument's clock at the start of cycle k of phase 0 (settling), 1 (trace) or
 * 2 (retrace); the sample under raster position (x, y) at time t (scan_sample.c). */
double tt_scan_clock_at(const tt_scan *S, long line, int phase, long nc, long k);
double tt_scan_sample_at(const tt_scan *S, double *x, double *y, double t, double *topo);

/* The surface at a cycle's start: the height the apex meets, the true height, the
 * dilated one (the apex's without tilt or drift) and the material (k < 0: none found). */
typedef struct {
    long k;
    double h, topo, dil;
    size_t mat;
    uint32_t geo; /* the contact's geometry (tt_scan_geometry_key; 0: a flat's) */
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
    uint32_t geo;     /* and the geometry of its law (0: the flat's) */
    double x[TT_SIM_DIM_MAX];  /* the tip's state at cycle k's start (tt_sim_dim of it):
                                * the sim's, or the model's */
    double x2[TT_SIM_DIM_MAX]; /* the second-order part of a model's x (0 after an
                                * integration) */
    surf_pt ahead[2]; /* the surface at the next two cycles' starts */
    long cycles;      /* the line's cycles so far (the noise's cycle count) */
    double worst;
    int clamped;
    /* the loss per mechanism (hysteresis, damping, viscous, J) of the last integrated
     * cycle; fresh: it is the cycle now ending's own (tt_scan_integrate) */
    double loss[3];
    int loss_fresh;
} line_state;

/* One cycle's inputs: the surface at its start and end, the z piezo's command at its
 * start, and the sample's position (separation at rest) at its start and end. */
typedef struct {
    long k; /* the cycle of this phase */
    int j;  /* its place in the lock-in block */
    double ha, hb, topo, dil, za, sa, sb;
    double zn; /* the z piezo's noise in sa, sb at the cycle's middle (0: none) */
    size_t mat, mat_next;
    uint32_t geo; /* the geometry at the cycle's start */
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

/* One line (scan_line.c): engage at its first pixel, settle, trace and retrace, each phase's
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

/* [tip] contact_geometry = local (scan_geometry.c): the key of the geometry where the
 * tip touches at (x, y), rho from its axis, material mat's law's slope and effective radius quantised (0:
 * within the flat's bin); the geometry a key's law is built for; that key's law of mat
 * on W's sim (0: the material's own), built per thread and kept among the last used. */
uint32_t tt_scan_geometry_key(const tt_scan *S, double x, double y, double rho, size_t mat);
tt_contact_geometry tt_scan_geometry_of_key(uint32_t key, double R);
int tt_scan_geometry_use(const tt_scan *S, worker *W, size_t mat, uint32_t key);

/* The surface at the start of cycle k of the phase (scan_sample.c). */
surf_pt tt_scan_surface_at(const line_ctx *L, long k);
/* The end of lock-in block b (its periods in W->y: samples, or components on the
 * envelope and averaged tiers): demodulate, update the feedback, and (trace, retrace)
 * add the lock-in's outputs to the pixel of the block's last cycle (scan_cycle.c). */
int tt_scan_block_end(const line_ctx *L, line_state *st, long b);

/* The scope (scan_scope.c): made ready for line `line` before it runs (its points NaN),
 * block b's point written at the block's end from the lock-in's filtered amplitude A
 * and phase ph (rad) after the feedback's update, and closed after the line (ok: the
 * line finished; else the scope holds none). */
int tt_scan_scope_begin(tt_scan_scope *sc, const tt_scan *S, long line);
void tt_scan_scope_put(const line_ctx *L, const line_state *st, long b, double A, double ph);
void tt_scan_scope_end(tt_scan_scope *sc, int ok);

/* The solver the averaged tier integrates its failed blocks with (scan_averaged.c). */
tt_solver tt_scan_averaged_solver(const tt_solver *s);

/* One line on the averaged tier (scan_averaged.c), through tt_scan_line_run;
 * *integrated counts the cycles integrated where the slow flow failed. */
int tt_scan_line_averaged(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          long *integrated, double *worst, int *clamped);

/* One line on the envelope tier (scan_envelope.c), through tt_scan_line_run;
 * *integrated counts the cycles integrated, the rest followed the model. */
int tt_scan_line_envelope(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          long *integrated, double *worst, int *clamped);

/* One line on the every-cycle tier (scan_line.c), through tt_scan_line_run. */
int tt_scan_line_every(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                       long *integrated, double *worst, int *clamped);

#endif
