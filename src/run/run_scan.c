/* tiptap scan's whole sequence (tt_run_scan) and its folder of outputs: GSF, PNG,
 * scan.gwy, profile.csv and scan.h5 (see include/tiptap/run/run.h). */
#include "tiptap/run/run.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/config/meta.h"
#include "tiptap/instrument/scan_hdf5.h"
#include "tiptap/io/files.h"
#include "tiptap/io/gsf.h"
#include "tiptap/io/gwy.h"
#include "tiptap/io/hdf5.h"
#include "tiptap/io/image.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/clock.h"
#include "tiptap/util/error.h"
#include "tiptap/version.h"

#include "run_scan_private.h"

static double display_scale(int ch, const char **unit, tt_colormap *cmap)
{
    if (ch == TT_CH_ARTEFACT_INDEX) { /* a difference: either sign */
        *unit = "nm";
        *cmap = TT_CMAP_DIVERGING;
        return 1e9;
    }
    if (ch >= TT_CH_LOSS_INDEX && ch < TT_CH_LOSS_INDEX + 3) { /* the loss per mechanism */
        *unit = "aJ";
        *cmap = TT_CMAP_VIRIDIS;
        return 1e18;
    }
    if (ch == TT_CH_CERTAINTY_INDEX) { /* 0 or 1 */
        *unit = "";
        *cmap = TT_CMAP_VIRIDIS;
        return 1;
    }
    /* higher harmonics are tens of picometres where the fundamental is nanometres */
    if (ch >= TT_CH_HARMONIC_PHASE_INDEX && ch < TT_CH_ARTEFACT_INDEX) {
        *unit = "deg";
        *cmap = TT_CMAP_VIRIDIS;
        return 1;
    }
    if (ch >= TT_CH_HARMONIC_INDEX && ch < TT_CH_ARTEFACT_INDEX) {
        *unit = "pm";
        *cmap = TT_CMAP_VIRIDIS;
        return 1e12;
    }
    switch (ch) {
    case 2: case TT_CH_PHASE2_INDEX: *unit = "deg"; *cmap = TT_CMAP_VIRIDIS; return 1;
    /* mode 2's amplitude: a fraction of a nanometre, on the phase's map to read beside it */
    case TT_CH_AMPLITUDE2_INDEX: *unit = "pm"; *cmap = TT_CMAP_VIRIDIS; return 1e12;
    case 3: *unit = "nN"; *cmap = TT_CMAP_VIRIDIS; return 1e9;
    case 5: *unit = "aJ"; *cmap = TT_CMAP_VIRIDIS; return 1e18;
    case 1: *unit = "nm"; *cmap = TT_CMAP_DIVERGING; return 1e9;
    default: *unit = "nm"; *cmap = TT_CMAP_GOLD; return 1e9;
    }
}

void tt_run_scan_channel_file(char *buf, size_t len, const char *dir, int ch, int r, int png)
{
    snprintf(buf, len, "%s/%s_%s.%s", dir, tt_scan_channel_name(ch), r ? "retrace" : "trace",
             png ? "png" : "gsf");
}

int tt_run_scan_check_outputs(const char *dir, const tt_scan *scan, int hdf5)
{
    /* written by every scan (scope.*: when the record holds a line) */
    static const char *const written[] = {"scene.ini", "profile.csv", "scan.gwy", "scope.csv", "scope.png"};
    char path[4200];
    int rc = TT_OK;
    for (size_t i = 0; i < sizeof written / sizeof written[0] && !rc; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, written[i]);
        rc = tt_output_check(path);
    }
    /* scan.h5 with hdf5 (without, an earlier run's is removed); the lock file checks
     * its own kind (tt_folder_lock) */
    snprintf(path, sizeof path, "%s/scan.h5", dir);
    if (!rc)
        rc = hdf5 ? tt_output_check(path) : tt_output_check_inputs(path);
    snprintf(path, sizeof path, "%s/.tiptap.lock", dir);
    if (!rc)
        rc = tt_output_check_inputs(path);
    /* every channel's files, also those this run does not write: it may remove them */
    for (int k = 0; k < 4 * TT_CH_COUNT && !rc; k++) {
        tt_run_scan_channel_file(path, sizeof path, dir, k / 4, k / 2 % 2, k % 2);
        rc = tt_scan_image(scan, k / 4, k / 2 % 2) ? tt_output_check(path) : tt_output_check_inputs(path);
    }
    return rc;
}

/* The run's metadata, as every file of the scan carries it: the version, the lines
 * finished and every key of the effective scene. */
