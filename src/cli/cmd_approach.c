/* tiptap approach: amplitude, phase and the rest against rest separation. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/run/run.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/util/phase.h"

static void help(void)
{
    printf("Usage: tiptap approach SCENE... [--set section.key=value]... [-o approach.csv]\n"
           "                        [--plot approach.png] [-q]\n"
           "Approach curve of the scene's [approach] section (Burnham et al.'s figures 1 and 4).\n\n"
           "  -o, --output FILE  CSV, one row per point: z_nm, amplitude_nm, phase_deg,\n"
           "                     mean_deflection_nm, peak_force_nN, max_indentation_nm,\n"
           "                     contact_fraction, dissipated_aJ, branch, settled, cycles,\n"
           "                     drive_work_aJ, energy_residual, deflection_min_nm,\n"
           "                     deflection_max_nm, period (default approach.csv); with a\n"
           "                     viscous material (viscosity, film_thickness) also the\n"
           "                     loss per mechanism: dissipated_hysteresis_aJ,\n"
           "                     dissipated_damping_aJ, dissipated_viscous_aJ; with mode 2\n"
           "                     driven ([cantilever] mode2_free_amplitude) also mode 2's\n"
           "                     lock-in: amplitude_2_nm, phase_2_deg (then amplitude_nm and\n"
           "                     phase_deg are mode 1's lock-in's, and each point settles)\n"
           "      --plot FILE    PNG of amplitude, phase (mode 2's too), loss against z\n"
           CLI_HELP_SET
           "  -q, --quiet        no summary on stderr\n\n"
           "period: steady mode, 1 for a steady oscillation, n for an orbit repeating every\n"
           "n cycles (up to 64; its row is the means over them), 0 when none was found within\n"
           "max_cycles (the means over the last 64 cycles); stderr warns of both.\n"
           "z is the rest separation: the gap between the undeflected, non-interacting tip\n"
           "and the sample (negative: the rest position is below the surface).\n"
           "stderr ends with the run time, the energy balance (the largest residual of a cycle,\n"
           "drive work - cantilever damping - tip-sample loss - change of stored energy,\n"
           "relative to the free oscillation's drive work per cycle: zero for the exact\n"
           "solution, a check of the integration) and the error estimate of amplitude and\n"
           "phase: twice their largest difference from a companion run at a 100 times tighter\n"
           "tolerance (rk4: 4 times the steps), over the points settled in both; a warning\n"
           "when it exceeds 1e-3 of the free amplitude or 0.1 deg.\n"
           "In steady mode with [approach] steady = shooting (the default) it also tells how\n"
           "many points Newton found as periodic orbits, their largest Floquet multiplier,\n"
           "each point settled instead and why, and where approach and retract found two\n"
           "stable orbits at the same separation.\n");
}

static void write_row(FILE *f, const tt_approach_point *p, int viscous, int bimodal)
{
    const tt_cycle *c = &p->cycle;
    double rel = c->residual_rel;
    fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%s,%d,%ld,%.9g,%.3g,%.9g,%.9g,%d", p->z * 1e9,
            c->amplitude * 1e9, c->phase * 180 / M_PI, c->mean * 1e9, c->peak_force * 1e9,
            c->max_indentation * 1e9, c->contact_fraction, c->e_ts * 1e18,
            p->retract ? "retract" : "approach", p->settled, p->cycles, c->e_drive * 1e18, rel,
            isfinite(c->y_min) ? c->y_min * 1e9 : NAN, isfinite(c->y_max) ? c->y_max * 1e9 : NAN,
            p->period);
    if (viscous)
        fprintf(f, ",%.9g,%.9g,%.9g", c->e_hyst * 1e18, c->e_ci * 1e18, c->e_visc * 1e18);
    if (bimodal)
        fprintf(f, ",%.9g,%.9g", p->amplitude2 * 1e9, p->phase2 * 180 / M_PI);
    fputc('\n', f);
}

/* The plot's series of one branch: z, amplitude, phase, loss, deflection's extremes and
 * mode 2's amplitude and phase, in nm, deg, aJ; their count. */
