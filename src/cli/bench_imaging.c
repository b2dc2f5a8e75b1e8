/* tiptap bench's imaging figures: a sample's lines scanned at each setting, timed, and
 * judged against the every-cycle reference on the same lines. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench.h"
#include "commands.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"

int bench_params_make(const bench_sample *s, const char *const *row_set, bench_params *bp)
{
    memset(bp, 0, sizeof *bp);
    tt_scene *c = tt_scene_copy(s->scene);
    if (!c)
        return tt_error_nomem("the bench's scene");
    int rc = TT_OK;
    for (size_t i = 0; s->set[i] && !rc; i++)
        rc = tt_scene_set(c, s->set[i]);
    for (size_t i = 0; row_set && row_set[i] && !rc; i++)
        rc = tt_scene_set(c, row_set[i]);
    if (!rc)
        rc = s->make(c, &s->lines, bp);
    tt_scene_free(c);
    return rc;
}

const char *bench_default_tier(void)
{
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    for (size_t i = 0; i < n; i++)
        for (size_t k = 0; strcmp(sec[i].name, "solver") == 0 && k < sec[i].nkeys; k++)
            if (strcmp(sec[i].keys[k].key, "tier") == 0 && sec[i].keys[k].def)
                return sec[i].keys[k].def;
    return "default tier";
}

void bench_params_free(bench_params *bp)
{
    bp->p.materials = bp->own;
    tt_config_scan_free(&bp->p);
    memset(bp, 0, sizeof *bp);
}

/* Two lines through the sample's features (at a quarter and three quarters of its
 * height), height and phase, trace and retrace, at the figure's pixels and rate. */
static void two_lines(const bench_lines *l, tt_scan_params *p)
{
    p->raster.lines = 2;
    if (l->pixels > 0)
        p->raster.pixels = l->pixels;
    if (l->line_rate > 0)
        p->raster.line_rate = l->line_rate;
    p->raster.retrace = 1;
    p->raster.fast_y = 0;
    p->profile_line = -1;
    p->channels = TT_CH_HEIGHT | TT_CH_PHASE;
}

int bench_plain_sample(const tt_scene *s, const bench_lines *l, bench_params *bp)
{
    int rc = tt_config_scan(s, &bp->p);
    bp->own = bp->p.materials;
    if (!rc)
        two_lines(l, &bp->p);
    return rc;
}

/* The edge sample of the imaging figure: the standard scene's polymer as a soft,
 * sticky, lossy matrix around stiff disks (a polymer blend: 500 nm lattice, 150 nm
 * radius), on 1 nm terraces every 250 nm; the two lines run through the disks' centres,
 * so each crosses four material edges and three height steps that do not coincide. */