static int scan_meta(tt_meta *m, const tt_scan *scan, const tt_scene *scene)
{
    char v[3][64];
    snprintf(v[0], sizeof v[0], "%s", TIPTAP_VERSION_STRING);
    snprintf(v[1], sizeof v[1], "%ld", tt_scan_lines_done(scan));
    snprintf(v[2], sizeof v[2], "%ld", tt_scan_lines(scan));
    const char *keys[] = {"tiptap_version", "lines_finished", "lines_total"};
    const char *vals[] = {v[0], v[1], v[2]};
    return tt_meta_scene(m, scene, keys, vals, 3);
}

/* path (docs/hdf5.md) with the metadata of the other files and the effective scene. */
static int write_hdf5(const tt_scan *scan, const tt_scene *scene, const char *path, const tt_meta *m)
{
    char *text = tt_scene_write_string(scene, NULL);
    if (!text)
        return TT_ENOMEM;
    int rc = tt_scan_write_hdf5(path, scan, (const char *const *)m->keys,
                                (const char *const *)m->values, m->n, text);
    free(text);
    return rc;
}

/* The folder's files as jobs for the scan's threads: each channel's GSF and PNG (the
 * PNGs' deflate is most of the writing, more than the lines of a small noisy scan), then
 * scan.gwy, scan.h5 and profile.csv; every file's bytes are the same on any number. */
struct run_folder {
    const tt_scan *scan;
    const tt_scene *scene;
    const char *dir;
    tt_meta meta;
    int nch, hdf5;
    int chan[2 * TT_CH_COUNT][2]; /* the channels written: (channel, retrace) */
    char title[2 * TT_CH_COUNT][128], gwy_title[2 * TT_CH_COUNT][128];
    tt_gwy_channel gch[2 * TT_CH_COUNT];
};
typedef run_folder folder;

/* Job j < nch: channel chan[j]'s GSF and PNG; *n counts the files written. */
static int write_channel(const folder *F, int j, int *n)
{
    const tt_scan *scan = F->scan;
    const int ch = F->chan[j][0], r = F->chan[j][1];
    const double *img = tt_scan_image(scan, ch, r);
    const long xres = tt_scan_xres(scan), yres = tt_scan_yres(scan);
    char path[4096];
    tt_gsf_field g = {(size_t)xres, (size_t)yres, tt_scan_size_x(scan), tt_scan_size_y(scan),
                      0, 0, "m", tt_scan_channel_unit(ch), F->title[j], img,
                      (const char *const *)F->meta.keys, (const char *const *)F->meta.values, F->meta.n};
    tt_run_scan_channel_file(path, sizeof path, F->dir, ch, r, 0);
    int rc = tt_gsf_write(path, &g);
    if (rc)
        return rc;
    tt_image im = {(size_t)xres, (size_t)yres, tt_scan_size_x(scan), tt_scan_size_y(scan),
                   img, F->title[j], NULL, 1, TT_CMAP_GOLD};
    im.unit_scale = display_scale(ch, &im.unit, &im.cmap);
    tt_run_scan_channel_file(path, sizeof path, F->dir, ch, r, 1);
    rc = tt_image_write_png(path, &im);
    *n += rc == TT_OK ? 2 : 1;
    return rc;
}

/* The line profile along the fast axis: a row, or a column when it is y. */
static int write_profile(const folder *F, int *n)
{
    const tt_scan *scan = F->scan;
    const long xres = tt_scan_xres(scan), yres = tt_scan_yres(scan);
    char path[4096];
    snprintf(path, sizeof path, "%s/profile.csv", F->dir);
    tt_outfile *of;
    int rc = tt_outfile_open(&of, path);
    if (rc)
        return rc;
    FILE *f = tt_outfile_stream(of);
    long line = tt_scan_profile_line(scan);
    int fy = tt_scan_fast_y(scan);
    long np = fy ? yres : xres;
    double size = fy ? tt_scan_size_y(scan) : tt_scan_size_x(scan);
    fprintf(f, "position_nm");
    for (int j = 0; j < F->nch; j++) {
        const int ch = F->chan[j][0], r = F->chan[j][1];
        fprintf(f, ",%s_%s%s%s", tt_scan_channel_name(ch), r ? "retrace" : "trace",
                *tt_scan_channel_unit(ch) ? "_" : "", tt_scan_channel_unit(ch));
    }
    fputc('\n', f);
    for (long px = 0; px < np; px++) {
        fprintf(f, "%.9g", (px + 0.5) * size / (double)np * 1e9);
        for (int j = 0; j < F->nch; j++) {
            const double *img = tt_scan_image(scan, F->chan[j][0], F->chan[j][1]);
            fprintf(f, ",%.9g", img[fy ? px * xres + line : line * xres + px]);
        }
        fputc('\n', f);
    }
    rc = tt_outfile_close(of, 1);
    *n += rc == TT_OK;
    return rc;
}

