/* The live console's benches (bench_private.h): a force curve and a thermal tune run
 * through the run layer on a thread of their own, their results as JSON for the page. */
#include "bench_private.h"

#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/run/force.h"
#include "tiptap/run/tune.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

enum {
    CURVE_POINTS = 3000, /* a force curve's rows sent at most (a screen's width, thrice) */
    SPECTRUM_POINTS = 400, /* a spectrum's log-spaced points sent at most */
    ZOOM_BINS = 2000       /* the resonance's own bins sent at most */
};

struct tt_live_bench {
    pthread_mutex_t mu;
    pthread_t thread;
    int started, busy, kind;
    int stop; /* the thread's own cancellation (tt_cancel_watch): set when freed */
    tt_scene *scene;
    void (*wake)(void *);
    void *user;
    char *msg[TT_BENCH_KINDS];
    size_t len[TT_BENCH_KINDS];
    unsigned long version[TT_BENCH_KINDS];
};

static const char *const kind_name[TT_BENCH_KINDS] = {"force", "tune"};

int tt_live_bench_alloc(tt_live_bench **out, void (*wake)(void *), void *user)
{
    tt_live_bench *b = calloc(1, sizeof *b);
    if (!b)
        return tt_error_nomem("the console's benches");
    pthread_mutex_init(&b->mu, NULL);
    b->wake = wake;
    b->user = user;
    *out = b;
    return TT_OK;
}

void tt_live_bench_free(tt_live_bench *b)
{
    if (!b)
        return;
    if (b->started) {
        __atomic_store_n(&b->stop, 1, __ATOMIC_SEQ_CST);
        pthread_join(b->thread, NULL);
    }
    tt_scene_free(b->scene);
    for (int k = 0; k < TT_BENCH_KINDS; k++)
        free(b->msg[k]);
    pthread_mutex_destroy(&b->mu);
    free(b);
}

/* The message of kind replaced by buf's text (under mu), and the page woken. */
static void publish(tt_live_bench *b, int kind, tt_live_buf *buf, int done)
{
    char *text = buf->failed ? NULL : malloc(buf->len + 1);
    if (text) {
        memcpy(text, tt_live_buf_text(buf), buf->len);
        text[buf->len] = '\0';
    }
    pthread_mutex_lock(&b->mu);
    free(b->msg[kind]);
    b->msg[kind] = text;
    b->len[kind] = text ? buf->len : 0;
    b->version[kind]++;
    if (done)
        b->busy = 0;
    pthread_mutex_unlock(&b->mu);
    if (b->wake)
        b->wake(b->user);
}

static void head(tt_live_buf *o, int kind, const char *state, const char *why)
{
    tt_live_buf_printf(o, "{\"type\":\"%s\",\"state\":\"%s\",\"error\":", kind_name[kind], state);
    if (why)
        tt_live_json_str(o, why);
    else
        tt_live_buf_printf(o, "null");
}

static void field(tt_live_buf *o, const char *name, double x)
{
    tt_live_buf_printf(o, ",\"%s\":", name);
    tt_live_json_num(o, x);
}

/* A column's values at every stride-th row into room (n of them). */
static void column(tt_live_buf *o, const char *name, const tt_table *t, const char *col, size_t stride,
                   double *room, size_t n)
{
    long c = tt_table_find(t, col);
    const double *x = c >= 0 ? tt_table_numbers(t, (size_t)c) : NULL;
    for (size_t i = 0; i < n; i++)
        room[i] = x ? x[i * stride] : NAN;
    tt_live_buf_printf(o, ",\"%s\":", name);
    tt_live_json_array(o, room, n);
}

/* The curve, every stride-th row, and its summary; the pull-off's separation is the
 * retract's row nearest its z (the summary gives its z and force). */
