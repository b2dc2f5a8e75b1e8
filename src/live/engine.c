/* The live console's instrument (include/tiptap/live/engine.h): a thread stepping the
 * scan line by line on the instrument's clock, publishing pixels, scope and state. */
#include "tiptap/live/engine.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "engine_private.h"
#include "live_private.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/util/clock.h"
#include "tiptap/util/warning.h"


static int channel_by_name(const char *name)
{
    for (int i = 0; i < TT_CH_COUNT; i++)
        if (strcmp(tt_scan_channel_name(i), name) == 0)
            return i;
    return -1;
}

/* Free the frame's published arrays (under mu). */
static void frame_free(tt_live_engine *e)
{
    for (int c = 0; c < TT_LIVE_NCH; c++)
        for (int r = 0; r < 2; r++) {
            free(e->rows[c][r]);
            e->rows[c][r] = NULL;
            e->v.rows[c][r] = NULL;
        }
    free(e->row_version);
    free(e->row_tier);
    e->row_version = NULL;
    e->row_tier = NULL;
    e->v.row_version = NULL;
    e->v.row_tier = NULL;
}

static void fresh_free(fresh *f)
{
    tt_scan_free(f->run.scan);
    for (int c = 0; c < TT_LIVE_NCH; c++)
        for (int r = 0; r < 2; r++)
            free(f->rows[c][r]);
    free(f->row_version);
    free(f->row_tier);
    free(f->line_buf);
    memset(f, 0, sizeof *f);
}

/* The scan of scene, made as tiptap scan makes it (tt_run_scan_begin: its checks and
 * refusals), and the page's empty images of it (the channels it records of height,
 * error, phase, amplitude and peak force; mode 2's amplitude and phase). */
static int fresh_alloc(fresh *f, const tt_scene *scene)
{
    static const char *const names[TT_LIVE_NCH] = {"height",     "error",       "phase",  "amplitude",
                                                   "peak_force", "amplitude_2", "phase_2"};
    memset(f, 0, sizeof *f);
    int rc = tt_run_scan_begin(scene, &f->run);
    if (rc)
        return rc;
    const tt_scan *s = f->run.scan;
    long px = tt_scan_fast_y(s) ? tt_scan_yres(s) : tt_scan_xres(s), nl = tt_scan_lines(s);
    size_t n = (size_t)px * (size_t)nl;
    f->row_version = calloc((size_t)nl, sizeof *f->row_version);
    f->row_tier = calloc((size_t)nl, 1);
    f->line_buf = malloc((size_t)px * sizeof(double));
    if (!f->row_version || !f->row_tier || !f->line_buf)
        rc = tt_error_nomem("the console's image, %ld lines of %ld pixels", nl, px);
    for (int c = 0; c < TT_LIVE_NCH && !rc; c++) {
        int k = channel_by_name(names[c]);
        f->ch_index[c] = k >= 0 && tt_scan_image(s, k, 0) ? k : -1;
        for (int r = 0; r < 2 && f->ch_index[c] >= 0 && !rc; r++) {
            if (!(f->rows[c][r] = malloc(n * sizeof(double))))
                rc = tt_error_nomem("the console's image, %ld x %ld pixels", px, nl);
            for (size_t i = 0; i < n && !rc; i++)
                f->rows[c][r][i] = NAN;
        }
    }
    if (rc)
        fresh_free(f);
    return rc;
}

/* The published frame of the running scan (f's, made for it): its raster, channels and
 * empty rows; f is left empty. */
