/* tiptap accuracy: error against run time for each solver setting (work-precision). */
#include <float.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/accuracy.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/config/units.h"

static void help(void)
{
    printf("Usage: tiptap accuracy SCENE... [--set section.key=value]... [-o accuracy.csv]\n"
           "                        [--plot accuracy.png] [--point Z] [--clock wall|cpu] [-q]\n"
           "Work-precision study: the error of each solver setting against its run time.\n\n"
           "What is judged:\n"
           "  a steady point (a scene without [scan], or with --point): the cantilever starts in\n"
           "    its free steady oscillation at rest separation Z and runs a fixed number of\n"
           "    cycles; observables of the last cycle: amplitude, phase, mean deflection, peak\n"
           "    force, tip-sample dissipation. Z: --point, else the scene's [approach] point\n"
           "    when it has exactly one, else 0.8 times the free amplitude (where tapping holds\n"
           "    the amplitude near 80 %% of free).\n"
           "  a scan line (a scene with [scan]): the first --pixels pixels of the middle line,\n"
           "    with the scene's pixel size and time per pixel; observables: the height and\n"
           "    phase profiles (trace and retrace), their largest and RMS differences from the\n"
           "    reference.\n"
           "Each setting of each ladder (dopri5: tolerance 1e-4 .. 1e-11; rk4: 32 .. 2048\n"
           "steps per cycle; radau: tolerance; on a scan line also envelope: the envelope\n"
           "tier over dopri5 at each tolerance, and averaged: the averaged preview tier, one\n"
           "row) runs from the same state for the same cycles,\n"
           "timed (wall clock and CPU time; a run under 0.5 s is timed in each of --repeats\n"
           "passes over the ladders and keeps its best time), against a reference that\n"
           "integrates every cycle with dopri5 at tolerance 1e-13. The floor, the reference's\n"
           "own error, is its difference from a second reference at 1e-12: smaller errors\n"
           "cannot be measured.\n\n"
           "  -o, --output FILE   CSV, one row per run (default accuracy.csv): method, tier\n"
           "                      (every, envelope, averaged), knob, value, run_time_s (wall\n"
           "                      clock),\n"
           "                      cpu_time_s, steps_per_cycle (accepted steps; NaN for a\n"
           "                      line), integrated (line: the fraction of cycles integrated;\n"
           "                      NaN for a point), the errors (point: amplitude_err_rel,\n"
           "                      phase_err_deg, mean_err_m, peak_force_err_rel,\n"
           "                      dissipation_err_rel; line: height_err_max_m,\n"
           "                      height_err_rms_m, phase_err_max_deg, phase_err_rms_deg),\n"
           "                      residual_rel (the run's energy-balance check), role\n"
           "                      (reference, floor, setting), is_default, status (ok, failed)\n"
           "      --plot FILE     PNG: error against run time, log-log, a curve per ladder\n"
           "                      and a panel per observable\n"
           "      --point Z       judge a steady point at rest separation Z (a length: 16nm)\n"
           "      --cycles N      point: cycles per run (default Q ln(1e8) / pi, when the free\n"
           "                      transient has decayed to 1e-8)\n"
           "      --pixels N      line: pixels of the segment (default 8)\n"
           "      --methods LIST  ladders to study, comma-separated: dopri5, envelope, rk4,\n"
           "                      radau, averaged (default: all; envelope and averaged on\n"
           "                      scan lines only)\n"
           "      --repeats N     timing passes (default 3; 1: every setting runs once)\n"
           "      --clock C       wall (default) or cpu: the run time the plot and the summary\n"
           "                      use; CPU time is steadier on a machine shared with others\n"
           "      --target X      accuracy asked of the primary observable (default 1e-4:\n"
           "                      relative amplitude; line: height error / free amplitude)\n"
           "      --set S.K=V     override a scene key (material.NAME.key for named sections)\n"
           "  -q, --quiet         no table and summary\n\n"
           "The default setting is the scene's [solver] (dopri5, tolerance 1e-8 unless set; on a\n"
           "scan line the envelope tier unless [solver] tier = every or averaged).\n"
           "stdout: the table. stderr: for each method the cheapest setting meeting the target\n"
           "(its loosest from which on every tighter setting meets it too, so that a lucky\n"
           "cancellation of errors does not count), the run time of the default and of the\n"
           "cheapest setting ten times more accurate than it, and at the end the run time and\n"
           "the error estimate (the floor). Ctrl-C stops and keeps the finished rows.\n");
}

