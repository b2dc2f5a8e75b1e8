/* tiptap bench: speed and accuracy figures on the standard tapping scene. */
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "commands.h"
#include "tiptap/util/error.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/standard.h"

static void help(void)
{
    printf("Usage: tiptap bench [--cycles N] [--seeds N] [--quick] [--no-steady] [--no-imaging]\n"
           "                    [--no-noise] [--no-scenes] [--no-lesson] [--lesson-only]\n"
           "                    [--lesson-lines N] [--lesson-setting N] [--lesson-tier TIER]\n"
           "                    [--print-scene]\n"
           "                    [--print-blend-scene]\n"
           "Benchmark on the standard tapping scene (300 kHz, Q 400, 40 N/m, 20 nm free\n"
           "amplitude, polymer with adhesion, 16 nm rest separation).\n\n"
           "Prints, for each solver setting: simulated cantilever cycles per wall-clock\n"
           "second, and the error of the steady amplitude (relative) and phase (degrees)\n"
           "against a reference run at tolerance 1e-12. Figures are measured in this one\n"
           "run; compare them as ratios, since a shared machine is noisy.\n\n"
           "Then the imaging figure: two lines of 256 pixels at 1 Hz over a sample with\n"
           "height and material edges, for each setting the real-time factor on two\n"
           "threads (from the wall and from the CPU time), the speedup of -j 2 over -j 1,\n"
           "the height and phase error against the every-cycle reference (dopri5 at\n"
           "tolerance 1e-10) on the same lines and the share of cycles integrated; the last\n"
           "rows are the envelope tier ([solver] tier = envelope) and the averaged tier\n"
           "(tier = averaged; 'not available' where this build lacks it) at the default\n"
           "tolerance.\n\n"
           "The noise figure: the same lines with the full noise set (300 K, detector\n"
           "100 fm/sqrt(Hz), z piezo 0.3 pm/sqrt(Hz)) and with detector noise alone, on the\n"
           "every-cycle tier and the default tier over several seeds: per line, the sd and\n"
           "the mean of each image's difference from the noise-free reference, with their\n"
           "standard errors, and the default tier's sd over every cycle's. Then the error\n"
           "estimate with noise: 300 K and detector noise on the default tier at 1e-8, seeds\n"
           "1 to 3 at most, against the same lines, tier and seed at 1e-11 (BELOW where its\n"
           "max lies under the measured: with noise it may, docs/dynamics.md).\n\n"
           "The scene figures: two lines of the README's main job (scans/quick.ini with\n"
           "surfaces/polymer-blend.ini, 64 pixels at 4 Hz) and of the standard scene at\n"
           "Q 1e4 (examples/extreme/vacuum-q1e4.ini; 0.5 nm steps, 256 pixels at 1 Hz),\n"
           "every cycle at tolerance 1e-8 and the default tier against the every-cycle\n"
           "reference.\n\n"
           "The lesson figure: the teaching scene of examples/feedback-tuning (scans/standard.ini,\n"
           "surfaces/grating.ini, common.ini: 64 pixels at 2 Hz, thermal and detector noise)\n"
           "at each lesson setting (ki 100 Hz, 1.18, 4, 10 and 30 kHz; P 5; 40 Hz lines), its\n"
           "lines stepped one at a time on one thread as tiptap live's engine steps them\n"
           "(tt_scan_step; tiptap scan runs the same line code): per setting the default\n"
           "tier's real time per CPU second (median over the lines after the first), its share\n"
           "of cycles integrated, the every-cycle tier's real time on the same lines, and the\n"
           "height and phase difference between the two; then why the envelope tier\n"
           "integrated its cycles (its controller's counts per line).\n\n"
           "  --cycles N      cycles timed per setting of the steady figure (10 to 1e9;\n"
           "                  default 5000, 200 with --quick)\n"
           "  --seeds N       noise seeds of the noise figure (1 to 100; default 3)\n"
           "  --quick         every imaging figure on lines of 16 pixels at 32 Hz, each run\n"
           "                  once, 2 seeds: a check that the figures come out, not a\n"
           "                  benchmark\n"
           "  --no-steady     skip the steady figure\n"
           "  --no-imaging    skip the imaging figure (but its reference, when the noise\n"
           "                  figure needs it)\n"
           "  --no-noise      skip the noise figure\n"
           "  --no-scenes     skip the scene figures (README main job, Q 1e4)\n"
           "  --no-lesson     skip the lesson figure\n"
           "  --lesson-only   the lesson figure alone\n"
           "  --lesson-lines N\n"
           "                  lines per lesson setting (2 to 64; default 7, 2 with --quick,\n"
           "                  which runs only the 40 Hz lines' setting)\n"
           "  --lesson-setting N\n"
           "                  the lesson figure's Nth setting alone (1 to 7, in the order\n"
           "                  above: a figure a loaded machine can finish)\n"           "  --lesson-tier TIER\n"
           "                  the lesson figure on envelope or averaged instead of the default\n"
           "                  tier, with that tier's own error besides (cold_h_nm, cold_ph_deg:\n"
           "                  both tiers again with the noise's powers 1e9 times lower)\n"
           "  --print-scene   print the standard scene and exit\n"
           "  --print-blend-scene\n"
           "                  print the README main job's scene and exit\n");
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

/* The imaging figures after the steady one: the edge sample's settings, its noise
 * figure, and two lines of the README's main job and of the Q 1e4 scene. */
static int bench_images(const tt_scene *scene, const bench_lines *lines, int imaging, int noise,
                        int scenes, int seeds)
{
    static const bench_row edge_rows[] = {
        {"reference dopri5 tol 1e-10", {"solver.tier=every", "solver.method=dopri5", "solver.tolerance=1e-10"}, 0},
        {"dopri5 tol 1e-6", {"solver.tier=every", "solver.method=dopri5", "solver.tolerance=1e-6"}, 0},
        {"dopri5 tol 1e-7", {"solver.tier=every", "solver.method=dopri5", "solver.tolerance=1e-7"}, 0},
        {"dopri5 tol 1e-8", {"solver.tier=every", "solver.method=dopri5", "solver.tolerance=1e-8"}, 0},
        {"envelope dopri5 tol 1e-8", {"solver.tier=envelope", "solver.method=dopri5", "solver.tolerance=1e-8"}, 0},
        /* refused by a build without the averaged tier: a row that says so */
        {"averaged dopri5 tol 1e-8", {"solver.tier=averaged", "solver.method=dopri5", "solver.tolerance=1e-8"}, 1},
    };
    char deflabel[48];
    snprintf(deflabel, sizeof deflabel, "%s (default) tol 1e-8", bench_default_tier());
    char quicklabel[64];
    snprintf(quicklabel, sizeof quicklabel, "%s tol 3e-8 (the scene's)", bench_default_tier());
    /* the blend's scene (scans/quick.ini) sets 3e-8, a quick look: its rows name their
     * tolerance, the scene's last */
    const bench_row scene_rows[] = {
        {"reference dopri5 tol 1e-10", {"solver.tier=every", "solver.tolerance=1e-10"}, 0},
        {"every cycle dopri5 tol 1e-8", {"solver.tier=every", "solver.tolerance=1e-8"}, 0},
        {deflabel, {"solver.tolerance=1e-8"}, 0},
        {quicklabel, {NULL}, 0},
    };
    bench_sample edge = {"imaging: standard cantilever over a polymer blend (soft sticky matrix, stiff "
                         "disks) on 1 nm steps",
                         scene, {NULL}, *lines, bench_edge_sample};
    int rc = TT_OK;
    if (imaging || noise) {
        bench_run ref = {0};
        size_t n = imaging ? sizeof edge_rows / sizeof edge_rows[0] : 1;
        rc = bench_imaging_figure(&edge, edge_rows, n, lines->repeat, &ref); /* --quick: no -j 1 */
        if (!rc && noise)
            rc = bench_noise_figure(&edge, &ref, seeds);
        if (!rc && noise)
            rc = bench_noise_estimate(&edge, seeds);
        bench_run_free(&ref);
    }
    if (rc || !scenes)
        return rc;
    tt_scene *blend = tt_scene_alloc();
    rc = blend ? tt_scene_load_string(blend, bench_blend_scene(), "README main job (bench)")
               : tt_error_nomem("the bench's blend scene");
    bench_sample job = {"the README's main job: scans/quick.ini + surfaces/polymer-blend.ini (flat "
                        "polymer blend), two lines through the disks' centres",
                        blend, {NULL}, *lines, bench_plain_sample};
    bench_sample vac = {"Q 1e4: the standard scene in vacuum (examples/extreme/vacuum-q1e4.ini), "
                        "integral gain 30 Hz, 20000 settling cycles, 0.5 nm steps every 300 nm",
                        scene,
                        {"cantilever.quality_factor=1e4", "feedback.integral_gain=30 Hz",
                         "scan.settle_cycles=20000", "surface.type=steps", "surface.step_height=0.5 nm",
                         "surface.step_width=300 nm", "scan.pixels=256", "scan.line_rate=1 Hz", NULL},
                        *lines, bench_plain_sample};
    if (!rc)
        rc = bench_imaging_figure(&job, scene_rows, 4, 0, NULL);
    if (!rc)
        rc = bench_imaging_figure(&vac, scene_rows, 3, 0, NULL);
    tt_scene_free(blend);
    return rc;
}

int cmd_bench(int argc, char **argv)
{
    static const struct option opts[] = {{"cycles", required_argument, NULL, 'n'},
                                         {"seeds", required_argument, NULL, 'S'},
                                         {"quick", no_argument, NULL, 'Q'},
                                         {"print-scene", no_argument, NULL, 'p'},
                                         {"print-blend-scene", no_argument, NULL, 'b'},
                                         {"no-steady", no_argument, NULL, 's'},
                                         {"no-imaging", no_argument, NULL, 'i'},
                                         {"no-noise", no_argument, NULL, 'N'},
                                         {"no-scenes", no_argument, NULL, 'e'},
                                         {"no-lesson", no_argument, NULL, 'l'},
                                         {"lesson-only", no_argument, NULL, 'L'},
                                         {"lesson-lines", required_argument, NULL, 'm'},
                                         {"lesson-setting", required_argument, NULL, 'g'},
                                         {"lesson-tier", required_argument, NULL, 't'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"bench", 0, opts, "", help};
    cli_args args = {0}; /* no --set: nothing to free */
    long n = -1, seeds = -1, lesson_lines = -1, only = 0;
    int steady = 1, imaging = 1, noise = 1, scenes = 1, lesson = 1, quick = 0, print_scene = 0;
    const char *lesson_tier = NULL;
    int c;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        switch (c) {
        case 'n':
            if (cli_whole("bench", "--cycles", optarg, 10, 1000000000L, NULL, &n))
                return CLI_USAGE;
            break;
        case 'S':
            if (cli_whole("bench", "--seeds", optarg, 1, 100, NULL, &seeds))
                return CLI_USAGE;
            break;
        case 'Q': quick = 1; break;
        case 's': steady = 0; break;
        case 'i': imaging = 0; break;
        case 'N': noise = 0; break;
        case 'e': scenes = 0; break;
        case 'l': lesson = 0; break;
        case 'L': steady = imaging = noise = scenes = 0; break;
        case 'm':
            if (cli_whole("bench", "--lesson-lines", optarg, 2, 64, NULL, &lesson_lines))
                return CLI_USAGE;
            break;
        case 'g':
            if (cli_whole("bench", "--lesson-setting", optarg, 1, 7, NULL, &only))
                return CLI_USAGE;
            break;
        case 't':
            if (strcmp(optarg, "envelope") != 0 && strcmp(optarg, "averaged") != 0) {
                fprintf(stderr, "tiptap bench: --lesson-tier: '%s' is not envelope or averaged\n", optarg);
                return CLI_USAGE;
            }
            lesson_tier = optarg;
            break;
        case 'p': print_scene = 1; break;
        case 'b': print_scene = 2; break;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    if (cli_no_operands("bench", argc, argv, optind, "it runs the built-in standard scene"))
        return CLI_USAGE;
    if (print_scene) {
        fputs(print_scene == 1 ? tt_standard_scene() : bench_blend_scene(), stdout);
        return CLI_OK;
    }
    if (n < 0)
        n = quick ? 200 : 5000;
    if (seeds < 0)
        seeds = quick ? 2 : 3;
    /* --quick: short lines, each run once (timings of a check, not a benchmark) */
    bench_lines lines = quick ? (bench_lines){16, 32, 0} : (bench_lines){0, 0, 1};
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
    if (!rc && (imaging || noise || scenes))
        rc = bench_images(scene, &lines, imaging, noise, scenes, (int)seeds);
    /* seven lines: the first engages and settles, six are the figures' median */
    if (!rc && lesson)
        rc = bench_lesson_figure(lesson_lines > 0 ? lesson_lines : quick ? 2 : 7, quick, (int)only,
                                 lesson_tier);
    tt_setup_free(st);
    tt_scene_free(scene);
    return rc ? cli_fail(rc, NULL) : CLI_OK;
}
