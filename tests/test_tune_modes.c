/* tiptap tune of a lever of two flexural modes (tiptap/run/tune.h): the record is the
 * optical lever's reading sum chi_n q_n (chi_n the mode's slope against the static end
 * load's); each mode's peak, fitted on its own window, gives f_n, Q_n and k_n within the
 * fit's stated uncertainty of the scene's (seeded); k_2 / k_1 = (f_2 / f_1)^2 at the
 * beam's defaults; the record's mean square is the modes' chi_n^2 kB T / k_n; over seeds
 * mode 2's k scatters as its stated error says; too few samples a period for mode 2 is
 * refused before anything runs. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/scene.h"
#include "tiptap/physics/cantilever.h"
#include "tiptap/run/tune.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

/* A soft lever (0.1 N/m, 10 kHz, Q 20) of two modes at the beam's defaults: mode 2 at
 * 62.67 kHz, 3.927 N/m, Q 125.3, sampled 16 times a drive period (Nyquist 80 kHz). */
static tt_tune_result tune2(long seed, const char *tune, const char *extra, int *rc)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[cantilever]\nspring_constant = 0.1 N/m\nresonance_frequency = 10 kHz\nquality_factor = 20\n"
             "free_amplitude = 10 nm\nmodes = 2\n%s[noise]\ntemperature = 300 K\nseed = %ld\n"
             "[tune]\n%s",
             extra, seed, tune);
    tt_scene *s = tt_scene_alloc();
    if (tt_scene_load_string(s, text, "two modes"))
        fail_msg("%s", tt_error_message());
    tt_table *t = NULL;
    tt_tune_result r;
    *rc = tt_run_tune(s, &t, &r, NULL, NULL);
    if (*rc == TT_OK) {
        /* f, psd, fit and each mode's own density */
        assert_int_equal(tt_table_columns(t), 5);
        assert_string_equal(tt_table_name(t, 4), "mode2");
    }
    tt_table_free(t);
    tt_scene_free(s);
    return r;
}

static tt_tune_result tune_ok(long seed, const char *tune)
{
    int rc;
    tt_tune_result r = tune2(seed, tune, "", &rc);
    if (rc)
        fail_msg("%s", tt_error_message());
    return r;
}

static void each_mode_recovered(void **state)
{
    (void)state;
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 0.1, 10e3, 20, 10e-9, 10e3, TT_DRIVE_BASE), TT_OK);
    assert_int_equal(tt_cantilever_set_modes(&c, 2, NULL, NULL, NULL), TT_OK);
    tt_tune_result r = tune_ok(1, "duration = 0.4 s\nsamples_per_cycle = 16\n");
    assert_int_equal(r.modes, 2);
    const double kT = TT_BOLTZMANN * 300, want_chi[2] = {0.9177, 3.1872};
    double equi = 0;
    for (int n = 0; n < 2; n++) {
        const tt_tune_mode *m = &r.mode[n];
        print_message("mode %d: k %.5g +- %.2g N/m (%.5g), f %.7g +- %.2g Hz (%.7g), Q %.4g +- %.2g (%.4g), "
                      "chi %.5f, chi2/dof %.3g\n",
                      n + 1, m->k, m->k_err, c.mode_k[n], m->f0, m->f0_err, c.mode_f[n], m->Q, m->Q_err,
                      c.mode_Q[n], m->chi, m->chi2_dof);
        assert_close(m->k, c.mode_k[n], 3 * m->k_err);
        assert_close(m->f0, c.mode_f[n], 3 * m->f0_err);
        assert_close(m->Q, c.mode_Q[n], 3 * m->Q_err);
        assert_true(m->k_err < 0.1 * m->k);
        assert_between(m->chi2_dof, 0.7, 1.4);
        /* the slope-calibrated lever: phi_n'(L) L / 1.5 */
        assert_close(m->chi, want_chi[n], 1e-4);
        equi += m->chi * m->chi * kT / c.mode_k[n] * m->noise_factor;
    }
    /* mode 1 repeats the result's own figures */
    assert_close(r.k, r.mode[0].k, 0);
    assert_close(r.chi, r.mode[0].chi, 0);
    /* the beam's rule read off the tune alone: k_2 = k_1 (f_2 / f_1)^2, the ratio's
     * error the two k's (the f's are known to 1e-3) */
    double ratio = r.mode[1].k / r.mode[0].k / pow(r.mode[1].f0 / r.mode[0].f0, 2);
    double err = hypot(r.mode[1].k_err / r.mode[1].k, r.mode[0].k_err / r.mode[0].k);
    print_message("k_2 / (k_1 (f_2 / f_1)^2) = %.4f +- %.4f\n", ratio, err);
    assert_close(ratio, 1, 3 * err);
    /* the record (no floor here) holds each mode's kB T / k_n through its chi_n^2: mode 2
     * read without its chi_2 = 3.19 would take (chi_2^2 - 1) kB T / k_2 off, 6 errors */
    print_message("<x*^2> = %.4g +- %.2g m^2, equipartition through the lever %.4g m^2\n", r.variance,
                  r.variance_err, equi);
    assert_close(r.variance, equi, 3 * r.variance_err);
}

static void mode2_scatter_matches_uncertainty(void **state)
{
    (void)state;
    enum { N = 6 };
    double k[N], sk = 0, se = 0;
    for (int i = 0; i < N; i++) {
        tt_tune_result r = tune_ok(21 + i, "duration = 0.15 s\nsamples_per_cycle = 16\nbin_width = 60 Hz\n");
        k[i] = r.mode[1].k;
        sk += k[i], se += r.mode[1].k_err;
    }
    double mk = sk / N, dk = 0;
    for (int i = 0; i < N; i++)
        dk += (k[i] - mk) * (k[i] - mk);
    double ratio = sqrt(dk / (N - 1)) / (se / N);
    print_message("mode 2 over %d seeds: k %.5g N/m, scatter / stated error %.3g\n", N, mk, ratio);
    /* the 99 % range of a standard deviation of 6 normal numbers over its true value */
    assert_between(ratio, 0.29, 1.84);
    assert_close(mk, 3.92739, 3 * (se / N) / sqrt(N));
}

static void too_few_samples_refused(void **state)
{
    (void)state;
    int rc;
    tune2(1, "duration = 0.4 s\n", "", &rc);
    assert_int_equal(rc, TT_EINVAL);
    assert_message_has("[tune] samples_per_cycle");
    assert_message_has("at least 16");
}

TT_TEST_MAIN(cmocka_unit_test(each_mode_recovered),
             cmocka_unit_test(mode2_scatter_matches_uncertainty),
             cmocka_unit_test(too_few_samples_refused))
