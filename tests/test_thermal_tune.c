/* tiptap tune (tiptap/run/tune.h): the fit recovers the scene's f, Q and k within its
 * own stated uncertainty on a soft, a medium and a stiff cantilever; over seeds its
 * scatter matches that uncertainty; the record's mean square deflection is kB T / k
 * times the factor the thermal force's interpolation gives, within its statistical
 * error, at 64 points a period (factor 0.999) and at 4 (factor 0.7, far from 1). */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/scene.h"
#include "tiptap/run/tune.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

typedef struct {
    const char *name;
    double k, f0, Q;
    const char *tune; /* [tune] keys: a record of some thousand drive periods */
} lever;

static const lever levers[3] = {
    {"soft", 0.1, 10e3, 20, "duration = 0.4 s\n"},
    {"medium", 2, 70e3, 100, "duration = 0.08 s\nbin_width = 150 Hz\n"},
    {"stiff", 40, 300e3, 400, "duration = 0.06 s\nbin_width = 200 Hz\n"},
};

static tt_tune_result tune(const lever *l, long seed, int points)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[cantilever]\nspring_constant = %.17g N/m\nresonance_frequency = %.17g Hz\n"
             "quality_factor = %.17g\nfree_amplitude = 10 nm\n"
             "[noise]\ntemperature = 300 K\nseed = %ld\npoints = %d\n[tune]\n%s",
             l->k, l->f0, l->Q, seed, points, l->tune);
    tt_scene *s = tt_scene_alloc();
    if (tt_scene_load_string(s, text, l->name))
        fail_msg("%s", tt_error_message());
    tt_table *t = NULL;
    tt_tune_result r;
    if (tt_run_tune(s, &t, &r, NULL, NULL) != TT_OK)
        fail_msg("%s: %s", l->name, tt_error_message());
    assert_true(tt_table_rows(t) > 100);
    tt_table_free(t);
    tt_scene_free(s);
    return r;
}

static void recovers_within_its_uncertainty(void **state)
{
    (void)state;
    for (int i = 0; i < 3; i++) {
        const lever *l = &levers[i];
        tt_tune_result r = tune(l, 1, 64);
        print_message("%s: k %.5g +- %.2g N/m (%.5g), f %.7g +- %.2g Hz, Q %.4g +- %.2g, chi2/dof %.3g, "
                      "%ld segments\n",
                      l->name, r.k, r.k_err, l->k, r.f0, r.f0_err, r.Q, r.Q_err, r.chi2_dof, r.segments);
        assert_close(r.k, l->k, 3 * r.k_err);
        assert_close(r.f0, l->f0, 3 * r.f0_err);
        assert_close(r.Q, l->Q, 3 * r.Q_err);
        /* an uncertainty that says something: a few percent for these records */
        assert_true(r.k_err < 0.1 * r.k);
        assert_between(r.chi2_dof, 0.7, 1.4);
        assert_close(r.chi, 1, 0);
    }
}

static void scatter_matches_uncertainty(void **state)
{
    (void)state;
    enum { N = 8 };
    const lever *l = &levers[0];
    double k[N], v[N], sk = 0, se = 0, sv = 0, sve = 0;
    for (int i = 0; i < N; i++) {
        tt_tune_result r = tune(l, 11 + i, 64);
        k[i] = r.k;
        v[i] = r.variance;
        sk += r.k, se += r.k_err, sv += r.variance, sve += r.variance_err;
    }
    double mk = sk / N, mv = sv / N, dk = 0, dv = 0;
    for (int i = 0; i < N; i++)
        dk += (k[i] - mk) * (k[i] - mk), dv += (v[i] - mv) * (v[i] - mv);
    double ratio_k = sqrt(dk / (N - 1)) / (se / N), ratio_v = sqrt(dv / (N - 1)) / (sve / N);
    print_message("over %d seeds: k %.5g, scatter / stated error %.3g; <x^2> scatter / stated %.3g\n", N, mk,
                  ratio_k, ratio_v);
    /* the 99 % range of a standard deviation of 8 normal numbers over its true value */
    assert_between(ratio_k, 0.38, 1.7);
    assert_between(ratio_v, 0.38, 1.7);
    assert_close(mk, l->k, 3 * (se / N) / sqrt(N));
}

static void equipartition_with_the_interpolation_factor(void **state)
{
    (void)state;
    const lever *l = &levers[0];
    const double kT = TT_BOLTZMANN * 300;
    /* a sharp resonance: sinc^4(f0 dt) */
    double s = sin(M_PI / 64) / (M_PI / 64);
    assert_close(tt_tune_noise_factor(300e3, 400, 300e3, 64), s * s * s * s, 2e-5);
    int points[2] = {64, 4};
    for (int i = 0; i < 2; i++) {
        tt_tune_result r = tune(l, 3, points[i]);
        double ratio = r.variance * l->k / kT, err = r.variance_err * l->k / kT;
        print_message("%d points: <x^2> k / kB T = %.4f +- %.4f, factor %.4f\n", points[i], ratio, err,
                      r.noise_factor);
        assert_close(ratio, r.noise_factor, 3 * err);
        /* the fit reads the factor out through the model's sinc^4: k stays the scene's */
        assert_close(r.k, l->k, 3 * r.k_err);
        if (points[i] == 4) {
            assert_true(r.noise_factor < 0.8);
            assert_true(fabs(ratio - 1) > 5 * err);
        }
    }
}

static void refusals(void **state)
{
    (void)state;
    tt_scene *s = tt_scene_alloc();
    if (tt_scene_load_string(s, "[cantilever]\nspring_constant = 1 N/m\n", "cold"))
        fail_msg("%s", tt_error_message());
    tt_table *t = NULL;
    assert_int_equal(tt_run_tune(s, &t, NULL, NULL, NULL), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "[noise] temperature"));
    if (tt_scene_load_string(s, "[noise]\ntemperature = 300 K\n[tune]\nduration = 1 ms\n", "short"))
        fail_msg("%s", tt_error_message());
    assert_int_equal(tt_run_tune(s, &t, NULL, NULL, NULL), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "[tune] duration"));
    assert_null(t);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(recovers_within_its_uncertainty),
        cmocka_unit_test(scatter_matches_uncertainty),
        cmocka_unit_test(equipartition_with_the_interpolation_factor),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
