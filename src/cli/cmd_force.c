/* tiptap force: a force-distance curve of the undriven cantilever (tiptap/run/force.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/run/force.h"
#include "tiptap/run/force_volume.h"
#include "tiptap/util/error.h"

static void help(void)
{
    printf("Usage: tiptap force SCENE... [--set section.key=value]... [-o force.csv]\n"
           "                     [--plot force.png] [-q]\n"
           "       tiptap force SCENE... --volume -o DIR [--hdf5] [-j N] [--set ...] [-q]\n"
           "Force-distance curve: the undriven cantilever's base ramps toward the sample from\n"
           "[force] from (or to + range) to [force] to at [force] speed, dwells, and goes back.\n\n"
           "  -o, --output FILE  CSV, a row per sample: t_ms, z_nm (rest separation),\n"
           "                     deflection_nm (tip - base, positive toward the sample),\n"
           "                     separation_nm (tip-sample gap z - deflection; negative:\n"
           "                     indentation), force_nN (tip-sample, repulsive positive),\n"
           "                     lever_force_nN (-k deflection, what the instrument reads),\n"
           "                     contact, leg (approach, dwell, retract)\n"
           "      --plot FILE    PNG: deflection and force against z, force against separation\n"
           "      --volume       force volume: a curve at every pixel of the [scan] raster\n"
           "                     (size, pixels, lines) over the [surface] and its materials,\n"
           "                     the ramp placed at each pixel's height, no feedback; -o DIR\n"
           "                     gets NAME.gsf and NAME.png for height (contact point),\n"
           "                     adhesion, stiffness (contact slope), pulloff_distance,\n"
           "                     pulloff_force, indentation, max_force and material, and\n"
           "                     force_volume.gwy, scene.ini (default folder force-volume)\n"
           "      --hdf5         with --volume: force_volume.h5 too\n"
           "  -j, --threads N    with --volume: lines computed in parallel (default: all\n"
           "                     cores); the maps are the same bytes on any number of them\n"
           CLI_HELP_SET
           "  -q, --quiet        no progress on stderr\n\n"
           "stdout: the jump-in (where the tip snapped, the force it held there), the first\n"
           "contact, the pull-off (where the tip first leaves, the force just before), the\n"
           "largest adhesion on the retract, the largest force, and the contact part's slope:\n"
           "-dF/dz (N/m) and d(deflection)/dz, a straight line through the points above half\n"
           "the largest force, and the largest indentation. [noise] temperature adds the\n"
           "thermal force (docs/force-and-tune.md).\n");
}

static int write_csv(const char *path, const tt_table *t)
{
    tt_outfile *of;
    int rc = tt_outfile_open(&of, path);
    if (rc)
        return rc;
    FILE *f = tt_outfile_stream(of);
    fprintf(f, "t_ms,z_nm,deflection_nm,separation_nm,force_nN,lever_force_nN,contact,leg\n");
    const double *c[7];
    for (int k = 0; k < 7; k++)
        c[k] = tt_table_numbers(t, (size_t)k);
    for (size_t i = 0; i < tt_table_rows(t); i++)
        fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%s\n", c[0][i] * 1e3, c[1][i] * 1e9, c[2][i] * 1e9,
                c[3][i] * 1e9, c[4][i] * 1e9, c[5][i] * 1e9, (int)c[6][i], tt_table_text(t, 7, i));
    return tt_outfile_close(of, 1);
}

/* The rows of one leg of column col, in the plot's units (scale), NAN elsewhere so that
 * each leg is a line of its own. */
static double *leg_series(const tt_table *t, size_t col, const char *leg, double scale)
{
    size_t n = tt_table_rows(t);
    double *v = malloc((n ? n : 1) * sizeof *v);
    const double *x = tt_table_numbers(t, col);
    for (size_t i = 0; v && i < n; i++)
        v[i] = strcmp(tt_table_text(t, 7, i), leg) == 0 ? x[i] * scale : NAN;
    return v;
}

static int plot(const char *path, const tt_table *t, const tt_force_summary *s, const char *title)
{
    tt_figure *f = tt_figure_alloc(3, title);
    if (!f)
        return tt_error_nomem("the plot %s", path);
    static const char *const legs[3] = {"approach", "dwell", "retract"};
    const unsigned style[3] = {1, 3, 2};
    size_t n = tt_table_rows(t);
    int rc = TT_OK;
    tt_figure_axes(f, 0, "z: rest separation (nm)", "deflection (nm)");
    tt_figure_axes(f, 1, "z: rest separation (nm)", "force (nN)");
    tt_figure_axes(f, 2, "tip-sample separation (nm)", "force (nN)");
    for (int l = 0; l < 3 && rc == TT_OK; l++) {
        double *z = leg_series(t, 1, legs[l], 1e9), *y = leg_series(t, 2, legs[l], 1e9);
        double *F = leg_series(t, 4, legs[l], 1e9), *sep = leg_series(t, 3, legs[l], 1e9);
        if (!z || !y || !F || !sep)
            rc = tt_error_nomem("the plot %s", path);
        else if (l != 1) {
            tt_figure_line(f, 0, z, y, n, legs[l], style[l]);
            tt_figure_line(f, 1, z, F, n, legs[l], style[l]);
            tt_figure_line(f, 2, sep, F, n, legs[l], style[l]);
        }
        free(z), free(y), free(F), free(sep);
    }
    if (isfinite(s->jumpin_z))
        tt_figure_vline(f, 1, s->jumpin_z * 1e9, "jump-in");
    if (isfinite(s->pulloff_z))
        tt_figure_vline(f, 1, s->pulloff_z * 1e9, "pull-off");
    if (isfinite(s->adhesion))
        tt_figure_hline(f, 2, -s->adhesion * 1e9, "largest adhesion");
    if (rc == TT_OK)
        rc = tt_figure_write_png(f, path, 1000, 1100);
    tt_figure_free(f);
    return rc;
}

