/* tiptap tune: the free lever's thermal spectrum and its fit (tiptap/run/tune.h). */
#include <math.h>
#include <stdlib.h>

#include "commands.h"
#include "tiptap/config/config.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/run/tune.h"
#include "tiptap/util/error.h"

static void help(void)
{
    printf("Usage: tiptap tune SCENE... [--set section.key=value]... [-o tune.csv]\n"
           "                    [--plot tune.png] [-q]\n"
           "Thermal tune: the free, undriven cantilever's deflection at the [noise] temperature\n"
           "for [tune] duration, through the [noise] detector floor; its Welch-averaged power\n"
           "spectral density and a damped-oscillator fit: resonance f, quality factor Q and\n"
           "spring constant k = chi^2 kB T / <x^2> by equipartition, each with its statistical\n"
           "standard error for the record's length.\n\n"
           "  -o, --output FILE  CSV: f_Hz, psd_m2_per_Hz (one-sided), fit_m2_per_Hz; with\n"
           "                     [cantilever] modes above 1 also modeN_m2_per_Hz, each mode's fit\n"
           "      --plot FILE    PNG: the spectrum and the fit, log-log, and a zoom on each peak\n"
           CLI_HELP_SET
           "  -q, --quiet        no progress on stderr\n\n"
           "stdout: f, Q, k with their errors, chi (the optical-lever correction: 1 for the\n"
           "point-mass lever, phi_n'(L) L / 1.5 for a beam's mode n, whose record is the\n"
           "slope-calibrated lever's sum chi_n q_n), the floor, the fit's chi2 per degree\n"
           "of freedom, the record's <x^2> with its error, and kB T / k times the factor\n"
           "the thermal force's interpolation gives it (noise_factor); modeN_ lines for\n"
           "modes 2.. (docs/force-and-tune.md, \"Several modes\").\n");
}

static int write_csv(const char *path, const tt_table *t)
{
    tt_outfile *of;
    int rc = tt_outfile_open(&of, path);
    if (rc)
        return rc;
    FILE *f = tt_outfile_stream(of);
    const size_t cols = tt_table_columns(t);
    fprintf(f, "f_Hz,psd_m2_per_Hz,fit_m2_per_Hz");
    for (size_t j = 3; j < cols; j++)
        fprintf(f, ",%s_m2_per_Hz", tt_table_name(t, j));
    fprintf(f, "\n");
    for (size_t i = 0; i < tt_table_rows(t); i++) {
        for (size_t j = 0; j < cols; j++)
            fprintf(f, j ? ",%.9g" : "%.9g", tt_table_numbers(t, j)[i]);
        fprintf(f, "\n");
    }
    return tt_outfile_close(of, 1);
}

static int plot(const char *path, const tt_table *t, const tt_tune_result *r, double k_scene)
{
    char title[256];
    snprintf(title, sizeof title, "Thermal tune at %.4g K: k = %.4g +- %.2g N/m (scene %.4g N/m)",
             r->temperature, r->k, r->k_err, k_scene);
    tt_figure *f = tt_figure_alloc(2, title);
    if (!f)
        return tt_error_nomem("the plot %s", path);
    size_t n = tt_table_rows(t);
    double *fk = malloc((n ? n : 1) * sizeof *fk), *p = malloc((n ? n : 1) * sizeof *p),
           *m = malloc((n ? n : 1) * sizeof *m);
    int rc = TT_OK;
    if (!fk || !p || !m)
        rc = tt_error_nomem("the plot %s", path);
    for (size_t i = 0; rc == TT_OK && i < n; i++) {
        fk[i] = tt_table_numbers(t, 0)[i] * 1e-3;
        /* in fm/sqrt(Hz), the unit of detector floors */
        p[i] = sqrt(tt_table_numbers(t, 1)[i]) * 1e15;
        m[i] = sqrt(tt_table_numbers(t, 2)[i]) * 1e15;
    }
    if (rc == TT_OK) {
        char fit[200];
        snprintf(fit, sizeof fit, "fit: f = %.6g +- %.2g kHz, Q = %.4g +- %.2g", r->f0 * 1e-3, r->f0_err * 1e-3,
                 r->Q, r->Q_err);
        /* the whole spectrum, log-log; then ten linewidths f0 / Q either side of the peak */
        tt_figure_axes(f, 0, "frequency (kHz)", "deflection noise density (fm/sqrt(Hz))");
        tt_figure_log(f, 0, 1, 1);
        tt_figure_line(f, 0, fk, p, n, "Welch spectrum", 1);
        tt_figure_line(f, 0, fk, m, n, fit, 2);
        double w = fmin(0.95, 10 / r->Q);
        tt_figure_axes(f, 1, "frequency (kHz)", "deflection noise density (fm/sqrt(Hz))");
        tt_figure_log(f, 1, 0, 1);
        tt_figure_xlim(f, 1, r->f0 * (1 - w) * 1e-3, r->f0 * (1 + w) * 1e-3);
        tt_figure_line(f, 1, fk, p, n, "Welch spectrum", 1 | TT_PLOT_POINTS);
        tt_figure_line(f, 1, fk, m, n, "fit", 2);
        rc = tt_figure_write_png(f, path, 1000, 1000);
    }
    free(fk), free(p), free(m);
    tt_figure_free(f);
    return rc;
}

