/* tiptap bench: speed and accuracy figures on the standard tapping scene. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "tiptap/util/error.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/standard.h"

static void help(void)
{
    printf("Usage: tiptap bench [--cycles N] [--print-scene]\n"
           "Benchmark on the standard tapping scene (300 kHz, Q 400, 40 N/m, 20 nm free\n"
           "amplitude, polymer with adhesion, 16 nm rest separation).\n\n"
           "Prints, for each solver setting: simulated cantilever cycles per wall-clock\n"
           "second, and the error of the steady amplitude (relative) and phase (degrees)\n"
           "against a reference run at tolerance 1e-12. Figures are measured in this one\n"
           "run; compare them as ratios, since a shared machine is noisy.\n\n"
           "Then the imaging figure: two lines of 256 pixels at 1 Hz over a sample with\n"
           "height and material edges, for each setting the real-time factor on two\n"
           "threads, the speedup of -j 2 over -j 1, and the height and phase error against\n"
           "the every-cycle reference (dopri5 at tolerance 1e-10) on the same lines; the last\n"
           "row is the envelope tier ([solver] tier = envelope) at the default tolerance.\n\n"
           "  --cycles N      cycles timed per setting of the steady figure (10 to 1e9;\n"
           "                  default 5000)\n"
           "  --no-steady     skip the steady figure\n"
           "  --no-imaging    skip the imaging figure\n"
           "  --print-scene   print the standard scene and exit\n");
}

typedef struct {
    const char *label;
    tt_method method;
    double tol;
    int steps;
    tt_tier tier;
} setting;

/* Settle the standard scene's tapping point with a solver, then time n cycles. */
static int run(const tt_setup *st, double sep, const setting *s, long n, tt_cycle *out,
               double *rate, double *steps_per_cycle)
{
    tt_solver sv = *tt_setup_solver(st);
    sv.method = s->method;
    sv.tolerance = s->tol;
    sv.steps_per_cycle = s->steps;
    tt_sim *sim = NULL;
    int rc = tt_sim_alloc(&sim, tt_setup_cantilever(st), &sv);
    if (rc)
        return rc;
    tt_sim_set_contact(sim, tt_setup_contact(st, 0), tt_setup_material(st, 0)->Qi);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, sep, 0);
    int settled;
    long cyc;
    if ((rc = tt_sim_settle(sim, 40000, 1e-11, out, &settled, &cyc)))
        goto done;
    long steps = 0;
    double t0 = cli_now();
    for (long i = 0; i < n && rc == TT_OK; i++) {
        rc = tt_sim_cycle(sim, out);
        steps += out->steps;
    }
    double t = cli_now() - t0;
    *rate = (double)n / t;
    *steps_per_cycle = (double)steps / (double)n;
done:
    tt_sim_free(sim);
    return rc;
}

/* The edge sample of the imaging figure: the standard scene's polymer as a soft,
 * sticky, lossy matrix around stiff disks (a polymer blend: 500 nm lattice, 150 nm
 * radius), on 1 nm terraces every 250 nm; the two lines run through the disks' centres,
 * so each crosses four material edges and three height steps that do not coincide. */
static int edge_sample(const tt_scene *scene, tt_scan_params *p, tt_material mat[2])
{
    tt_tip tip;
    int rc;
    if ((rc = tt_config_scan(scene, p)) || (rc = tt_config_tip(scene, &tip)))
        return rc;
    mat[0] = p->materials[0];
    snprintf(mat[0].name, sizeof mat[0].name, "matrix");
    mat[1] = mat[0];
    snprintf(mat[1].name, sizeof mat[1].name, "disk");
    mat[1].contact.K = tt_material_reduced_modulus(&tip, 30e9, 0.3);
    mat[1].Qi = NAN;
    p->raster.size_x = p->raster.size_y = 1e-6;
    p->raster.pixels = 256;
    p->raster.lines = 2;
    p->raster.line_rate = 1;
    p->raster.retrace = 1;
    p->raster.fast_y = 0;
    p->profile_line = -1;
    p->channels = TT_CH_HEIGHT | TT_CH_PHASE;
    p->feedback.setpoint = 0.8 * p->cantilever.A0;
    p->surface.type = TT_SURFACE_STEPS;
    p->surface.step_height = 1e-9;
    p->surface.step_width = 250e-9;
    p->surface.map = TT_MAP_DISKS;
    p->surface.materials[0] = 0;
    p->surface.materials[1] = 1;
    p->surface.map_period = 500e-9;
    p->surface.map_radius = 150e-9;
    return TT_OK;
}

/* One imaging run: wall time on a number of threads, and the height (m) and phase (deg)
 * images of trace and retrace, [retrace][pixel of both lines]. */
