/* tiptap scan: closed-loop imaging into Gwyddion files, PNG previews, a line profile
 * and the effective scene. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "commands.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/io/gsf.h"
#include "tiptap/io/gwy.h"
#include "tiptap/io/image.h"
#include "tiptap/io/files.h"
#include "tiptap/io/lock.h"
#include "tiptap/io/outfile.h"
#include "tiptap/config/config.h"
#include "tiptap/config/meta.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_hdf5.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/run/run.h"
#include "tiptap/version.h"

static void help(void)
{
    printf("Usage: tiptap scan SCENE... -o DIR [--set section.key=value]... [--threads N] [--hdf5]\n"
           "                   [-q]\n"
           "Closed-loop tapping image of the scene's [surface] under [scan], [lockin] and\n"
           "[feedback].\n\n"
           "  -o, --output DIR   folder for the results (made if missing): scan.gwy (one\n"
           "                     Gwyddion file: every channel, trace and retrace, the run's\n"
           "                     parameters as metadata),\n"
           "                     CHANNEL_trace.gsf, CHANNEL_retrace.gsf (Gwyddion Simple Field,\n"
           "                     SI units), CHANNEL_trace.png, ... (previews with colour bar and\n"
           "                     scale bar), profile.csv (the [scan] profile_line), scope.csv and\n"
           "                     scope.png (that line's full-rate record: z, error,\n"
           "                     amplitude, phase and the true surface at every lock-in\n"
           "                     block, trace and retrace), scene.ini (the effective scene)\n"
           "  -j, --threads N    lines computed in parallel (default: all cores); the images\n"
           "                     do not depend on it\n"
           "      --hdf5         also DIR/scan.h5: every channel, trace and retrace, in float64\n"
           "                     with x and y in metres as dimension scales, the parameters and\n"
           "                     the effective scene (docs/hdf5.md; h5py reads it)\n"
           CLI_HELP_SET
           "  -q, --quiet        no progress and summary on stderr\n\n"
           "Channels ([scan] channels): height (m), error (the error signal: lock-in amplitude -\n"
           "setpoint, m), amplitude (the lock-in amplitude, m), phase (lag, deg), peak_force (N),\n"
           "indentation (m), dissipation (J per cycle),\n"
           "topography (the true surface, m), harmonic2 ... harmonic8 (amplitude of the\n"
           "deflection's harmonic h, m; needs [lockin] harmonics >= h), harmonic2_phase ...\n"
           "harmonic8_phase (its lag behind cos(h w t), deg), artefact (height - topography, m;\n"
           "added on a measured surface unless [scan] channels is set).\nCtrl-C (or SIGTERM) abandons the\n"
           "lines under way and writes the finished lines (the others are NaN, shown grey).\n"
           "stderr starts with an estimate of the cycles, time and memory; a scan needing\n"
           "more memory than the machine has is refused, and so is a second scan into a\n"
           "folder in use (DIR/.tiptap.lock). Channel files of an earlier run in DIR that\n"
           "this run does not write are removed once its files are written, and named.\n"
           "stderr ends with the run time, the real-time factor (instrument time / run time),\n"
           "the energy balance (the largest energy-balance residual of a cycle relative to the\n"
           "free oscillation's drive work per cycle: a check) and the error estimate of height,\n"
           "phase and amplitude: twice their difference from a companion run at a 100 times\n"
           "tighter tolerance (rk4: 4 times the steps) of the image's hardest line (the largest\n"
           "height step between pixels; the profile line on a flat image), or of a stretch of\n"
           "it: the companion runs at most a fifth of the cycles the scan integrated\n"
           "(estimate_cycles, estimate_cpu_s); run_time_s includes it. A warning when the\n"
           "estimate exceeds 1e-3 of the free amplitude or 0.1 deg.\n"
           "[solver] tier: envelope (default; most cycles from the cycle map's model under\n"
           "error control), every (every cycle integrated) or averaged (a preview: the\n"
           "averaged slow flow of amplitude and phase, no cycle integrated, about 50 times\n"
           "real time on one core; its error estimate's companion runs on the envelope tier,\n"
           "and pixels where an impact collapsed the oscillation are named; docs/dynamics.md).\n");
}

static void show_progress(void *user, long done, long total)
{
    cli_progress_show(user, done, total);
}

static double display_scale(int ch, const char **unit, tt_colormap *cmap)
{
    if (ch == TT_CH_ARTEFACT_INDEX) { /* a difference: either sign */
        *unit = "nm";
        *cmap = TT_CMAP_DIVERGING;
        return 1e9;
    }
    /* higher harmonics are tens of picometres where the fundamental is nanometres */
    if (ch >= TT_CH_HARMONIC_PHASE_INDEX) {
        *unit = "deg";
        *cmap = TT_CMAP_VIRIDIS;
        return 1;
    }
    if (ch >= TT_CH_HARMONIC_INDEX) {
        *unit = "pm";
        *cmap = TT_CMAP_VIRIDIS;
        return 1e12;
    }
    switch (ch) {
    case 2: *unit = "deg"; *cmap = TT_CMAP_VIRIDIS; return 1;
    case 3: *unit = "nN"; *cmap = TT_CMAP_VIRIDIS; return 1e9;
    case 5: *unit = "aJ"; *cmap = TT_CMAP_VIRIDIS; return 1e18;
    case 1: *unit = "nm"; *cmap = TT_CMAP_DIVERGING; return 1e9;
    default: *unit = "nm"; *cmap = TT_CMAP_GOLD; return 1e9;
    }
}