static size_t branch_series(const tt_approach_point *pts, size_t n, int branch, double *const *v)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++) {
        if (pts[i].retract != branch)
            continue;
        const tt_cycle *c = &pts[i].cycle;
        const double row[8] = {pts[i].z * 1e9, c->amplitude * 1e9, c->phase * 180 / M_PI, c->e_ts * 1e18,
                               c->y_min * 1e9, c->y_max * 1e9, pts[i].amplitude2 * 1e9,
                               pts[i].phase2 * 180 / M_PI};
        for (int k = 0; k < 8; k++)
            v[k][m] = row[k];
        m++;
    }
    return m;
}

/* Amplitude, phase (and mode 2's, when driven) and dissipation against z. */
static int plot(const char *path, const tt_approach_point *pts, size_t n, int ramp, int bimodal)
{
    double *v[8] = {NULL};
    int ok = 1;
    for (int k = 0; k < 8; k++)
        ok &= (v[k] = malloc(n * sizeof *v[k])) != NULL;
    const int panels = bimodal ? 5 : 3, loss = panels - 1;
    tt_figure *f = tt_figure_alloc(panels, ramp ? "Approach (ramp)" : "Approach (steady state)");
    int rc = (ok && f) ? TT_OK : tt_error_nomem("the plot %s", path);
    for (int branch = 0; branch < 2 && rc == TT_OK; branch++) {
        size_t m = branch_series(pts, n, branch, v);
        if (m == 0)
            continue;
        double *x = v[0];
        unsigned style = branch ? (TT_PLOT_DASHED | 2) : 1;
        const char *label = branch ? "retract" : "approach";
        tt_figure_line(f, 0, x, v[1], m, label, style);
        if (ramp) {
            unsigned es = branch ? (6 | TT_PLOT_DASHED) : 5;
            tt_figure_line(f, 0, x, v[4], m, branch ? "deflection min/max (retract)" : "deflection min/max", es);
            tt_figure_line(f, 0, x, v[5], m, NULL, es);
        }
        tt_figure_line(f, 1, x, v[2], m, label, style);
        if (bimodal) {
            tt_figure_line(f, 2, x, v[6], m, label, style);
            tt_figure_line(f, 3, x, v[7], m, label, style);
        }
        tt_figure_line(f, loss, x, v[3], m, label, style);
    }
    if (rc == TT_OK) {
        tt_figure_axes(f, 0, "rest separation z (nm)", ramp ? "amplitude, deflection (nm)" : "amplitude (nm)");
        tt_figure_axes(f, 1, "rest separation z (nm)", "phase lag (deg)");
        tt_figure_hline(f, 1, 90, NULL);
        if (bimodal) {
            tt_figure_axes(f, 2, "rest separation z (nm)", "mode 2 amplitude (nm)");
            tt_figure_axes(f, 3, "rest separation z (nm)", "mode 2 phase lag (deg)");
            tt_figure_hline(f, 3, 90, NULL);
        }
        tt_figure_axes(f, loss, "rest separation z (nm)", "tip-sample loss per cycle (aJ)");
        rc = tt_figure_write_png(f, path, 900, bimodal ? 1500 : 1000);
    }
    tt_figure_free(f);
    for (int k = 0; k < 8; k++)
        free(v[k]);
    return rc;
}

/* Why a steady point did not settle: no period up to TT_SETTLE_MAX_PERIOD cycles, and
 * how its amplitude moved over the cycles its row is the mean of (approach.h). */
