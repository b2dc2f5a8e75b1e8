/* The lock-in: exact demodulation over whole periods, harmonics kept apart, and the
 * filter's step response. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/lockin.h"

static void demodulates_exactly(void **st)
{
    (void)st;
    int Ns[] = {8, 32, 100};
    for (int a = 0; a < 3; a++)
        for (int P = 1; P <= 3; P++) {
            tt_lockin_params p = {1e5, Ns[a], P, 3, 0, 1, 0};
            tt_lockin *l;
            assert_int_equal(tt_lockin_alloc(&l, &p), TT_OK);
            int n = Ns[a] * P;
            double *y = malloc((size_t)n * sizeof *y);
            for (int k = 0; k < n; k++) {
                double wt = 2 * M_PI * k / Ns[a];
                y[k] = 0.7 + 2.0 * cos(wt - 1.2) + 0.3 * cos(2 * wt - 0.4) + 0.1 * cos(3 * wt + 2.9);
            }
            assert_int_equal(tt_lockin_push(l, y), TT_OK);
            assert_close(tt_lockin_amplitude(l, 1), 2.0, 1e-12);
            assert_close(tt_lockin_phase(l, 1), 1.2, 1e-12);
            assert_close(tt_lockin_amplitude(l, 2), 0.3, 1e-12);
            assert_close(tt_lockin_phase(l, 2), 0.4, 1e-12);
            assert_close(tt_lockin_amplitude(l, 3), 0.1, 1e-12);
            assert_close(tt_lockin_phase(l, 3), -2.9 + 2 * M_PI, 1e-12);
            assert_close(tt_lockin_mean(l), 0.7, 1e-12);
            free(y);
            tt_lockin_free(l);
        }
}

/* A block fed as its periods' components (tt_lockin_transform of each) gives the
 * filter the results the transform of its samples gives, up to rounding, through a
 * filter of two orders over several blocks of differing periods. */
static void components_as_samples(void **st)
{
    (void)st;
    int Ns[] = {8, 32, 100};
    for (int a = 0; a < 3; a++)
        for (int P = 1; P <= 3; P++) {
            tt_lockin_params p = {1e5, Ns[a], P, 3, 2e-5, 2, 0};
            tt_lockin *ls, *lc;
            assert_int_equal(tt_lockin_alloc(&ls, &p), TT_OK);
            assert_int_equal(tt_lockin_alloc(&lc, &p), TT_OK);
            const int N = Ns[a], nc = tt_lockin_components(lc);
            assert_int_equal(nc, 7);
            double *y = malloc((size_t)(N * P) * sizeof *y), *c = malloc((size_t)(nc * P) * sizeof *c);
            for (int b = 0; b < 4; b++) {
                for (int k = 0; k < N * P; k++) {
                    double wt = 2 * M_PI * k / N, f = 1 + 0.1 * b + 0.01 * k / N;
                    y[k] = 0.7 * f + 2.0 * cos(wt - 1.2 * f) + 0.3 * f * cos(2 * wt - 0.4) +
                           0.1 * cos(3 * wt + 2.9 * f) + 0.05 * cos(5 * wt);
                }
                for (int j = 0; j < P; j++)
                    tt_lockin_transform(lc, y + j * N, c + j * nc);
                assert_int_equal(tt_lockin_push(ls, y), TT_OK);
                assert_int_equal(tt_lockin_push_components(lc, c), TT_OK);
                for (int h = 1; h <= 3; h++) {
                    assert_close(tt_lockin_amplitude(lc, h), tt_lockin_amplitude(ls, h), 1e-13);
                    assert_close(tt_lockin_phase(lc, h), tt_lockin_phase(ls, h), 1e-12);
                    assert_close(tt_lockin_raw_amplitude(lc, h), tt_lockin_raw_amplitude(ls, h), 1e-13);
                }
                assert_close(tt_lockin_mean(lc), tt_lockin_mean(ls), 1e-13);
            }
            free(y);
            free(c);
            tt_lockin_free(ls);
            tt_lockin_free(lc);
        }
}

static void filter_step_response(void **st)
{
    (void)st;
    /* an n-th order cascade of first-order sections a / (1 - (1 - a) z^-1) driven by a
     * step: after K blocks the output is sum over m < K of a^n C(m + n - 1, n - 1) b^m
     * (the negative binomial series of the cascade's transfer function) */
    for (int order = 1; order <= 4; order++) {
        double f = 1e5, tau = 50e-6;
        tt_lockin_params p = {f, 16, 1, 1, tau, order, 0};
        tt_lockin *l;
        assert_int_equal(tt_lockin_alloc(&l, &p), TT_OK);
        tt_lockin_reset(l, 0, 0);
        double y[16];
        for (int k = 0; k < 16; k++)
            y[k] = cos(2 * M_PI * k / 16);
        double a = 1 - exp(-1 / (f * tau));
        for (int k = 1; k <= 40; k++) {
            tt_lockin_push(l, y);
            double cdf = 0, c = 1;
            for (int m = 0; m < k; m++) {
                if (m > 0)
                    c = c * (m + order - 1) / m;
                cdf += pow(a, order) * c * pow(1 - a, m);
            }
            assert_close(tt_lockin_amplitude(l, 1), cdf, 1e-9);
        }
        tt_lockin_free(l);
    }
}

static void reset_starts_settled(void **st)
{
    (void)st;
    tt_lockin_params p = {3e5, 32, 4, 1, 100e-6, 2, 0};
    tt_lockin *l;
    assert_int_equal(tt_lockin_alloc(&l, &p), TT_OK);
    tt_lockin_reset(l, 1.5, M_PI / 2);
    double y[128];
    for (int k = 0; k < 128; k++)
        y[k] = 1.5 * cos(2 * M_PI * k / 32 - M_PI / 2);
    tt_lockin_push(l, y);
    assert_close(tt_lockin_amplitude(l, 1), 1.5, 1e-12);
    assert_close(tt_lockin_phase(l, 1), M_PI / 2, 1e-12);
    tt_lockin_free(l);
    p.harmonics = 20;
    assert_int_equal(tt_lockin_alloc(&l, &p), TT_EINVAL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(demodulates_exactly),
        cmocka_unit_test(components_as_samples),
        cmocka_unit_test(filter_step_response),
        cmocka_unit_test(reset_starts_settled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
