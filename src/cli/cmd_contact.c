/* tiptap contact: a contact-mechanics curve (Burnham et al.'s figure 3) and its summary. */
#include <float.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"
#include "tiptap/config/config.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/files.h"
#include "tiptap/io/plot.h"
#include "tiptap/run/run.h"

static void help(void)
{
    printf("Usage: tiptap contact --lambda L [--model maugis|hertz|dmt|jkr] [-o curve.csv]\n"
           "                      [--plot curve.png]\n"
           "       tiptap contact SCENE... [--set section.key=value]... [--material NAME]\n"
           "                      [-o curve.csv] [--plot curve.png]\n"
           "The normalised load-penetration curve of the Maugis-Dugdale contact (Burnham et al. eq. 7)\n"
           "or one of its limits, in Burnham et al.'s units (eq. 3: load / pi w R, penetration /\n"
           "(pi^2 w^2 R / K^2)^(1/3), contact radius / (pi w R^2 / K)^(1/3)).\n\n"
           "  -l, --lambda L     Maugis parameter (1e-4 to 1e4)\n"
           "  -m, --model M      maugis (default), hertz, dmt or jkr\n"
           "      --xi0 X        normalised interatomic distance for the van der Waals\n"
           "                     branch (default 0.3, at most 1e6)\n"
           "      --material NAME  the scene's material (default: the first)\n"
           "  -o, --output FILE  CSV with columns A,Delta,P,stable (stable = 1 on the\n"
           "                     displacement-controlled stable branch)\n"
           "      --plot FILE    PNG of P against Delta, with the van der Waals branch and\n"
           "                     the Hertz, DMT and JKR curves for reference\n\n"
           "stdout: key = value lines: lambda (\"inf (JKR limit)\" for jkr), P0 and Delta0\n"
           "(the A -> 0 end, eq. 8), pulloff_load (least load: pull-off under load control),\n"
           "jumpout_delta (least penetration on the stable branch: pull-off under\n"
           "displacement control), jumpin_load, hysteresis, loop_area; for a scene also\n"
           "physical values and the Hamaker constant implied by continuity at (P0, Delta0).\n"
           "stderr: run_time_s and error_estimate, the largest error of the tabulated load\n"
           "against eq. 7 evaluated directly at 2000 points of the stable branch.\n");
}

/* The curve's table (tt_run_contact_table: the A -> 0 end of an adhesive law first). */
static int write_csv(const char *path, const tt_contact *c, double Amax)
{
    tt_table *t;
    int rc = tt_run_contact_table(c, NULL, NAN, 600, Amax, &t);
    if (rc)
        return rc;
    tt_outfile *o;
    if ((rc = tt_outfile_open(&o, path))) {
        tt_table_free(t);
        return rc;
    }
    FILE *f = tt_outfile_stream(o);
    fprintf(f, "A,Delta,P,stable\n");
    const double *A = tt_table_numbers(t, 0), *D = tt_table_numbers(t, 1), *P = tt_table_numbers(t, 2),
                 *st = tt_table_numbers(t, 3);
    for (size_t i = 0; i < tt_table_rows(t); i++)
        fprintf(f, "%.10g,%.10g,%.10g,%d\n", A[i], D[i], P[i], (int)st[i]);
    tt_table_free(t);
    return tt_outfile_close(o, 1);
}

/* lambda as a person reads it: JKR's is infinite, which "inf" alone does not explain;
 * the number stays first, so "key = value" parsers still read it. */
static const char *lambda_text(double lambda, const char *fmt, char *buf, size_t n)
{
    if (isinf(lambda))
        return "inf (JKR limit)";
    snprintf(buf, n, fmt, lambda);
    return buf;
}

