/* A faster tier's noise against the every-cycle tier's at the same seeds, per line of
 * scans on a scene base: the variance (so the sd), the mean and the line spectrum in
 * three bands of height, error (amplitude - setpoint) and phase of (noisy - noiseless),
 * over seeds, with standard errors from the paired units (tests/test_envelope_noise.c,
 * tests/test_averaged_noise.c). Include after tt_test.h and tt_scan_test.h. */
#ifndef TT_NOISE_COMPARE_H
#define TT_NOISE_COMPARE_H

#include <math.h>
#include <stdio.h>

enum { NC_CH = 3, NC_PX = 64, NC_MAXU = 2 * 2 * 16, NC_BANDS = 3 };

/* The noise tests' scene: the standard lever engaged on a flat soft polymer, two lines of
 * NC_PX pixels at 8 Hz. */
static inline const char *nc_polymer_base(void)
{
    return "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
           "free_amplitude = 20 nm\n"
           "[material polymer]\nyoungs_modulus = 1 GPa\nadhesion_energy = 40 mJ/m^2\n"
           "interaction_quality_factor = 5\n"
           "[scan]\nsize = 1 um\npixels = 64\nlines = 2\nline_rate = 8 Hz\nsettle_cycles = 3000\n"
           "channels = height, error, phase\n"
           "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";
}

/* One scan on a tier: the base plus sample, with noise (seed > 0) or without. */
static inline tt_scan *nc_noisy(const char *base, const char *sample, const char *noise,
                                const char *tier, int seed, long *integrated, long *cycles)
{
    char extra[1024];
    snprintf(extra, sizeof extra, "%s[solver]\ntier = %s\n[noise]\nseed = %d\n%s", sample, tier,
             seed > 0 ? seed : 1, seed > 0 ? noise : "");
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, extra, &sc);
    tt_scene_free(sc);
    if (integrated) {
        *integrated += tt_scan_cycles_integrated(s);
        *cycles += tt_scan_cycles(s);
    }
    return s;
}

/* Per unit (a line in one direction at one seed) and channel: the variance and the mean
 * of (noisy - noiseless) over the line's pixels, and its periodogram summed in NC_BANDS
 * bands of the line's frequencies (1-3, 4-11 and 12-32 periods a line). */
typedef struct {
    int units;
    double var[NC_CH][NC_MAXU], mean[NC_CH][NC_MAXU], band[NC_CH][NC_BANDS][NC_MAXU];
} nc_units;

static inline void nc_line_stats(const double *a, const double *b, nc_units *u, int c, int k)
{
    static const int lo[NC_BANDS] = {1, 4, 12}, hi[NC_BANDS] = {3, 11, 32};
    double d[NC_PX], m = 0, q = 0;
    for (int i = 0; i < NC_PX; i++)
        m += (d[i] = a[i] - b[i]) / NC_PX;
    for (int i = 0; i < NC_PX; i++)
        q += (d[i] - m) * (d[i] - m) / (NC_PX - 1);
    u->var[c][k] = q;
    u->mean[c][k] = m;
    for (int bd = 0; bd < NC_BANDS; bd++) {
        double p = 0;
        for (int f = lo[bd]; f <= hi[bd]; f++) {
            double re = 0, im = 0;
            for (int i = 0; i < NC_PX; i++) {
                re += d[i] * cos(2 * M_PI * f * i / NC_PX);
                im += d[i] * sin(2 * M_PI * f * i / NC_PX);
            }
            p += re * re + im * im;
        }
        u->band[c][bd][k] = p;
    }
}

/* The units of seeds 1 to seeds on a tier (scans of two lines of NC_PX pixels). */
static inline void nc_units_of(const char *base, const char *sample, const char *noise,
                               const char *tier, int seeds, nc_units *u, long *integrated,
                               long *cycles)
{
    tt_scan *clean = nc_noisy(base, sample, noise, tier, 0, NULL, NULL);
    assert_int_equal(tt_scan_xres(clean), NC_PX);
    u->units = 4 * seeds;
    assert_true(u->units <= NC_MAXU);
    for (int s = 0; s < seeds; s++) {
        tt_scan *sc = nc_noisy(base, sample, noise, tier, s + 1, integrated, cycles);
        for (int c = 0; c < NC_CH; c++)
            for (int r = 0; r < 2; r++)
                for (long l = 0; l < 2; l++)
                    nc_line_stats(tt_scan_image(sc, c, r) + l * NC_PX,
                                  tt_scan_image(clean, c, r) + l * NC_PX, u, c, (s * 2 + r) * 2 + (int)l);
        tt_scan_free(sc);
    }
    tt_scan_free(clean);
}

