/* The scan's private state, shared by its line loops: scan.c (every cycle) and
 * scan_envelope.c (the envelope tier). Private to libtiptap. */
#ifndef TIPTAP_SCAN_PRIVATE_H
#define TIPTAP_SCAN_PRIVATE_H

#include "tiptap/instrument/scan.h"
#include "tiptap/solver/envelope.h"

enum { NHARM = TT_CH_HARMONIC_MAX - 1 }; /* harmonic channels of each kind */
_Static_assert(TT_CH_COUNT <= 8 * sizeof(unsigned), "a channel mask holds every channel");

/* One thread's workspace: its own simulation, lock-in and sample buffer. */
typedef struct {
    tt_sim *sim;
    tt_lockin *lockin;
    tt_sample *samples;
    double *y;
    /* continuous lines: the feedback and the z piezo's ramp where the last line ended */
    int engaged;
    tt_feedback fb;
    double z_from, z_to;
    tt_piezo pz;
    double z_act;
    /* the envelope tier (NULL: every cycle): its model, a snapshot of the lock-in and
     * of the block's samples to roll back to, and two observable vectors */
    tt_envelope *env;
    tt_lockin *lockin_save;
    double *y_save, *obs;
} worker;

struct tt_scan {
    tt_cantilever cantilever;
    tt_solver solver;
    size_t nmaterials;
    tt_contact **contacts; /* every material's force law, shared by the threads */
    double *Qi;
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
    double sd, sz;       /* per-sample detector and per-cycle z piezo noise, m rms */
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
    /* the first failure of any thread */
    int status;
    char message[1024];
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

/* What a line starts from and leaves to the next (continuous lines): the feedback, the
 * z piezo's command ramp and actual height, and the material set on the sim. */
typedef struct {
    tt_feedback fb;
    double z_from, z_to, z_act;
    tt_piezo pz;
    size_t current;
} scan_carry;

/* Engage at the line's first pixel (scan.c): the material there on the sim, and, unless
 * continuous lines carry on from the last retrace, the feedback at that pixel's height,
 * the piezo at rest there, the tip and the lock-in on the free oscillation. */
void tt_scan_engage(tt_scan *S, worker *W, long line, long nc, scan_carry *e);
/* A line finished: its state kept for the next (continuous lines), its pixels' means
 * into the images. */
void tt_scan_line_done(const tt_scan *S, worker *W, long line, const scan_carry *e,
                       const pixel_acc *pix, const line_out *out);

/* One line on the envelope tier (scan_envelope.c); the arguments as scan.c's
 * scan_line. */
int tt_scan_line_envelope(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          long *integrated, double *worst, int *clamped);

#endif