static void frame_publish(tt_live_engine *e, fresh *f)
{
    static const char *const names[TT_LIVE_NCH] = {"height",     "error",       "phase",  "amplitude",
                                                   "peak_force", "amplitude_2", "phase_2"};
    const tt_scan *s = e->run.scan;
    pthread_mutex_lock(&e->mu);
    frame_free(e);
    e->v.frame++;
    e->v.pixels = tt_scan_fast_y(s) ? tt_scan_yres(s) : tt_scan_xres(s);
    e->v.lines = tt_scan_lines(s);
    e->v.fast_y = tt_scan_fast_y(s);
    e->v.size_fast = e->v.fast_y ? tt_scan_size_y(s) : tt_scan_size_x(s);
    e->v.size_slow = e->v.fast_y ? tt_scan_size_x(s) : tt_scan_size_y(s);
    e->v.retrace = tt_scan_has_retrace(s);
    e->row_version = f->row_version;
    e->row_tier = f->row_tier;
    for (int c = 0; c < TT_LIVE_NCH; c++) {
        int k = e->ch_index[c] = f->ch_index[c];
        e->v.channel_name[c] = k >= 0 ? names[c] : NULL;
        e->v.channel_unit[c] = k >= 0 ? tt_scan_channel_unit(k) : NULL;
        e->v.channel_file[c] = k >= 0 ? tt_scan_channel_name(k) : NULL;
        for (int r = 0; r < 2; r++)
            e->v.rows[c][r] = e->rows[c][r] = f->rows[c][r];
    }
    e->v.row_version = e->row_version;
    e->v.row_tier = e->row_tier;
    e->v.lines_done = 0;
    e->v.line = 0;
    e->v.passes = 0;
    e->v.first_line_as_set = 0;
    e->v.reproducible = 0;
    e->v.note[0] = '\0';
    e->clean_pass = 0;
    e->v.tier = (int)e->params.solver.tier;
    e->v.frame_version = ++e->v.version;
    e->v.status_version = e->v.version;
    pthread_mutex_unlock(&e->mu);
    free(e->line_buf);
    e->line_buf = f->line_buf;
    f->run.scan = NULL; /* the engine's now */
    memset(f, 0, sizeof *f);
}

/* The averaged tier's twin of a scan on a slower tier, for the preview lines; NULL
 * where the scene is on the averaged tier already (its own line is as quick as a
 * preview) or the averaged tier refuses it (Q under 30, a drive off resonance; a
 * sample's relaxation arms it takes, src/solver/averaged_arms.c). */
static tt_scan *preview_alloc(const tt_scan_params *p)
{
    tt_scan_params q = *p;
    tt_scan *s = NULL;
    if (p->solver.tier == TT_TIER_AVERAGED)
        return NULL;
    q.solver.tier = TT_TIER_AVERAGED;
    if (!tt_scan_averaged_tier(&q) || tt_scan_alloc(&s, &q) != TT_OK)
        return NULL;
    return s;
}

/* The settings a running scan takes between lines (instrument/scan.h); 0 when all of
 * them took, else a new scan is needed. */
static int apply_live(tt_scan *s, const tt_scan_params *p)
{
    if (!s)
        return -1;
    tt_feedback_params fb = p->feedback;
    if (fabs(tt_scan_free_amplitude(s) - p->cantilever.A0) > 0 &&
        tt_scan_set_free_amplitude(s, p->cantilever.A0))
        return -1;
    if (tt_scan_set_feedback(s, &fb) || tt_scan_set_noise(s, &p->noise))
        return -1;
    if (tt_scan_line_rate(s) != p->raster.line_rate && tt_scan_set_line_rate(s, p->raster.line_rate))
        return -1;
    return 0;
}

static void note(tt_live_engine *e, const char *what)
{
    pthread_mutex_lock(&e->mu);
    tt_live_text(e->v.note, sizeof e->v.note, what);
    e->v.status_version = ++e->v.version;
    pthread_mutex_unlock(&e->mu);
    e->wake(e->user);
}

/* Take up a submitted scene: on the running scan where it can (its setters), else as
 * f's new scan and frame. It cannot fail: whatever it needs was made when it was
 * submitted. */