/* --volume: the maps into the folder; a run cut short writes the lines it finished. */
static int run_volume(tt_scene *scene, const char *dir, int hdf5, int threads, int quiet)
{
    cli_progress prog;
    tt_force_volume *v = NULL;
    int written = 0;
    double t0 = cli_now();
    cli_progress_begin(&prog, "force", "lines", quiet);
    cli_catch_interrupt();
    const tt_force_volume_job job = {threads, dir, hdf5, cli_progress_callback, &prog};
    int rc = tt_run_force_volume(scene, &job, &v, &written);
    cli_progress_end(&prog);
    if (v)
        printf("lines_finished = %ld\nlines_total = %ld\ndrive_periods = %ld\n", tt_force_volume_lines_done(v),
               tt_force_volume_lines(v), tt_force_volume_cycles(v));
    if (v && !quiet)
        fprintf(stderr, "run_time_s = %.3f\noutput = %s (%d files)\n", cli_now() - t0, dir, written);
    if (rc)
        cli_fail(rc, NULL);
    tt_force_volume_free(v);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}

static int usage(cli_args *a, const char *msg)
{
    fprintf(stderr, "tiptap force: %s\n", msg);
    cli_args_free(a);
    return CLI_USAGE;
}

int cmd_force(int argc, char **argv)
{
    static const struct option own[] = {{"volume", no_argument, NULL, 'V'},
                                        {"hdf5", no_argument, NULL, 'H'},
                                        {"threads", required_argument, NULL, 'j'},
                                        {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"force", CLI_OPT_OUTPUT | CLI_OPT_PLOT | CLI_OPT_SET | CLI_OPT_QUIET,
                                  own, "j:", help};
    static const cli_spec vspec = {"force", CLI_OPT_OUTPUT | CLI_OUTPUT_FOLDER | CLI_OPT_SET | CLI_OPT_QUIET,
                                   own, "j:", help};
    cli_args args = {.output = NULL};
    int code, c, volume = 0, hdf5 = 0, threaded = 0;
    long threads = 0;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        if (c == 'V')
            volume = 1;
        else if (c == 'H')
            hdf5 = 1;
        else if (c == 'j' && (threaded = 1) &&
                 cli_whole("force", "-j", optarg, 1, 4096, "a number of threads", &threads)) {
            cli_args_free(&args);
            return CLI_USAGE;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    if (!volume && (hdf5 || threaded))
        return usage(&args, hdf5 ? "--hdf5 goes with --volume" : "--threads goes with --volume");
    if (volume && args.plot)
        return usage(&args, "--plot draws one curve; --volume writes a PNG per map into -o DIR");
    if (!args.output)
        args.output = volume ? "force-volume" : "force.csv";
    tt_scene *scene = cli_args_scene(volume ? &vspec : &spec, &args, argc, argv, &code);
    if (!scene)
        return code;
    if (volume)
        return run_volume(scene, args.output, hdf5, (int)threads, args.quiet);
    tt_table *t = NULL;
    tt_force_summary s;
    cli_progress prog;
    double t0 = cli_now();
    cli_progress_begin(&prog, "force", "drive periods", args.quiet);
    cli_catch_interrupt();
    int rc = tt_run_force(scene, &t, &s, cli_progress_callback, &prog);
    cli_progress_end(&prog);
    /* a curve cut short keeps no file: its jump-in and pull-off would be missing */
    if (rc == TT_OK)
        rc = write_csv(args.output, t);
    if (rc == TT_OK && args.plot) {
        tt_force_params fp;
        const char *mat = tt_config_force(scene, &fp) == TT_OK ? fp.material : NULL;
        char title[256];
        snprintf(title, sizeof title, "Force curve%s%s: k = %.3g N/m, %.3g um/s", mat ? " on " : "",
                 mat ? mat : "", s.k, s.speed * 1e6);
        rc = plot(args.plot, t, &s, title);
    }
    if (rc == TT_OK) {
        printf("spring_constant_N_per_m = %.6g\nspeed_m_per_s = %.6g\ndrive_periods = %ld\n"
               "jumpin_z_nm = %.6g\njumpin_force_nN = %.6g\njumpin_gap_nm = %.6g\n"
               "contact_z_nm = %.6g\npulloff_z_nm = %.6g\npulloff_force_nN = %.6g\n"
               "adhesion_nN = %.6g\nmax_force_nN = %.6g\nslope_N_per_m = %.6g\n"
               "slope_deflection = %.6g\nslope_retract_N_per_m = %.6g\nindentation_nm = %.6g\n",
               s.k, s.speed, s.cycles, s.jumpin_z * 1e9, s.jumpin_force * 1e9, s.jumpin_gap * 1e9,
               s.contact_z * 1e9, s.pulloff_z * 1e9, s.pulloff_force * 1e9, s.adhesion * 1e9,
               s.max_force * 1e9, s.slope, s.slope_deflection, s.slope_retract, s.indentation * 1e9);
        if (!args.quiet)
            fprintf(stderr, "run_time_s = %.3f\noutput = %s%s%s\n", cli_now() - t0, args.output,
                    args.plot ? ", plot " : "", args.plot ? args.plot : "");
    }
    if (rc)
        cli_fail(rc, NULL);
    tt_table_free(t);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}
