/* Force volume: a force curve per pixel of the scan's raster (see
 * include/tiptap/run/force_volume.h). */
#include "tiptap/run/force_volume.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run_force_private.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scanner.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

struct tt_force_volume {
    tt_raster r;
    long xres, yres;
    double *map[TT_FV_COUNT];
    tt_force_summary *pixel; /* by tt_raster_index */
    char *line_done;
    long lines_done, cycles;
    int status;         /* the first failure's code (TT_OK: none) */
    char message[1024]; /* and its line */
};

static const struct {
    const char *name, *unit;
} channels[TT_FV_COUNT] = {
    {"height", "m"},        {"adhesion", "N"},   {"stiffness", "N/m"}, {"pulloff_distance", "m"},
    {"pulloff_force", "N"}, {"indentation", "m"}, {"max_force", "N"},  {"material", ""},
};

const char *tt_force_volume_channel_name(int ch)
{
    return ch >= 0 && ch < TT_FV_COUNT ? channels[ch].name : NULL;
}

const char *tt_force_volume_channel_unit(int ch)
{
    return ch >= 0 && ch < TT_FV_COUNT ? channels[ch].unit : NULL;
}

void tt_force_volume_free(tt_force_volume *v)
{
    if (!v)
        return;
    for (int ch = 0; ch < TT_FV_COUNT; ch++)
        free(v->map[ch]);
    free(v->pixel);
    free(v->line_done);
    free(v);
}

static int volume_alloc(const tt_raster *r, tt_force_volume **out)
{
    tt_force_volume *v = calloc(1, sizeof *v);
    const size_t n = (size_t)r->pixels * (size_t)r->lines;
    *out = v;
    if (!v)
        return tt_error_nomem("the force volume");
    v->r = *r;
    v->xres = r->fast_y ? r->lines : r->pixels;
    v->yres = r->fast_y ? r->pixels : r->lines;
    int ok = (v->pixel = calloc(n, sizeof *v->pixel)) && (v->line_done = calloc((size_t)r->lines, 1));
    for (int ch = 0; ch < TT_FV_COUNT && ok; ch++) {
        ok = (v->map[ch] = malloc(n * sizeof *v->map[ch])) != NULL;
        for (size_t i = 0; ok && i < n; i++)
            v->map[ch][i] = NAN;
    }
    return ok ? TT_OK : tt_error_nomem("the force volume's %ld by %ld maps", r->pixels, r->lines);
}

/* The pixel's figures into the maps at index i. */
static void put_pixel(tt_force_volume *v, long i, const tt_force_summary *s, double h, size_t mat)
{
    const double m[TT_FV_COUNT] = {h + s->contact_z, s->adhesion,     s->slope,     s->pulloff_z,
                                   s->pulloff_force, s->indentation, s->max_force, (double)mat};
    for (int ch = 0; ch < TT_FV_COUNT; ch++)
        v->map[ch][i] = m[ch];
    v->pixel[i] = *s;
}

/* One line's curves, each pixel at its centre's height and material; the maps get the
 * line only when all of it is done. */
static int volume_line(tt_force_volume *v, force_lever *L, const tt_surface *surf, long line, long *cycles)
{
    const tt_raster *r = &v->r;
    const long total = 2 * L->p.leg_periods + L->p.dwell_periods;
    tt_force_summary *sums = malloc((size_t)r->pixels * sizeof *sums);
    double *h = malloc((size_t)r->pixels * sizeof *h);
    size_t *mat = malloc((size_t)r->pixels * sizeof *mat);
    int rc = sums && h && mat ? TT_OK : tt_error_nomem("a force volume line of %ld pixels", r->pixels);
    for (long px = 0; px < r->pixels && rc == TT_OK; px++) {
        const double fast = (r->fast_y ? r->size_y : r->size_x) * ((double)px + 0.5) / (double)r->pixels;
        const double slow = (r->fast_y ? r->size_x : r->size_y) * ((double)line + 0.5) / (double)r->lines;
        const double x = r->fast_y ? slow : fast, y = r->fast_y ? fast : slow;
        h[px] = tt_surface_height(surf, x, y);
        mat[px] = (size_t)tt_surface_material(surf, x, y);
        tt_table *t = force_table();
        long done = 0;
        /* the pixel's own stream: the same noise whichever thread runs it */
        const uint64_t key = tt_noise_key(L->seed, TT_NOISE_THERMAL, line * r->pixels + px);
        rc = t ? force_curve(L, mat[px], key, t, &sums[px], NULL, NULL, &done, total) : TT_ENOMEM;
        *cycles += done;
        tt_table_free(t);
    }
    for (long px = 0; px < r->pixels && rc == TT_OK; px++)
        put_pixel(v, tt_raster_index(r, line, px), &sums[px], h[px], mat[px]);
    free(sums), free(h), free(mat);
    return rc;
}

