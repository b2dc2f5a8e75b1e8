/* The live console's engine inside (src/live/engine.c, engine_publish.c): its state, and
 * what publishing a line takes (the rows, the scope decimated for a screen, the loop's
 * judgement). Nothing outside src/live/ includes it.
 *
 * Ownership: as include/tiptap/live/engine.h says; the publishing functions write the
 * engine's view and its arrays under its lock.
 */
#ifndef TIPTAP_LIVE_ENGINE_PRIVATE_H
#define TIPTAP_LIVE_ENGINE_PRIVATE_H

#include <pthread.h>

#include "tiptap/config/scene.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/live/engine.h"
#include "tiptap/run/run.h"

/* What a change needs made before the engine takes it: the scan of a new frame and the
 * page's images of it, made on the submitting thread, so that taking a change cannot
 * fail (a running scan that takes it between lines frees them unused). */
typedef struct {
    tt_run_scan_lines run; /* tiptap scan's scan, stepped a line at a time */
    double *rows[TT_LIVE_NCH][2];
    unsigned long *row_version;
    unsigned char *row_tier;
    double *line_buf;
    int ch_index[TT_LIVE_NCH];
} fresh;

struct tt_live_engine {
    pthread_t thread;
    int started;
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int stop;
    void (*wake)(void *);
    void *user;
    /* the next scene, from the console (the latest wins) */
    tt_scene *next_scene;
    tt_scan_params next_params;
    fresh next_fresh;
    int have_next, next_restart;
    double next_at; /* when it arrived */
    double rate;    /* the line rate in force (under mu) */
    /* set (under mu, read atomically by tt_cancel_requested on each thread) when a change
     * makes the line under way meaningless: a new frame or line rate abandons the engine's
     * line; any change, the preview's */
    int abandon, pabandon;
    /* what runs: owned by the thread */
    tt_scene *scene;
    tt_scan_params params;
    tt_run_scan_lines run; /* run.scan: the scan running */
    tt_scan_scope *scope;
    double *line_buf;
    int running; /* the thread is inside a line (under mu) */
    long steps;  /* lines asked for while paused (under mu) */
    /* the preview thread: the averaged tier's twin of the scan, its own scope and line,
     * and the latest change for it (a copy of the engine's) */
    pthread_t pthread;
    int pstarted;
    tt_scan *pscan;
    tt_scan_scope *pscope;
    double *pline;
    long ppixels;
    tt_scan_params pnext;
    int pnext_have, prestart;
    double pat;
    unsigned long pwant, pdone, pchange;
    /* exports */
    int (*write)(void *, const tt_scan *, const tt_scene *, const char *);
    void *write_user;
    unsigned long export_asked, export_done;
    int export_status;
    char export_dir[4096], export_why[512];
    /* published, under mu */
    tt_live_view v;
    double *rows[TT_LIVE_NCH][2];
    unsigned long *row_version;
    unsigned char *row_tier;
    double *series[2][TT_LIVE_NS];
    int ch_index[TT_LIVE_NCH];
    long clean_pass; /* the first pass that runs wholly at the current settings */
};

/* A scope record, decimated for a screen, into the view (under mu). */
void tt_live_publish_scope(tt_live_engine *e, const tt_scan *s, const tt_scan_scope *sc, long line, int tier);
/* Line `line`'s pixels from scan s (buf: a line's room) into the published rows, as
 * tier's (under mu). */
void tt_live_publish_row(tt_live_engine *e, const tt_scan *s, double *buf, long line, int tier);
/* The oscillation warning, the gain suggestion and the lag from the line just run on the
 * scan's own tier (under mu). */
void tt_live_judge_loop(tt_live_engine *e);
/* The engine thread's warning handler (util/warning.h; data: the engine): the warning
 * kept in the view for the page, and printed on stderr. */
void tt_live_publish_warning(const char *category, const char *message, void *data);

#endif