/* Job j: the channels' files, then scan.gwy, scan.h5 (the only HDF5 user, so one
 * thread at a time) and profile.csv. */
int run_folder_job(const run_folder *F, int j, int *n)
{
    char path[4096];
    int rc = TT_OK;
    if (j < F->nch)
        return write_channel(F, j, n);
    if (j == F->nch) {
        snprintf(path, sizeof path, "%s/scan.gwy", F->dir);
        if (F->nch > 0 && (rc = tt_gwy_write(path, F->gch, (size_t)F->nch, (const char *const *)F->meta.keys,
                                             (const char *const *)F->meta.values, F->meta.n)) == TT_OK)
            (*n)++;
        return rc;
    }
    if (j == F->nch + 1) {
        snprintf(path, sizeof path, "%s/scan.h5", F->dir);
        if (F->hdf5 && (rc = write_hdf5(F->scan, F->scene, path, &F->meta)) == TT_OK)
            (*n)++;
        return rc;
    }
    return write_profile(F, n);
}

static void folder_channels(folder *F)
{
    const tt_scan *scan = F->scan;
    for (int ch = 0; ch < TT_CH_COUNT; ch++)
        for (int r = 0; r < 2; r++) {
            const double *img = tt_scan_image(scan, ch, r);
            if (!img)
                continue;
            const int j = F->nch++;
            F->chan[j][0] = ch;
            F->chan[j][1] = r;
            snprintf(F->title[j], sizeof F->title[j], "%s (%s)", tt_scan_channel_name(ch),
                     r ? "retrace" : "trace");
            tt_gwy_title(F->gwy_title[j], sizeof F->gwy_title[j], tt_scan_channel_name(ch), r);
            F->gch[j] = (tt_gwy_channel){F->gwy_title[j], (size_t)tt_scan_xres(scan),
                                         (size_t)tt_scan_yres(scan), tt_scan_size_x(scan),
                                         tt_scan_size_y(scan), 0, 0, "m", tt_scan_channel_unit(ch), img};
        }
}

int run_folder_open(run_folder **out, const tt_scan *scan, const tt_scene *scene, const char *dir,
                    int hdf5)
{
    *out = NULL;
    folder *F = calloc(1, sizeof *F);
    if (!F)
        return tt_error_nomem("the scan's files");
    *F = (folder){.scan = scan, .scene = scene, .dir = dir, .hdf5 = hdf5};
    int rc = scan_meta(&F->meta, scan, scene);
    if (rc) {
        free(F);
        return rc;
    }
    folder_channels(F);
    *out = F;
    return TT_OK;
}

int run_folder_jobs(const run_folder *F)
{
    return F->nch + 3;
}

void run_folder_free(run_folder *F)
{
    if (!F)
        return;
    tt_meta_free(&F->meta);
    free(F);
}

int tt_run_scan_write_outputs(const tt_scan *scan, const tt_scene *scene, const char *dir, int hdf5,
                              int threads, int *written)
{
    run_after A = {.threads = threads};
    int rc = run_folder_open(&A.folder, scan, scene, dir, hdf5);
    if (rc == TT_OK)
        rc = run_after_files(&A, written);
    run_folder_free(A.folder);
    return rc;
}

int tt_run_scan_write_hdf5(const tt_scan *scan, const tt_scene *scene, const char *path)
{
    tt_meta meta;
    int rc = scan_meta(&meta, scan, scene);
    if (rc)
        return rc;
    rc = write_hdf5(scan, scene, path, &meta);
    tt_meta_free(&meta);
    return rc;
}

/* path can be written (made and removed again), and is no file the scene reads. */
static int check_hdf5(const tt_scene *scene, const char *path)
{
    tt_h5 *f;
    tt_config_note_inputs(scene);
    int rc = tt_h5_create(&f, path);
    return rc ? rc : tt_h5_close(f, 0);
}

