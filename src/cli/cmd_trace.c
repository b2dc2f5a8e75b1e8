/* tiptap trace: a time series of the tapping cantilever, with an optional ramp of one
 * scene key over the run (Burnham et al.'s figures 4b to 8). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/io/decimate.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/config/config.h"
#include "tiptap/config/read_trace.h"
#include "tiptap/config/setup.h"
#include "tiptap/instrument/trace.h"
#include "tiptap/util/phase.h"

static void help(void)
{
    printf("Usage: tiptap trace SCENE... [--set section.key=value]... [-o trace.csv]\n"
           "                     [--plot trace.png] [-q]\n"
           "Time series of the scene's [trace] section (Burnham et al.'s figures 4b, 5 to 8).\n\n"
           "  -o, --output FILE  CSV, samples_per_cycle rows per cycle: t_us, base_nm, tip_nm,\n"
           "                     sample_nm, deflection_nm, force_nN, contact_radius_nm,\n"
           "                     pressure_GPa (Hertzian K a / pi R, as in Burnham et al.), contact,\n"
           "                     and the ramped key's value when [trace] ramp is set\n"
           "      --plot FILE    PNG: positions and deflection; force; pressure (each cycle's\n"
           "                     peak marked where the integrator located it)\n"
           CLI_HELP_SET
           "  -q, --quiet        no summary on stderr\n\n"
           "Positions are along the axis into the sample, the base at rest at 0; the\n"
           "deflection is tip - base, what a beam-deflection detector measures. [noise] as in\n"
           "a scan (seed, temperature, points, detector, z_piezo, z_piezo_bandwidth): the\n"
           "thermal force moves the tip, z piezo noise through its bandwidth the sample, and\n"
           "the detector's noise is added to deflection_nm only.\n"
           "stderr ends with the run time, the energy balance (the largest energy-balance\n"
           "residual of a cycle relative to the free drive work per cycle, pi c w A0^2: zero\n"
           "for the exact solution, a check) and the error estimate: twice the largest\n"
           "difference of the deflection, and of each cycle's amplitude and phase, from a\n"
           "companion run beside it at a 100 times tighter tolerance (rk4: 4 times the steps);\n"
           "a warning when it exceeds 1e-3 of the free amplitude or 0.1 deg.\n");
}

/* The plot holds at most PLOT_BUDGET points a line: a figure 1000 pixels wide shows no
 * more, and 1e8 cycles would otherwise fill the memory (tt_decimate keeps each
 * bucket's extremes, so envelopes and contact peaks stay in the picture). */
#define PLOT_BUDGET 100000

/* One sample in the plot's units: t, base, tip, sample, deflection, force, pressure. */
static int series_push(tt_decimate *S, const tt_trace_sample *x)
{
    const double v[7] = {x->t * 1e6, x->base * 1e9, x->tip * 1e9, x->sample * 1e9,
                         x->deflection * 1e9, x->force * 1e9, x->pressure * 1e-9};
    return tt_decimate_push(S, v);
}

/* A cycle's located peak, at the middle of its contact (else the largest sample): time
 * (us), peak force (nN), pressure at the greatest indentation (GPa). */
static int peak_push(tt_decimate *P, const tt_trace_row *r)
{
    if (!(r->summary.contact_fraction > 0) || r->nsamples == 0)
        return TT_OK;
    const tt_cycle *c = &r->summary;
    double t = r->samples[0].t + 0.5 * (c->t_contact + c->t_release);
    if (!(c->t_release > c->t_contact)) {
        size_t kmax = 0;
        for (size_t k = 1; k < r->nsamples; k++)
            if (r->samples[k].force > r->samples[kmax].force)
                kmax = k;
        t = r->samples[kmax].t;
    }
    const double v[3] = {t * 1e6, c->peak_force * 1e9, r->peak_pressure * 1e-9};
    return tt_decimate_push(P, v);
}