static void unsettled_why(const tt_approach_point *pt, long max_cycles)
{
    fprintf(stderr, "unsettled: z = %.6g nm after %ld cycles (max_cycles %ld): no period up to "
                    "%d cycles: amplitude %.4g to %.4g nm over the last %d cycles, changing by "
                    "%.3g nm per cycle on average\n", pt->z * 1e9, pt->cycles, max_cycles,
            TT_SETTLE_MAX_PERIOD, pt->amp_min * 1e9, pt->amp_max * 1e9, pt->window,
            pt->amp_change * 1e9);
}

/* How shooting fared: points by Newton, points settled instead and why, the orbits'
 * largest Floquet multiplier, and where the approach and retract branches found two
 * different stable orbits at the same separation (bistability). */
static void shooting_summary(const tt_approach_point *pts, size_t n)
{
    size_t newton = 0;
    double mu = 0;
    for (size_t i = 0; i < n; i++) {
        if (pts[i].shot.how != TT_SHOOT_NEWTON) {
            fprintf(stderr, "shooting: z = %.6g nm settled instead (%s)\n", pts[i].z * 1e9,
                    pts[i].shot.why[0] ? pts[i].shot.why : "no Newton attempt");
            continue;
        }
        newton++;
        mu = fmax(mu, pts[i].shot.mu_abs);
    }
    fprintf(stderr, "shooting = %zu of %zu points by Newton, largest Floquet |mu| = %.6g\n",
            newton, n, mu);
    size_t lo = 0, hi = 0, both = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            if (pts[j].retract && !pts[i].retract && fabs(pts[i].z - pts[j].z) < 1e-15 &&
                pts[i].shot.how == TT_SHOOT_NEWTON && pts[j].shot.how == TT_SHOOT_NEWTON &&
                fabs(pts[i].cycle.amplitude - pts[j].cycle.amplitude) >
                    1e-3 * fmax(pts[i].cycle.amplitude, pts[j].cycle.amplitude)) {
                if (both == 0 || pts[i].z < pts[lo].z)
                    lo = i;
                if (both == 0 || pts[i].z > pts[hi].z)
                    hi = i;
                both++;
            }
    if (both)
        fprintf(stderr, "bistable: two stable orbits (approach and retract branch) at %zu "
                        "separations from %.6g to %.6g nm\n", both, pts[lo].z * 1e9, pts[hi].z * 1e9);
}

/* The message of a Ctrl-C or SIGTERM: what was kept, or that nothing was. */
static int interrupted(const char *out, size_t rows)
{
    if (rows == 0)
        return tt_error(TT_EINTR, "interrupted before the first row finished: %s not written", out);
    return tt_error(TT_EINTR, "interrupted: %s keeps the %zu rows finished", out, rows);
}

/* The run's own error estimate: the approach again at the companion setting
 * (tt_companion_solver), twice the largest difference of amplitude (relative to the
 * free amplitude) and phase (deg) over the points settled in both runs (steady mode; a
 * point that did not settle reports one cycle of an orbit that is not periodic, whose
 * difference is no integration error). The energy balance per cycle is no estimate of
 * these: at setpoint-10 it read 3.1e-6 where the phase was off by 2.0e-5 rad. */
typedef struct {
    double amplitude_rel, phase_deg;
    double amplitude2_rel, phase2_deg; /* mode 2 driven: its amplitude relative to A2 */
    size_t used;
    tt_solver tight;
} approach_est;

/* The difference of two phases, deg, in [0, 180]. */
static double phase_diff_deg(double a, double b)
{
    return tt_phase_diff_deg((a - b) * 180 / M_PI, 0);
}