typedef struct {
    double wall, cpu, inst, err_est, integrated; /* integrated: the share of cycles */
    tt_scan_error est; /* the companion's estimate, taken after the timing */
    double *img[2][2]; /* [height, phase][trace, retrace] */
} imaging_run;

/* One scan on a number of threads, its wall and CPU times; the caller frees *scan. */
static int timed_scan(const tt_scan_params *p, int threads, tt_scan **scan, double *wall, double *cpu)
{
    *scan = NULL;
    int rc = tt_scan_alloc(scan, p);
    double t0 = cli_now();
    clock_t c0 = clock();
    if (!rc)
        rc = tt_scan_run(*scan, threads, NULL, NULL);
    *wall = cli_now() - t0;
    *cpu = (double)(clock() - c0) / CLOCKS_PER_SEC;
    return rc;
}

static int imaging_once(const tt_scan_params *p, int threads, int estimate, imaging_run *out)
{
    tt_scan *scan;
    int rc = timed_scan(p, threads, &scan, &out->wall, &out->cpu);
    if (!rc) {
        size_t n = (size_t)(p->raster.pixels * p->raster.lines);
        out->inst = tt_scan_instrument_time(scan);
        out->err_est = tt_scan_error_estimate(scan);
        out->integrated = (double)tt_scan_cycles_integrated(scan) / (double)tt_scan_cycles(scan);
        if (estimate)
            rc = tt_scan_estimate_error(scan, &out->est);
        for (int c = 0; c < 2 && !rc; c++)
            for (int r = 0; r < 2 && !rc; r++) {
                out->img[c][r] = malloc(n * sizeof(double));
                if (!out->img[c][r])
                    rc = tt_error_nomem("the imaging figure's images");
                else
                    memcpy(out->img[c][r], tt_scan_image(scan, c ? 2 : 0, r), n * sizeof(double));
            }
    }
    tt_scan_free(scan);
    return rc;
}

/* A run shorter than a second is timed again, up to five runs, keeping the best wall
 * and CPU times: a fifth of a second is at the mercy of one burst of load. */
static int imaging_timed(const tt_scan_params *p, int threads, int estimate, imaging_run *out)
{
    int rc = imaging_once(p, threads, estimate, out);
    for (int k = 1; k < 5 && !rc && out->wall < 1.0; k++) {
        tt_scan *scan;
        double wall, cpu;
        rc = timed_scan(p, threads, &scan, &wall, &cpu);
        out->wall = fmin(out->wall, wall);
        out->cpu = fmin(out->cpu, cpu);
        tt_scan_free(scan);
    }
    return rc;
}

static void imaging_free(imaging_run *r)
{
    for (int c = 0; c < 2; c++)
        for (int k = 0; k < 2; k++)
            free(r->img[c][k]);
    memset(r, 0, sizeof *r);
}

/* Largest and rms difference of channel c between a run and the reference. */
static void image_error(const imaging_run *a, const imaging_run *ref, int c, size_t n, double *max,
                        double *rms)
{
    double m = 0, s = 0;
    for (int r = 0; r < 2; r++)
        for (size_t i = 0; i < n; i++) {
            double e = fabs(a->img[c][r][i] - ref->img[c][r][i]);
            if (e > m)
                m = e;
            s += e * e;
        }
    *max = m;
    *rms = sqrt(s / (double)(2 * n));
}

/* The run's own error estimate (tt_scan_estimate_error, a companion line) against the
 * error measured against the reference, per setting: [h rms, h max, ph rms, ph max]. */
static void print_estimates(const setting *set, size_t nset, double (*est)[4], double (*meas)[4])
{
    printf("\n# error estimate (a companion run of one line at a 100x tighter setting) against the "
           "measured error\n");
    printf("%-28s %11s %11s %11s %11s %11s %11s %11s %11s\n", "setting", "h_rms_est", "h_rms_meas",
           "h_max_est", "h_max_meas", "ph_rms_est", "ph_rms_meas", "ph_max_est", "ph_max_meas");
    for (size_t i = 1; i < nset; i++)
        printf("%-28s %11.3g %11.3g %11.3g %11.3g %11.3g %11.3g %11.3g %11.3g\n", set[i].label,
               est[i][0] * 1e12, meas[i][0] * 1e12, est[i][1] * 1e12, meas[i][1] * 1e12, est[i][2],
               meas[i][2], est[i][3], meas[i][3]);
    printf("# heights in pm, phases in deg; the estimate is never to be below the measured error\n");
}

/* The imaging figure: for each solver setting, the real-time factor of the edge
 * sample's lines on two threads and the speedup over one, and the height and phase
 * error against the every-cycle reference at a tight tolerance on the same lines. */