/* The clock the plot and the summary go by (--clock). */
static int use_cpu;

static double cost(const tt_accuracy_row *r) { return use_cpu ? r->cpu_time : r->run_time; }


/* "dopri5 tolerance 1e-08", or with the ladder's own name "envelope (dopri5) tolerance 1e-08" */
static void describe(char *buf, size_t n, const tt_accuracy_row *r)
{
    const char *m = tt_method_name(r->method);
    if (strcmp(r->name, m) == 0)
        snprintf(buf, n, "%s %s %g", m, r->knob, r->value);
    else
        snprintf(buf, n, "%s (%s) %s %g", r->name, m, r->knob, r->value);
}

static void write_row(FILE *f, const tt_accuracy_row *r, size_t nobs)
{
    fprintf(f, "%s,%s,%s,%.6g,%.6g,%.6g,%.6g,%.4g", tt_method_name(r->method), tt_accuracy_tier_name(r->tier),
            r->knob, r->value, r->run_time, r->cpu_time, r->steps_per_cycle, r->integrated);
    for (size_t i = 0; i < nobs; i++)
        fprintf(f, ",%.6g", r->err[i]);
    fprintf(f, ",%.3g,%s,%d,%s\n", r->residual_rel, tt_accuracy_role_name(r->role), r->is_default,
            r->status == TT_OK ? "ok" : "failed");
}

static void print_row(const tt_accuracy_row *r, size_t nobs)
{
    char s[96];
    describe(s, sizeof s, r);
    if (r->role == TT_ACCURACY_REFERENCE)
        strcat(s, " (reference)");
    else if (r->role == TT_ACCURACY_FLOOR)
        strcat(s, " (floor)");
    else if (r->is_default)
        strcat(s, " (default)");
    printf("%-44s", s);
    if (r->status != TT_OK) {
        printf(" failed: %s\n", r->message);
        return;
    }
    /* a line counts the cycles integrated, not the steps */
    printf(" %10.4f %10.4f %9.3g", r->run_time, r->cpu_time,
           isfinite(r->integrated) ? r->integrated : r->steps_per_cycle);
    for (size_t i = 0; i < nobs; i++)
        printf(" %11.2e", r->err[i]);
    printf(" %11.2e\n", r->residual_rel);
    fflush(stdout);
}

/* Short column titles of the table, in the order of the observables. */
static void print_header(const tt_accuracy_observable *obs, size_t nobs, int line)
{
    printf("%-44s %10s %10s %9s", "setting", "run_time_s", "cpu_time_s", line ? "integr." : "steps/cyc");
    for (size_t i = 0; i < nobs; i++) {
        char t[16];
        snprintf(t, sizeof t, "%.11s", obs[i].column);
        printf(" %11s", t);
    }
    printf(" %11s\n", "residual");
}

/* Whether row i (past the reference and the floor, rows 0 and 1) is its ladder's first:
 * the plot draws and the summary reports each ladder once. */
static int first_of_ladder(const tt_accuracy *a, size_t i)
{
    for (size_t k = 2; k < i; k++)
        if (strcmp(tt_accuracy_row_at(a, k)->name, tt_accuracy_row_at(a, i)->name) == 0)
            return 0;
    return 1;
}