/* The path of channel ch's image file in dir: retrace r, PNG or GSF. */
static void channel_path(char *buf, size_t len, const char *dir, int ch, int r, int png)
{
    snprintf(buf, len, "%s/%s_%s.%s", dir, tt_scan_channel_name(ch), r ? "retrace" : "trace",
             png ? "png" : "gsf");
}

int cli_scan_check_outputs(const char *dir, const tt_scan *scan, int hdf5)
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
        channel_path(path, sizeof path, dir, k / 4, k / 2 % 2, k % 2);
        rc = tt_scan_image(scan, k / 4, k / 2 % 2) ? tt_output_check(path) : tt_output_check_inputs(path);
    }
    return rc;
}

int cli_scan_folder_take(const char *cmd, const char *dir, const tt_scan *scan, int hdf5, int *lock)
{
    int rc;
    *lock = -1;
    if ((rc = cli_scan_check_outputs(dir, scan, hdf5)) || (rc = tt_mkdirs(dir)))
        return rc;
    return tt_folder_lock(dir, cmd, lock);
}

/* The channel files of an earlier run in dir that this one did not write (a run with
 * fewer channels, or without --hdf5: its scan.h5): removed, so that the folder holds one
 * run's images, and named on stderr. Only the names tiptap writes are touched; a link is
 * removed, not followed. */
static void remove_stale(const tt_scan *scan, const char *dir, int hdf5)
{
    char path[4200], names[4096] = "";
    int n = 0;
    for (int k = 0; k <= 4 * TT_CH_COUNT; k++) {
        int ch = k / 4, r = k / 2 % 2;
        struct stat st;
        if (k == 4 * TT_CH_COUNT ? hdf5 : tt_scan_image(scan, ch, r) != NULL)
            continue;
        if (k == 4 * TT_CH_COUNT)
            snprintf(path, sizeof path, "%s/scan.h5", dir);
        else
            channel_path(path, sizeof path, dir, ch, r, k % 2);
        if (lstat(path, &st) != 0 || !(S_ISREG(st.st_mode) || S_ISLNK(st.st_mode)) ||
            unlink(path) != 0)
            continue;
        size_t used = strlen(names);
        snprintf(names + used, sizeof names - used, "%s%s", n++ ? ", " : "", path + strlen(dir) + 1);
    }
    if (n)
        fprintf(stderr, "tiptap: %s: removed %d file%s of an earlier run with channels this run "
                        "does not write: %s\n", dir, n, n > 1 ? "s" : "", names);
}

/* DIR/scan.h5 can be written (made and removed again), before the scan runs. */
static int check_hdf5(const char *dir)
{
    char path[4200];
    tt_h5 *f;
    snprintf(path, sizeof path, "%s/scan.h5", dir);
    int rc = tt_h5_create(&f, path);
    return rc ? rc : tt_h5_close(f, 0);
}

/* DIR/scan.h5 (docs/hdf5.md) with the metadata of the other files and the effective
 * scene. */
