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
           "indentation (m), dissipation (J per cycle), dissipation_hysteresis,\n"
           "dissipation_damping, dissipation_viscous (its parts: adhesion hysteresis,\n"
           "interaction damping, the sample's viscosity; added where a material is viscous\n"
           "unless [scan] channels is set; not on the averaged tier),\n"
           "topography (the true surface, m), harmonic2 ... harmonic8 (amplitude of the\n"
           "deflection's harmonic h, m; needs [lockin] harmonics >= h), harmonic2_phase ...\n"
           "harmonic8_phase (its lag behind cos(h w t), deg), artefact (height - topography, m;\n"
           "added on a measured surface unless [scan] channels is set), amplitude_2, phase_2\n"
           "(bimodal: mode 2's lock-in at its drive, m and deg; needs [cantilever]\n"
           "mode2_free_amplitude).\nCtrl-C (or SIGTERM) abandons the\n"
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
           "height step between pixels; the profile line on a flat image), or of stretches of\n"
           "the trace at that step, at its line's start and at the first edge of each pair of\n"
           "materials; with thermal or z piezo noise, of as many whole lines as fit, where\n"
           "the error signal strays furthest. The companion spends at most a fifth of the\n"
           "scan's work (integrator steps and one a cycle: estimate_work; averaged tier: a\n"
           "fifth of the cycles it integrated), or runs the hardest line whole and says it\n"
           "is over (estimate_cycles, estimate_cpu_s); run_time_s includes it. A warning\n"
           "when the estimate exceeds 1e-3 of the free amplitude or 0.1 deg.\n"
           "[solver] tier: envelope (default; most cycles from the cycle map's model under\n"
           "error control), every (every cycle integrated) or averaged (a preview: the\n"
           "averaged slow flow of amplitude and phase, cycles integrated only where it fails\n"
           "(impacts, a ringing loop), about 50 times real time on one core where none is; its\n"
           "error estimate's companion runs on the envelope tier, and pixels where the slow\n"
           "flow ran with the oscillation collapsed are named; docs/dynamics.md).\n");
}

static void show_progress(void *user, long done, long total);