/* The lines over threads, as the scan runs them: dynamic, one line at a time. */
static void run_lines(tt_force_volume *v, force_lever *W, int threads, const tt_surface *surf,
                      tt_progress_fn progress, void *user)
{
    const long total = v->r.lines;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long line = 0; line < total; line++) {
        int failed;
#pragma omp atomic read
        failed = v->status;
        if (failed || tt_cancel_requested())
            continue;
        long cycles = 0;
        int rc = volume_line(v, &W[omp_get_thread_num()], surf, line, &cycles);
#pragma omp critical(tt_force_volume_result)
        {
            v->cycles += cycles;
            if (rc == TT_OK) {
                v->line_done[line] = 1;
                v->lines_done++;
                if (progress)
                    progress(user, v->lines_done, total);
            } else if (rc != TT_EINTR && v->status == TT_OK) {
                snprintf(v->message, sizeof v->message, "line %ld: %s", line, tt_error_message());
                v->status = rc;
            }
        }
    }
}

/* The lines run and, with a folder, their maps written, also when the run was cut short. */
static int run_and_write(tt_force_volume *v, const tt_scene *s, const tt_force_volume_job *job, force_lever *W,
                         int threads, const tt_surface *surf, int *written)
{
    run_lines(v, W, threads, surf, job->progress, job->user);
    int rc = TT_OK;
    if (v->status != TT_OK)
        rc = tt_error(v->status, "%s", v->message);
    else if (v->lines_done < v->r.lines)
        rc = tt_error(TT_EINTR, "interrupted after %ld of %ld lines", v->lines_done, v->r.lines);
    if (job->folder && v->lines_done > 0) {
        char saved[1024];
        snprintf(saved, sizeof saved, "%s", tt_error_message());
        int wrc = tt_force_volume_write(v, s, job->folder, job->hdf5, written);
        if (wrc && !rc)
            rc = wrc;
        else if (rc)
            tt_error(rc, "%s", saved);
    }
    return rc;
}

int tt_run_force_volume(const tt_scene *s, const tt_force_volume_job *job, tt_force_volume **out,
                        int *written)
{
    tt_raster r;
    tt_surface *surf = NULL;
    force_lever *W = NULL;
    int dummy = 0, threads = job->threads;
    *out = NULL;
    written = written ? written : &dummy;
    int rc;
    if ((rc = tt_scene_locate(s, tt_config_raster(s, &r))))
        return rc;
    if (threads <= 0)
        threads = omp_get_max_threads();
    if (threads > r.lines)
        threads = (int)r.lines;
    if (threads < 1)
        threads = 1;
    if (!(W = calloc((size_t)threads, sizeof *W)))
        return tt_error_nomem("%d force volume threads", threads);
    /* every lever made, the surface and the folder, before a line runs: a bad key fails
     * at once and leaves no folder */
    for (int i = 0; i < threads && rc == TT_OK; i++)
        rc = force_lever_alloc(s, &W[i]);
    if (rc == TT_OK)
        rc = tt_config_surface_alloc(&surf, s, r.size_x, r.size_y);
    if (rc == TT_OK && job->folder)
        rc = tt_force_volume_check_outputs(job->folder, job->hdf5);
    if (rc == TT_OK && (rc = volume_alloc(&r, out)) == TT_OK)
        rc = run_and_write(*out, s, job, W, threads, surf, written);
    else {
        tt_force_volume_free(*out);
        *out = NULL;
    }
    for (int i = 0; i < threads; i++)
        force_lever_free(&W[i]);
    free(W);
    tt_surface_free(surf);
    return rc;
}

long tt_force_volume_xres(const tt_force_volume *v) { return v->xres; }
long tt_force_volume_yres(const tt_force_volume *v) { return v->yres; }
double tt_force_volume_size_x(const tt_force_volume *v) { return v->r.size_x; }
double tt_force_volume_size_y(const tt_force_volume *v) { return v->r.size_y; }
long tt_force_volume_lines(const tt_force_volume *v) { return v->r.lines; }
long tt_force_volume_lines_done(const tt_force_volume *v) { return v->lines_done; }
long tt_force_volume_cycles(const tt_force_volume *v) { return v->cycles; }

const double *tt_force_volume_map(const tt_force_volume *v, int ch)
{
    return ch >= 0 && ch < TT_FV_COUNT ? v->map[ch] : NULL;
}

const tt_force_summary *tt_force_volume_pixel(const tt_force_volume *v, long line, long pixel)
{
    if (line < 0 || line >= v->r.lines || pixel < 0 || pixel >= v->r.pixels || !v->line_done[line])
        return NULL;
    return &v->pixel[tt_raster_index(&v->r, line, pixel)];
}