static int approach_companion(const tt_scene *scene, const tt_solver *s, double A0, double A2,
                              const tt_approach_point *pts, size_t n, approach_est *e)
{
    tt_scene *c = cli_companion_scene(scene, s, &e->tight);
    tt_setup *st = NULL;
    tt_approach *ap = NULL;
    tt_approach_params p;
    int rc = c ? TT_OK : tt_error(TT_ENOMEM, "out of memory");
    if (rc || (rc = tt_setup_alloc(&st, c)) || (rc = tt_config_approach_alloc(&ap, st, c, &p)))
        goto done;
    double da = 0, dp = 0, da2 = 0, dp2 = 0;
    for (size_t i = 0; i < n && !tt_approach_done(ap); i++) {
        tt_approach_point q;
        if (tt_cancel_requested()) {
            rc = tt_error(TT_EINTR, "interrupted in the error estimate's companion run");
            break;
        }
        if ((rc = tt_approach_iterate(ap, &q)))
            break;
        if (p.mode == TT_APPROACH_STEADY && !(pts[i].settled && q.settled))
            continue;
        da = fmax(da, fabs(pts[i].cycle.amplitude - q.cycle.amplitude) / A0);
        dp = fmax(dp, phase_diff_deg(pts[i].cycle.phase, q.cycle.phase));
        if (A2 > 0) {
            da2 = fmax(da2, fabs(pts[i].amplitude2 - q.amplitude2) / A2);
            dp2 = fmax(dp2, phase_diff_deg(pts[i].phase2, q.phase2));
        }
        e->used++;
    }
    e->amplitude_rel = 2 * da;
    e->phase_deg = 2 * dp;
    e->amplitude2_rel = 2 * da2;
    e->phase2_deg = 2 * dp2;
done:
    tt_approach_free(ap);
    tt_setup_free(st);
    tt_scene_free(c);
    return rc;
}