static int plot(const char *path, const tt_accuracy *a, const char *title)
{
    const tt_accuracy_observable *obs;
    size_t nobs = tt_accuracy_observables(a, &obs), n = tt_accuracy_rows(a);
    tt_figure *f = tt_figure_alloc((int)nobs, title);
    double *x = malloc((n + 2) * sizeof *x), *y = malloc((n + 2) * sizeof *y);
    int rc = (f && x && y) ? TT_OK : tt_error_nomem("the plot %s", path);
    const tt_accuracy_row *floor = tt_accuracy_row_at(a, 1), *def = tt_accuracy_default_row(a);
    double tlo = INFINITY, thi = 0;
    for (size_t i = 0; i < n; i++) {
        const tt_accuracy_row *r = tt_accuracy_row_at(a, i);
        if (r->status == TT_OK && r->role == TT_ACCURACY_SETTING && cost(r) > 0) {
            tlo = fmin(tlo, cost(r));
            thi = fmax(thi, cost(r));
        }
    }
    for (size_t o = 0; o < nobs && rc == TT_OK; o++) {
        tt_figure_axes(f, (int)o, use_cpu ? "run time (s, CPU)" : "run time (s, wall clock)",
                       obs[o].label);
        tt_figure_log(f, (int)o, 1, 1);
        /* one curve per ladder, in the order the rows came */
        int colour = 0;
        for (size_t i = 2; i < n && rc == TT_OK; i++) {
            const tt_accuracy_row *r = tt_accuracy_row_at(a, i);
            if (!first_of_ladder(a, i))
                continue;
            colour++;
            size_t m = 0;
            for (size_t k = i; k < n; k++) {
                const tt_accuracy_row *q = tt_accuracy_row_at(a, k);
                if (strcmp(q->name, r->name) != 0)
                    continue;
                x[m] = cost(q);
                y[m] = q->err[o];
                m++;
                /* the knob values next to the points of the first panel */
                if (o == 0 && q->status == TT_OK) {
                    char t[32];
                    snprintf(t, sizeof t, "%g", q->value);
                    tt_figure_text(f, 0, cost(q), q->err[o], t);
                }
            }
            char label[64];
            snprintf(label, sizeof label, "%s (%s)", r->name, r->knob);
            rc = tt_figure_line(f, (int)o, x, y, m, o == 0 ? label : NULL, (unsigned)colour | TT_PLOT_THICK);
            if (rc == TT_OK)
                rc = tt_figure_line(f, (int)o, x, y, m, NULL, (unsigned)colour | TT_PLOT_POINTS);
        }
        if (rc == TT_OK && floor && floor->status == TT_OK && thi > 0) {
            x[0] = tlo;
            x[1] = thi;
            y[0] = y[1] = floor->err[o];
            rc = tt_figure_line(f, (int)o, x, y, 2, o == 0 ? "reference floor" : NULL, 7 | TT_PLOT_DASHED);
        }
        if (rc == TT_OK && def && def->status == TT_OK) {
            char label[96], s[64];
            describe(s, sizeof s, def);
            snprintf(label, sizeof label, "default: %s", s);
            double dt = cost(def);
            rc = tt_figure_line(f, (int)o, &dt, &def->err[o], 1, o == 0 ? label : NULL,
                                6 | TT_PLOT_POINTS);
        }
    }
    if (rc == TT_OK)
        rc = tt_figure_write_png(f, path, 900, 330 * (int)nobs + 40);
    tt_figure_free(f);
    free(x);
    free(y);
    return rc;
}

