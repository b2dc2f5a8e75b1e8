/* tiptap bench: speed and accuracy figures on the standard tapping scene. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
           "  --cycles N      cycles timed per setting (default 20000)\n"
           "  --imaging-lines N  lines of the imaging figure (default 4; 0: none)\n"
           "  --print-scene   print the standard scene and exit\n");
}

typedef struct {
    const char *label;
    tt_method method;
    double tol;
    int steps;
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

/* The imaging figure: the standard scene scanned closed-loop, 256 pixels per line at
 * 1 Hz with an 80 % setpoint; wall time per line and the real-time factor. */
static int bench_imaging(const tt_scene *scene, long lines)
{
    tt_scan_params p;
    int rc = tt_config_scan(scene, &p);
    if (rc)
        return rc;
    p.raster.size_x = p.raster.size_y = 1e-6;
    p.raster.pixels = 256;
    p.raster.lines = lines;
    p.raster.line_rate = 1;
    p.raster.retrace = 1;
    p.profile_line = -1;
    p.feedback.setpoint = 0.8 * p.cantilever.A0;
    tt_scan *scan = NULL;
    rc = tt_scan_alloc(&scan, &p);
    tt_config_scan_free(&p);
    double t0 = cli_now();
    if (!rc)
        rc = tt_scan_run(scan, 0, NULL, NULL);
    double wall = cli_now() - t0;
    if (!rc) {
        double inst = tt_scan_instrument_time(scan);
        printf("\n# imaging: standard scene, 1 um, 256 pixels per line, 1 Hz (trace + retrace), "
               "80 %% setpoint, %ld lines on all cores\n",
               lines);
        printf("wall_time_per_line_s = %.3f\ninstrument_time_per_line_s = %.3f\nreal_time_factor = %.3f\n"
               "cycles_per_second = %.0f\n",
               wall / (double)lines, inst / (double)lines, inst / wall, (double)tt_scan_cycles(scan) / wall);
    }
    tt_scan_free(scan);
    return rc;
}

int cmd_bench(int argc, char **argv)
{
    static const struct option opts[] = {{"cycles", required_argument, NULL, 'n'},
                                         {"print-scene", no_argument, NULL, 'p'},
                                         {"imaging-lines", required_argument, NULL, 'i'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"bench", 0, opts, "", help};
    cli_args args = {0}; /* no --set: nothing to free */
    long n = 20000, ilines = 4;
    int c;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        switch (c) {
        case 'n': n = atol(optarg); break;
        case 'i': ilines = atol(optarg); break;
        case 'p': fputs(tt_standard_scene(), stdout); return CLI_OK;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    if (n < 10) {
        fprintf(stderr, "tiptap bench: --cycles must be at least 10\n");
        return CLI_USAGE;
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
    static const setting settings[] = {
        {"reference dopri5 tol 1e-12", TT_METHOD_DOPRI5, 1e-12, 512},
        {"dopri5 tol 1e-6", TT_METHOD_DOPRI5, 1e-6, 512},
        {"dopri5 tol 1e-7", TT_METHOD_DOPRI5, 1e-7, 512},
        {"dopri5 tol 1e-8 (default)", TT_METHOD_DOPRI5, 1e-8, 512},
        {"rk4 128 steps", TT_METHOD_RK4, 1e-8, 128},
        {"rk4 512 steps", TT_METHOD_RK4, 1e-8, 512},
        {"radau tol 1e-6", TT_METHOD_RADAU, 1e-6, 512},
        {"radau tol 1e-8", TT_METHOD_RADAU, 1e-8, 512},
    };
    tt_cycle ref = {0};
    double rate, spc;
    printf("# standard tapping scene: 300 kHz, Q 400, 40 N/m, 20 nm free amplitude, 16 nm separation\n");
    printf("%-28s %12s %10s %12s %12s %12s\n", "setting", "cycles/s", "steps/cyc", "amp_rel_err",
           "phase_err_deg", "real_time_x");
    for (size_t i = 0; i < sizeof settings / sizeof settings[0]; i++) {
        tt_cycle cy;
        long cycles = i == 0 ? n / 4 : n;
        if ((rc = run(st, ap.from, &settings[i], cycles, &cy, &rate, &spc)))
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
    if (!rc && ilines > 0)
        rc = bench_imaging(scene, ilines);
    tt_setup_free(st);
    tt_scene_free(scene);
    return rc ? cli_fail(rc, NULL) : CLI_OK;
}