/* Several modes: the whole spectrum with each mode's fit marked, then a zoom on each peak. */
static int plot_modes(const char *path, const tt_table *t, const tt_tune_result *r, const tt_cantilever *c)
{
    char title[256];
    snprintf(title, sizeof title, "Thermal tune of %d modes at %.4g K through the optical lever", r->modes,
             r->temperature);
    tt_figure *f = tt_figure_alloc(1 + r->modes, title);
    size_t n = tt_table_rows(t), cols = tt_table_columns(t);
    double *buf = f ? malloc((n ? n : 1) * cols * sizeof *buf) : NULL;
    int rc = buf ? TT_OK : tt_error_nomem("the plot %s", path);
    for (size_t j = 0; rc == TT_OK && j < cols; j++)
        for (size_t i = 0; i < n; i++) {
            double v = tt_table_numbers(t, j)[i];
            /* kHz, and densities in fm/sqrt(Hz), the unit of detector floors */
            buf[j * n + i] = j == 0 ? v * 1e-3 : sqrt(v) * 1e15;
        }
    const char *ylab = "detector noise density (fm/sqrt(Hz))";
    if (rc == TT_OK) {
        tt_figure_axes(f, 0, "frequency (kHz)", ylab);
        tt_figure_log(f, 0, 1, 1);
        tt_figure_line(f, 0, buf, buf + n, n, "Welch spectrum", 1);
        tt_figure_line(f, 0, buf, buf + 2 * n, n, "fit: every mode and the floor", 2);
    }
    for (int m = 0; rc == TT_OK && m < r->modes; m++) {
        const tt_tune_mode *md = &r->mode[m];
        double ks = m ? c->mode_k[m] : c->k;
        char lab[200];
        snprintf(lab, sizeof lab, "mode %d: f = %.6g +- %.2g kHz, Q = %.4g +- %.2g, k = %.4g +- %.2g N/m (scene %.4g)",
                 m + 1, md->f0 * 1e-3, md->f0_err * 1e-3, md->Q, md->Q_err, md->k, md->k_err, ks);
        tt_figure_line(f, 0, buf, buf + (size_t)(3 + m) * n, n, lab, (3 + m) | TT_PLOT_DASHED);
        tt_figure_axes(f, 1 + m, "frequency (kHz)", ylab);
        tt_figure_log(f, 1 + m, 0, 1);
        tt_figure_xlim(f, 1 + m, md->fit_low * 1e-3, md->f0 * (1 + fmin(0.95, 10 / md->Q)) * 1e-3);
        tt_figure_line(f, 1 + m, buf, buf + n, n, "Welch spectrum", 1 | TT_PLOT_POINTS);
        snprintf(lab, sizeof lab, "fit of mode %d (chi = %.4g)", m + 1, md->chi);
        tt_figure_line(f, 1 + m, buf, buf + 2 * n, n, lab, 2);
    }
    if (rc == TT_OK)
        rc = tt_figure_write_png(f, path, 1000, 500 * (1 + r->modes));
    free(buf);
    tt_figure_free(f);
    return rc;
}