int cmd_approach(int argc, char **argv)
{
    static const cli_spec spec = {"approach", CLI_OPT_OUTPUT | CLI_OPT_PLOT | CLI_OPT_SET | CLI_OPT_QUIET,
                                  NULL, "", help};
    cli_args args = {.output = "approach.csv"};
    int code;
    tt_scene *scene = cli_options_scene(&spec, &args, argc, argv, &code);
    if (!scene)
        return code;
    const char *out = args.output, *plotpath = args.plot;
    int quiet = args.quiet;
    double t0 = cli_now();
    tt_setup *st = NULL;
    tt_approach *ap = NULL;
    tt_outfile *of = NULL;
    tt_approach_point *pts = NULL;
    tt_approach_params p;
    size_t n = 0;
    int rc;
    if ((rc = tt_setup_alloc(&st, scene)) || (rc = tt_config_approach_alloc(&ap, st, scene, &p)))
        goto done;
    {
        tt_estimate e;
        const tt_cantilever *cl = tt_setup_cantilever(st);
        tt_config_approach_estimate(cl, tt_setup_solver(st), &p, &e);
        cli_report_estimate("approach", e.cycles, e.seconds, e.upper_bound, 1, cl->f0, cl->fd, quiet);
    }
    cli_catch_interrupt(); /* from here on a signal keeps the rows finished */
    if ((rc = tt_outfile_open(&of, out)))
        goto done;
    pts = calloc(tt_approach_rows(ap), sizeof *pts);
    if (!pts) {
        rc = tt_error_nomem("%zu approach points", tt_approach_rows(ap));
        goto done;
    }
    FILE *f = tt_outfile_stream(of);
    int viscous = tt_setup_viscous(st); /* the loss per mechanism: viscous scenes only */
    int bimodal = tt_setup_cantilever(st)->A2 > 0; /* mode 2's lock-in: mode 2 driven only */
    fprintf(f, "z_nm,amplitude_nm,phase_deg,mean_deflection_nm,peak_force_nN,max_indentation_nm,"
               "contact_fraction,dissipated_aJ,branch,settled,cycles,drive_work_aJ,energy_residual,"
               "deflection_min_nm,deflection_max_nm,period%s%s\n",
            viscous ? ",dissipated_hysteresis_aJ,dissipated_damping_aJ,dissipated_viscous_aJ" : "",
            bimodal ? ",amplitude_2_nm,phase_2_deg" : "");
    cli_progress prog;
    cli_progress_begin(&prog, "approach", "points", quiet);
    while (!tt_approach_done(ap)) {
        /* within a point (settling, shooting, the move to it) the point is abandoned */
        if (tt_cancel_requested() || (rc = tt_approach_iterate(ap, &pts[n])) == TT_EINTR) {
            rc = interrupted(out, n);
            break;
        }
        if (rc)
            break;
        write_row(f, &pts[n], viscous, bimodal);
        n++;
        cli_progress_show(&prog, (long)n, (long)tt_approach_rows(ap));
    }
    cli_progress_end(&prog);
    /* Keep what finished, also when interrupted or when the solver failed later on. */
    {
        int crc = tt_outfile_close(of, n > 0);
        of = NULL;
        if (!rc)
            rc = crc;
    }
    if (plotpath && n > 0) {
        int prc = plot(plotpath, pts, n, p.mode == TT_APPROACH_RAMP, bimodal);
        if (!rc)
            rc = prc;
    }
    if (!quiet && n > 0) {
        double worst = 0;
        long cycles = 0;
        for (size_t i = 0; i < n; i++) {
            double r = pts[i].cycle.residual_rel;
            if (r > worst)
                worst = r;
            cycles += pts[i].cycles;
        }
        fprintf(stderr, "points = %zu\ncycles = %ld\nrun_time_s = %.3f\n", n, cycles, cli_now() - t0);
        fprintf(stderr, "output = %s (%zu rows)%s%s\n", out, n, plotpath ? ", plot " : "", plotpath ? plotpath : "");
        fprintf(stderr, "energy_balance = %.3g (largest energy-balance residual of a cycle / free "
                        "drive work per cycle: a check, not the error)\n", worst);
        if (rc == TT_OK) {
            const tt_solver *sv = tt_setup_solver(st);
            double A0 = tt_setup_cantilever(st)->A0, A2 = tt_setup_cantilever(st)->A2;
            approach_est e = {0};
            int erc = approach_companion(scene, sv, A0, A2, pts, n, &e);
            if (erc == TT_EINTR)
                rc = erc;
            else if (erc)
                fprintf(stderr, "tiptap: no error estimate: %s\n", tt_error_message());
            else if (e.used == 0)
                fprintf(stderr, "error_estimate: none (no point settled in both the run and its "
                                "companion)\n");
            else {
                int rk4 = sv->method == TT_METHOD_RK4;
                fprintf(stderr, "error_estimate_amplitude_rel = %.2g (largest)\n"
                                "error_estimate_phase_deg = %.2g (largest)\n"
                                "# over the %zu of %zu points settled in both this run and a "
                                "companion run at %s %.3g; run_time_s excludes it\n",
                        e.amplitude_rel, e.phase_deg, e.used, n,
                        rk4 ? "steps_per_cycle" : "tolerance",
                        rk4 ? (double)e.tight.steps_per_cycle : e.tight.tolerance);
                if (bimodal)
                    fprintf(stderr, "error_estimate_amplitude_2_rel = %.2g (largest, of mode 2's free "
                                    "amplitude)\nerror_estimate_phase_2_deg = %.2g (largest)\n",
                            e.amplitude2_rel, e.phase2_deg);
                /* one warning for both modes: the same key tightens them */
                tt_run_warn_estimate(sv, A0, NAN, bimodal ? "amplitude (mode 1's or 2's, of its own)" : "amplitude",
                                     fmax(e.amplitude_rel, e.amplitude2_rel), fmax(e.phase_deg, e.phase2_deg));
            }
        }
        if (p.mode == TT_APPROACH_STEADY && p.steady == TT_STEADY_SHOOTING)
            shooting_summary(pts, n);
        for (size_t i = 0; p.mode == TT_APPROACH_STEADY && i < n; i++)
            if (!pts[i].settled)
                unsettled_why(&pts[i], p.max_cycles);
    }
    if (n > 0)
        tt_approach_warn(ap); /* under -q too: they are about the table */
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
