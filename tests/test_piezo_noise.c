/* The z piezo's position noise (docs/dynamics.md, "Noise"): a density n through a
 * first-order low-pass of corner fc (an Ornstein-Uhlenbeck process), sampled exactly
 * once per drive cycle as the scan draws it. Its samples have the low-pass's variance
 * n^2 pi fc / 2 and lag-one correlation exp(-2 pi fc T); their averaged periodogram is
 * the low-pass's spectrum n^2 / (1 + (f / fc)^2) well below the sampling rate; the same
 * key and index give the same sample; a bandwidth outside (0, fs / 2] is refused. */
#include <gsl/gsl_fft_real.h>
#include <math.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

static const double n = 0.3e-12, fc = 2e3, T = 1 / 300e3;

/* N samples of the process from its first, key 7. */
static double *draw(long N)
{
    tt_noise_ou p;
    assert_int_equal(tt_noise_ou_init(&p, n, fc, T), TT_OK);
    const uint64_t key = tt_noise_key(7, TT_NOISE_PIEZO, 3);
    double *z = malloc((size_t)N * sizeof *z);
    z[0] = tt_noise_ou_first(&p, key);
    for (long i = 1; i < N; i++)
        z[i] = tt_noise_ou_next(&p, key, (uint64_t)i, z[i - 1]);
    return z;
}

/* The mean of x over B batches and its standard error from their spread. */
static void batch_mean(const double *x, int B, double *m, double *se)
{
    double s = 0, q = 0;
    for (int b = 0; b < B; b++)
        s += x[b] / B;
    for (int b = 0; b < B; b++)
        q += (x[b] - s) * (x[b] - s) / (B - 1);
    *m = s;
    *se = sqrt(q / B);
}

/* Variance and lag-one correlation over 2^21 samples in 128 batches (each 680 times the
 * correlation time of 24 samples). */
static void variance_and_correlation(void **st)
{
    (void)st;
    enum { B = 128, N = 1 << 21, PER = N / B };
    double *z = draw(N), v[B], c[B];
    for (int b = 0; b < B; b++) {
        double s2 = 0, s11 = 0;
        for (long i = (long)b * PER; i < (long)(b + 1) * PER; i++) {
            s2 += z[i] * z[i] / PER;
            if (i > 0)
                s11 += z[i] * z[i - 1] / PER;
        }
        v[b] = s2;
        c[b] = s11;
    }
    double var, var_se, cov, cov_se;
    batch_mean(v, B, &var, &var_se);
    batch_mean(c, B, &cov, &cov_se);
    const double want = n * n * M_PI * fc / 2, a = exp(-2 * M_PI * fc * T);
    print_message("z piezo noise: variance %.4g m^2 against n^2 pi fc / 2 = %.4g (ratio %.4f +- %.4f); "
                  "lag-one correlation %.5f against %.5f\n",
                  var, want, var / want, var_se / want, cov / var, a);
    assert_true(var_se < 0.01 * want);
    assert_close(var, want, 3.5 * var_se);
    assert_close(cov, a * want, 3.5 * cov_se);
    free(z);
}

/* The averaged periodogram (Hann-windowed segments of 4096 samples, 73 Hz bins) in three
 * bands, around fc / 5, fc and 5 fc (150-650 Hz, 1.5-2.5 kHz, 8-12 kHz), against the low-pass's spectrum over the same bins;
 * the standard errors from the spread over the segments. */
static void spectrum(void **st)
{
    (void)st;
    enum { L = 4096, K = 1024, NB = 3 };
    const double fs = 1 / T;
    static const double band[NB][2] = {{150, 650}, {1500, 2500}, {8000, 12000}};
    double *z = draw((long)L * K), *x = malloc(L * sizeof *x), meas[NB][K], want[NB] = {0};
    int bins[NB] = {0};
    double w2 = 0;
    for (int i = 0; i < L; i++) {
        const double w = 0.5 - 0.5 * cos(2 * M_PI * i / L);
        w2 += w * w;
    }
    for (int k = 0; k < K; k++) {
        for (int i = 0; i < L; i++)
            x[i] = z[(long)k * L + i] * (0.5 - 0.5 * cos(2 * M_PI * i / L));
        assert_int_equal(gsl_fft_real_radix2_transform(x, 1, L), 0);
        for (int b = 0; b < NB; b++) {
            meas[b][k] = 0;
            for (int f = 1; f < L / 2; f++) {
                const double hz = f * fs / L;
                if (hz < band[b][0] || hz > band[b][1])
                    continue;
                /* half-complex output: x[f] real, x[L - f] imaginary; one-sided density */
                meas[b][k] += 2 * (x[f] * x[f] + x[L - f] * x[L - f]) / (fs * w2);
                if (k == 0) {
                    want[b] += n * n / (1 + (hz / fc) * (hz / fc));
                    bins[b]++;
                }
            }
        }
    }
    for (int b = 0; b < NB; b++) {
        double m, se;
        for (int k = 0; k < K; k++)
            meas[b][k] /= bins[b];
        batch_mean(meas[b], K, &m, &se);
        want[b] /= bins[b];
        print_message("z piezo noise: %5.0f-%5.0f Hz: PSD %.4g against n^2 / (1 + (f / fc)^2) %.4g "
                      "(ratio %.4f +- %.4f)\n",
                      band[b][0], band[b][1], m, want[b], m / want[b], se / want[b]);
        assert_true(se < 0.03 * want[b]);
        assert_close(m, want[b], 3.5 * se);
    }
    free(x);
    free(z);
}

/* A sample is a function of (key, index) and the one before: drawn again, the same; and
 * bandwidths outside (0, fs / 2], negative or non-finite densities are refused. */
static void reproducible_and_refused(void **st)
{
    (void)st;
    double *a = draw(1000), *b = draw(1000);
    assert_memory_equal(a, b, 1000 * sizeof *a);
    free(a);
    free(b);
    tt_noise_ou p;
    assert_int_equal(tt_noise_ou_init(&p, n, 0, T), TT_EINVAL);
    assert_int_equal(tt_noise_ou_init(&p, n, -1e3, T), TT_EINVAL);
    assert_int_equal(tt_noise_ou_init(&p, n, NAN, T), TT_EINVAL);
    assert_int_equal(tt_noise_ou_init(&p, n, 150.001e3, T), TT_EINVAL);
    assert_int_equal(tt_noise_ou_init(&p, -n, fc, T), TT_EINVAL);
    assert_int_equal(tt_noise_ou_init(&p, INFINITY, fc, T), TT_EINVAL);
    assert_int_equal(tt_noise_ou_init(&p, n, 150e3, T), TT_OK);
    tt_error_clear();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(variance_and_correlation),
        cmocka_unit_test(spectrum),
        cmocka_unit_test(reproducible_and_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