static int write_hdf5(const tt_scan *scan, const tt_scene *scene, const char *dir, const tt_meta *m)
{
    char path[4200];
    char *text = tt_scene_write_string(scene, NULL);
    if (!text)
        return TT_ENOMEM;
    snprintf(path, sizeof path, "%s/scan.h5", dir);
    int rc = tt_scan_write_hdf5(path, scan, (const char *const *)m->keys,
                                (const char *const *)m->values, m->n, text);
    free(text);
    return rc;
}

/* Every channel, trace and retrace, with the run's parameters: GSF and PNG files, and
 * one .gwy holding them all (scan.gwy); with hdf5 also scan.h5. *written counts the
 * files. */
int cli_scan_write_outputs(const tt_scan *scan, const tt_scene *scene, const char *dir, int hdf5,
                           int *written)
{
    char path[4096], title[TT_CH_COUNT][2][128];
    long xres = tt_scan_xres(scan), yres = tt_scan_yres(scan);
    char v[3][64];
    snprintf(v[0], sizeof v[0], "%s", TIPTAP_VERSION_STRING);
    snprintf(v[1], sizeof v[1], "%ld", tt_scan_lines_done(scan));
    snprintf(v[2], sizeof v[2], "%ld", tt_scan_lines(scan));
    const char *keys[] = {"tiptap_version", "lines_finished", "lines_total"};
    const char *vals[] = {v[0], v[1], v[2]};
    tt_meta meta;
    int rc = tt_meta_scene(&meta, scene, keys, vals, 3);
    if (rc)
        return rc;
    tt_gwy_channel gch[2 * TT_CH_COUNT];
    size_t ng = 0;
    for (int ch = 0; ch < TT_CH_COUNT && rc == TT_OK; ch++) {
        for (int r = 0; r < 2 && rc == TT_OK; r++) {
            const double *img = tt_scan_image(scan, ch, r);
            if (!img)
                continue;
            const char *dirn = r ? "retrace" : "trace";
            snprintf(title[ch][r], sizeof title[ch][r], "%s (%s)", tt_scan_channel_name(ch), dirn);
            tt_gsf_field g = {(size_t)xres, (size_t)yres, tt_scan_size_x(scan), tt_scan_size_y(scan),
                              0, 0, "m", tt_scan_channel_unit(ch), title[ch][r], img,
                              (const char *const *)meta.keys, (const char *const *)meta.values, meta.n};
            gch[ng++] = (tt_gwy_channel){title[ch][r], (size_t)xres, (size_t)yres, tt_scan_size_x(scan),
                                         tt_scan_size_y(scan), 0, 0, "m", tt_scan_channel_unit(ch), img};
            channel_path(path, sizeof path, dir, ch, r, 0);
            if ((rc = tt_gsf_write(path, &g)))
                break;
            tt_image im = {(size_t)xres, (size_t)yres, tt_scan_size_x(scan), tt_scan_size_y(scan),
                           img, title[ch][r], NULL, 1, TT_CMAP_GOLD};
            im.unit_scale = display_scale(ch, &im.unit, &im.cmap);
            channel_path(path, sizeof path, dir, ch, r, 1);
            rc = tt_image_write_png(path, &im);
            *written += rc == TT_OK ? 2 : 1;
        }
    }
    snprintf(path, sizeof path, "%s/scan.gwy", dir);
    if (rc == TT_OK && ng > 0 &&
        (rc = tt_gwy_write(path, gch, ng, (const char *const *)meta.keys,
                           (const char *const *)meta.values, meta.n)) == TT_OK)
        (*written)++;
    if (rc == TT_OK && hdf5 && (rc = write_hdf5(scan, scene, dir, &meta)) == TT_OK)
        (*written)++;
    tt_meta_free(&meta);
    if (rc)
        return rc;
    /* the line profile along the fast axis */
    snprintf(path, sizeof path, "%s/profile.csv", dir);
    tt_outfile *of;
    if ((rc = tt_outfile_open(&of, path)))
        return rc;
    FILE *f = tt_outfile_stream(of);
    long line = tt_scan_profile_line(scan);
    /* the profile runs along the fast axis: a row, or a column when it is y */
    int fy = tt_scan_fast_y(scan);
    long n = fy ? yres : xres;
    double size = fy ? tt_scan_size_y(scan) : tt_scan_size_x(scan);
    fprintf(f, "position_nm");
    for (int ch = 0; ch < TT_CH_COUNT; ch++)
        for (int r = 0; r < 2; r++)
            if (tt_scan_image(scan, ch, r))
                fprintf(f, ",%s_%s_%s", tt_scan_channel_name(ch), r ? "retrace" : "trace",
                        tt_scan_channel_unit(ch));
    fputc('\n', f);
    for (long px = 0; px < n; px++) {
        fprintf(f, "%.9g", (px + 0.5) * size / (double)n * 1e9);
        for (int ch = 0; ch < TT_CH_COUNT; ch++)
            for (int r = 0; r < 2; r++) {
                const double *img = tt_scan_image(scan, ch, r);
                if (img)
                    fprintf(f, ",%.9g", img[fy ? px * xres + line : line * xres + px]);
            }
        fputc('\n', f);
    }
    rc = tt_outfile_close(of, 1);
    *written += rc == TT_OK;
    if (rc == TT_OK)
        remove_stale(scan, dir, hdf5);
    return rc;
}