static int bench_imaging(const tt_scene *scene, const setting *set, size_t nset)
{
    tt_scan_params p;
    tt_material mat[2];
    int rc = edge_sample(scene, &p, mat);
    if (rc)
        return rc;
    const tt_material *own = p.materials;
    p.materials = mat;
    p.nmaterials = 2;
    size_t n = (size_t)(p.raster.pixels * p.raster.lines);
    printf("\n# imaging: standard cantilever over a polymer blend (soft sticky matrix, stiff disks) "
           "on 1 nm steps;\n# 1 um, %ld lines of %ld pixels at %.0f Hz (trace + retrace), "
           "80 %% setpoint; errors against the reference\n",
           p.raster.lines, p.raster.pixels, p.raster.line_rate);
    printf("%-28s %8s %8s %8s %8s %8s %10s %10s %10s %10s %10s %9s\n", "setting", "wall_j1", "wall_j2",
           "j2/j1", "rtf_j2", "rtf_cpu", "h_max_pm", "h_rms_pm", "ph_max_deg", "ph_rms_deg", "energy_bal",
           "integr_%");
    imaging_run ref = {0};
    double est[8][4] = {{0}}, meas[8][4] = {{0}};
    for (size_t i = 0; i < nset && !rc; i++) {
        p.solver.method = set[i].method;
        p.solver.tolerance = set[i].tol;
        p.solver.steps_per_cycle = set[i].steps;
        p.solver.tier = set[i].tier;
        imaging_run r1 = {0}, r2 = {0};
        if (i > 0)
            rc = imaging_timed(&p, 1, 0, &r1);
        if (!rc)
            rc = imaging_timed(&p, 2, i > 0, &r2);
        if (!rc) {
            if (i == 0) {
                ref = r2;
                memset(&r2, 0, sizeof r2);
                printf("%-28s %8s %8.2f %8s %8.3f %8.3f %10s %10s %10s %10s %10.1e %9.1f\n",
                       set[i].label, "-", ref.wall, "-", ref.inst / ref.wall, 2 * ref.inst / ref.cpu, "-",
                       "-", "-", "-", ref.err_est, 100 * ref.integrated);
            } else {
                double hm, hr, pm, pr;
                image_error(&r2, &ref, 0, n, &hm, &hr);
                image_error(&r2, &ref, 1, n, &pm, &pr);
                if (i < 8) {
                    double e[4] = {r2.est.height_rms, r2.est.height_max, r2.est.phase_rms, r2.est.phase_max};
                    double m[4] = {hr, hm, pr, pm};
                    memcpy(est[i], e, sizeof e);
                    memcpy(meas[i], m, sizeof m);
                }
                printf("%-28s %8.2f %8.2f %8.2f %8.3f %8.3f %10.3g %10.3g %10.3g %10.3g %10.1e %9.1f\n",
                       set[i].label, r1.wall, r2.wall, r1.wall / r2.wall, r2.inst / r2.wall,
                       2 * r2.inst / r2.cpu, hm * 1e12, hr * 1e12, pm, pr, r2.err_est,
                       100 * r2.integrated);
            }
            fflush(stdout);
        }
        imaging_free(&r1);
        imaging_free(&r2);
    }
    imaging_free(&ref);
    p.materials = own;
    tt_config_scan_free(&p);
    if (!rc)
        printf("# runs under a second: the best of five\n"
               "# rtf_j2: instrument time / wall time on two threads (10 is the goal); rtf_cpu: the\n"
               "# same from the CPU time, what two idle cores give (a shared machine's wall time is\n"
               "# not); energy_bal: the energy-balance check (largest residual / free drive work);\n"
               "# integr_%%: the share of the cycles integrated (the envelope tier skips the rest)\n");
    if (!rc)
        print_estimates(set, nset < 8 ? nset : 8, est, meas);
    return rc;
}

/* The steady figure: each setting's cycles per second at the standard scene's tapping
 * point and its steady amplitude and phase against a reference at tolerance 1e-12. */
