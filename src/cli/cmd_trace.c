/* tiptap trace: a time series of the tapping cantilever, with an optional ramp of one
 * scene key over the run (seed figures 4b to 8). */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/physics/material.h"
#include "tiptap/config/setup.h"

static void help(void)
{
    printf("Usage: tiptap trace SCENE... [--set section.key=value]... [-o trace.csv]\n"
           "                     [--plot trace.png] [-q]\n"
           "Time series of the scene's [trace] section (seed figures 4b, 5 to 8).\n\n"
           "  -o, --output FILE  CSV, samples_per_cycle rows per cycle: t_us, base_nm, tip_nm,\n"
           "                     sample_nm, deflection_nm, force_nN, contact_radius_nm,\n"
           "                     pressure_GPa (Hertzian K a / pi R, as in the seed), contact,\n"
           "                     and the ramped key's value when [trace] ramp is set\n"
           "      --plot FILE    PNG: positions and deflection; force and pressure\n"
           "      --set S.K=V    override a scene key (material.NAME.key for named sections)\n"
           "  -q, --quiet        no summary on stderr\n\n"
           "Positions are along the axis into the sample, the base at rest at 0; the\n"
           "deflection is tip - base, what a beam-deflection detector measures.\n"
           "stderr ends with the run time and the error estimate: the largest energy-balance\n"
           "residual of a cycle relative to the free drive work per cycle, pi c w A0^2 (zero\n"
           "for the exact solution).\n");
}

typedef struct {
    double *t, *z, *d, *s, *y, *F, *p;
    size_t n, cap;
} series;

static int series_push(series *S, double t, double z, double d, double s, double F, double p)
{
    if (S->n == S->cap) {
        size_t cap = S->cap ? 2 * S->cap : 4096;
        double **arr[] = {&S->t, &S->z, &S->d, &S->s, &S->y, &S->F, &S->p};
        for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
            double *nw = realloc(*arr[i], cap * sizeof **arr[i]);
            if (!nw)
                return tt_error(TT_ENOMEM, "out of memory");
            *arr[i] = nw;
        }
        S->cap = cap;
    }
    S->t[S->n] = t * 1e6;
    S->z[S->n] = z * 1e9;
    S->d[S->n] = d * 1e9;
    S->s[S->n] = s * 1e9;
    S->y[S->n] = (d - z) * 1e9;
    S->F[S->n] = F * 1e9;
    S->p[S->n] = p * 1e-9;
    S->n++;
    return TT_OK;
}

static void series_free(series *S)
{
    free(S->t);
    free(S->z);
    free(S->d);
    free(S->s);
    free(S->y);
    free(S->F);
    free(S->p);
}

static int plot(const char *path, const series *S, const char *ramp)
{
    char title[256];
    snprintf(title, sizeof title, "Trace%s%s", ramp ? ": ramp of " : "", ramp ? ramp : "");
    tt_figure *f = tt_figure_alloc(2, title);
    if (!f)
        return tt_error(TT_ENOMEM, "out of memory");
    tt_figure_axes(f, 0, "time (us)", "position (nm)");
    tt_figure_line(f, 0, S->t, S->z, S->n, "base", 1);
    tt_figure_line(f, 0, S->t, S->d, S->n, "tip", 2);
    tt_figure_line(f, 0, S->t, S->s, S->n, "sample surface", 3 | TT_PLOT_DASHED);
    tt_figure_line(f, 0, S->t, S->y, S->n, "deflection (tip - base)", 4);
    tt_figure_axes(f, 1, "time (us)", "tip-sample force (nN)");
    tt_figure_axis_right(f, 1, "Hertzian pressure K a / pi R (GPa)");
    tt_figure_line(f, 1, S->t, S->F, S->n, "force", 1);
    tt_figure_line(f, 1, S->t, S->p, S->n, "pressure", 2 | TT_PLOT_RIGHT);
    int rc = tt_figure_write_png(f, path, 1000, 800);
    tt_figure_free(f);
    return rc;
}