/* The first line on stderr once every check passed: the cycles, the time and the memory
 * by estimate (tt_run_scan_alloc). */
static void report_cost(const tt_run_scan_cost *e, int quiet)
{
    char need[32], t[32], lo[32], tier[160] = "";
    int n = e->threads;
    /* the envelope tier's time depends on how many cycles the scene lets the model
     * follow: a range (src/config/estimate.c) */
    if (e->envelope)
        snprintf(tier, sizeof tier, "%s to %s (envelope tier: %.0f %% to %.0f %% of the cycles "
                                    "integrated, as on the bundled surfaces)",
                 cli_duration(e->seconds_low / n, lo, sizeof lo), cli_duration(e->seconds / n, t, sizeof t),
                 100 * e->integrated_low, 100 * e->integrated_high);
    else
        cli_duration(e->seconds / n, tier, sizeof tier);
    if (!quiet)
        fprintf(stderr, "scan: %ld x %ld pixels, %.3g drive cycles, about %s by estimate on %d "
                        "thread%s, %s of memory\n",
                e->pixels, e->lines, e->cycles, tier, n, n > 1 ? "s" : "",
                cli_bytes(e->bytes, need, sizeof need));
}

/* The averaged tier's pixels where the tip's amplitude or penetration left its table. */
static void note_averaged(const tt_scan *scan)
{
    long out = tt_scan_averaged_outside(scan);
    if (out > 0)
        fprintf(stderr, "tiptap scan: note: in %ld pixel%s the tip's amplitude passed 1.5 "
                        "free amplitudes or its penetration one free amplitude, beyond the "
                        "averaged tier's table: its forces there came from quadrature (slower)\n",
                out, out > 1 ? "s" : "");
}

