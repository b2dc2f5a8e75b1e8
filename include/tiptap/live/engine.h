/* tiptap: the live console's instrument (tiptap live; docs/live.md).
 *
 * One thread runs the scan a line at a time (tt_scan_step), paced to the instrument's
 * clock: a line takes 1 / line_rate of wall time, or longer where the machine cannot
 * keep up (the view's realtime says by how much). After each line it publishes the
 * line's pixels (height, error, phase, amplitude, peak force, trace and retrace), its
 * scope record decimated for a screen, and the loop's state; the server reads them under
 * the engine's lock. Paused, or with no page looking, it waits between lines (no CPU).
 *
 * A change from the console (tt_live_engine_submit) takes effect at the next line: the
 * gains, setpoint, line rate, free amplitude and noise on the running scan (its setters
 * in instrument/scan.h), anything else as a new scan and a new frame, made by the
 * submitter. A new frame or line rate abandons the line under way. When the scan is
 * on the envelope or every-cycle tier, the next line after a change runs first on the
 * averaged tier (a preview, published at once, tier "averaged") and then on the scan's
 * own tier, which replaces it; the averaged tier's preview has its own scan object, so
 * the accurate lines never depend on it.
 *
 * Ownership: the engine takes the scenes submitted to it (and frees them), owns its
 * scans, the published view and its thread; tt_live_engine_free stops the thread at
 * its next poll (within a drive cycle's work) and frees everything. The view's arrays
 * belong to the engine: read them only between tt_live_engine_lock and _unlock.
 */
#ifndef TIPTAP_LIVE_ENGINE_H
#define TIPTAP_LIVE_ENGINE_H

#include <stddef.h>

#include "tiptap/config/scene.h"
#include "tiptap/instrument/scan.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The channels the console images, in this order, where the scene records them (mode
 * 2's, after the one-mode five, only in a bimodal scene). */
enum { TT_LIVE_HEIGHT, TT_LIVE_ERROR, TT_LIVE_PHASE, TT_LIVE_AMPLITUDE, TT_LIVE_PEAK_FORCE,
       TT_LIVE_AMPLITUDE2, TT_LIVE_PHASE2, TT_LIVE_NCH };
/* row_tier's flag: the line came from the averaged preview (the low bits: its tt_tier). */
enum { TT_LIVE_PREVIEW = 0x10 };
/* The scope's series on the page (a subset of the scan's record). */
enum { TT_LIVE_S_POS, TT_LIVE_S_Z, TT_LIVE_S_ERROR, TT_LIVE_S_AMPLITUDE, TT_LIVE_S_PHASE,
       TT_LIVE_S_SURFACE, TT_LIVE_NS };
/* The run's warnings the page is shown at most (the newest). */
enum { TT_LIVE_WARNINGS = 4 };
/* Points of a scope series on the page at most (min and max of each bucket). */
enum { TT_LIVE_SCOPE_BUDGET = 1600 };