static int plot(const char *path, const tt_decimate *D, const tt_decimate *P, const char *ramp)
{
    const double *tp = tt_decimate_line(P, 0);
    size_t np = tt_decimate_count(P);
    const double *t = tt_decimate_line(D, 0);
    size_t n = tt_decimate_count(D);
    char title[256];
    snprintf(title, sizeof title, "Trace%s%s", ramp ? ": ramp of " : "", ramp ? ramp : "");
    tt_figure *f = tt_figure_alloc(3, title);
    if (!f)
        return tt_error_nomem("the plot %s", path);
    tt_figure_axes(f, 0, "time (us)", "position (nm)");
    tt_figure_line(f, 0, t, tt_decimate_line(D, 1), n, "base", 1);
    tt_figure_line(f, 0, t, tt_decimate_line(D, 2), n, "tip", 2);
    tt_figure_line(f, 0, t, tt_decimate_line(D, 3), n, "sample surface", 3 | TT_PLOT_DASHED);
    tt_figure_line(f, 0, t, tt_decimate_line(D, 4), n, "deflection (tip - base)", 4);
    /* The samples are at fixed times and miss most of a short contact: each cycle's
     * peak is marked as the integrator located it. */
    tt_figure_axes(f, 1, "time (us)", "tip-sample force (nN)");
    tt_figure_line(f, 1, t, tt_decimate_line(D, 5), n, "force (samples)", 1);
    tt_figure_line(f, 1, tp, tt_decimate_line(P, 1), np, "peak of each cycle (located)", 2 | TT_PLOT_POINTS);
    tt_figure_axes(f, 2, "time (us)", "Hertzian pressure K a / pi R (GPa)");
    tt_figure_line(f, 2, t, tt_decimate_line(D, 6), n, "pressure (samples)", 3);
    tt_figure_line(f, 2, tp, tt_decimate_line(P, 2), np, "at each cycle's greatest indentation",
                   2 | TT_PLOT_POINTS);
    int rc = tt_figure_write_png(f, path, 1000, 1100);
    tt_figure_free(f);
    return rc;
}

static void write_row(FILE *f, const tt_trace_row *r, int ramp)
{
    for (size_t k = 0; k < r->nsamples; k++) {
        const tt_trace_sample *x = &r->samples[k];
        fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d", x->t * 1e6, x->base * 1e9,
                x->tip * 1e9, x->sample * 1e9, x->deflection * 1e9, x->force * 1e9,
                x->contact_radius * 1e9, x->pressure * 1e-9, x->contact);
        if (ramp)
            fprintf(f, ",%.9g", r->ramp_value);
        fputc('\n', f);
    }
}

/* The message of a Ctrl-C or SIGTERM: what was kept, or that nothing was. The plot is
 * not drawn then: cairo takes seconds for the lines of a few thousand cycles (30 s for
 * 5000), and a signal is answered within one. */
static int interrupted(const char *out, long cycles, const char *plotpath)
{
    if (cycles == 0)
        return tt_error(TT_EINTR, "interrupted before the first cycle finished: %s not written", out);
    return tt_error(TT_EINTR, "interrupted: %s keeps the %ld cycles finished%s%s%s", out, cycles,
                    plotpath ? " (" : "", plotpath ? plotpath : "", plotpath ? " not drawn)" : "");
}

/* The run's own error estimate: the trace again at the companion setting
 * (tt_companion_solver), cycle for cycle beside the run (nothing stored), twice the
 * largest difference of the deflection samples and of each cycle's amplitude (relative
 * to the free amplitude) and phase (deg). The energy balance is no estimate of these:
 * at setpoint-10 it read 1.4e-6 where the phase was off by 2e-5 rad. */
typedef struct {
    tt_scene *scene;
    tt_setup *st;
    tt_trace *tr;
    tt_solver tight;
    double A0, deflection_rel, amplitude_rel, phase_deg, seconds;
} trace_est;

static int companion_open(trace_est *e, const tt_scene *scene, const tt_setup *st)
{
    tt_trace_params p;
    e->A0 = tt_setup_cantilever(st)->A0;
    e->scene = cli_companion_scene(scene, tt_setup_solver(st), &e->tight);
    if (!e->scene)
        return tt_error(TT_ENOMEM, "out of memory");
    int rc;
    if ((rc = tt_setup_alloc(&e->st, e->scene)) || (rc = tt_config_trace(e->scene, &p)) ||
        (rc = tt_trace_alloc(&e->tr, e->st, &p)))
        return rc;
    return TT_OK;
}