static int plot(const char *path, const tt_contact *c, double xi0n, int references)
{
    enum { N = 600 };
    static double A[N], D[N], P[N], Ds[N], Ps[N], Du[N], Pu[N];
    int st[N];
    const tt_contact_summary *s = tt_contact_summary_of(c);
    char title[160];
    snprintf(title, sizeof title, "Contact mechanics (Burnham et al.'s figure 3): %s",
             s->adhesive ? "Maugis-Dugdale" : "Hertz");
    char lt[32];
    if (s->adhesive)
        snprintf(title, sizeof title, "Contact mechanics (Burnham et al.'s figure 3), lambda = %s",
                 lambda_text(s->lambda, "%.4g", lt, sizeof lt));
    tt_figure *f = tt_figure_alloc(1, title);
    if (!f)
        return tt_error_nomem("the plot %s", path);
    tt_figure_axes(f, 0, "normalised penetration Delta", "normalised load P");
    int rc = tt_contact_curve(c, N, 2.2, A, D, P, st);
    for (int i = 0; i < N && rc == TT_OK; i++) {
        Ds[i] = st[i] ? D[i] : NAN;
        Ps[i] = st[i] ? P[i] : NAN;
        Du[i] = st[i] ? NAN : D[i];
        Pu[i] = st[i] ? NAN : P[i];
    }
    tt_figure_line(f, 0, Ds, Ps, N, "contact, stable branch", 1 | TT_PLOT_THICK);
    tt_figure_line(f, 0, Du, Pu, N, "contact, unstable branch", 1 | TT_PLOT_DASHED);
    if (s->adhesive && s->P0 != 0) {
        /* the van der Waals branch up to the junction (eq. 10) */
        double x[200], y[200];
        for (int i = 0; i < 200; i++) {
            x[i] = s->Delta0 - 2.5 + 2.5 * i / 199.0;
            y[i] = tt_contact_load(c, x[i] * s->depth_scale, 0, NULL, NULL) / s->force_scale;
        }
        tt_figure_line(f, 0, x, y, 200, "van der Waals (out of contact)", 2);
    }
    if (references) {
        static const tt_contact_model m[3] = {TT_CONTACT_HERTZ, TT_CONTACT_DMT, TT_CONTACT_JKR};
        static const char *lab[3] = {"Hertz", "DMT", "JKR"};
        for (int k = 0; k < 3; k++) {
            tt_contact *r;
            if (tt_contact_alloc_normalised(&r, m[k], 1, xi0n))
                continue;
            tt_contact_curve(r, N, 2.2, A, D, P, st);
            tt_figure_line(f, 0, D, P, N, lab[k], (unsigned)(3 + k) | TT_PLOT_DASHED);
            tt_contact_free(r);
        }
        tt_figure_vline(f, 0, -3 * pow(6, -2.0 / 3.0), "JKR pull-off, displacement control");
    }
    tt_figure_hline(f, 0, 0, NULL);
    tt_figure_xlim(f, 0, -2.5, 3.5);
    tt_figure_ylim(f, 0, -2.5, 3.5);
    if (rc == TT_OK)
        rc = tt_figure_write_png(f, path, 900, 700);
    tt_figure_free(f);
    return rc;
}

static void print_summary(const tt_contact *c, const tt_contact_params *phys, double Qi)
{
    const tt_contact_summary *s = tt_contact_summary_of(c);
    if (!s->adhesive) {
        printf("model = hertz\nadhesive = 0\nlambda = 0\n");
        if (phys) {
            /* the same physical keys as an adhesive contact's, so a script need not ask which */
            printf("reduced_modulus_Pa = %.10g\nradius_m = %.10g\nadhesion_energy_J_per_m2 = %.10g\n"
                   "hamaker_J = 0\nloop_energy_J = 0\n",
                   phys->K, phys->R, phys->w);
            if (isfinite(Qi))
                printf("interaction_quality_factor = %.10g\n", Qi);
        }
        return;
    }
    char lt[32];
    printf("lambda = %s\nP0 = %.10g\nDelta0 = %.10g\npulloff_load = %.10g\npulloff_delta = %.10g\n"
           "jumpout_delta = %.10g\njumpout_load = %.10g\njumpin_delta = %.10g\njumpin_load = %.10g\n"
           "hysteresis = %d\n",
           lambda_text(s->lambda, "%.10g", lt, sizeof lt), s->P0, s->Delta0, s->pulloff_load, s->pulloff_delta, s->jumpout_delta,
           s->jumpout_load, s->jumpin_delta, s->jumpin_load, s->hysteresis);
    if (!phys) {
        printf("loop_area = %.10g\n", s->loop_energy);
        return;
    }
    double F = s->force_scale, d = s->depth_scale;
    printf("loop_area = %.10g\n", s->loop_energy / (F * d));
    printf("reduced_modulus_Pa = %.10g\nradius_m = %.10g\nadhesion_energy_J_per_m2 = %.10g\n"
           "xi0_m = %.10g\nforce_scale_N = %.10g\ndepth_scale_m = %.10g\nradius_scale_m = %.10g\n"
           "P0_N = %.10g\ndelta0_m = %.10g\npulloff_load_N = %.10g\njumpout_delta_m = %.10g\n"
           "jumpin_load_N = %.10g\nhamaker_J = %.10g\nloop_energy_J = %.10g\n",
           phys->K, phys->R, phys->w, s->xi0, F, d, s->radius_scale, s->P0 * F, s->Delta0 * d,
           s->pulloff_load * F, s->jumpout_delta * d, s->jumpin_load * F, s->hamaker, s->loop_energy);
    if (isfinite(Qi))
        printf("interaction_quality_factor = %.10g\n", Qi);
}