int bench_edge_sample(const tt_scene *s, const bench_lines *l, bench_params *bp)
{
    tt_tip tip;
    tt_scan_params *p = &bp->p;
    int rc = tt_config_scan(s, p);
    bp->own = p->materials;
    if (rc || (rc = tt_config_tip(s, &tip)))
        return rc;
    tt_material *mat = bp->mat;
    mat[0] = p->materials[0];
    snprintf(mat[0].name, sizeof mat[0].name, "matrix");
    mat[1] = mat[0];
    snprintf(mat[1].name, sizeof mat[1].name, "disk");
    mat[1].contact.K = tt_material_reduced_modulus(&tip, 30e9, 0.3);
    mat[1].Qi = NAN;
    p->materials = mat;
    p->nmaterials = 2;
    p->raster.size_x = p->raster.size_y = 1e-6;
    p->raster.pixels = 256;
    p->raster.line_rate = 1;
    two_lines(l, p);
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

const char *bench_blend_scene(void)
{
    return "; A quick look: the standard cantilever, 64 x 64 pixels at 4 Hz.\n"
           "[cantilever]\n"
           "spring_constant = 40 N/m\n"
           "resonance_frequency = 300 kHz\n"
           "quality_factor = 400\n"
           "free_amplitude = 20 nm\n"
           "\n"
           "[scan]\n"
           "size = 1 um\n"
           "pixels = 64\n"
           "lines = 64\n"
           "line_rate = 4 Hz\n"
           "\n"
           "[feedback]\n"
           "setpoint = 80 %\n"
           "\n"
           "; A quick look trades accuracy for time: at 3e-8 the default envelope tier runs the\n"
           "; README's main job in about 80 % of the CPU time it takes at the default 1e-8, and its\n"
           "; images stay within 0.4 pm rms in height and 0.01 deg rms in phase of the every-cycle\n"
           "; tier at 1e-10 (docs/dynamics.md, Tiers); the run's own error estimate says so.\n"
           "[solver]\n"
           "tolerance = 3e-8\n"
           "; A polymer blend: stiff glassy disks (polystyrene-like) in a soft, sticky, lossy\n"
           "; rubbery matrix. The sample is flat: every height contrast in its images is an artifact\n"
           "; of the material contrast.\n"
           "[material matrix]\n"
           "youngs_modulus = 100 MPa\n"
           "poisson_ratio = 0.49\n"
           "adhesion_energy = 60 mJ/m^2\n"
           "interatomic_distance = 0.3 nm\n"
           "interaction_quality_factor = 10\n"
           "\n"
           "[material disk]\n"
           "youngs_modulus = 3 GPa\n"
           "poisson_ratio = 0.35\n"
           "adhesion_energy = 40 mJ/m^2\n"
           "interatomic_distance = 0.3 nm\n"
           "\n"
           "[surface]\n"
           "type = flat\n"
           "map = disks\n"
           "map_materials = matrix, disk\n"
           "map_period = 500 nm\n"
           "map_radius = 150 nm\n";
}

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

static int run_once(const tt_scan_params *p, int threads, int estimate, bench_run *out)
{
    tt_scan *scan;
    int rc = timed_scan(p, threads, &scan, &out->wall, &out->cpu);
    if (!rc) {
        size_t n = (size_t)(p->raster.pixels * p->raster.lines);
        out->pixels = p->raster.pixels;
        out->lines = p->raster.lines;
        out->inst = tt_scan_instrument_time(scan);
        out->err_est = tt_scan_error_estimate(scan);
        out->cycles = tt_scan_cycles(scan);
        out->cycles_integrated = tt_scan_cycles_integrated(scan);
        out->integrated = (double)out->cycles_integrated / (double)out->cycles;
        if (estimate)
            rc = tt_scan_estimate_error(scan, &out->est);
        for (int c = 0; c < 2 && !rc; c++)
            for (int r = 0; r < 2 && !rc; r++) {
                out->img[c][r] = malloc(n * sizeof(double));
                if (!out->img[c][r])
                    rc = tt_error_nomem("the bench's images");
                else
                    memcpy(out->img[c][r], tt_scan_image(scan, c ? 2 : 0, r), n * sizeof(double));
            }
    }
    tt_scan_free(scan);
    return rc;
}

/* A run shorter than a second is timed again, up to five runs, keeping the best wall
 * and CPU times: a fifth of a second is at the mercy of one burst of load. */
int bench_run_scan(const tt_scan_params *p, int threads, int estimate, int repeat, bench_run *out)
{
    memset(out, 0, sizeof *out);
    int rc = run_once(p, threads, estimate, out);
    for (int k = 1; k < 5 && repeat && !rc && out->wall < 1.0; k++) {
        tt_scan *scan;
        double wall, cpu;
        rc = timed_scan(p, threads, &scan, &wall, &cpu);
        out->wall = fmin(out->wall, wall);
        out->cpu = fmin(out->cpu, cpu);
        tt_scan_free(scan);
    }
    return rc;
}

void bench_run_free(bench_run *r)
{
    for (int c = 0; c < 2; c++)
        for (int k = 0; k < 2; k++)
            free(r->img[c][k]);
    memset(r, 0, sizeof *r);
}

/* Largest and rms difference of channel c between a run and the reference. */
void bench_image_error(const bench_run *a, const bench_run *ref, int c, double *max, double *rms)
{
    size_t n = (size_t)(a->pixels * a->lines);
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

enum { MAX_ROWS = 8 };

void bench_estimate_header(const char *first)
{
    printf("%-32s %11s %11s %11s %11s %11s %11s %11s %11s %s\n", first, "h_rms_est", "h_rms_meas",
           "h_max_est", "h_max_meas", "ph_rms_est", "ph_rms_meas", "ph_max_est", "ph_max_meas", "check");
}

int bench_estimate_row(const char *label, const double est[4], const double meas[4])
{
    /* the largest errors are what the estimate bounds: a max read below is flagged */
    char check[64] = "ok";
    const int below = est[1] < meas[1] || est[3] < meas[3];
    if (below)
        snprintf(check, sizeof check, "BELOW:%s%s", est[1] < meas[1] ? " height" : "",
                 est[3] < meas[3] ? " phase" : "");
    printf("%-32s %11.3g %11.3g %11.3g %11.3g %11.3g %11.3g %11.3g %11.3g %s\n", label, est[0] * 1e12,
           meas[0] * 1e12, est[1] * 1e12, meas[1] * 1e12, est[2], meas[2], est[3], meas[3], check);
    return below;
}

/* The run's own error estimate (tt_scan_estimate_error, a companion line) against the
 * error measured against the reference, per row: [h rms, h max, ph rms, ph max]. */
static void print_estimates(const bench_row *rows, size_t n, const int *ran, double (*est)[4],
                            double (*meas)[4])
{
    printf("\n# error estimate (a companion run of one line at a 100x tighter setting) against the "
           "measured error\n");
    bench_estimate_header("setting");
    int below = 0;
    for (size_t i = 1; i < n; i++)
        if (ran[i])
            below += bench_estimate_row(rows[i].label, est[i], meas[i]);
    printf("# heights in pm, phases in deg; the estimate is never to be below the measured error:\n"
           "# check says BELOW where its max is (%d row%s)\n", below, below == 1 ? "" : "s");
}

/* One row after the reference: timed on one thread (j1) and two, judged against ref. */
static int figure_row(const bench_row *row, const tt_scan_params *p, int j1, int repeat,
                      const bench_run *ref, double est[4], double meas[4])
{
    bench_run r1 = {0}, r2 = {0};
    int rc = j1 ? bench_run_scan(p, 1, 0, repeat, &r1) : TT_OK;
    if (!rc)
        rc = bench_run_scan(p, 2, 1, repeat, &r2);
    if (!rc) {
        double hm, hr, pm, pr;
        bench_image_error(&r2, ref, 0, &hm, &hr);
        bench_image_error(&r2, ref, 1, &pm, &pr);
        double e[4] = {r2.est.height_rms, r2.est.height_max, r2.est.phase_rms, r2.est.phase_max};
        double m[4] = {hr, hm, pr, pm};
        memcpy(est, e, sizeof e);
        memcpy(meas, m, sizeof m);
        char w1[16] = "-", sp[16] = "-";
        if (j1) {
            snprintf(w1, sizeof w1, "%.2f", r1.wall);
            snprintf(sp, sizeof sp, "%.2f", r1.wall / r2.wall);
        }
        printf("%-32s %8s %8.2f %8s %8.3f %8.3f %10.3g %10.3g %10.3g %10.3g %10.1e %9.1f\n", row->label,
               w1, r2.wall, sp, r2.inst / r2.wall, 2 * r2.inst / r2.cpu, hm * 1e12, hr * 1e12, pm, pr,
               r2.err_est, 100 * r2.integrated);
    }
    bench_run_free(&r1);
    bench_run_free(&r2);
    return rc;
}

int bench_imaging_figure(const bench_sample *s, const bench_row *rows, size_t n, int j1, bench_run *keep)
{
    bench_run ref = {0};
    double est[MAX_ROWS][4] = {{0}}, meas[MAX_ROWS][4] = {{0}};
    int ran[MAX_ROWS] = {0};
    int rc = TT_OK;
    if (n > MAX_ROWS)
        n = MAX_ROWS;
    for (size_t i = 0; i < n && !rc; i++) {
        bench_params bp;
        rc = bench_params_make(s, rows[i].set, &bp);
        if (rc && rows[i].optional && i > 0) {
            printf("%-32s not available: %s\n", rows[i].label, tt_error_message());
            tt_error_clear();
            bench_params_free(&bp);
            rc = TT_OK;
            continue;
        }
        const tt_scan_params *p = &bp.p;
        if (!rc && i == 0) {
            printf("\n# %s;\n# %.3g um, %ld lines of %ld pixels at %.3g Hz (trace + retrace), %.0f %% "
                   "setpoint; errors against the reference\n",
                   s->title, p->raster.size_x * 1e6, p->raster.lines, p->raster.pixels,
                   p->raster.line_rate, 100 * p->feedback.setpoint / p->cantilever.A0);
            printf("%-32s %8s %8s %8s %8s %8s %10s %10s %10s %10s %10s %9s\n", "setting", "wall_j1",
                   "wall_j2", "j2/j1", "rtf_j2", "rtf_cpu", "h_max_pm", "h_rms_pm", "ph_max_deg",
                   "ph_rms_deg", "energy_bal", "integr_%");
            rc = bench_run_scan(p, 2, 0, s->lines.repeat, &ref);
            if (!rc)
                printf("%-32s %8s %8.2f %8s %8.3f %8.3f %10s %10s %10s %10s %10.1e %9.1f\n", rows[0].label,
                       "-", ref.wall, "-", ref.inst / ref.wall, 2 * ref.inst / ref.cpu, "-", "-", "-",
                       "-", ref.err_est, 100 * ref.integrated);
        } else if (!rc) {
            rc = figure_row(&rows[i], p, j1, s->lines.repeat, &ref, est[i], meas[i]);
            ran[i] = !rc;
        }
        fflush(stdout);
        bench_params_free(&bp);
    }
    if (!rc && n > 1) {
        printf(s->lines.repeat ? "# runs under a second: the best of five\n"
                               : "# --quick: each run once; its times are not a benchmark\n");
        printf("# rtf_j2: instrument time / wall time on two threads (10 is the goal); rtf_cpu: the\n"
               "# same from the CPU time, what two idle cores give (a shared machine's wall time is\n"
               "# not); energy_bal: the energy-balance check (largest residual / free drive work);\n"
               "# integr_%%: the share of the cycles integrated (the envelope tier skips the rest)\n");
        print_estimates(rows, n, ran, est, meas);
    }
    if (keep && !rc)
        *keep = ref;
    else
        bench_run_free(&ref);
    return rc;
}