int cmd_scan(int argc, char **argv)
{
    static const struct option opts[] = {{"threads", required_argument, NULL, 'j'},
                                         {"hdf5", no_argument, NULL, 'H'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"scan", CLI_OPT_OUTPUT | CLI_OUTPUT_FOLDER | CLI_OPT_SET | CLI_OPT_QUIET,
                                  opts, "j:", help};
    cli_args args = {0};
    int threads = 0, hdf5 = 0, c;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) { /* 'j' and 'H' */
        if (c == 'H') {
            hdf5 = 1;
            continue;
        }
        /* atoi read "abc" and "-3" as 0, which means all cores */
        long j;
        if (cli_whole("scan", "-j", optarg, 1, 4096, "a number of threads", &j)) {
            cli_args_free(&args);
            return CLI_USAGE;
        }
        threads = (int)j;
    }
    if (c == CLI_EXIT)
        return args.exit;
    const char *dir = args.output;
    int quiet = args.quiet;
    if (!dir) {
        cli_args_free(&args);
        fprintf(stderr, "tiptap scan: needs -o DIR; see 'tiptap scan --help'\n");
        return CLI_USAGE;
    }
    int code;
    tt_scene *scene = cli_args_scene(&spec, &args, argc, argv, &code);
    if (!scene)
        return code;
    double t0 = cli_now();
    tt_scan *scan = NULL;
    tt_scan_scope *scope = NULL;
    tt_scan_params params;
    char path[4096];
    tt_outfile *of = NULL;
    int rc, reported = 0, lock = -1;
    /* Every key, every material and the surface are checked, the force laws built and
     * the memory estimated, before the folder is made: a refused scan leaves no folder
     * and touches none. */
    tt_run_scan_cost cost;
    if ((rc = tt_run_scan_alloc(scene, threads, &scan, &cost))) {
        if (rc == TT_ENOMEM) {
            fprintf(stderr, "tiptap scan: %s\n", tt_error_message());
            reported = 1;
        }
        goto done;
    }
    /* the plain values the summary reads (tt_run_scan_alloc read them already) */
    if ((rc = tt_config_scan(scene, &params)))
        goto done;
    tt_config_scan_free(&params);
    if ((rc = tt_scan_scope_alloc(&scope)))
        goto done;
    tt_scan_scope_attach(scan, tt_scan_profile_line(scan), scope);
    report_cost(&cost, quiet);
    tt_run_scan_warn_inputs(scene, &cost);
    /* Then the folder and the effective scene: a bad output folder fails at once, not
     * after an hour of scanning. The folder is locked for the run: two scans into one
     * folder would mix their images and scene.ini. From here on a signal keeps the lines
     * finished. */
    if ((rc = cli_scan_check_outputs(dir, scan, hdf5)))
        goto done;
    cli_catch_interrupt();
    if ((rc = tt_mkdirs(dir)))
        goto done;
    if ((lock = cli_lock_folder("scan", dir)) < 0) {
        rc = TT_EINVAL;
        reported = 1;
        goto done;
    }
    if (hdf5 && (rc = check_hdf5(dir)))
        goto done;
    snprintf(path, sizeof path, "%s/scene.ini", dir);
    if ((rc = tt_outfile_open(&of, path)))
        goto done;
    if ((rc = tt_scene_write(scene, tt_outfile_stream(of), NULL))) {
        tt_outfile_close(of, 0);
        goto done;
    }
    if ((rc = tt_outfile_close(of, 1)))
        goto done;
    cli_progress prog;
    cli_progress_begin(&prog, "scan", "lines", quiet);
    rc = tt_scan_run(scan, threads, quiet ? NULL : show_progress, &prog);
    cli_progress_end(&prog);
    tt_run_scan_warn_result(scan);
    note_averaged(scan);
    int written = 1; /* scene.ini */
    if (tt_scan_lines_done(scan) > 0) {
        char saved[1024];
        snprintf(saved, sizeof saved, "%s", tt_error_message());
        int wrc = cli_scan_write_outputs(scan, scene, dir, hdf5, &written);
        if (!wrc)
            wrc = cli_scope_write(scan, scope, dir, &written);
        cli_scope_warn("scan", scan, scope);
        if (wrc && !rc)
            rc = wrc;
        else if (rc)
            tt_error(rc, "%s", saved);
    }
    double scan_wall = cli_now() - t0;
    tt_scan_error est;
    int erc = rc == TT_OK && !quiet ? tt_scan_estimate_error(scan, &est) : TT_EINVAL;
    /* run_time_s is the whole run's, the estimate's companion line included */
    double wall = cli_now() - t0;
    int have_est = erc == TT_OK;
    if (erc == TT_EINTR) /* stopped in the companion: the images are written, the exit says so */
        rc = tt_error(erc, "interrupted in the error estimate's companion line; the images "
                           "(%ld of %ld lines) are written", tt_scan_lines_done(scan),
                      tt_scan_lines(scan));
    else if (rc == TT_OK && !quiet && !have_est)
        fprintf(stderr, "tiptap: no error estimate: %s\n", tt_error_message());
    if (!quiet && (params.solver.tier == TT_TIER_ENVELOPE ||
                   (params.solver.tier == TT_TIER_AVERAGED && !tt_scan_averaged_tier(&params)))) {
        long all = tt_scan_cycles(scan), done = tt_scan_cycles_integrated(scan);
        /* the tier runs at any Q and with any noise: every cycle integrated means the
         * model held on no stretch */
        const char *why = done < all ? ": the rest followed on the cycle map's model"
                                     : ": the model held on none (docs/dynamics.md)";
        fprintf(stderr, "cycles_integrated = %ld (%.1f %%; envelope tier%s)\n", done,
                all > 0 ? 100.0 * (double)done / (double)all : 0.0, why);
    }
    if (params.solver.tier == TT_TIER_AVERAGED && !tt_scan_averaged_tier(&params))
        fprintf(stderr, "tiptap scan: note: the averaged tier needs a quality factor of 30 or "
                        "more and the drive within 5 %% of resonance (here Q %g, drive at %g of "
                        "resonance): the scan ran on the envelope tier's terms "
                        "(docs/dynamics.md, Averaged)\n",
                params.cantilever.Q, params.cantilever.fd / params.cantilever.f0);
    if (!quiet && tt_scan_averaged_tier(&params))
        fprintf(stderr, "averaged_tables_s = %.3f (averaged tier: the force's harmonics of %zu "
                        "material%s tabulated once, in run_time_s; table error %.2g of k A0; no "
                        "cycle integrated)\n",
                tt_scan_averaged_build_seconds(scan), tt_scan_materials(scan),
                tt_scan_materials(scan) > 1 ? "s" : "", tt_scan_averaged_table_error(scan));
    if (!quiet) {
        fprintf(stderr, "lines = %ld/%ld\ncycles = %ld\nrun_time_s = %.3f (the whole run; the scan %.3f, "
                        "the error estimate %.3f)\ninstrument_time_s = %.3f\n"
                        "real_time_factor = %.3f\nenergy_balance = %.3g (largest energy-balance "
                        "residual of a cycle / free drive work per cycle: a check, not the error)\n",
                tt_scan_lines_done(scan), tt_scan_lines(scan), tt_scan_cycles(scan), wall, scan_wall,
                wall - scan_wall, tt_scan_instrument_time(scan),
                tt_scan_instrument_time(scan) * (double)tt_scan_lines_done(scan) /
                    (double)tt_scan_lines(scan) / wall,
                tt_scan_error_estimate(scan));
        int rk4 = params.solver.method == TT_METHOD_RK4, avg = tt_scan_averaged_tier(&params);
        if (have_est) {
            fprintf(stderr, "error_estimate_height_m = %.2g (rms; max %.2g)\n"
                            "error_estimate_phase_deg = %.2g (rms; max %.2g)\n"
                            "error_estimate_amplitude_rel = %.2g (rms; max %.2g)\n"
                            "# from a companion run of line %ld %s %s %.3g, ",
                    est.height_rms, est.height_max, est.phase_rms, est.phase_max, est.amplitude_rms,
                    est.amplitude_max, est.line,
                    avg ? "on the envelope tier (the averaged model's error) at" : "at",
                    rk4 ? "steps_per_cycle" : "tolerance",
                    rk4 ? (double)tt_companion_solver(&params.solver).steps_per_cycle : est.tolerance);
            if (est.step > 0)
                fprintf(stderr, "the image's hardest line (height steps up to %.2g m between pixels)",
                        est.step);
            else
                fprintf(stderr, "the profile line (no height step in the image)");
            long integ = tt_scan_cycles_integrated(scan);
            if (est.pixels < est.pixels_line)
                fprintf(stderr, ", %ld of its %ld pixels (the trace's from pixel %ld)", est.pixels,
                        est.pixels_line, est.first);
            else
                fprintf(stderr, ", all its %ld pixels", est.pixels_line);
            fprintf(stderr, "\nestimate_cycles = %ld", est.cycles);
            if (integ > 0)
                fprintf(stderr, " (%.1f %% of the scan's %ld cycles integrated)",
                        100.0 * (double)est.cycles / (double)integ, integ);
            else /* the averaged tier integrates none: its companion has no bound */
                fprintf(stderr, " (the scan integrated none)");
            fprintf(stderr, "\nestimate_cpu_s = %.3f\n", est.seconds);
        }
        if (have_est)
            tt_run_scan_warn_error(scan, &cost, &est);
        fprintf(stderr, "output = %s: %d files (scan.gwy: every channel, trace and retrace; "
                        "CHANNEL_trace/retrace.gsf and .png; profile.csv; scope.csv and .png; scene.ini%s)\n",
                dir, written, hdf5 ? "; scan.h5" : "");
    }
done:
    if (rc && !reported)
        cli_fail(rc, NULL);
    cli_unlock_folder(dir, lock);
    tt_scan_free(scan);
    tt_scan_scope_free(scope);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}