static void take_change(tt_live_engine *e, tt_scene *scene, tt_scan_params *p, int restart, fresh *f)
{
    /* the console says which of its knobs need a new scan (controls.h); a setter that
     * refuses leaves the running scan half set: replaced too */
    int use_fresh = restart || !e->run.scan || apply_live(e->run.scan, p);
    if (use_fresh) {
        /* the old scan's lines said what tiptap scan says of them, before it goes */
        if (e->run.scan)
            tt_run_scan_end(&e->run, NULL, NULL);
        tt_scan_free(e->run.scan);
        e->run = f->run;
        f->run.scan = NULL;
    }
    tt_scene_free(e->scene);
    if (e->scene)
        tt_config_scan_free(&e->params);
    e->scene = scene;
    e->params = *p;
    pthread_mutex_lock(&e->mu);
    e->rate = p->raster.line_rate;
    pthread_mutex_unlock(&e->mu);
    if (use_fresh) {
        frame_publish(e, f);
        return;
    }
    fresh_free(f);
    pthread_mutex_lock(&e->mu);
    e->v.first_line_as_set = e->v.line;
    e->v.reproducible = 0;
    /* continuous lines carry the old settings' state into the new: only a pass that
     * starts afresh at line 0 is what tiptap scan gives for the new scene */
    e->clean_pass = e->v.line == 0 ? e->v.passes : e->v.passes + 1;
    e->v.note[0] = '\0';
    e->v.status_version = ++e->v.version;
    pthread_mutex_unlock(&e->mu);
}

/* Run line `line` on the scan's own tier and publish it. */
static int run_line(tt_live_engine *e, long line, double changed_at)
{
    pthread_mutex_lock(&e->mu);
    e->running = e->v.running = 1;
    e->v.status_version = ++e->v.version;
    pthread_mutex_unlock(&e->mu);
    e->wake(e->user);
    double t0 = tt_clock(TT_CLOCK_WALL), c0 = tt_clock(TT_CLOCK_THREAD);
    int rc = tt_run_scan_step(&e->run, e->scene, line, e->scope);
    double t1 = tt_clock(TT_CLOCK_WALL), c1 = tt_clock(TT_CLOCK_THREAD);
    pthread_mutex_lock(&e->mu);
    e->running = e->v.running = 0;
    e->v.status_version = ++e->v.version;
    if (rc) {
        pthread_mutex_unlock(&e->mu);
        return rc;
    }
    tt_live_publish_row(e, e->run.scan, e->line_buf, line, (int)e->params.solver.tier);
    tt_live_publish_scope(e, e->run.scan, e->scope, line, (int)e->params.solver.tier);
    tt_live_judge_loop(e);
    if (changed_at > 0)
        e->v.accurate_ms = 1e3 * (t1 - changed_at);
    e->v.line_seconds = t1 - t0;
    e->v.realtime = (1.0 / e->params.raster.line_rate) / (t1 - t0);
    e->v.realtime_cpu = (1.0 / e->params.raster.line_rate) / (c1 - c0);
    if (e->v.passes == 0)
        e->v.lines_done = line + 1;
    /* the next line, in the same lock as the end of this one: the preview thread reads
     * "not running" and the line to run next together */
    int wrapped = ++e->v.line >= e->v.lines;
    if (wrapped) {
        /* the next pass engages afresh at line 0, as a new tiptap scan would */
        e->v.reproducible = e->v.passes >= e->clean_pass && !e->have_next;
        e->v.line = 0;
        e->v.passes++;
        e->v.first_line_as_set = 0;
        e->v.status_version = ++e->v.version;
    }
    pthread_mutex_unlock(&e->mu);
    if (wrapped) {
        /* a pass is a scan: its result warnings, as tiptap scan gives them */
        tt_run_scan_end(&e->run, NULL, NULL);
        tt_scan_disengage(e->run.scan);
    }
    e->wake(e->user);
    return TT_OK;
}

static void remove_folder(const char *dir)
{
    DIR *d = opendir(dir);
    struct dirent *x;
    char path[4400];
    while (d && (x = readdir(d)))
        if (strcmp(x->d_name, ".") && strcmp(x->d_name, "..")) {
            snprintf(path, sizeof path, "%s/%s", dir, x->d_name);
            unlink(path);
        }
    if (d)
        closedir(d);
    rmdir(dir);
}