/* Modes 2..: their figures after mode 1's lines. */
static void print_modes(const tt_tune_result *r, const tt_cantilever *c)
{
    printf("modes = %d\n", r->modes);
    for (int m = 1; m < r->modes; m++) {
        const tt_tune_mode *md = &r->mode[m];
        printf("mode%d_f_Hz = %.8g\nmode%d_f_err_Hz = %.3g\nmode%d_Q = %.6g\nmode%d_Q_err = %.3g\n"
               "mode%d_k_N_per_m = %.6g\nmode%d_k_err_N_per_m = %.3g\nmode%d_k_scene_N_per_m = %.6g\n"
               "mode%d_chi = %.6g\nmode%d_noise_factor = %.6g\nmode%d_chi2_dof = %.4g\n"
               "mode%d_fit_low_Hz = %.6g\nmode%d_fit_high_Hz = %.6g\n",
               m + 1, md->f0, m + 1, md->f0_err, m + 1, md->Q, m + 1, md->Q_err, m + 1, md->k, m + 1, md->k_err,
               m + 1, c->mode_k[m], m + 1, md->chi, m + 1, md->noise_factor, m + 1, md->chi2_dof, m + 1,
               md->fit_low, m + 1, md->fit_high);
    }
}

int cmd_tune(int argc, char **argv)
{
    static const cli_spec spec = {"tune", CLI_OPT_OUTPUT | CLI_OPT_PLOT | CLI_OPT_SET | CLI_OPT_QUIET,
                                  NULL, "", help};
    cli_args args = {.output = "tune.csv"};
    int code;
    tt_scene *scene = cli_options_scene(&spec, &args, argc, argv, &code);
    if (!scene)
        return code;
    tt_table *t = NULL;
    tt_tune_result r;
    cli_progress prog;
    double t0 = cli_now(), k_scene = NAN;
    tt_cantilever lever;
    if (tt_config_cantilever(scene, &lever) == TT_OK)
        k_scene = lever.k;
    cli_progress_begin(&prog, "tune", "drive periods", args.quiet);
    cli_catch_interrupt();
    int rc = tt_run_tune(scene, &t, &r, cli_progress_callback, &prog);
    cli_progress_end(&prog);
    if (rc == TT_OK)
        rc = write_csv(args.output, t);
    if (rc == TT_OK && args.plot)
        rc = r.modes > 1 ? plot_modes(args.plot, t, &r, &lever) : plot(args.plot, t, &r, k_scene);
    if (rc == TT_OK) {
        const double kT = 1.380649e-23 * r.temperature;
        /* what equipartition gives the record without the floor: each mode's kB T / k_n
         * through its chi_n^2 and its interpolation factor */
        double equi = kT / k_scene * r.noise_factor;
        for (int m = 0; r.modes > 1 && m < r.modes; m++) {
            const tt_tune_mode *md = &r.mode[m];
            equi = (m ? equi : 0) + md->chi * md->chi * kT / lever.mode_k[m] * md->noise_factor;
        }
        printf("temperature_K = %.6g\nsample_rate_Hz = %.6g\nbin_width_Hz = %.6g\nsegments = %ld\n"
               "averages = %.6g\nf0_Hz = %.8g\nf0_err_Hz = %.3g\nQ = %.6g\nQ_err = %.3g\n"
               "k_N_per_m = %.6g\nk_err_N_per_m = %.3g\nchi = %.6g\nfloor_m2_per_Hz = %.6g\n"
               "floor_err_m2_per_Hz = %.3g\nchi2_dof = %.4g\nvariance_m2 = %.6g\n"
               "variance_err_m2 = %.3g\nequipartition_m2 = %.6g\nnoise_factor = %.6g\n"
               "fit_low_Hz = %.6g\nfit_high_Hz = %.6g\n",
               r.temperature, r.fs, r.bin_width, r.segments, r.averages, r.f0, r.f0_err, r.Q, r.Q_err,
               r.k, r.k_err, r.chi, r.white, r.white_err, r.chi2_dof, r.variance, r.variance_err,
               equi, r.noise_factor, r.fit_low, r.fit_high);
        if (r.modes > 1)
            print_modes(&r, &lever);
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
