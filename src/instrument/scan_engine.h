/* The scan's state and its line engine as the scan's drivers see them (scan.c,
 * scan_estimate.c, scan_live.c, scan_oscillation.c): a worker, made for a solver
 * setting, runs one line at a time on its tier (tt_scan_worker_line). The line's own
 * machinery (its context, state, cycles and pixel sums) is scan_private.h's, which
 * only the line engine's files include. Private to libtiptap. */
#ifndef TIPTAP_SCAN_ENGINE_H
#define TIPTAP_SCAN_ENGINE_H

#include <stdint.h>

#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/solver/averaged.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/solver/graze.h"
#include "tiptap/solver/noise.h"

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
    /* its plans by the state's dimension, one per dimension of the materials' laws
     * (relaxation arms add theirs): env is the one for the sim's law, chosen with it
     * (tt_scan_worker_contact) */
    tt_envelope *envs[TT_SIM_DIM_MAX + 1];
    tt_graze *graze; /* the touch branch of a grazing tip (the free one: env), for the
                      * dimension it was made at (graze_dim) */
    int graze_dim;
    tt_lockin *lockin_save;
    double *y_save, *obs;
    /* the greatest indentation of the trace and retrace cycles, per material */
    double *indent;
    /* [tip] contact_geometry = local: the laws this thread built for the geometries it
     * met (scan_geometry.c; NULL until the first) */
    struct tt_scan_laws *laws;
    /* the averaged tier (averaged: on): its slow state where the last line ended */
    int averaged;
    tt_averaged_state avg;
    /* the rest separation at z = 0 of the line's engage: continuous lines keep the
     * first engage's, so that a new setpoint does not move the sample */
    double s_ref;
    /* the scope the line under way records into (NULL: none) */
    tt_scan_scope *scope;
    /* the error estimate's companion line stops once its work (tt_scan_line_work; its
     * cycles where budget_cycles is set) reaches budget (0: never), so that it costs a
     * bounded share of the scan; budget_hit says it stopped there; work0: its sim's work
     * where the line began */
    long budget, work0;
    int budget_cycles, budget_hit;
    /* the work of the last line's settling (tt_scan_line_work after it) */
    long settle_work;
    /* and engages and starts its trace at this cycle of the direction (0: the line's
     * start), so that its stretch lies where the image is hardest */
    long k0;
} worker;

/* A line stopped at its worker's budget: its pixels so far are kept. */
enum { TT_SCAN_BUDGET = 100 };

/* What a cycle costs beside its integration, in integrator steps: the lock-in, the
 * feedback and the pixel of every cycle, and the model's prediction of one it follows
 * (0.4 to 2 steps' time on the companion lines of the viscoelastic blend and the
 * steps, with noise and without). */
#define TT_CYCLE_WORK 1

/* A line's work after cycles of it on W: its sim's steps, accepted and rejected, since
 * the line began, and TT_CYCLE_WORK a cycle. A measure of its cost that is the same on
 * any machine and thread (the estimate's budget). */
static inline long tt_scan_line_work(const worker *W, long cycles)
{
    return tt_sim_work(W->sim) - W->work0 + TT_CYCLE_WORK * cycles;
}

struct tt_scan {
    tt_cantilever cantilever;
    tt_solver solver;
    size_t nmaterials;
    tt_contact **contacts; /* every material's force law, shared by the threads */
    double *Qi;
    double *contact_R;     /* each force law's radius, m */
    tt_contact_params *contact_p; /* each material's law's parameters */
    int local;             /* each cycle's law built for the geometry where the tip
                            * touches (a surface that is not flat) */
    double geo_step;       /* the geometry's differences apart, of the law's radius */
    char (*names)[128];    /* each material's name, for messages */
    double *indent;        /* the greatest indentation recorded in each material, m */
    tt_raster raster;
    tt_surface *surface;
    tt_dilation *dilation; /* the surface as the tip's shape images it; NULL: the apex */
    tt_tip_shape tip;      /* its shape (the contact normal at a corner) */
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
    long work;       /* the lines' work (tt_scan_line_work), settle_work of it settling */
    long settle_work;
    double worst_residual;
    int clamped;
    long laws_built, tables_built; /* [tip] contact_geometry = local: laws and tables
                                    * the runs' threads built */
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

/* Where a line's pixels go: the scan's images, or (packed) one line's worth per
 * channel and direction. */
typedef struct {
    double *img[2][TT_CH_COUNT];
    int packed;
} line_out;

/* What one line added to the scan's totals. */
typedef struct {
    long cycles, integrated;
    long work, settle_work; /* tt_scan_line_work: the line's, and its settling's */
    double worst;
    int clamped;
} line_tally;

/* The line engine (scan_worker.c). A worker made for a solver setting: its sim,
 * lock-in and buffers, and the tier the setting runs on here (every cycle, the
 * envelope tier's model, or the averaged tier's tables, made once per scan). */
int tt_scan_worker_alloc(tt_scan *S, worker *W, const tt_solver *solver);
/* One line on W's tier into out (NULL: the scan's images), recorded into scope when it
 * is not NULL (the scope is closed after the line); t receives what the line ran. */
int tt_scan_worker_line(tt_scan *S, worker *W, long line, const line_out *out,
                        tt_scan_scope *scope, line_tally *t);
/* A worker's buffers freed. */
void tt_scan_worker_free(worker *W);
/* A worker made to fit the scan's noise after a change: the thermal force on its sim,
 * the envelope tier's model made anew where the noise changes its inputs or order (z
 * piezo noise: the travel; thermal or z piezo: second order) and its noise. */
int tt_scan_worker_retune(tt_scan *S, worker *W);
/* Material mat's force law on W's sim and, on the envelope tier, the plan for the
 * state's dimension it gives (relaxation arms add states); inline, as the line's files
 * call it and scan_worker.c calls them. */
static inline void tt_scan_worker_contact(const tt_scan *S, worker *W, size_t mat)
{
    tt_sim_set_contact(W->sim, S->contacts[mat], S->Qi[mat]);
    if (W->env)
        W->env = W->envs[tt_sim_dim(W->sim)];
}
/* [tip] contact_geometry = local: the laws a worker built for the geometries it met
 * (in *tables, if not NULL, the tables among them built at their R_eff), and its laws
 * freed (scan_geometry.c). */
long tt_scan_geometry_built(const worker *W, long *tables);
void tt_scan_geometry_free(worker *W);
/* Whether a solver setting runs on the averaged tier here, and on the envelope tier
 * (the averaged tier's fallback included). */
int tt_scan_averaged_usable(const tt_scan *S, const tt_solver *solver);
int tt_scan_envelope_usable(const tt_scan *S, const tt_solver *solver);
/* The averaged tier's tables, once per scan (before any thread runs a line). */
int tt_scan_averaged_tables(tt_scan *S);

/* Noise that moves the tip's state (the thermal force, the z piezo's) takes the envelope
 * tier's model to second order (tiptap/solver/envelope.h); the detector's does not. */
static inline int tt_scan_second_order(const tt_scan *S)
{
    return S->noise.temperature > 0 || S->zn.sd > 0;
}

/* The z piezo's noise of n for the cantilever's drive period (sd 0: off); TT_EINVAL naming
 * [noise] z_piezo_bandwidth when its band is not within (0, fd / 2] (scan.c). */
int tt_scan_piezo_noise(const tt_scan_noise *n, const tt_cantilever *c, tt_noise_ou *zn);

#endif