typedef struct {
    /* the frame: one scan's raster (a new scan starts a new frame) */
    long frame;
    long pixels, lines;
    double size_fast, size_slow; /* m, along the fast and the slow axis */
    int fast_y, retrace;
    const char *channel_name[TT_LIVE_NCH]; /* NULL: not recorded by the scene */
    const char *channel_unit[TT_LIVE_NCH];
    const char *channel_file[TT_LIVE_NCH]; /* the scan's name of it, as in its files */
    unsigned long version;       /* of the last publication, of any kind */
    unsigned long frame_version; /* when the frame began */
    /* rows: line l's pixels of channel c, direction r (0 trace, 1 retrace), along the
     * fast axis, at rows[c][r] + l * pixels; NaN before it ran */
    const double *rows[TT_LIVE_NCH][2];
    const unsigned long *row_version; /* per line: when it was last published (0: never) */
    const unsigned char *row_tier;    /* per line: the tt_tier of that publication, with
                                       * TT_LIVE_PREVIEW where the preview made it */
    long lines_done;                  /* lines finished on the scan's own tier, this frame */
    long line;                        /* the line running or next */
    long first_line_as_set;           /* the first line of this frame run at the current
                                       * settings (0: the whole frame) */
    long passes;                      /* how many times the frame's lines wrapped around
                                       * (each pass engages afresh at line 0) */
    int reproducible;                 /* a whole pass ran at the current settings: the
                                       * images are tiptap scan's of the current scene */
    /* the scope: the last line published, decimated (min and max per bucket) */
    unsigned long scope_version;
    long scope_line;
    int scope_tier;
    size_t scope_n[2];
    const double *scope[2][TT_LIVE_NS];
    double scope_t0[2], scope_t1[2]; /* instrument time of its first and last point, s */
    double scope_rate;                /* points per second of the record (lock-in blocks) */
    double scope_kp, scope_ki;        /* the gains the line ran with (m/m, 1/s) */
    /* the loop */
    unsigned long status_version;
    double realtime;       /* instrument time / wall time of the last line's work, >= 1: keeps up */
    double realtime_cpu;   /* the same per CPU second of the engine's thread: what a
                            * core of its own would give on a shared machine */
    double line_seconds;   /* wall time of the last accurate line's work */
    double preview_ms;     /* from the last change's arrival to its first published line */
    double accurate_ms;    /* and to its line on the scan's own tier */
    int tier;              /* the scan's own tier (tt_tier) */
    int oscillating;       /* the loop rings (from the z and error records) */
    double ring_hz;        /* its frequency (0: none) */
    double ring_nm;        /* its peak-to-peak height, m */
    double ring_damping;   /* its damping ratio, from the swings' decay (0: none) */
    double suggest_ki;     /* a suggested integral gain, 1/s (0: none) */
    long judged;           /* lines judged by the oscillation check since the start */
    long judged_line;      /* the line the warning's figures come from (-1: none yet) */
    double error_rms;      /* that line's error, rms over its record, m */
    double setpoint;       /* the setpoint in force then, m */
    double height_range;   /* that line's height pixels (trace), max - min, m */
    double track_rms;      /* rms of z - the true surface over its record, mean taken off, m */
    double surface_range;  /* the true surface's peak to peak over the record, m */
    int lagging;           /* track_rms > 0.35 surface_range, where that is 1 nm or more */
    int paused;            /* the page paused the scan (lines run only on a step) */
    int running;           /* a line on the scan's own tier is under way */
    int idle;              /* no page looks: the scan waits */
    char note[512];        /* the engine's last message ("" none): a change it refused */
    /* tiptap scan's warnings of the run (run/run.h: the inputs at a scan's first line,
     * the results at a pass's end), the newest last, each once, with its frame */
    int nwarnings;
    char warning[TT_LIVE_WARNINGS][512];
    char warning_category[TT_LIVE_WARNINGS][16];
    long warning_frame[TT_LIVE_WARNINGS];
} tt_live_view;

typedef struct tt_live_engine tt_live_engine;

/* wake(user) is called from the engine's thread after each publication (the server's
 * lws_cancel_service). scene and p: the first scene and its parameters (both taken). */
int tt_live_engine_alloc(tt_live_engine **out, tt_scene *scene, tt_scan_params *p,
                         void (*wake)(void *user), void *user);
void tt_live_engine_free(tt_live_engine *e);

/* A new scene and its parameters for the next line (both taken, whatever it returns; an
 * earlier one not yet taken up is dropped: the latest wins). restart: a new frame even
 * where the running scan could take the change. Everything the change may need (its scan
 * of a new frame and the page's images of it) is made here, on the caller's thread:
 * TT_OK when the change will take effect, else the error and nothing changes. A change
 * that starts a new frame or changes the line rate abandons the line under way (within
 * a drive cycle's work, as cancellation does: util/cancel.h); any change abandons the
 * preview line under way. */
int tt_live_engine_submit(tt_live_engine *e, tt_scene *scene, tt_scan_params *p, int restart);

/* Exports: write(user, scan, scene, dir) writes the current scan's files into dir (as
 * tiptap scan does), on the engine's thread between two lines. tt_live_engine_export asks
 * for one and returns its number; tt_live_engine_exported tells the last one written and
 * where (its folder, the engine's: NULL while none), and its status. */
void tt_live_engine_set_writer(tt_live_engine *e,
                               int (*write)(void *user, const tt_scan *scan,
                                            const tt_scene *scene, const char *dir),
                               void *user);
unsigned long tt_live_engine_export(tt_live_engine *e);
unsigned long tt_live_engine_exported(tt_live_engine *e, const char **dir, int *status,
                                      const char **why);

/* Pause (1) or resume (0) the scan between lines; step: one line more while paused.
 * A paused or idle engine's thread waits on a condition (no CPU); a line under way
 * finishes first. */
void tt_live_engine_pause(tt_live_engine *e, int paused);
void tt_live_engine_step(tt_live_engine *e);
/* How many pages look: at 0 the engine is idle until one comes (it starts idle). */
void tt_live_engine_watched(tt_live_engine *e, int pages);

void tt_live_engine_lock(tt_live_engine *e);
void tt_live_engine_unlock(tt_live_engine *e);
/* Between lock and unlock. */
const tt_live_view *tt_live_engine_view(const tt_live_engine *e);

#ifdef __cplusplus
}
#endif
#endif