int cmd_trace(int argc, char **argv)
{
    static const struct option opts[] = {{"output", required_argument, NULL, 'o'},
                                         {"plot", required_argument, NULL, 'p'},
                                         {"set", required_argument, NULL, 's'},
                                         {"quiet", no_argument, NULL, 'q'},
                                         {"help", no_argument, NULL, 'h'},
                                         {NULL, 0, NULL, 0}};
    const char *out = "trace.csv", *plotpath = NULL;
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
    tt_scene *scene = cli_scene_args("trace", argc, argv, optind, sets, nsets, &code);
    if (!scene)
        return code;
    double t0 = cli_now();
    tt_setup *st = NULL;
    tt_outfile *of = NULL;
    tt_sample *smp = NULL;
    series S = {0};
    size_t mat = 0;
    long cycles = 0, settle = 0, nsamp = 0, done_cycles = 0;
    double sep = 0, sep_end = 0, worst = 0, ramp_from = 0, ramp_to = 0;
    const char *ramp = tt_scene_get_string(scene, "trace", NULL, "ramp");
    int rc;
    if ((rc = tt_setup_alloc(&st, scene)) ||
        (rc = tt_setup_find_material(st, tt_scene_get_string(scene, "trace", NULL, "material"),
                                     "trace", "material", &mat)) ||
        (rc = tt_setup_use_material(st, mat)) ||
        (rc = tt_scene_get_double(scene, "trace", NULL, "separation", &sep)) ||
        (rc = tt_scene_get_int(scene, "trace", NULL, "cycles", &cycles)) ||
        (rc = tt_scene_get_int(scene, "trace", NULL, "settle_cycles", &settle)) ||
        (rc = tt_scene_get_int(scene, "trace", NULL, "samples_per_cycle", &nsamp)))
        goto done;
    sep_end = sep;
    if (tt_scene_has(scene, "trace", NULL, "separation_end") &&
        (rc = tt_scene_get_double(scene, "trace", NULL, "separation_end", &sep_end)))
        goto done;
    if (ramp) {
        const char *from = tt_scene_get_string(scene, "trace", NULL, "ramp_from");
        const char *to = tt_scene_get_string(scene, "trace", NULL, "ramp_to");
        if (!from || !to) {
            rc = tt_scene_fail(scene, "trace", NULL, from ? "ramp_to" : "ramp_from",
                               "missing; a ramp needs ramp_from and ramp_to");
            goto done;
        }
        if (tt_setup_parse_key_value(st, ramp, from, &ramp_from) ||
            tt_setup_parse_key_value(st, ramp, to, &ramp_to)) {
            rc = tt_scene_fail(scene, "trace", NULL, "ramp", "%s", tt_error_message());
            goto done;
        }
        if ((rc = tt_setup_apply(st, ramp, ramp_from))) {
            rc = tt_scene_fail(scene, "trace", NULL, "ramp", "%s", tt_error_message());
            goto done;
        }
    }
    smp = calloc((size_t)nsamp, sizeof *smp);
    if (!smp) {
        rc = tt_error(TT_ENOMEM, "out of memory");
        goto done;
    }
    if ((rc = tt_outfile_open(&of, out)))
        goto done;
    FILE *f = tt_outfile_stream(of);
    fprintf(f, "t_us,base_nm,tip_nm,sample_nm,deflection_nm,force_nN,contact_radius_nm,pressure_GPa,"
               "contact%s%s\n",
            ramp ? "," : "", ramp ? ramp : "");
    const tt_cantilever *cant = tt_setup_cantilever(st);
    tt_sim *sim = tt_setup_sim(st);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, sep, 0);
    tt_cycle cy;
    for (long i = 0; i < settle && rc == TT_OK; i++)
        rc = tt_sim_cycle(sim, &cy);
    if (rc)
        goto done;
    cli_catch_interrupt();
    tt_sim_set_sampling(sim, (int)nsamp, smp);
    double sdot = (sep_end - sep) / ((double)cycles * cant->T);
    for (long i = 0; i < cycles; i++) {
        if (tt_cancel_requested()) {
            rc = tt_error(TT_EINTR, "interrupted: %s keeps the %ld cycles finished", out, done_cycles);
            break;
        }
        double rv = 0;
        if (ramp) {
            rv = cycles > 1 ? ramp_from + (ramp_to - ramp_from) * (double)i / (double)(cycles - 1) : ramp_from;
            if ((rc = tt_setup_apply(st, ramp, rv)))
                break;
        }
        tt_sim_set_sample(sim, sep + sdot * (double)i * cant->T, sdot);
        if ((rc = tt_sim_cycle(sim, &cy)))
            break;
        double rel = cy.residual_rel;
        if (rel > worst)
            worst = rel;
        /* pressure: the seed's instantaneous Hertzian pressure K a / (pi R) */
        const tt_contact_params *cp = &tt_setup_material(st, mat)->contact;
        double K = cp->K, R = cp->R;
        for (long k = 0; k < nsamp; k++) {
            double a = 0;
            double F = tt_sim_force(sim, &smp[k], &a);
            double p = smp[k].contact ? K * a / (M_PI * R) : 0;
            fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d", smp[k].t * 1e6, smp[k].z * 1e9,
                    smp[k].d * 1e9, smp[k].s * 1e9, (smp[k].d - smp[k].z) * 1e9, F * 1e9, a * 1e9,
                    p * 1e-9, smp[k].contact);
            if (ramp)
                fprintf(f, ",%.9g", rv);
            fputc('\n', f);
            if (plotpath && (rc = series_push(&S, smp[k].t, smp[k].z, smp[k].d, smp[k].s, F, p)))
                break;
        }
        if (rc)
            break;
        done_cycles++;
    }
    {
        int crc = tt_outfile_close(of, done_cycles > 0);
        of = NULL;
        if (!rc)
            rc = crc;
    }
    if (plotpath && S.n > 0) {
        int prc = plot(plotpath, &S, ramp);
        if (!rc)
            rc = prc;
    }
    if (!quiet)
        fprintf(stderr, "cycles = %ld\nrun_time_s = %.3f\nerror_estimate = %.3g (largest energy-balance "
                        "residual of a cycle / free drive work per cycle)\n",
                done_cycles, cli_now() - t0, worst);
done:
    if (of)
        tt_outfile_close(of, 0);
    if (rc)
        cli_fail(rc, NULL);
    series_free(&S);
    free(smp);
    tt_setup_free(st);
    tt_scene_free(scene);
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}