/* The built-in ladders named in list ("dopri5,envelope,rk4"). */
static void summary(const tt_accuracy *a, double target, double t0)
{
    const tt_accuracy_observable *obs;
    size_t nobs = tt_accuracy_observables(a, &obs), n = tt_accuracy_rows(a);
    int line = tt_accuracy_kind_of(a) == TT_ACCURACY_LINE;
    const char *what = line ? "largest height error / free amplitude" : "relative amplitude error";
    const char *clock = use_cpu ? "cpu_time_s" : "run_time_s";
    const tt_accuracy_row *ref = tt_accuracy_row_at(a, 0), *floor = tt_accuracy_row_at(a, 1);
    char s[96];
    if (line) {
        size_t np;
        tt_accuracy_reference_profile(a, &np);
        np /= 2; /* height, then phase */
        fprintf(stderr, "judged: the height and phase along a scan line of %ld pixels (%s)\n",
                tt_accuracy_line_pixels(a),
                np > (size_t)tt_accuracy_line_pixels(a) ? "trace and retrace" : "trace");
    } else {
        const tt_cycle *c = tt_accuracy_reference_cycle(a);
        fprintf(stderr, "judged: steady point at rest separation %.4g nm, %ld cycles from the free state\n",
                tt_accuracy_point(a) * 1e9, tt_accuracy_cycles(a));
        if (c)
            fprintf(stderr,
                    "reference: amplitude %.6f nm (%.1f %% of free), phase %.4f deg, mean deflection "
                    "%.4g nm, peak force %.4g nN, dissipation %.4g aJ per cycle; its last cycle "
                    "changed the amplitude by %.2g of free\n",
                    c->amplitude * 1e9, 100 * c->amplitude / tt_accuracy_free_amplitude(a),
                    c->phase * 180 / M_PI, c->mean * 1e9, c->peak_force * 1e9, c->e_ts * 1e18,
                    tt_accuracy_reference_drift(a));
    }
    if (floor && floor->status == TT_OK) {
        fprintf(stderr, "reference floor (dopri5 tolerance %g against %g):", floor->value, ref->value);
        for (size_t i = 0; i < nobs; i++)
            fprintf(stderr, " %s %.2g", obs[i].column, floor->err[i]);
        fprintf(stderr, "\n");
    }
    for (size_t i = 2; i < n; i++) {
        const tt_accuracy_row *r = tt_accuracy_row_at(a, i);
        if (r->role != TT_ACCURACY_SETTING)
            continue;
        if (!first_of_ladder(a, i))
            continue;
        const tt_accuracy_row *c = tt_accuracy_cheapest(a, r->name, target);
        if (c) {
            describe(s, sizeof s, c);
            fprintf(stderr, "cheapest %s with %s <= %g: %s, %s = %.4f (error %.2g", r->name, what,
                    target, s, clock, cost(c), c->primary);
            if (line)
                fprintf(stderr, "; phase rms %.2g deg; %.3g of the cycles integrated",
                        c->err[TT_ACCURACY_PHASE_RMS],
                        c->integrated);
            fprintf(stderr, ")\n");
        } else {
            fprintf(stderr, "cheapest %s with %s <= %g: none on its ladder\n", r->name, what, target);
        }
    }
    const tt_accuracy_row *def = tt_accuracy_default_row(a);
    if (def && def->status == TT_OK) {
        describe(s, sizeof s, def);
        fprintf(stderr, "default %s: %s = %.4f, %s %.2g", s, clock, cost(def), what, def->primary);
        if (isfinite(def->steps_per_cycle))
            fprintf(stderr, ", steps_per_cycle = %.1f", def->steps_per_cycle);
        if (line)
            fprintf(stderr, ", phase rms %.2g deg, %.3g of the cycles integrated",
                    def->err[TT_ACCURACY_PHASE_RMS],
                    def->integrated);
        fprintf(stderr, "\n");
        double want = def->primary / 10;
        const tt_accuracy_row *ten = tt_accuracy_cheapest(a, NULL, want);
        if (floor && floor->status == TT_OK && want < 10 * floor->primary)
            fprintf(stderr, "ten times more accurate (%.2g): not measurable, within 10 times the "
                            "reference floor (%.2g)\n",
                    want, floor->primary);
        else if (ten) {
            describe(s, sizeof s, ten);
            fprintf(stderr, "ten times more accurate (%s <= %.2g): %s, %s = %.4f (%.2f times the default)",
                    what, want, s, clock, cost(ten), cost(ten) / cost(def));
            if (isfinite(ten->steps_per_cycle))
                fprintf(stderr, ", steps_per_cycle = %.1f", ten->steps_per_cycle);
            fprintf(stderr, "\n");
        } else {
            fprintf(stderr, "ten times more accurate (%.2g): no setting on the ladders\n", want);
        }
    } else if (def) {
        describe(s, sizeof s, def);
        fprintf(stderr, "default %s failed: %s\n", s, def->message);
    }
    fprintf(stderr, "run_time_s = %.3f\n", cli_now() - t0);
    if (floor && floor->status == TT_OK)
        fprintf(stderr, "error_estimate = %.3g (the reference's own error in the %s: its difference "
                        "from the check reference)\n",
                floor->primary, what);
}