static int bench_steady(const tt_setup *st, const tt_approach_params *ap, long n)
{
    static const setting settings[] = {
        {"reference dopri5 tol 1e-12", TT_METHOD_DOPRI5, 1e-12, 512, TT_TIER_EVERY},
        {"dopri5 tol 1e-6", TT_METHOD_DOPRI5, 1e-6, 512, TT_TIER_EVERY},
        {"dopri5 tol 1e-7", TT_METHOD_DOPRI5, 1e-7, 512, TT_TIER_EVERY},
        {"dopri5 tol 1e-8 (default)", TT_METHOD_DOPRI5, 1e-8, 512, TT_TIER_EVERY},
        {"rk4 128 steps", TT_METHOD_RK4, 1e-8, 128, TT_TIER_EVERY},
        {"rk4 512 steps", TT_METHOD_RK4, 1e-8, 512, TT_TIER_EVERY},
        {"radau tol 1e-6", TT_METHOD_RADAU, 1e-6, 512, TT_TIER_EVERY},
        {"radau tol 1e-8", TT_METHOD_RADAU, 1e-8, 512, TT_TIER_EVERY},
    };
    int rc = TT_OK;
    tt_cycle ref = {0};
    double rate, spc;
    printf("# standard tapping scene: 300 kHz, Q 400, 40 N/m, 20 nm free amplitude, 16 nm separation\n");
    printf("%-28s %12s %10s %12s %12s %12s\n", "setting", "cycles/s", "steps/cyc", "amp_rel_err",
           "phase_err_deg", "real_time_x");
    for (size_t i = 0; i < sizeof settings / sizeof settings[0]; i++) {
        tt_cycle cy;
        long cycles = i == 0 ? n / 4 : n;
        if ((rc = run(st, ap->from, &settings[i], cycles, &cy, &rate, &spc)))
            break;
        if (i == 0)
            ref = cy;
        double ea = fabs(cy.amplitude - ref.amplitude) / ref.amplitude;
        double ep = fabs(cy.phase - ref.phase) * 180 / M_PI;
        printf("%-28s %12.0f %10.1f %12.2e %12.2e %12.3f\n", settings[i].label, rate, spc, ea, ep,
               rate / 300e3);
        fflush(stdout);
    }
    printf("# reference: amplitude %.6f nm, phase %.6f deg, peak force %.4f nN, "
           "tip-sample loss %.4f aJ per cycle\n",
           ref.amplitude * 1e9, ref.phase * 180 / M_PI, ref.peak_force * 1e9, ref.e_ts * 1e18);
    printf("# real_time_x: simulated time / wall time for one cantilever on one core "
           "(1 = as fast as the instrument)\n");
    return rc;
}

int cmd_bench(int argc, char **argv)
{
    static const struct option opts[] = {{"cycles", required_argument, NULL, 'n'},
                                         {"print-scene", no_argument, NULL, 'p'},
                                         {"no-steady", no_argument, NULL, 's'},
                                         {"no-imaging", no_argument, NULL, 'i'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"bench", 0, opts, "", help};
    cli_args args = {0}; /* no --set: nothing to free */
    long n = 5000;
    int steady = 1, imaging = 1, print_scene = 0;
    int c;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        switch (c) {
        case 'n':
            if (cli_whole("bench", "--cycles", optarg, 10, 1000000000L, NULL, &n))
                return CLI_USAGE;
            break;
        case 's': steady = 0; break;
        case 'i': imaging = 0; break;
        case 'p': print_scene = 1; break;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    if (cli_no_operands("bench", argc, argv, optind, "it runs the built-in standard scene"))
        return CLI_USAGE;
    if (print_scene) {
        fputs(tt_standard_scene(), stdout);
        return CLI_OK;
    }
    tt_scene *scene = tt_scene_alloc();
    tt_setup *st = NULL;
    tt_approach_params ap;
    int rc = scene ? tt_scene_load_string(scene, tt_standard_scene(), "standard scene") : TT_ENOMEM;
    if (!rc && !(rc = tt_setup_alloc(&st, scene)))
        rc = tt_config_approach(scene, &ap);
    if (rc) {
        tt_setup_free(st);
        tt_scene_free(scene);
        return cli_fail(rc, NULL);
    }
    if (steady)
        rc = bench_steady(st, &ap, n);
    if (!rc && imaging) {
        static const setting imaging_settings[] = {
            {"reference dopri5 tol 1e-10", TT_METHOD_DOPRI5, 1e-10, 512, TT_TIER_EVERY},
            {"dopri5 tol 1e-6", TT_METHOD_DOPRI5, 1e-6, 512, TT_TIER_EVERY},
            {"dopri5 tol 1e-7", TT_METHOD_DOPRI5, 1e-7, 512, TT_TIER_EVERY},
            {"dopri5 tol 1e-8", TT_METHOD_DOPRI5, 1e-8, 512, TT_TIER_EVERY},
            {"envelope dopri5 tol 1e-8", TT_METHOD_DOPRI5, 1e-8, 512, TT_TIER_ENVELOPE},
        };
        rc = bench_imaging(scene, imaging_settings, sizeof imaging_settings / sizeof imaging_settings[0]);
    }
    tt_setup_free(st);
    tt_scene_free(scene);
    return rc ? cli_fail(rc, NULL) : CLI_OK;
}