/* The ratio of the means of a and b over n units, with its standard error from the
 * paired units (delta method: the same seed draws the same z piezo noise on both tiers,
 * which makes a pair's difference tighter than either). */
static inline void nc_paired_ratio(const double *a, const double *b, int n, double *ratio, double *se)
{
    double ma = 0, mb = 0, zm = 0, zv = 0;
    for (int k = 0; k < n; k++) {
        ma += a[k] / n;
        mb += b[k] / n;
    }
    *ratio = ma / mb;
    for (int k = 0; k < n; k++)
        zm += (a[k] - *ratio * b[k]) / n;
    for (int k = 0; k < n; k++)
        zv += (a[k] - *ratio * b[k] - zm) * (a[k] - *ratio * b[k] - zm) / (n - 1);
    *se = sqrt(zv / n) / mb;
}

/* The mean over n units of a - b and its standard error. */
static inline void nc_paired_difference(const double *a, const double *b, int n, double *diff, double *se)
{
    double m = 0, v = 0;
    for (int k = 0; k < n; k++)
        m += (a[k] - b[k]) / n;
    for (int k = 0; k < n; k++)
        v += (a[k] - b[k] - m) * (a[k] - b[k] - m) / (n - 1);
    *diff = m;
    *se = sqrt(v / n);
}

/* The mean of n batch means and its standard error. */
static inline double nc_batch_mean(const double *bat, int n, double *se)
{
    double m = 0, v = 0;
    for (int b = 0; b < n; b++)
        m += bat[b] / n;
    for (int b = 0; b < n; b++)
        v += (bat[b] - m) * (bat[b] - m);
    *se = sqrt(v / (n - 1) / n);
    return m;
}

/* The tier's noise against the every-cycle tier's at the same seeds: per line the
 * variance (so the sd), the mean and the line spectrum in three bands of height, error
 * and phase agree within 3.5 standard errors of their paired ratio or difference, and
 * within slack (a fraction of the sd; of the ratio) of it, the sd's error being under
 * 4 % (so that the test means something); the means within mean_slack of the sd
 * besides. Returns the fraction of the tier's cycles integrated. */
static inline double nc_compare_tiers(const char *base, const char *what, const char *sample,
                                      const char *noise, const char *tier, int seeds, double slack,
                                      double mean_slack)
{
    static nc_units fast, every;
    long integrated = 0, cycles = 0;
    nc_units_of(base, sample, noise, tier, seeds, &fast, &integrated, &cycles);
    nc_units_of(base, sample, noise, "every", seeds, &every, NULL, NULL);
    const int n = fast.units;
    const double frac = (double)integrated / (double)cycles;
    print_message("%s: the %s tier integrated %.1f %% of the cycles\n", what, tier, 100.0 * frac);
    const char *name[NC_CH] = {"height (m)", "amplitude error (m)", "phase (deg)"};
    for (int c = 0; c < NC_CH; c++) {
        double r, se, d, dse, sd = 0;
        nc_paired_ratio(fast.var[c], every.var[c], n, &r, &se);
        for (int k = 0; k < n; k++)
            sd += every.var[c][k] / n;
        sd = sqrt(sd);
        /* the sds' ratio is the square root of the variances' */
        print_message("  %-20s sd every %.3g, %s / every %.3f +- %.3f; ", name[c], sd, tier, sqrt(r),
                      se / (2 * sqrt(r)));
        assert_true(se / (2 * sqrt(r)) < 0.04);
        assert_close(r, 1, 3.5 * se + 2 * slack);
        nc_paired_difference(fast.mean[c], every.mean[c], n, &d, &dse);
        print_message("mean, %s - every %.3g +- %.2g; bands", tier, d, dse);
        assert_close(d, 0, 3.5 * dse + mean_slack * sd);
        for (int bd = 0; bd < NC_BANDS; bd++) {
            nc_paired_ratio(fast.band[c][bd], every.band[c][bd], n, &r, &se);
            print_message(" %.3f +- %.3f", r, se);
            assert_close(r, 1, 3.5 * se + 2 * slack);
        }
        print_message("\n");
    }
    return frac;
}

#endif