/* The message of a Ctrl-C: what was kept, or that nothing was. */
static int interrupted(const char *out, size_t n)
{
    if (n == 0)
        return tt_error(TT_EINTR, "interrupted before the first row finished: %s not written", out);
    return tt_error(TT_EINTR, "interrupted: %s keeps the %zu rows finished", out, n);
}

/* A whole-number option from min to 1e8 into *out; 1 (reported) when it is not. */
static int whole(const char *text, const char *option, long min, long *out)
{
    return cli_whole("accuracy", option, text, min, 100000000L, NULL, out) != CLI_OK;
}

int cmd_accuracy(int argc, char **argv)
{
    static const struct option opts[] = {{"point", required_argument, NULL, 'z'},
                                         {"cycles", required_argument, NULL, 'c'},
                                         {"pixels", required_argument, NULL, 'x'},
                                         {"methods", required_argument, NULL, 'm'},
                                         {"repeats", required_argument, NULL, 'r'},
                                         {"target", required_argument, NULL, 't'},
                                         {"clock", required_argument, NULL, 'k'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"accuracy", CLI_OPT_OUTPUT | CLI_OPT_PLOT | CLI_OPT_SET | CLI_OPT_QUIET,
                                  opts, "", help};
    cli_args args = {.output = "accuracy.csv"};
    const char *methods = NULL;
    int c;
    double target = 1e-4;
    tt_accuracy_params p;
    tt_accuracy_params_default(&p);
    char why[256];
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        int bad = 0;
        switch (c) {
        case 'z':
            if (tt_units_parse(optarg, TT_DIM_LENGTH, &p.point, NULL, why, sizeof why) != 0) {
                fprintf(stderr, "tiptap accuracy: --point: '%s': %s\n", optarg, why);
                bad = 1;
            }
            p.kind = TT_ACCURACY_POINT;
            break;
        case 'c': bad = whole(optarg, "--cycles", 10, &p.cycles); break;
        case 'x': bad = whole(optarg, "--pixels", 2, &p.line_pixels); break;
        case 'r': {
            long r = 0;
            bad = whole(optarg, "--repeats", 1, &r);
            p.repeats = (int)r;
            break;
        }
        case 't':
            bad = cli_real("accuracy", "--target", optarg, DBL_MIN, nextafter(1.0, 0.0), "a number between 0 and 1",
                           &target) != CLI_OK;
            break;
        case 'm': methods = optarg; break;
        case 'k':
            bad = strcmp(optarg, "wall") != 0 && strcmp(optarg, "cpu") != 0;
            if (bad)
                fprintf(stderr, "tiptap accuracy: --clock: '%s' is not wall or cpu\n", optarg);
            use_cpu = p.cpu_clock = strcmp(optarg, "cpu") == 0;
            break;
        }
        if (bad) {
            cli_args_free(&args);
            return CLI_USAGE;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    const char *out = args.output, *plotpath = args.plot;
    int quiet = args.quiet;
    tt_accuracy_ladder picked[16];
    if (methods) {
        if (tt_accuracy_pick(methods, picked, sizeof picked / sizeof picked[0], &p.nladders) != 0) {
            fprintf(stderr, "tiptap accuracy: --methods: %s\n", tt_error_message());
            cli_args_free(&args);
            return CLI_USAGE;
        }
        p.ladders = picked;
    }
    int code;
    tt_scene *scene = cli_args_scene(&spec, &args, argc, argv, &code);
    if (!scene)
        return code;
    double t0 = cli_now();
    tt_accuracy *a = NULL;
    tt_outfile *of = NULL;
    int rc;
    /* The output opens first: a bad path fails at once, not after the study. */
    if ((rc = tt_config_accuracy_alloc(&a, scene, &p)))
        goto done;
    cli_catch_interrupt(); /* from here on a signal keeps the rows finished */
    if ((rc = tt_outfile_open(&of, out)))
        goto done;
    const tt_accuracy_observable *obs;
    size_t nobs = tt_accuracy_observables(a, &obs), n = 0;
    FILE *f = tt_outfile_stream(of);
    fprintf(f, "method,tier,knob,value,run_time_s,cpu_time_s,steps_per_cycle,integrated");
    for (size_t i = 0; i < nobs; i++)
        fprintf(f, ",%s", obs[i].column);
    fprintf(f, ",residual_rel,role,is_default,status\n");
    if (!quiet)
        print_header(obs, nobs, tt_accuracy_kind_of(a) == TT_ACCURACY_LINE);
    /* the first pass's runs, then the timing passes, each with the time left */
    cli_progress runs, passes;
    cli_progress_begin(&runs, "accuracy", "runs", quiet);
    int timing = 0;
    while (!tt_accuracy_done(a)) {
        if (tt_cancel_requested()) {
            rc = interrupted(out, n);
            break;
        }
        const tt_accuracy_row *r;
        int pass = tt_accuracy_pass(a);
        if (pass > 1 && !timing) {
            cli_progress_end(&runs);
            cli_progress_begin(&passes, "accuracy", "timing passes", quiet);
            timing = 1;
        }
        if (pass > 2)
            cli_progress_show(&passes, pass - 2, p.repeats - 1);
        if ((rc = tt_accuracy_iterate(a, &r))) {
            if (rc == TT_EINTR)
                rc = interrupted(out, n);
            break;
        }
        /* rows are shown as they are computed; the later passes only refine times */
        if (pass == 1) {
            n++;
            if (!quiet)
                print_row(r, nobs);
            cli_progress_show(&runs, (long)n, (long)tt_accuracy_rows(a));
        }
    }
    if (timing) {
        if (!rc)
            cli_progress_show(&passes, p.repeats - 1, p.repeats - 1);
        cli_progress_end(&passes);
    } else {
        cli_progress_end(&runs);
    }
    for (size_t i = 0; i < n; i++)
        write_row(f, tt_accuracy_row_at(a, i), nobs);
    /* Keep what finished, also when interrupted. */
    {
        int crc = tt_outfile_close(of, n > 0);
        of = NULL;
        if (!rc)
            rc = crc;
    }
    if (plotpath && n > 2) {
        char title[256];
        if (tt_accuracy_kind_of(a) == TT_ACCURACY_LINE)
            snprintf(title, sizeof title, "Work-precision: %s, scan line of %ld pixels",
                     tt_scene_origin(scene), tt_accuracy_line_pixels(a));
        else
            snprintf(title, sizeof title, "Work-precision: %s, steady point at %.3g nm",
                     tt_scene_origin(scene), tt_accuracy_point(a) * 1e9);
        int prc = plot(plotpath, a, title);
        if (!rc)
            rc = prc;
    }
    if (!quiet && n > 2)
        summary(a, target, t0);
done:
    if (of)
        tt_outfile_close(of, 0);
    if (rc)
        cli_fail(rc, NULL);
    tt_accuracy_free(a);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}
