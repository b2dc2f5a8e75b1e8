/* tiptap bench's noise figure: the edge sample's lines with noise on, on the every-cycle
 * tier and the default tier, judged by statistics rather than by a difference.
 *
 * Noise's effect on an image is its difference from the noise-free reference of the
 * same lines (the figure before, every cycle at tolerance 1e-10). A unit is one line in
 * one direction at one seed; over each unit's pixels that difference has a mean (the
 * shift: noise's deterministic effect, the tier's integration error, and the part of
 * the noise slower than a line) and a standard deviation (the noise seen in the image).
 * The figures are their averages over the units, and each has a standard error from its
 * spread over them, which holds whatever the pixels' correlation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "tiptap/util/error.h"

/* A tier's per-unit figures for both channels and its timing, summed over seeds. */
typedef struct {
    double *mean[2], *var[2]; /* [height, phase][unit] */
    double wall, cpu, inst;
    long cycles, integrated;
    int every; /* the every-cycle tier; else the default */
} tier_stats;

/* The mean of x[0..n) and its standard error (0 for fewer than two). */
static void mean_se(const double *x, size_t n, double *mean, double *se)
{
    double s = 0, q = 0;
    for (size_t i = 0; i < n; i++)
        s += x[i];
    *mean = s / (double)n;
    for (size_t i = 0; i < n; i++)
        q += (x[i] - *mean) * (x[i] - *mean);
    *se = n > 1 ? sqrt(q / (double)(n - 1) / (double)n) : 0;
}

/* Each unit's mean and variance of (run - ref) for channel c, from unit u0 on. */
static void add_units(const bench_run *run, const bench_run *ref, int c, double *mean, double *var, size_t u0)
{
    long np = run->pixels;
    for (int r = 0; r < 2; r++)
        for (long l = 0; l < run->lines; l++) {
            const double *a = run->img[c][r] + l * np, *b = ref->img[c][r] + l * np;
            double s = 0, q = 0;
            for (long i = 0; i < np; i++)
                s += a[i] - b[i];
            double m = s / (double)np;
            for (long i = 0; i < np; i++)
                q += (a[i] - b[i] - m) * (a[i] - b[i] - m);
            size_t u = u0 + (size_t)(r * run->lines + l);
            mean[u] = m;
            var[u] = q / (double)(np - 1);
        }
}

/* Sum of squared differences between two runs' channel c images. */
static double sq_diff(const bench_run *a, const bench_run *b, int c)
{
    double s = 0;
    size_t n = (size_t)(a->pixels * a->lines);
    for (int r = 0; r < 2; r++)
        for (size_t i = 0; i < n; i++)
            s += (a->img[c][r][i] - b->img[c][r][i]) * (a->img[c][r][i] - b->img[c][r][i]);
    return s;
}

/* "value+-se" in a field, scaled. */
static const char *pm(char *buf, size_t len, double v, double se, double scale)
{
    snprintf(buf, len, "%.4g+-%.2g", v * scale, se * scale);
    return buf;
}

static void print_tier(const char *noise, const tier_stats *t, size_t units)
{
    char label[64], b[4][40];
    if (t->every)
        snprintf(label, sizeof label, "%s, every cycle", noise);
    else
        snprintf(label, sizeof label, "%s, %s (default)", noise, bench_default_tier());
    double sd[2], sd_se[2], sh[2], sh_se[2];
    for (int c = 0; c < 2; c++) {
        double v, v_se;
        mean_se(t->var[c], units, &v, &v_se);
        sd[c] = sqrt(v);
        sd_se[c] = v > 0 ? v_se / (2 * sd[c]) : 0;
        mean_se(t->mean[c], units, &sh[c], &sh_se[c]);
    }
    printf("%-40s %8.3f %8.3f %9.1f %17s %17s %19s %19s\n", label, t->inst / t->wall, 2 * t->inst / t->cpu,
           100 * (double)t->integrated / (double)t->cycles, pm(b[0], 40, sd[0], sd_se[0], 1e12),
           pm(b[1], 40, sh[0], sh_se[0], 1e12), pm(b[2], 40, sd[1], sd_se[1], 1),
           pm(b[3], 40, sh[1], sh_se[1], 1));
}

/* The default tier (a) against every cycle (b), unit by unit at the same seeds: the ratio
 * of their sds (delta method on the paired variances) and the difference of their shifts. */
static void print_paired(const char *noise, const tier_stats *a, const tier_stats *b, size_t units,
                         const double rms[2])
{
    char bf[4][40];
    double r[2], r_se[2], d[2], d_se[2];
    double *z = malloc(units * sizeof *z);
    for (int c = 0; c < 2; c++) {
        double va, vb, se;
        mean_se(a->var[c], units, &va, &se);
        mean_se(b->var[c], units, &vb, &se);
        double R = va / vb;
        for (size_t u = 0; z && u < units; u++)
            z[u] = a->var[c][u] - R * b->var[c][u];
        double zm = 0, zse = NAN;
        if (z)
            mean_se(z, units, &zm, &zse);
        r[c] = sqrt(R);
        r_se[c] = zse / vb / (2 * r[c]);
        for (size_t u = 0; z && u < units; u++)
            z[u] = a->mean[c][u] - b->mean[c][u];
        d[c] = d_se[c] = NAN;
        if (z)
            mean_se(z, units, &d[c], &d_se[c]);
    }
    free(z);
    printf("%-16s %17s %17s %19s %19s %13.4g %13.4g\n", noise, pm(bf[0], 40, r[0], r_se[0], 1),
           pm(bf[1], 40, r[1], r_se[1], 1), pm(bf[2], 40, d[0], d_se[0], 1e12),
           pm(bf[3], 40, d[1], d_se[1], 1), rms[0] * 1e12, rms[1]);
}

