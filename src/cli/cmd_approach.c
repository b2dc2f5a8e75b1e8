/* tiptap approach: amplitude, phase and the rest against rest separation. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"

static void help(void)
{
    printf("Usage: tiptap approach SCENE... [--set section.key=value]... [-o approach.csv]\n"
           "                        [--plot approach.png] [-q]\n"
           "Approach curve of the scene's [approach] section (seed figures 1 and 4).\n\n"
           "  -o, --output FILE  CSV, one row per point: z_nm, amplitude_nm, phase_deg,\n"
           "                     mean_deflection_nm, peak_force_nN, max_indentation_nm,\n"
           "                     contact_fraction, dissipated_aJ, branch, settled, cycles,\n"
           "                     drive_work_aJ, energy_residual, deflection_min_nm,\n"
           "                     deflection_max_nm (default approach.csv)\n"
           "      --plot FILE    PNG of amplitude, phase and dissipation against z\n"
           "      --set S.K=V    override a scene key (material.NAME.key for named sections)\n"
           "  -q, --quiet        no summary on stderr\n\n"
           "z is the rest separation: the gap between the undeflected, non-interacting tip\n"
           "and the sample (negative: the rest position is below the surface).\n"
           "stderr ends with the run time and the error estimate: the largest energy-balance\n"
           "residual of a cycle (drive work - cantilever damping - tip-sample loss - change\n"
           "of stored energy) relative to the free oscillation's drive work per cycle. It is zero for the\n"
           "exact solution, so it measures the integration error of this run.\n");
}

static void write_row(FILE *f, const tt_approach_point *p)
{
    const tt_cycle *c = &p->cycle;
    double rel = c->residual_rel;
    fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%s,%d,%ld,%.9g,%.3g,%.9g,%.9g\n", p->z * 1e9,
            c->amplitude * 1e9, c->phase * 180 / M_PI, c->mean * 1e9, c->peak_force * 1e9,
            c->max_indentation * 1e9, c->contact_fraction, c->e_ts * 1e18,
            p->retract ? "retract" : "approach", p->settled, p->cycles, c->e_drive * 1e18, rel,
            isfinite(c->y_min) ? c->y_min * 1e9 : NAN, isfinite(c->y_max) ? c->y_max * 1e9 : NAN);
}

static int plot(const char *path, const tt_approach_point *pts, size_t n, int ramp)
{
    double *x = malloc(n * sizeof *x), *a = malloc(n * sizeof *a), *ph = malloc(n * sizeof *ph),
           *e = malloc(n * sizeof *e), *lo = malloc(n * sizeof *lo), *hi = malloc(n * sizeof *hi);
    tt_figure *f = tt_figure_alloc(3, ramp ? "Approach (ramp)" : "Approach (steady state)");
    int rc = (x && a && ph && e && lo && hi && f) ? TT_OK : tt_error(TT_ENOMEM, "out of memory");
    for (int branch = 0; branch < 2 && rc == TT_OK; branch++) {
        size_t m = 0;
        for (size_t i = 0; i < n; i++) {
            if (pts[i].retract != branch)
                continue;
            x[m] = pts[i].z * 1e9;
            a[m] = pts[i].cycle.amplitude * 1e9;
            ph[m] = pts[i].cycle.phase * 180 / M_PI;
            e[m] = pts[i].cycle.e_ts * 1e18;
            lo[m] = pts[i].cycle.y_min * 1e9;
            hi[m] = pts[i].cycle.y_max * 1e9;
            m++;
        }
        if (m == 0)
            continue;
        unsigned style = branch ? (TT_PLOT_DASHED | 2) : 1;
        const char *label = branch ? "retract" : "approach";
        tt_figure_line(f, 0, x, a, m, label, style);
        if (ramp) {
            unsigned es = branch ? (6 | TT_PLOT_DASHED) : 5;
            tt_figure_line(f, 0, x, lo, m, branch ? "deflection min/max (retract)" : "deflection min/max", es);
            tt_figure_line(f, 0, x, hi, m, NULL, es);
        }
        tt_figure_line(f, 1, x, ph, m, label, style);
        tt_figure_line(f, 2, x, e, m, label, style);
    }
    if (rc == TT_OK) {
        tt_figure_axes(f, 0, "rest separation z (nm)", ramp ? "amplitude, deflection (nm)" : "amplitude (nm)");
        tt_figure_axes(f, 1, "rest separation z (nm)", "phase lag (deg)");
        tt_figure_hline(f, 1, 90, NULL);
        tt_figure_axes(f, 2, "rest separation z (nm)", "tip-sample loss per cycle (aJ)");
        rc = tt_figure_write_png(f, path, 900, 1000);
    }
    tt_figure_free(f);
    free(x);
    free(a);
    free(ph);
    free(e);
    free(lo);
    free(hi);
    return rc;
}

int cmd_approach(int argc, char **argv)
{
    static const struct option opts[] = {{"output", required_argument, NULL, 'o'},
                                         {"plot", required_argument, NULL, 'p'},
                                         {"set", required_argument, NULL, 's'},
                                         {"quiet", no_argument, NULL, 'q'},
                                         {"help", no_argument, NULL, 'h'},
                                         {NULL, 0, NULL, 0}};
    const char *out = "approach.csv", *plotpath = NULL;
    char **sets = calloc((size_t)argc, sizeof *sets);
    int nsets = 0, quiet = 0, c;
    if (!sets)
        return cli_fail(TT_ENOMEM, "out of memory");
    while ((c = getopt_long(argc, argv, "o:qh", opts, NULL)) != -1) {
        switch (c) {
        case 'o': out = optarg; break;
        case 'p': plotpath = optarg; break;
        case 's': sets[nsets++] = optarg; break;
        case 'q': quiet = 1; break;
        case 'h': help(); free(sets); return CLI_OK;
        default: free(sets); return CLI_USAGE;
        }
    }
    int code;
    tt_scene *scene = cli_scene_args("approach", argc, argv, optind, sets, nsets, &code);
    if (!scene)
        return code;
    double t0 = cli_now();
    tt_setup *st = NULL;
    tt_approach *ap = NULL;
    tt_outfile *of = NULL;
    tt_approach_point *pts = NULL;
    tt_approach_params p;
    size_t mat = 0, n = 0;
    int rc;
    if ((rc = tt_setup_alloc(&st, scene)) || (rc = tt_config_approach(scene, &p)) ||
        (rc = tt_config_material_index(scene, "approach", tt_setup_material(st, 0),
                                       tt_setup_materials(st), &mat)) ||
        (rc = tt_setup_use_material(st, mat)) || (rc = tt_approach_alloc(&ap, tt_setup_sim(st), &p)) ||
        (rc = tt_outfile_open(&of, out)))
        goto done;
    pts = calloc(tt_approach_rows(ap), sizeof *pts);
    if (!pts) {
        rc = tt_error(TT_ENOMEM, "out of memory");
        goto done;
    }
    FILE *f = tt_outfile_stream(of);
    fprintf(f, "z_nm,amplitude_nm,phase_deg,mean_deflection_nm,peak_force_nN,max_indentation_nm,"
               "contact_fraction,dissipated_aJ,branch,settled,cycles,drive_work_aJ,energy_residual,"
               "deflection_min_nm,deflection_max_nm\n");
    cli_catch_interrupt();
    int progress = !quiet && cli_progress_enabled();
    while (!tt_approach_done(ap)) {
        if (tt_cancel_requested()) {
            rc = tt_error(TT_EINTR, "interrupted: %s keeps the %zu rows finished", out, n);
            break;
        }
        if ((rc = tt_approach_iterate(ap, &pts[n])))
            break;
        write_row(f, &pts[n]);
        n++;
        if (progress)
            fprintf(stderr, "\rapproach: %zu/%zu points", n, tt_approach_rows(ap));
    }
    if (progress)
        fprintf(stderr, "\n");
    /* Keep what finished, also when interrupted or when the solver failed later on. */
    {
        int crc = tt_outfile_close(of, n > 0);
        of = NULL;
        if (!rc)
            rc = crc;
    }
    if (plotpath && n > 0) {
        int prc = plot(plotpath, pts, n, p.mode == TT_APPROACH_RAMP);
        if (!rc)
            rc = prc;
    }
    if (!quiet && n > 0) {
        double worst = 0;
        long unsettled = 0, cycles = 0;
        for (size_t i = 0; i < n; i++) {
            double r = pts[i].cycle.residual_rel;
            if (r > worst)
                worst = r;
            if (p.mode == TT_APPROACH_STEADY && !pts[i].settled)
                unsettled++;
            cycles += pts[i].cycles;
        }
        fprintf(stderr, "points = %zu\ncycles = %ld\nrun_time_s = %.3f\n", n, cycles, cli_now() - t0);
        fprintf(stderr, "error_estimate = %.3g (largest energy-balance residual of a cycle / free drive work per cycle)\n",
                worst);
        if (unsettled)
            fprintf(stderr, "warning: %ld points did not settle within max_cycles = %ld "
                            "(period doubling or chaos, or raise [approach] max_cycles)\n",
                    unsettled, p.max_cycles);
    }
done:
    if (of)
        tt_outfile_close(of, 0);
    if (rc)
        cli_fail(rc, NULL);
    free(pts);
    tt_approach_free(ap);
    tt_setup_free(st);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}