static int companion_step(trace_est *e, const tt_trace_row *r)
{
    double t0 = cli_now();
    tt_trace_row q;
    int rc = tt_trace_iterate(e->tr, &q);
    e->seconds += cli_now() - t0;
    if (rc)
        return rc;
    for (size_t k = 0; k < r->nsamples && k < q.nsamples; k++) {
        double a = r->samples[k].deflection, b = q.samples[k].deflection;
        e->deflection_rel = fmax(e->deflection_rel, 2 * fabs(a - b) / e->A0);
    }
    const double dphi = (r->summary.phase - q.summary.phase) * 180 / M_PI;
    e->phase_deg = fmax(e->phase_deg, 2 * tt_phase_diff_deg(dphi, 0));
    e->amplitude_rel = fmax(e->amplitude_rel, 2 * fabs(r->summary.amplitude - q.summary.amplitude) / e->A0);
    return TT_OK;
}

static void companion_close(trace_est *e)
{
    tt_trace_free(e->tr);
    tt_setup_free(e->st);
    tt_scene_free(e->scene);
}

int cmd_trace(int argc, char **argv)
{
    static const cli_spec spec = {"trace", CLI_OPT_OUTPUT | CLI_OPT_PLOT | CLI_OPT_SET | CLI_OPT_QUIET,
                                  NULL, "", help};
    cli_args args = {.output = "trace.csv"};
    int code;
    tt_scene *scene = cli_options_scene(&spec, &args, argc, argv, &code);
    if (!scene)
        return code;
    const char *out = args.output, *plotpath = args.plot;
    int quiet = args.quiet;
    double t0 = cli_now(), worst = 0;
    tt_setup *st = NULL;
    tt_trace *tr = NULL;
    tt_outfile *of = NULL;
    tt_trace_params p;
    tt_decimate *S = NULL, *Pk = NULL; /* samples; each cycle's located peak */
    long done_cycles = 0;
    trace_est est = {0};
    int rc, have_est = 0;
    /* the trace's own checks name the file that set the key, as the scene's do */
    if ((rc = tt_setup_alloc(&st, scene)) || (rc = tt_config_trace(scene, &p)) ||
        (rc = tt_scene_locate(scene, tt_trace_alloc(&tr, st, &p))))
        goto done;
    {
        tt_estimate e;
        const tt_cantilever *cl = tt_setup_cantilever(st);
        tt_config_trace_estimate(cl, tt_setup_solver(st), &p, &e);
        cli_report_estimate("trace", e.cycles, e.seconds, e.upper_bound, 1, cl->f0, cl->fd, quiet);
    }
    cli_catch_interrupt(); /* from here on a signal keeps the cycles finished */
    if ((rc = tt_outfile_open(&of, out)))
        goto done;
    if (plotpath && (rc = tt_decimate_alloc(&S, 7, (double)tt_trace_rows(tr) * (double)p.samples_per_cycle,
                                           PLOT_BUDGET)))
        goto done;
    if (plotpath && (rc = tt_decimate_alloc(&Pk, 3, (double)tt_trace_rows(tr), PLOT_BUDGET)))
        goto done;
    FILE *f = tt_outfile_stream(of);
    fprintf(f, "t_us,base_nm,tip_nm,sample_nm,deflection_nm,force_nN,contact_radius_nm,pressure_GPa,"
               "contact%s%s\n",
            p.ramp ? "," : "", p.ramp ? p.ramp : "");
    if (!quiet) {
        have_est = companion_open(&est, scene, st) == TT_OK;
        if (!have_est)
            fprintf(stderr, "tiptap: no error estimate: %s\n", tt_error_message());
    }
    cli_progress prog;
    cli_progress_begin(&prog, "trace", "cycles", quiet);
    while (!tt_trace_done(tr)) {
        tt_trace_row row;
        /* within a cycle (or the settling) the cycle is abandoned */
        if (tt_cancel_requested() || (rc = tt_trace_iterate(tr, &row)) == TT_EINTR) {
            rc = interrupted(out, done_cycles, plotpath);
            break;
        }
        if (rc)
            break;
        if (row.summary.residual_rel > worst)
            worst = row.summary.residual_rel;
        write_row(f, &row, p.ramp != NULL);
        if (have_est && companion_step(&est, &row)) {
            fprintf(stderr, "tiptap: no error estimate: the companion run at tolerance %g: %s\n",
                    est.tight.tolerance, tt_error_message());
            have_est = 0;
        }
        for (size_t k = 0; plotpath && k < row.nsamples && rc == TT_OK; k++)
            rc = series_push(S, &row.samples[k]);
        if (plotpath && rc == TT_OK)
            rc = peak_push(Pk, &row);
        if (rc)
            break;
        done_cycles++;
        /* a cycle takes a millisecond or less: the clock is read every 64 */
        if (done_cycles % 64 == 0 || tt_trace_done(tr))
            cli_progress_show(&prog, done_cycles, (long)tt_trace_rows(tr));
    }
    cli_progress_end(&prog);
    if (done_cycles > 0)
        tt_trace_warn_contact(tr); /* under -q too: it is about the numbers */
    /* Keep the cycles finished when interrupted; a run that failed (the solver, a ramp
     * value) keeps no file: a partial CSV would read as complete. */
    {
        int keep = done_cycles > 0 && (rc == TT_OK || rc == TT_EINTR);
        int crc = tt_outfile_close(of, keep);
        of = NULL;
        if (!rc)
            rc = crc;
        else if (!keep && rc != TT_EINTR) {
            char why[1024];
            snprintf(why, sizeof why, "%s", tt_error_message());
            tt_error(rc, "%s; %s not written (%ld cycles had finished; a failed trace keeps no "
                         "partial file)", why, out, done_cycles);
        }
    }
    if (!rc) {
        /* both finished, whatever the first says: the plot shows both */
        int frc = S ? tt_decimate_finish(S) : TT_OK, prc = Pk ? tt_decimate_finish(Pk) : TT_OK;
        if (!rc)
            rc = frc ? frc : prc;
    }
    if (plotpath && rc == TT_OK && tt_cancel_requested()) /* came as the CSV was closed */
        rc = interrupted(out, done_cycles, plotpath);
    int plotted = plotpath && S && tt_decimate_count(S) > 0 && rc == TT_OK;
    if (plotted) {
        /* the CSV is complete; drawing a long trace takes seconds, and a signal ends it
         * at once (after the PNG, if it is being written) */
        char why[8400];
        snprintf(why, sizeof why, "interrupted while drawing %s: %s is complete, the plot not drawn",
                 plotpath, out);
        cli_interrupt_at_once(why);
        int prc = plot(plotpath, S, Pk, p.ramp);
        if (!rc)
            rc = prc;
    }
    if (!quiet)
        fprintf(stderr, "cycles = %ld\nrun_time_s = %.3f\nenergy_balance = %.3g (largest energy-balance "
                        "residual of a cycle / free drive work per cycle: a check, not the error)\n",
                done_cycles, cli_now() - t0 - est.seconds, worst);
    if (!quiet && have_est && done_cycles > 0) {
        const tt_solver *sv = tt_setup_solver(st);
        int rk4 = sv->method == TT_METHOD_RK4;
        fprintf(stderr, "error_estimate_deflection_rel = %.2g (largest, of the free amplitude)\n"
                        "error_estimate_amplitude_rel = %.2g (largest)\n"
                        "error_estimate_phase_deg = %.2g (largest)\n"
                        "# from a companion run at %s %.3g beside it; run_time_s excludes it\n",
                est.deflection_rel, est.amplitude_rel, est.phase_deg, rk4 ? "steps_per_cycle" : "tolerance",
                rk4 ? (double)est.tight.steps_per_cycle : est.tight.tolerance);
        int defl = est.deflection_rel >= est.amplitude_rel;
        tt_run_warn_estimate(sv, est.A0, NAN, defl ? "deflection" : "amplitude",
                             defl ? est.deflection_rel : est.amplitude_rel, est.phase_deg);
    }
    if (!quiet && done_cycles > 0)
        fprintf(stderr, "output = %s (%ld cycles x %ld samples)%s%s\n", out, done_cycles,
                p.samples_per_cycle, plotted ? ", plot " : "", plotted ? plotpath : "");
done:
    companion_close(&est);
    if (of)
        tt_outfile_close(of, 0);
    if (rc)
        cli_fail(rc, NULL);
    tt_decimate_free(S);
    tt_decimate_free(Pk);
    tt_trace_free(tr);
    tt_setup_free(st);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}