static void stats_free(tier_stats *t)
{
    for (int c = 0; c < 2; c++) {
        free(t->mean[c]);
        free(t->var[c]);
    }
}

/* One noise set at seeds 1 to seeds on both tiers ([0] every cycle, [1] the default). */
static int noise_set(const bench_sample *s, const bench_run *ref, const char *const *noise, int seeds,
                     tier_stats t[2], double rms[2])
{
    size_t per = (size_t)(2 * ref->lines), units = per * (size_t)seeds;
    for (int k = 0; k < 2; k++)
        for (int c = 0; c < 2; c++) {
            t[k].mean[c] = malloc(units * sizeof(double));
            t[k].var[c] = malloc(units * sizeof(double));
            if (!t[k].mean[c] || !t[k].var[c])
                return tt_error_nomem("the noise figure's statistics");
        }
    double sq[2] = {0, 0};
    int rc = TT_OK;
    for (int seed = 1; seed <= seeds && !rc; seed++) {
        bench_run run[2] = {{0}};
        for (int k = 0; k < 2 && !rc; k++) {
            char seed_set[32];
            const char *set[8];
            size_t n = 0;
            while (noise[n] && n < 5) {
                set[n] = noise[n];
                n++;
            }
            snprintf(seed_set, sizeof seed_set, "noise.seed=%d", seed);
            set[n++] = seed_set;
            if (k == 0)
                set[n++] = "solver.tier=every";
            set[n] = NULL;
            bench_params bp;
            rc = bench_params_make(s, set, &bp);
            if (!rc)
                rc = bench_run_scan(&bp.p, 2, 0, 0, &run[k]);
            if (!rc) {
                t[k].every = k == 0;
                t[k].wall += run[k].wall;
                t[k].cpu += run[k].cpu;
                t[k].inst += run[k].inst;
                t[k].cycles += run[k].cycles;
                t[k].integrated += run[k].cycles_integrated;
                for (int c = 0; c < 2; c++)
                    add_units(&run[k], ref, c, t[k].mean[c], t[k].var[c], per * (size_t)(seed - 1));
            }
            bench_params_free(&bp);
        }
        for (int c = 0; c < 2 && !rc; c++)
            sq[c] += sq_diff(&run[0], &run[1], c);
        bench_run_free(&run[0]);
        bench_run_free(&run[1]);
    }
    for (int c = 0; c < 2; c++)
        rms[c] = sqrt(sq[c] / (double)(units * (size_t)ref->pixels));
    return rc;
}

int bench_noise_figure(const bench_sample *s, const bench_run *ref, int seeds)
{
    static const struct {
        const char *name;
        const char *set[4];
    } noises[] = {
        {"full noise", {"noise.temperature=300 K", "noise.detector=100 fm/sqrt(Hz)",
                        "noise.z_piezo=0.3 pm/sqrt(Hz)", NULL}},
        {"thermal + detector", {"noise.temperature=300 K", "noise.detector=100 fm/sqrt(Hz)", NULL}},
        {"detector noise", {"noise.detector=100 fm/sqrt(Hz)", NULL}},
    };
    enum { NN = sizeof noises / sizeof noises[0] };
    tier_stats t[NN][2];
    double rms[NN][2];
    memset(t, 0, sizeof t);
    size_t units = (size_t)(2 * ref->lines * seeds);
    printf("\n# noise: the same lines with noise, seeds 1 to %d, on the every-cycle tier and the default\n"
           "# tier (dopri5 tol 1e-8). full noise: 300 K, detector 100 fm/sqrt(Hz), z piezo 0.3 pm/sqrt(Hz)\n"
           "# through its bandwidth ([noise] z_piezo_bandwidth, default); thermal + detector: without\n"
           "# the z piezo's; detector noise: the detector's alone. Each image's difference from the\n"
           "# noise-free reference above, per line and direction (%zu of them): sd, its standard\n"
           "# deviation over the line's pixels (the noise the image shows); shift, its mean\n",
           seeds, units);
    printf("%-40s %8s %8s %9s %17s %17s %19s %19s\n", "setting", "rtf_j2", "rtf_cpu", "integr_%", "h_sd_pm",
           "h_shift_pm", "ph_sd_deg", "ph_shift_deg");
    int rc = TT_OK;
    for (size_t i = 0; i < NN && !rc; i++) {
        rc = noise_set(s, ref, noises[i].set, seeds, t[i], rms[i]);
        for (int k = 0; k < 2 && !rc; k++)
            print_tier(noises[i].name, &t[i][k], units);
        fflush(stdout);
    }
    if (!rc) {
        printf("# +-: the standard error of the average over the lines (from their spread)\n");
        printf("\n# the default tier (%s) against every cycle at the same seeds, line by line\n",
               bench_default_tier());
        printf("%-16s %17s %17s %19s %19s %13s %13s\n", "noise", "h_sd_ratio", "ph_sd_ratio",
               "h_shift_diff_pm", "ph_shift_diff_deg", "h_rms_diff_pm", "ph_rms_diff_deg");
        for (size_t i = 0; i < NN; i++)
            print_paired(noises[i].name, &t[i][1], &t[i][0], units, rms[i]);
        printf("# sd_ratio: the default tier's sd over every cycle's; shift_diff: its shift minus every "
               "cycle's;\n# rms_diff: the rms of the two tiers' difference pixel by pixel (0: the same "
               "images)\n");
    }
    for (size_t i = 0; i < NN; i++)
        for (int k = 0; k < 2; k++)
            stats_free(&t[i][k]);
    return rc;
}