int tt_run_scan(const tt_scene *s, const tt_run_scan_job *job, tt_run_scan_result *r)
{
    memset(r, 0, sizeof *r);
    r->estimate_status = -1;
    const double t0 = tt_clock(TT_CLOCK_WALL), c0 = tt_clock(TT_CLOCK_PROCESS);
    void *u = job->user;
    tt_scan *scan = NULL;
    int rc = tt_run_scan_alloc(s, job->threads, &scan, &r->cost);
    r->scan = scan;
    if (rc)
        return rc;
    if (job->scope)
        tt_scan_scope_attach(scan, tt_scan_profile_line(scan), job->scope);
    if (job->made && (rc = job->made(u, scan, &r->cost)))
        return rc;
    tt_run_scan_warn_inputs(s, &r->cost);
    /* the outputs checked and their folder made before the lines run: a bad output fails
     * at once, not after an hour of scanning */
    if (job->folder && ((rc = tt_run_scan_check_outputs(job->folder, scan, job->hdf5)) ||
                        (rc = tt_mkdirs(job->folder))))
        return rc;
    if (job->ready && (rc = job->ready(u, scan)))
        return rc;
    if (job->hdf5_file && (rc = check_hdf5(s, job->hdf5_file)))
        return rc;
    rc = tt_scan_run(scan, job->threads, job->progress, u);
    tt_run_scan_warn_result(scan);
    /* the estimate's companion lines run beside the files (after a scan that finished) */
    tt_scan_estimate *est = NULL;
    int erc = rc == TT_OK && job->estimate ? tt_scan_estimate_plan(scan, &est) : -1;
    char erc_msg[1024]; /* a failed plan's message, kept past the files */
    snprintf(erc_msg, sizeof erc_msg, "%s", erc > 0 ? tt_error_message() : "");
    double files_end = tt_clock(TT_CLOCK_WALL);
    if (tt_scan_lines_done(scan) > 0) {
        /* the lines finished are written, also after a failure or a cancel, whose
         * message is kept */
        char saved[1024];
        snprintf(saved, sizeof saved, "%s", tt_error_message());
        run_after A = {.threads = job->threads, .est = est, .scan = scan, .user = u,
                       .file = job->files};
        A.nfiles = job->files ? job->files(u, scan, -1, NULL) : 0;
        int wrc = job->folder ? run_folder_open(&A.folder, scan, s, job->folder, job->hdf5) : TT_OK;
        if (!wrc)
            wrc = run_after_files(&A, &r->written);
        run_folder_free(A.folder);
        const double after = tt_clock(TT_CLOCK_WALL);
        if (!wrc && job->hdf5_file)
            wrc = tt_run_scan_write_hdf5(scan, s, job->hdf5_file);
        if (job->finished) {
            int frc = job->finished(u, scan, wrc);
            wrc = wrc ? wrc : frc;
        }
        /* the files' end, and what the hooks took after the loop */
        files_end = A.files_end + (tt_clock(TT_CLOCK_WALL) - after);
        if (job->scope)
            r->oscillating = tt_run_scan_warn_oscillation(scan, job->scope, job->scope_files);
        if (wrc && !rc)
            rc = wrc;
        else if (rc)
            tt_error(rc, "%s", saved);
    } else if (job->finished) {
        int frc = job->finished(u, scan, TT_OK);
        rc = rc ? rc : frc;
    }
    r->scan_seconds = files_end - t0;
    if (rc == TT_OK && job->estimate) {
        /* the companion lines ran with the files; a scan without lines runs them now */
        if (erc == TT_OK && tt_scan_lines_done(scan) == 0) {
            for (int j = 0; j < tt_scan_estimate_jobs(est); j++)
                tt_scan_estimate_job(est, j);
        }
        r->estimate_status = erc == TT_OK ? tt_scan_estimate_finish(est, &r->est)
                                          : tt_error(erc, "%s", erc_msg);
        est = NULL;
        /* stopped in the companion: the images are written, the status says so */
        if (r->estimate_status == TT_EINTR)
            rc = tt_error(TT_EINTR, "interrupted in the error estimate's companion line; the "
                                    "images (%ld of %ld lines) are written",
                          tt_scan_lines_done(scan), tt_scan_lines(scan));
    }
    tt_scan_estimate_free(est); /* not reported: the run failed */
    /* the whole run's time, the estimate's companion line included */
    r->seconds = tt_clock(TT_CLOCK_WALL) - t0;
    r->cpu_seconds = tt_clock(TT_CLOCK_PROCESS) - c0;
    if (job->summary)
        job->summary(u, scan, r); /* which raises the estimate's warning among its lines */
    else if (r->estimate_status == TT_OK)
        tt_run_scan_warn_error(scan, &r->cost, &r->est);
    return rc;
}