static void force_message(tt_live_buf *o, const tt_table *t, const tt_force_summary *s, const char *material)
{
    size_t rows = tt_table_rows(t), stride = rows / CURVE_POINTS + 1, n = (rows + stride - 1) / stride;
    double *room = malloc((n ? n : 1) * sizeof *room);
    long leg = tt_table_find(t, "leg"), zc = tt_table_find(t, "z"), sc = tt_table_find(t, "separation");
    double pull_sep = NAN, best = INFINITY;
    for (size_t i = 0; leg >= 0 && zc >= 0 && sc >= 0 && i < rows; i++)
        if (strcmp(tt_table_text(t, (size_t)leg, i), "retract") == 0 &&
            fabs(tt_table_numbers(t, (size_t)zc)[i] - s->pulloff_z) < best) {
            best = fabs(tt_table_numbers(t, (size_t)zc)[i] - s->pulloff_z);
            pull_sep = tt_table_numbers(t, (size_t)sc)[i];
        }
    head(o, TT_BENCH_FORCE, "done", NULL);
    tt_live_buf_printf(o, ",\"material\":");
    tt_live_json_str(o, material ? material : "");
    field(o, "k", s->k), field(o, "speed", s->speed), field(o, "jumpin_z", s->jumpin_z);
    field(o, "jumpin_force", s->jumpin_force), field(o, "jumpin_separation", s->jumpin_gap);
    field(o, "pulloff_z", s->pulloff_z), field(o, "pulloff_force", s->pulloff_force);
    field(o, "pulloff_separation", pull_sep), field(o, "adhesion", s->adhesion);
    field(o, "max_force", s->max_force), field(o, "slope", s->slope), field(o, "indentation", s->indentation);
    if (!room) {
        o->failed = 1;
        return;
    }
    column(o, "z", t, "z", stride, room, n);
    column(o, "separation", t, "separation", stride, room, n);
    column(o, "force", t, "force", stride, room, n);
    /* the legs as numbers: 0 approach, 1 dwell, 2 retract */
    for (size_t i = 0; i < n; i++) {
        const char *l = leg >= 0 ? tt_table_text(t, (size_t)leg, i * stride) : "";
        room[i] = strcmp(l, "approach") == 0 ? 0 : strcmp(l, "dwell") == 0 ? 1 : 2;
    }
    tt_live_buf_printf(o, ",\"leg\":");
    tt_live_json_array(o, room, n);
    tt_live_buf_printf(o, "}");
    free(room);
}

/* Mode m's resonance bin by bin, f0 +- 12 f0 / Q, where log-spaced points are too coarse
 * to show its peak (a point there spans many of its widths): its figures, its scene's k
 * and its bins as one object of the message's "modes". */
static void tune_mode(tt_live_buf *o, const tt_tune_mode *md, double k_scene, const double *f, const double *p,
                      const double *q, size_t rows)
{
    size_t lo = rows, hi = 0;
    for (size_t i = 1; i < rows; i++)
        if (fabs(f[i] - md->f0) <= 12 * md->f0 / md->Q)
            lo = i < lo ? i : lo, hi = i;
    size_t nz = lo <= hi && hi - lo < ZOOM_BINS ? hi + 1 - lo : 0;
    lo = nz ? lo : 0;
    tt_live_buf_printf(o, "{\"f0\":");
    tt_live_json_num(o, md->f0);
    field(o, "f0_err", md->f0_err), field(o, "Q", md->Q), field(o, "Q_err", md->Q_err);
    field(o, "k", md->k), field(o, "k_err", md->k_err), field(o, "k_scene", k_scene), field(o, "chi", md->chi);
    field(o, "chi2_dof", md->chi2_dof), field(o, "fit_low", md->fit_low), field(o, "fit_high", md->fit_high);
    tt_live_buf_printf(o, ",\"zoom_f\":");
    tt_live_json_array(o, f + lo, nz);
    tt_live_buf_printf(o, ",\"zoom_psd\":");
    tt_live_json_array(o, p + lo, nz);
    tt_live_buf_printf(o, ",\"zoom_fit\":");
    tt_live_json_array(o, q + lo, nz);
    tt_live_buf_printf(o, "}");
}

/* The spectrum on log-spaced points (each the mean of the bins it covers: the fit where
 * every bin has one), mode 1's figures beside the scene's k, and every mode's figures and
 * resonance in "modes" (the fit column: the whole model in each mode's window). */
static void tune_message(tt_live_buf *o, const tt_table *t, const tt_tune_result *r, const tt_cantilever *c)
{
    size_t rows = tt_table_rows(t);
    double *m = calloc(3 * SPECTRUM_POINTS, sizeof *m);
    long fc = tt_table_find(t, "f"), pc = tt_table_find(t, "psd"), qc = tt_table_find(t, "fit");
    size_t n = 0;
    head(o, TT_BENCH_TUNE, "done", NULL);
    field(o, "f0", r->f0), field(o, "f0_err", r->f0_err), field(o, "Q", r->Q), field(o, "Q_err", r->Q_err);
    field(o, "k", r->k), field(o, "k_err", r->k_err), field(o, "k_scene", c->k), field(o, "chi", r->chi);
    field(o, "temperature", r->temperature), field(o, "averages", r->averages);
    field(o, "fit_low", r->fit_low), field(o, "fit_high", r->fit_high), field(o, "floor", r->white);
    field(o, "chi2_dof", r->chi2_dof), field(o, "bin_width", r->bin_width);
    if (!m || fc < 0 || pc < 0 || qc < 0 || rows < 2) {
        o->failed = 1;
        free(m);
        return;
    }
    const double *f = tt_table_numbers(t, (size_t)fc), *p = tt_table_numbers(t, (size_t)pc),
                 *q = tt_table_numbers(t, (size_t)qc);
    double *fo = m, *po = m + SPECTRUM_POINTS, *qo = m + 2 * SPECTRUM_POINTS;
    /* bins 1 .. rows-1 (0 is DC, off a log axis) grouped by log(i) */
    for (size_t i = 1, j; i < rows; i = j) {
        double edge = exp(log((double)rows) * (double)(n + 1) / SPECTRUM_POINTS);
        double sf = 0, sp = 0, sq = 0;
        for (j = i; j < rows && (j == i || (double)j < edge); j++)
            sf += f[j], sp += p[j], sq += q[j];
        double w = (double)(j - i);
        fo[n] = sf / w, po[n] = sp / w, qo[n] = sq / w; /* NAN where a bin is outside the fit */
        if (++n == SPECTRUM_POINTS)
            break;
    }
    tt_live_buf_printf(o, ",\"f\":");
    tt_live_json_array(o, fo, n);
    tt_live_buf_printf(o, ",\"psd\":");
    tt_live_json_array(o, po, n);
    tt_live_buf_printf(o, ",\"fit\":");
    tt_live_json_array(o, qo, n);
    tt_live_buf_printf(o, ",\"modes\":[");
    for (int k = 0; k < r->modes; k++) {
        tt_live_buf_printf(o, k ? "," : "");
        tune_mode(o, &r->mode[k], k ? c->mode_k[k] : c->k, f, p, q, rows);
    }
    tt_live_buf_printf(o, "]}");
    free(m);
}