int cmd_contact(int argc, char **argv)
{
    static const struct option opts[] = {{"lambda", required_argument, NULL, 'l'},
                                         {"model", required_argument, NULL, 'm'},
                                         {"xi0", required_argument, NULL, 'x'},
                                         {"material", required_argument, NULL, 'M'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"contact", CLI_OPT_OUTPUT | CLI_OPT_PLOT | CLI_OPT_SET, opts, "l:m:", help};
    cli_args args = {0};
    double lambda = NAN, xi0n = 0.3;
    const char *model = NULL, *material = NULL;
    int c;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        switch (c) {
        case 'l':
            /* the range of Maugis' tables (tt_contact_alloc_normalised) */
            if (cli_real("contact", "--lambda", optarg, 1e-4, 1e4, "a number from 1e-4 to 1e4", &lambda)) {
                cli_args_free(&args);
                return CLI_USAGE;
            }
            break;
        case 'x':
            if (cli_real("contact", "--xi0", optarg, DBL_MIN, TT_CONTACT_XI0N_MAX,
                         "a positive number up to 1e6", &xi0n)) {
                cli_args_free(&args);
                return CLI_USAGE;
            }
            break;
        case 'm': model = optarg; break;
        case 'M': material = optarg; break;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    int code;
    if ((code = cli_outputs_distinct(&spec, &args)) != CLI_OK) {
        cli_args_free(&args);
        return code;
    }
    const char *out = args.output, *plotpath = args.plot;
    tt_contact_model m = TT_CONTACT_MAUGIS;
    if (model && tt_contact_model_parse(model, &m) != 0) {
        cli_args_free(&args);
        fprintf(stderr, "tiptap contact: --model: '%s' is not one of maugis, hertz, dmt, jkr\n", model);
        return CLI_USAGE;
    }
    int have_scene = optind < argc;
    if (have_scene && isfinite(lambda)) {
        cli_args_free(&args);
        return cli_no_operands("contact", argc, argv, optind,
                               "--lambda draws the normalised curve, which takes no scene");
    }
    if (have_scene == isfinite(lambda) && !(model && !have_scene && m != TT_CONTACT_MAUGIS)) {
        cli_args_free(&args);
        fprintf(stderr, "tiptap contact: give either --lambda or a scene; see 'tiptap contact --help'\n");
        return CLI_USAGE;
    }
    double t0 = cli_now();
    tt_contact *ct = NULL;
    tt_scene *scene = NULL;
    tt_contact_params p;
    double Qi = NAN;
    int rc, reported = 0;
    if (have_scene) {
        scene = cli_load_scene(argv + optind, argc - optind, args.sets, args.nsets);
        cli_args_free(&args);
        if (!scene)
            return CLI_FAIL;
        /* an output that is the scene just read is refused before the summary */
        if ((code = cli_outputs_check(&spec, &args)) != CLI_OK) {
            rc = TT_EINVAL;
            reported = 1;
            goto done;
        }
        if ((rc = tt_run_contact_alloc(scene, material, model, &ct, &p, &Qi)))
            goto done;
        xi0n = tt_contact_summary_of(ct)->adhesive
                   ? tt_contact_summary_of(ct)->xi0 / tt_contact_summary_of(ct)->depth_scale
                   : 0.3;
    } else {
        cli_args_free(&args);
        if ((code = cli_outputs_check(&spec, &args)) != CLI_OK) {
            rc = TT_EINVAL;
            reported = 1;
            goto done;
        }
        if ((rc = tt_contact_alloc_normalised(&ct, m, isfinite(lambda) ? lambda : 1, xi0n)))
            goto done;
    }
    print_summary(ct, have_scene ? &p : NULL, Qi);
    cli_catch_interrupt(); /* the files are finished, not left half-written */
    if (out && (rc = write_csv(out, ct, 3.0)))
        goto done;
    if (plotpath && (rc = plot(plotpath, ct, xi0n, !have_scene)))
        goto done;
    /* the run's error estimate: its table checked against the curve itself */
    double terr = tt_contact_table_error(ct, 2000);
    fprintf(stderr, "run_time_s = %.3f\nerror_estimate = %.3g (largest error of the tabulated "
                    "load against eq. 7 at 2000 points of the stable branch, relative to "
                    "max(1, |P|))\n",
            cli_now() - t0, terr);
done:
    if (rc && !reported)
        cli_fail(rc, NULL);
    tt_contact_free(ct);
    tt_scene_free(scene);
    return rc ? CLI_FAIL : CLI_OK;
}