/* An export asked for: the current scan's files in a fresh folder, the last one's
 * removed (the server has read what it serves). */
static void do_export(tt_live_engine *e)
{
    pthread_mutex_lock(&e->mu);
    unsigned long want = e->export_asked;
    pthread_mutex_unlock(&e->mu);
    if (want == e->export_done || !e->write || !e->run.scan)
        return;
    char dir[4096], old[4096];
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/tiptap-live-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    int rc = mkdtemp(dir) ? e->write(e->write_user, e->run.scan, e->scene, dir)
                          : tt_error(TT_EIO, "cannot make a folder for the export: %s", strerror(errno));
    pthread_mutex_lock(&e->mu);
    snprintf(old, sizeof old, "%s", e->export_dir);
    snprintf(e->export_dir, sizeof e->export_dir, "%s", dir);
    e->export_status = rc;
    tt_live_text(e->export_why, sizeof e->export_why, rc ? tt_error_message() : "");
    e->export_done = want;
    pthread_mutex_unlock(&e->mu);
    if (old[0])
        remove_folder(old);
    e->wake(e->user);
}

/* Wait until `until` (monotonic s) or until a change, an export or the stop comes. */
static void pace(tt_live_engine *e, double until)
{
    pthread_mutex_lock(&e->mu);
    while (!e->stop && !e->have_next && e->export_asked == e->export_done) {
        double left = until - tt_clock(TT_CLOCK_WALL);
        if (left <= 0)
            break;
        struct timespec ts;
        clock_gettime(CLOCK_REALTIME, &ts);
        double t = (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec + left;
        ts.tv_sec = (time_t)t;
        ts.tv_nsec = (long)((t - (double)ts.tv_sec) * 1e9);
        pthread_cond_timedwait(&e->cv, &e->mu, &ts);
    }
    pthread_mutex_unlock(&e->mu);
}

static void *engine_main(void *arg)
{
    tt_live_engine *e = arg;
    double changed_at = 0;
    /* the run layer's warnings go to the page; none is raised while this thread holds mu,
     * which the handler takes */
    tt_warning_push(tt_live_publish_warning, e);
    /* a change that abandons the line under way interrupts it as Ctrl-C would */
    tt_cancel_watch(&e->abandon);
    for (;;) {
        pthread_mutex_lock(&e->mu);
        int stop = e->stop, have = e->have_next, restart = e->next_restart;
        tt_scene *scene = e->next_scene;
        tt_scan_params p = e->next_params;
        fresh f = e->next_fresh;
        double at = e->next_at;
        e->have_next = 0;
        e->next_scene = NULL;
        memset(&e->next_fresh, 0, sizeof e->next_fresh);
        if (have)
            __atomic_store_n(&e->abandon, 0, __ATOMIC_RELAXED);
        pthread_mutex_unlock(&e->mu);
        if (stop) {
            if (have) {
                tt_scene_free(scene);
                tt_config_scan_free(&p);
                fresh_free(&f);
            }
            break;
        }
        /* an export asked for before the change shows the image and scene it was asked of */
        do_export(e);
        if (have) {
            take_change(e, scene, &p, restart, &f);
            changed_at = at;
        }
        if (!e->run.scan || !e->line_buf) {
            pace(e, tt_clock(TT_CLOCK_WALL) + 1);
            continue;
        }
        /* paused, or no page looks: wait (no CPU) for a step, a resume, a page, a change,
         * an export or the stop */
        pthread_mutex_lock(&e->mu);
        while (!e->stop && !e->have_next && e->export_asked == e->export_done &&
               (e->v.idle || (e->v.paused && e->steps == 0))) {
            pthread_cond_wait(&e->cv, &e->mu);
        }
        int go = !e->stop && !e->have_next && e->export_asked == e->export_done &&
                 !e->v.idle && (!e->v.paused || e->steps > 0);
        if (go && e->v.paused)
            e->steps--;
        pthread_mutex_unlock(&e->mu);
        if (!go)
            continue;
        double t0 = tt_clock(TT_CLOCK_WALL);
        int rc = run_line(e, e->v.line, changed_at);
        if (rc == TT_EINTR && __atomic_load_n(&e->abandon, __ATOMIC_RELAXED)) {
            /* abandoned for a change: that line again, engaged afresh, at once */
            tt_scan_disengage(e->run.scan);
            continue;
        }
        if (rc == TT_EINTR)
            break;
        if (rc)
            note(e, tt_error_message());
        changed_at = 0;
        pace(e, t0 + 1.0 / e->params.raster.line_rate);
    }
    return NULL;
}

/* The preview: a change's next line on the averaged tier, at once, on a thread of its
 * own, while the scan's own tier finishes the line under way. It runs the line the
 * instrument will run next (the one after the line under way), engaged afresh at its
 * first pixel, and publishes it unless the scan's own tier got there first. A change
 * that starts a new frame is previewed by nothing: its frame comes with its first line. */
static void preview_line(tt_live_engine *e, unsigned long change, double at)
{
    pthread_mutex_lock(&e->mu);
    /* a line abandoned for the change runs again: it is the next */
    int next = e->running && !__atomic_load_n(&e->abandon, __ATOMIC_RELAXED);
    long line = next ? (e->v.line + 1) % e->v.lines : e->v.line, frame = e->v.frame;
    int fits = e->v.pixels == e->ppixels && e->v.lines == tt_scan_lines(e->pscan);
    pthread_mutex_unlock(&e->mu);
    if (!fits)
        return;
    tt_scan_disengage(e->pscan);
    if (tt_scan_step(e->pscan, line, e->pscope))
        return;
    pthread_mutex_lock(&e->mu);
    if (e->v.frame == frame && e->row_version[line] < change) {
        tt_live_publish_row(e, e->pscan, e->pline, line, TT_TIER_AVERAGED | TT_LIVE_PREVIEW);
        tt_live_publish_scope(e, e->pscan, e->pscope, line, TT_TIER_AVERAGED);
        e->v.preview_ms = 1e3 * (tt_clock(TT_CLOCK_WALL) - at);
    }
    pthread_mutex_unlock(&e->mu);
    e->wake(e->user);
}

static void *preview_main(void *arg)
{
    tt_live_engine *e = arg;
    /* a newer change abandons the preview line under way */
    tt_cancel_watch(&e->pabandon);
    for (;;) {
        pthread_mutex_lock(&e->mu);
        while (!e->stop && e->pwant == e->pdone)
            pthread_cond_wait(&e->cv, &e->mu);
        __atomic_store_n(&e->pabandon, 0, __ATOMIC_RELAXED);
        if (e->stop) {
            pthread_mutex_unlock(&e->mu);
            break;
        }
        tt_scan_params p = e->pnext;
        int restart = e->prestart;
        double at = e->pat;
        unsigned long change = e->pchange;
        e->pnext_have = 0;
        e->prestart = 0;
        e->pdone = e->pwant;
        pthread_mutex_unlock(&e->mu);
        if (restart || !e->pscan || apply_live(e->pscan, &p)) {
            tt_scan_free(e->pscan);
            e->pscan = preview_alloc(&p);
            /* its tables now, not in the first change's line, which must beat the scan's */
            if (e->pscan && tt_scan_step_prepare(e->pscan)) {
                tt_scan_free(e->pscan);
                e->pscan = NULL;
            }
            free(e->pline);
            e->ppixels = e->pscan ? (p.raster.fast_y ? tt_scan_yres(e->pscan) : tt_scan_xres(e->pscan)) : 0;
            e->pline = e->pscan ? malloc((size_t)e->ppixels * sizeof(double)) : NULL;
        }
        if (!restart && e->pscan && e->pline)
            preview_line(e, change, at);
        tt_config_scan_free(&p);
    }
    return NULL;
}

int tt_live_engine_alloc(tt_live_engine **out, tt_scene *scene, tt_scan_params *p,
                         void (*wake)(void *user), void *user)
{
    tt_live_engine *e = calloc(1, sizeof *e);
    if (!e) {
        tt_scene_free(scene);
        tt_config_scan_free(p);
        return tt_error_nomem("the console's instrument");
    }
    pthread_mutex_init(&e->mu, NULL);
    pthread_cond_init(&e->cv, NULL);
    e->wake = wake;
    e->user = user;
    /* nothing judged, no change yet (the page shows neither), no page yet (idle) */
    e->v.judged_line = -1;
    e->v.preview_ms = e->v.accurate_ms = NAN;
    e->v.error_rms = e->v.setpoint = e->v.height_range = NAN;
    e->v.track_rms = e->v.surface_range = NAN;
    e->v.idle = 1;
    int rc = tt_scan_scope_alloc(&e->scope);
    if (!rc)
        rc = tt_scan_scope_alloc(&e->pscope);
    /* the preview thread makes its scan at once (not previewed: the first change's
     * preview then costs a line, not the averaged tier's tables too) */
    tt_material *m = rc ? NULL : malloc((p->nmaterials ? p->nmaterials : 1) * sizeof *m);
    if (m) {
        memcpy(m, p->materials, p->nmaterials * sizeof *m);
        e->pnext = *p;
        e->pnext.materials = m;
        e->pnext_have = 1;
        e->prestart = 1;
        e->pwant = 1;
    }
    fresh f;
    if (!rc && !(rc = fresh_alloc(&f, scene))) {
        take_change(e, scene, p, 1, &f);
    } else {
        tt_scene_free(scene);
        tt_config_scan_free(p);
    }
    if (!rc) {
        /* the signals stay with the server's thread, which stops the engine */
        sigset_t all, old;
        sigfillset(&all);
        pthread_sigmask(SIG_BLOCK, &all, &old);
        if (pthread_create(&e->thread, NULL, engine_main, e) != 0)
            rc = tt_error(TT_ENOMEM, "cannot start the console's instrument thread");
        else
            e->started = 1;
        if (!rc && pthread_create(&e->pthread, NULL, preview_main, e) != 0)
            rc = tt_error(TT_ENOMEM, "cannot start the console's preview thread");
        else if (!rc)
            e->pstarted = 1;
        pthread_sigmask(SIG_SETMASK, &old, NULL);
    }
    if (rc) {
        tt_live_engine_free(e);
        return rc;
    }
    *out = e;
    return TT_OK;
}

void tt_live_engine_free(tt_live_engine *e)
{
    if (!e)
        return;
    pthread_mutex_lock(&e->mu);
    e->stop = 1;
    pthread_cond_broadcast(&e->cv);
    pthread_mutex_unlock(&e->mu);
    if (e->started)
        pthread_join(e->thread, NULL);
    if (e->pstarted)
        pthread_join(e->pthread, NULL);
    if (e->pnext_have)
        tt_config_scan_free(&e->pnext);
    tt_scan_free(e->pscan);
    tt_scan_scope_free(e->pscope);
    free(e->pline);
    if (e->have_next) {
        tt_scene_free(e->next_scene);
        tt_config_scan_free(&e->next_params);
        fresh_free(&e->next_fresh);
    }
    if (e->export_dir[0])
        remove_folder(e->export_dir);
    frame_free(e);
    for (int r = 0; r < 2; r++)
        for (int k = 0; k < TT_LIVE_NS; k++)
            free(e->series[r][k]);
    tt_scan_scope_free(e->scope);
    tt_scan_free(e->run.scan);
    if (e->scene) {
        tt_scene_free(e->scene);
        tt_config_scan_free(&e->params);
    }
    free(e->line_buf);
    pthread_cond_destroy(&e->cv);
    pthread_mutex_destroy(&e->mu);
    free(e);
}

int tt_live_engine_submit(tt_live_engine *e, tt_scene *scene, tt_scan_params *p, int restart)
{
    fresh f, old = {0};
    int rc = fresh_alloc(&f, scene);
    if (rc) {
        tt_scene_free(scene);
        tt_config_scan_free(p);
        return rc;
    }
    tt_scene *old_scene = NULL;
    tt_scan_params old_params;
    pthread_mutex_lock(&e->mu);
    if (e->have_next) {
        old_scene = e->next_scene;
        old_params = e->next_params;
        old = e->next_fresh;
        restart |= e->next_restart;
    }
    e->next_scene = scene;
    e->next_params = *p;
    e->next_fresh = f;
    e->next_restart = restart;
    e->have_next = 1;
    e->next_at = tt_clock(TT_CLOCK_WALL);
    /* a new frame or line rate makes the line under way meaningless: abandoned */
    if (restart || p->raster.line_rate != e->rate)
        __atomic_store_n(&e->abandon, 1, __ATOMIC_RELAXED);
    __atomic_store_n(&e->pabandon, 1, __ATOMIC_RELAXED);
    /* the preview thread's own copy (the materials are plain values) */
    tt_material *m = malloc((p->nmaterials ? p->nmaterials : 1) * sizeof *m);
    if (m) {
        if (e->pnext_have)
            tt_config_scan_free(&e->pnext);
        memcpy(m, p->materials, p->nmaterials * sizeof *m);
        e->pnext = *p;
        e->pnext.materials = m;
        e->pnext_have = 1;
        e->prestart |= restart;
        e->pat = e->next_at;
        e->pwant++;
    }
    e->v.reproducible = 0; /* the image is no longer the current scene's */
    e->v.status_version = ++e->v.version;
    e->pchange = e->v.version;
    pthread_cond_broadcast(&e->cv);
    pthread_mutex_unlock(&e->mu);
    /* the change it replaced, freed outside the lock (its images may be large) */
    if (old_scene) {
        tt_scene_free(old_scene);
        tt_config_scan_free(&old_params);
        fresh_free(&old);
    }
    return TT_OK;
}

void tt_live_engine_set_writer(tt_live_engine *e,
                               int (*write)(void *, const tt_scan *, const tt_scene *, const char *),
                               void *user)
{
    pthread_mutex_lock(&e->mu);
    e->write = write;
    e->write_user = user;
    pthread_mutex_unlock(&e->mu);
}

unsigned long tt_live_engine_export(tt_live_engine *e)
{
    pthread_mutex_lock(&e->mu);
    unsigned long n = ++e->export_asked;
    pthread_cond_broadcast(&e->cv);
    pthread_mutex_unlock(&e->mu);
    return n;
}

/* Under the lock. */
unsigned long tt_live_engine_exported(tt_live_engine *e, const char **dir, int *status,
                                      const char **why)
{
    *dir = e->export_dir[0] ? e->export_dir : NULL;
    *status = e->export_status;
    *why = e->export_why;
    return e->export_done;
}

void tt_live_engine_pause(tt_live_engine *e, int paused)
{
    pthread_mutex_lock(&e->mu);
    e->v.paused = paused != 0;
    e->steps = 0;
    e->v.status_version = ++e->v.version;
    pthread_cond_broadcast(&e->cv);
    pthread_mutex_unlock(&e->mu);
}

void tt_live_engine_step(tt_live_engine *e)
{
    pthread_mutex_lock(&e->mu);
    /* a step pauses a running scan after the line it asks for */
    e->v.paused = 1;
    e->steps++;
    e->v.status_version = ++e->v.version;
    pthread_cond_broadcast(&e->cv);
    pthread_mutex_unlock(&e->mu);
}

void tt_live_engine_watched(tt_live_engine *e, int pages)
{
    pthread_mutex_lock(&e->mu);
    e->v.idle = pages <= 0;
    e->v.status_version = ++e->v.version;
    pthread_cond_broadcast(&e->cv);
    pthread_mutex_unlock(&e->mu);
}

void tt_live_engine_lock(tt_live_engine *e) { pthread_mutex_lock(&e->mu); }
void tt_live_engine_unlock(tt_live_engine *e) { pthread_mutex_unlock(&e->mu); }
const tt_live_view *tt_live_engine_view(const tt_live_engine *e) { return &e->v; }