static void *bench_main(void *arg)
{
    tt_live_bench *b = arg;
    tt_cancel_watch(&b->stop);
    tt_live_buf o = {.max = 64 << 20};
    tt_table *t = NULL;
    int rc;
    if (b->kind == TT_BENCH_FORCE) {
        tt_force_summary s;
        tt_force_params fp;
        tt_material *m = NULL;
        size_t nm = 0;
        const char *mat = tt_config_force(b->scene, &fp) == TT_OK ? fp.material : NULL;
        /* the name of the material under the tip: [force] material's, else the first */
        if (!mat && tt_config_materials(b->scene, &m, &nm) == TT_OK && nm)
            mat = m[0].name;
        if ((rc = tt_run_force(b->scene, &t, &s, NULL, NULL)) == TT_OK)
            force_message(&o, t, &s, mat);
        free(m);
    } else {
        tt_tune_result r;
        tt_cantilever lever;
        if (tt_config_cantilever(b->scene, &lever) != TT_OK)
            lever = (tt_cantilever){.k = NAN}; /* (tt_run_tune refuses it with its line) */
        if ((rc = tt_run_tune(b->scene, &t, &r, NULL, NULL)) == TT_OK)
            tune_message(&o, t, &r, &lever);
    }
    if (rc || o.failed) {
        const char *why = rc ? tt_error_message() : "console: the result is too large to send";
        tt_live_buf_reset(&o);
        head(&o, b->kind, "failed", why);
        tt_live_buf_printf(&o, "}");
    }
    tt_table_free(t);
    publish(b, b->kind, &o, 1);
    tt_live_buf_free(&o);
    return NULL;
}

int tt_live_bench_run(tt_live_bench *b, int kind, tt_scene *scene)
{
    tt_force_params fp;
    tt_tune_params tp;
    pthread_mutex_lock(&b->mu);
    int busy = b->busy, other = b->kind;
    pthread_mutex_unlock(&b->mu);
    /* (only this, the server's thread, starts runs: busy cannot become 1 meanwhile) */
    int rc = busy ? tt_error(TT_EINVAL, "console: a %s is under way; wait for it",
                             other == TT_BENCH_FORCE ? "force curve" : "thermal tune")
             : kind == TT_BENCH_FORCE ? tt_config_force(scene, &fp)
                                      : tt_config_tune(scene, &tp);
    if (rc) {
        tt_scene_free(scene);
        return rc;
    }
    if (b->started)
        pthread_join(b->thread, NULL); /* the last run's, finished */
    b->started = 0;
    tt_scene_free(b->scene);
    b->scene = scene;
    pthread_mutex_lock(&b->mu);
    b->kind = kind;
    b->busy = 1;
    pthread_mutex_unlock(&b->mu);
    tt_live_buf o = {.max = 4096};
    head(&o, kind, "running", NULL);
    tt_live_buf_printf(&o, "}");
    publish(b, kind, &o, 0);
    tt_live_buf_free(&o);
    /* the signals stay with the server's thread, whose poll they end (as the engine's) */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, &old);
    int failed = pthread_create(&b->thread, NULL, bench_main, b);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (failed) {
        pthread_mutex_lock(&b->mu);
        b->busy = 0;
        pthread_mutex_unlock(&b->mu);
        return tt_error(TT_ENOMEM, "console: no thread for the %s", kind_name[kind]);
    }
    b->started = 1;
    return TT_OK;
}

int tt_live_bench_message(tt_live_bench *b, int kind, unsigned long *seen, tt_live_buf *out)
{
    int wrote = 0;
    pthread_mutex_lock(&b->mu);
    if (b->version[kind] != *seen) {
        *seen = b->version[kind];
        if (b->msg[kind]) {
            tt_live_buf_printf(out, "%s", b->msg[kind]);
            wrote = 1;
        }
    }
    pthread_mutex_unlock(&b->mu);
    return wrote;
}