int cli_scan_check_outputs(const char *dir, const tt_scan *scan, int hdf5)
{
    return tt_run_scan_check_outputs(dir, scan, hdf5);
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
            tt_run_scan_channel_file(path, sizeof path, dir, ch, r, k % 2);
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

int cli_scan_write_outputs(const tt_scan *scan, const tt_scene *scene, const char *dir, int hdf5,
                           int *written)
{
    int rc = tt_run_scan_write_outputs(scan, scene, dir, hdf5, 1, written);
    if (rc == TT_OK)
        remove_stale(scan, dir, hdf5);
    return rc;
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

/* What the program adds to the library's scan sequence (tt_run_scan): its stderr,
 * the folder's lock and scene.ini, the scope's files and the stale channel files. */
typedef struct {
    const tt_scene *scene;
    const char *dir;
    int quiet, hdf5, lock, reported, written;
    int scope_rc; /* the scope's check failed: its files not written */
    cli_scope_out scope_out;
    tt_scan_params params; /* the plain values the summary reads */
    int have_params;
    double t0;
    tt_scan_scope *scope;
    cli_progress prog;
} scan_cli;

static void show_progress(void *user, long done, long total)
{
    cli_progress_show(&((scan_cli *)user)->prog, done, total);
}

static int scan_made(void *user, const tt_scan *scan, const tt_run_scan_cost *cost)
{
    (void)scan;
    scan_cli *x = user;
    int rc = tt_config_scan(x->scene, &x->params);
    if (rc)
        return rc;
    tt_config_scan_free(&x->params);
    x->have_params = 1;
    report_cost(cost, x->quiet);
    return TT_OK;
}

/* The folder locked for the run (two scans into one folder would mix their images and
 * scene.ini), scan.h5 checked, the effective scene written; from here on a signal keeps
 * the lines finished. */
static int scan_ready(void *user, tt_scan *scan)
{
    (void)scan;
    scan_cli *x = user;
    char path[4096];
    tt_outfile *of;
    int rc;
    cli_catch_interrupt();
    if ((x->lock = cli_lock_folder("scan", x->dir)) < 0) {
        x->reported = 1;
        return TT_EINVAL;
    }
    if (x->hdf5 && (rc = check_hdf5(x->dir)))
        return rc;
    snprintf(path, sizeof path, "%s/scene.ini", x->dir);
    if ((rc = tt_outfile_open(&of, path)))
        return rc;
    if ((rc = tt_scene_write(x->scene, tt_outfile_stream(of), NULL))) {
        tt_outfile_close(of, 0);
        return rc;
    }
    if ((rc = tt_outfile_close(of, 1)))
        return rc;
    x->written = 1; /* scene.ini */
    cli_progress_begin(&x->prog, "scan", "lines", x->quiet);
    return TT_OK;
}

static int scan_finished(void *user, tt_scan *scan, int status)
{
    scan_cli *x = user;
    cli_progress_end(&x->prog);
    note_averaged(scan);
    if (tt_scan_lines_done(scan) == 0 || status)
        return TT_OK;
    remove_stale(scan, x->dir, x->hdf5);
    return x->scope_rc;
}

/* The scope's files, as jobs beside the folder's (j -1: how many). */
static int scan_files(void *user, const tt_scan *scan, int j, int *written)
{
    scan_cli *x = user;
    int n;
    if (j >= 0)
        return cli_scope_file(&x->scope_out, j, written);
    x->scope_rc = cli_scope_prepare(&x->scope_out, scan, x->scope, x->dir, &n);
    return x->scope_rc ? 0 : n;
}

static void scan_summary(void *user, const tt_scan *scan, const tt_run_scan_result *r)
{
    scan_cli *x = user;
    const tt_scan_params *p = &x->params;
    const int quiet = x->quiet, have_est = r->estimate_status == TT_OK;
    const double wall = r->seconds, scan_wall = r->scan_seconds;
    if (r->oscillating)
        cli_scope_note("scan", scan, x->scope);
    if (!x->have_params)
        return;
    if (r->estimate_status > 0 && r->estimate_status != TT_EINTR && !quiet)
        fprintf(stderr, "tiptap: no error estimate: %s\n", tt_error_message());
    if (!quiet && (p->solver.tier == TT_TIER_ENVELOPE ||
                   (p->solver.tier == TT_TIER_AVERAGED && !tt_scan_averaged_tier(p)))) {
        long all = tt_scan_cycles(scan), done = tt_scan_cycles_integrated(scan);
        /* the tier runs at any Q and with any noise: every cycle integrated means the
         * model held on no stretch */
        const char *why = done < all ? ": the rest followed on the cycle map's model"
                                     : ": the model held on none (docs/dynamics.md)";
        fprintf(stderr, "cycles_integrated = %ld (%.1f %%; envelope tier%s)\n", done,
                all > 0 ? 100.0 * (double)done / (double)all : 0.0, why);
    }
    if (p->solver.tier == TT_TIER_AVERAGED && !tt_scan_averaged_tier(p))
        fprintf(stderr, "tiptap scan: note: the averaged tier needs a quality factor of 30 or "
                        "more and the drive within 5 %% of resonance (here Q %g, drive at %g of "
                        "resonance): the scan ran on the envelope tier's terms "
                        "(docs/dynamics.md, Averaged)\n",
                p->cantilever.Q, p->cantilever.fd / p->cantilever.f0);
    if (!quiet && tt_scan_averaged_tier(p))
        fprintf(stderr, "averaged_tables_s = %.3f (averaged tier: the force's harmonics of %zu "
                        "material%s tabulated once, in run_time_s; table error %.2g of k A0; %ld "
                        "cycles integrated where the slow flow failed)\n",
                tt_scan_averaged_build_seconds(scan), tt_scan_materials(scan),
                tt_scan_materials(scan) > 1 ? "s" : "", tt_scan_averaged_table_error(scan),
                tt_scan_cycles_integrated(scan));
    if (!quiet) {
        fprintf(stderr, "lines = %ld/%ld\ncycles = %ld\nrun_time_s = %.3f (the whole run; the scan and "
                        "its files %.3f, the error estimate's companion lines %.3f past them)\n"
                        "instrument_time_s = %.3f\n"
                        "real_time_factor = %.3f\nenergy_balance = %.3g (largest energy-balance "
                        "residual of a cycle / free drive work per cycle: a check, not the error)\n",
                tt_scan_lines_done(scan), tt_scan_lines(scan), tt_scan_cycles(scan), wall, scan_wall,
                wall - scan_wall, tt_scan_instrument_time(scan),
                tt_scan_instrument_time(scan) * (double)tt_scan_lines_done(scan) /
                    (double)tt_scan_lines(scan) / wall,
                tt_scan_error_estimate(scan));
        long tables = 0, laws = tt_scan_contact_laws_built(scan, &tables);
        if (p->local_geometry)
            fprintf(stderr, "contact_laws_built = %ld (contact_geometry = local: a law per "
                            "material, slope and radius met, per thread; %ld tables rebuilt "
                            "at their R_eff, the rest copied)\n",
                    laws, tables);
        int rk4 = p->solver.method == TT_METHOD_RK4, avg = tt_scan_averaged_tier(p);
        if (have_est) {
            const tt_scan_error *e = &r->est;
            fprintf(stderr, "error_estimate_height_m = %.2g (rms; max %.2g)\n"
                            "error_estimate_phase_deg = %.2g (rms; max %.2g)\n"
                            "error_estimate_amplitude_rel = %.2g (rms; max %.2g)\n"
                            "# from a companion run of line %ld %s %s %.3g, ",
                    e->height_rms, e->height_max, e->phase_rms, e->phase_max, e->amplitude_rms,
                    e->amplitude_max, e->line,
                    avg ? "on the envelope tier (the averaged model's error) at" : "at",
                    rk4 ? "steps_per_cycle" : "tolerance",
                    rk4 ? (double)tt_companion_solver(&p->solver).steps_per_cycle : e->tolerance);
            if (e->signal > 0)
                fprintf(stderr, "the line where the error signal strays furthest (up to %.2g m "
                                "from the setpoint)", e->signal);
            else if (e->step > 0)
                fprintf(stderr, "the image's hardest line (height steps up to %.2g m between pixels)",
                        e->step);
            else
                fprintf(stderr, "the profile line (no height step in the image)");
            long integ = tt_scan_cycles_integrated(scan);
            if (e->pixels < e->pixels_line && e->stretches > 1)
                fprintf(stderr, ", %ld pixels of the trace in %ld stretches (the largest step's from "
                                "pixel %ld, and the first edge of each pair of materials)",
                        e->pixels, e->stretches, e->first);
            else if (e->pixels < e->pixels_line)
                fprintf(stderr, ", %ld of its %ld pixels (the trace's from pixel %ld)", e->pixels,
                        e->pixels_line, e->first);
            else
                fprintf(stderr, ", all its %ld pixels", e->pixels_line);
            if (e->lines > 1)
                fprintf(stderr, ", and the next %ld such line%s whole (noise that moves the "
                                "state)", e->lines - 1, e->lines > 2 ? "s" : "");
            if (e->lines > 0) /* what it cannot bound */
                fprintf(stderr, "\n# with noise that moves the state the largest error differs "
                                "from line to line with the noise: on the blend and the steps at "
                                "300 K other lines erred up to 2.6 times this max (its rms held to "
                                "1.2 times)");
            fprintf(stderr, "\nestimate_cycles = %ld", e->cycles);
            /* the averaged tier's budget is counted in the cycles it integrated */
            if (e->budget == 0 && integ > 0)
                fprintf(stderr, " (%.1f %% of the scan's %ld cycles integrated)",
                        100.0 * (double)e->cycles / (double)integ, integ);
            else if (e->budget == 0) /* it integrated none: no bound */
                fprintf(stderr, " (the scan integrated none)");
            if (e->scan_work > 0)
                fprintf(stderr, "\nestimate_work = %ld (%.1f %% of the scan's %ld: integrator "
                                "steps, accepted and rejected, and one a cycle)",
                        e->work, 100.0 * (double)e->work / (double)e->scan_work, e->scan_work);
            if (e->over && e->lines) /* never silently over the share */
                fprintf(stderr, "\n# over the share: with noise that moves the state the "
                                "companion runs whole lines, and a fifth of this scan's work "
                                "does not hold one: the hardest line ran");
            else if (e->over)
                fprintf(stderr, "\n# over the share: a fifth of this scan does not hold each "
                                "stretch's settling (%ld cycles) and two pixels: the whole line ran",
                        p->settle_cycles);
            fprintf(stderr, "\nestimate_cpu_s = %.3f (%.1f %% of the run's %.3f s CPU)\n", e->seconds,
                    r->cpu_seconds > 0 ? 100 * e->seconds / r->cpu_seconds : 0.0, r->cpu_seconds);
        }
        if (have_est)
            tt_run_scan_warn_error(scan, &r->cost, &r->est);
        fprintf(stderr, "output = %s: %d files (scan.gwy: every channel, trace and retrace; "
                        "CHANNEL_trace/retrace.gsf and .png; profile.csv; scope.csv and .png; scene.ini%s)\n",
                x->dir, x->written + r->written, x->hdf5 ? "; scan.h5" : "");
    }
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
    scan_cli x = {.scene = scene, .dir = dir, .quiet = quiet, .hdf5 = hdf5, .lock = -1};
    tt_run_scan_result r;
    int rc = tt_scan_scope_alloc(&x.scope);
    /* Every key, every material and the surface are checked, the force laws built and
     * the memory estimated, before the folder is made: a refused scan leaves no folder
     * and touches none. Then the folder's outputs: a bad output folder fails at once,
     * not after an hour of scanning. */
    const tt_run_scan_job job = {.threads = threads, .progress = quiet ? NULL : show_progress,
                                 .user = &x, .scope = x.scope, .scope_files = "scope.csv, scope.png",
                                 .folder = dir, .hdf5 = hdf5, .estimate = !quiet,
                                 .made = scan_made, .ready = scan_ready,
                                 .finished = scan_finished, .summary = scan_summary,
                                 .files = scan_files};
    if (!rc)
        rc = tt_run_scan(scene, &job, &r);
    else
        r.scan = NULL;
    if (rc == TT_ENOMEM && !r.scan) {
        fprintf(stderr, "tiptap scan: %s\n", tt_error_message());
        x.reported = 1;
    }
    if (rc && !x.reported)
        cli_fail(rc, NULL);
    cli_unlock_folder(dir, x.lock);
    tt_scan_free(r.scan);
    tt_scan_scope_free(x.scope);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}
