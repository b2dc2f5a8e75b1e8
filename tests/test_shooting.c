/* Steady points by shooting (tiptap/solver/shooting.h): the fixed point of the
 * one-period map and its Floquet multipliers on the free oscillator against the
 * analytic steady state; agreement with settling on the standard scene; both
 * branches of the bistable scene (Garcia and San Paulo 1999); and the n x n algebra
 * (the generic solve, eigenvalues and Lyapunov equation against the one-mode closed
 * forms at n = 2, and against a known spectrum and the equation's residual at n = 4). */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "tt_test.h"
#include "tt_sim_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/standard.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/solver/shooting.h"
#include "tiptap/util/error.h"
#include "solver/shooting_linalg.h"

#include <gsl/gsl_errno.h>

static tt_sim *free_sim(tt_cantilever *c, double Q, double fd_ratio)
{
    assert_int_equal(tt_cantilever_init(c, 40, 300e3, Q, 20e-9, 300e3 * fd_ratio, TT_DRIVE_BASE),
                     TT_OK);
    return tt_test_sim(c, 1e-10);
}

/* From rest, Newton lands on y = A cos(w t - lag) of the transfer function of
 * m y'' + c y' + k y = m w^2 a_d cos(w t) (Burnham et al. eq. 2 without the sample),
 * written out here independently of the library, in a few cycles. */
static void free_fixed_point_is_the_analytic_steady_state(void **st)
{
    (void)st;
    const double ratios[] = {1.0, 0.999, 1.002, 0.7};
    for (size_t i = 0; i < sizeof ratios / sizeof ratios[0]; i++) {
        tt_cantilever c;
        tt_sim *sim = free_sim(&c, 400, ratios[i]);
        double w = c.wd, m = c.k / (c.w0 * c.w0), cc = m * c.w0 / c.Q;
        double A = m * w * w * c.a_d / hypot(c.k - m * w * w, cc * w);
        double lag = atan2(cc * w, c.k - m * w * w);
        tt_sim_set_state(sim, 0, 0, 0);
        tt_shoot_params p;
        tt_shoot_default(&p);
        tt_shoot_result r;
        tt_cycle cy;
        int settled;
        assert_int_equal(tt_shoot_steady(sim, &p, 20000, 1e-7, &cy, &settled, &r), TT_OK);
        assert_true(settled);
        assert_int_equal(r.how, TT_SHOOT_NEWTON);
        assert_true(r.cycles < 100);
        /* at t = 0: d = z + y with z = a_d, y = A cos(-lag), v = y' */
        assert_close(r.d, c.a_d + A * cos(lag), 1e-9 * A);
        assert_close(r.v, A * w * sin(lag), 1e-9 * A * w);
        assert_close(cy.amplitude, A, 1e-8 * A);
        assert_close(cy.phase, lag, 1e-8);
        tt_sim_free(sim);
    }
}

/* The free oscillator's monodromy is exp(S T) of its linear system: multipliers
 * exp((-w0 / 2Q +- i w0 sqrt(1 - 1/4Q^2)) T), |mu| = exp(-w0 T / 2Q). */
static void free_multipliers_are_analytic(void **st)
{
    (void)st;
    const double Qs[] = {400, 10, 1.5}, ratios[] = {0.999, 0.8, 1.3};
    for (size_t i = 0; i < 3; i++) {
        tt_cantilever c;
        tt_sim *sim = free_sim(&c, Qs[i], ratios[i]);
        tt_sim_reset_free(sim);
        tt_shoot_params p;
        tt_shoot_default(&p);
        double re[2], im[2];
        assert_int_equal(tt_shoot_multipliers(sim, &p, re, im), TT_OK);
        double T = c.T, decay = exp(-c.w0 * T / (2 * c.Q));
        double wdamp = c.w0 * sqrt(1 - 1 / (4 * c.Q * c.Q));
        double mre = decay * cos(wdamp * T), mim = decay * fabs(sin(wdamp * T));
        for (int j = 0; j < 2; j++) {
            assert_close(re[j], mre, 1e-6);
            assert_close(fabs(im[j]), mim, 1e-6);
            assert_close(hypot(re[j], im[j]), decay, 1e-6);
        }
        assert_close(im[0], -im[1], 1e-15);
        tt_sim_free(sim);
    }
}

/* One steady point of a scene of one approach point (the standard scene's at 16 nm) by
 * each steady mode of approach. */
static tt_approach_point scene_point(const char *text, const char *steady)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "scene"), TT_OK);
    char set[64];
    snprintf(set, sizeof set, "approach.steady=%s", steady);
    assert_int_equal(tt_scene_set(s, set), TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_approach_params p;
    assert_int_equal(tt_config_approach(s, &p), TT_OK);
    tt_approach *a;
    assert_int_equal(tt_approach_alloc(&a, tt_setup_sim(su), &p), TT_OK);
    tt_approach_point pt;
    assert_int_equal(tt_approach_iterate(a, &pt), TT_OK);
    assert_true(tt_approach_done(a));
    tt_approach_free(a);
    tt_setup_free(su);
    tt_scene_free(s);
    return pt;
}

static tt_approach_point standard_point(const char *steady) { return scene_point(tt_standard_scene(), steady); }

static void standard_scene_agrees_with_settling(void **st)
{
    (void)st;
    tt_approach_point sh = standard_point("shooting"), se = standard_point("settle");
    print_message("shooting %ld cycles, settling %ld: amplitude %.9g / %.9g nm, phase %.9g / "
                  "%.9g deg, |mu| %.6g\n", sh.cycles, se.cycles, sh.cycle.amplitude * 1e9,
                  se.cycle.amplitude * 1e9, sh.cycle.phase * 180 / M_PI,
                  se.cycle.phase * 180 / M_PI, sh.shot.mu_abs);
    assert_true(sh.settled && se.settled);
    assert_int_equal(sh.shot.how, TT_SHOOT_NEWTON);
    assert_true(sh.shot.mu_abs < 1);
    assert_true(sh.cycle.contact_fraction > 0); /* a tapping orbit, not the free one */
    assert_close(sh.cycle.amplitude, se.cycle.amplitude, 1e-6 * se.cycle.amplitude);
    assert_close(sh.cycle.phase, se.cycle.phase, 1e-4);
    assert_close(sh.cycle.e_ts, se.cycle.e_ts, 1e-5 * se.cycle.e_ts);
    assert_true(sh.cycles * 5 < se.cycles);
}

/* Three modes tapping at 13.5 nm (tolerance 3e-8): mode 3's components carry the
 * integrator's error, about the tolerance and not smooth in the state, so Newton stalls
 * at |F| ~ 1e-7, far above its 1e-9 step; within ten tolerances it has converged
 * (src/solver/shooting.c, noise_floor), and agrees with settling to what that floor
 * allows (5.6e-5 deg measured), in under half its cycles. */
static void three_modes_converge_on_a_noisy_map(void **st)
{
    (void)st;
    /* scans/quick.ini's lever and tolerance on the default sample */
    static const char *text = "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\n"
                              "quality_factor = 400\nfree_amplitude = 20 nm\nmodes = 3\n"
                              "[solver]\ntolerance = 3e-8\n"
                              "[approach]\nfrom = 13.5 nm\nto = 13.5 nm\npoints = 1\n";
    tt_approach_point sh = scene_point(text, "shooting"), se = scene_point(text, "settle");
    print_message("shooting %ld cycles, settling %ld: amplitude %.9g / %.9g nm, phase %.9g / %.9g deg, "
                  "|mu| %.6g\n",
                  sh.cycles, se.cycles, sh.cycle.amplitude * 1e9, se.cycle.amplitude * 1e9,
                  sh.cycle.phase * 180 / M_PI, se.cycle.phase * 180 / M_PI, sh.shot.mu_abs);
    assert_true(sh.settled && se.settled);
    assert_int_equal(sh.shot.how, TT_SHOOT_NEWTON);
    assert_true(sh.cycle.contact_fraction > 0);
    assert_close(sh.cycle.amplitude, se.cycle.amplitude, 1e-6 * se.cycle.amplitude);
    assert_close(sh.cycle.phase, se.cycle.phase, 1e-5);
    assert_true(sh.cycles * 2 < se.cycles);
}

/* examples/extreme/bistable.ini at 4 nm: started near the attractive orbit (amplitude
 * 3.9 nm, lag 128 deg) the tip finds it (never touching, phase above 90 deg); started on
 * a tapping motion (4.1 nm, lag 60 deg) it finds the repulsive one (phase below
 * 90 deg). Both are Newton's, both stable; else shooting says which it could not find. */
static void bistable_scene_shows_both_branches(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load(s, TT_SOURCE_DIR "/examples/extreme/bistable.ini"), TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_shoot_params p;
    tt_shoot_default(&p);
    tt_shoot_result r[2];
    tt_cycle cy[2];
    for (int b = 0; b < 2; b++) {
        int settled;
        const tt_cantilever *c = tt_sim_cantilever(tt_setup_sim(su));
        double A = b ? 4.1e-9 : 3.9e-9, lag = (b ? 60 : 128) * M_PI / 180;
        tt_sim_set_state(tt_setup_sim(su), c->a_d + A * cos(lag), A * c->wd * sin(lag), 0);
        tt_sim_set_sample(tt_setup_sim(su), 4e-9, 0);
        assert_int_equal(tt_shoot_steady(tt_setup_sim(su), &p, 20000, 1e-7, &cy[b], &settled, &r[b]), TT_OK);
        print_message("%s: %s, amplitude %.6f nm, phase %.3f deg, |mu| %.6g, %ld cycles %s\n",
                      b ? "from tapping" : "from hovering",
                      r[b].how == TT_SHOOT_NEWTON ? "Newton" : "settled", cy[b].amplitude * 1e9,
                      cy[b].phase * 180 / M_PI, r[b].mu_abs, r[b].cycles, r[b].why);
        assert_true(settled);
        if (r[b].how != TT_SHOOT_NEWTON)
            assert_true(strlen(r[b].why) > 0);
        else
            assert_true(r[b].mu_abs < 1);
    }
    assert_int_equal(r[0].how, TT_SHOOT_NEWTON);
    assert_int_equal(r[1].how, TT_SHOOT_NEWTON);
    assert_true(cy[0].phase > M_PI / 2 && cy[0].contact_fraction == 0);
    assert_true(cy[1].phase < M_PI / 2 && cy[1].contact_fraction > 0);
    assert_true(cy[1].amplitude > cy[0].amplitude + 0.02 * 5e-9);
    tt_setup_free(su);
    tt_scene_free(s);
}

/* A damped rotation's monodromy, r R(a) sheared by [1 0.1; 0 1]: its determinant r^2,
 * its multipliers a complex pair of modulus r. */
static void monodromy2(double J[4])
{
    const double r = 0.93, a = 0.7, c = r * cos(a), s = r * sin(a);
    J[0] = c;
    J[1] = 0.1 * c - s;
    J[2] = s;
    J[3] = 0.1 * s + c;
}

static void generic_algebra_equals_closed_forms_at_n2(void **state)
{
    (void)state;
    double J[4], A[4], b[2] = {0.3, -1.1}, s2[2], sg[2];
    monodromy2(J);
    memcpy(A, J, sizeof A);
    assert_int_equal(tt_shoot_solve(2, A, b, s2, 0), 1);
    memcpy(A, J, sizeof A);
    assert_int_equal(tt_shoot_solve(2, A, b, sg, 1), 1);
    for (int i = 0; i < 2; i++)
        assert_close(sg[i], s2[i], 1e-13 * fabs(s2[i]));
    double re2[2], im2[2], reg[2], img[2];
    assert_int_equal(tt_shoot_eigen(2, J, re2, im2, 0), 1);
    assert_int_equal(tt_shoot_eigen(2, J, reg, img, 1), 1);
    /* the pair in either order: compare by the imaginary part's sign */
    for (int i = 0; i < 2; i++) {
        const int k = (img[i] > 0) == (im2[0] > 0) ? 0 : 1;
        assert_close(reg[i], re2[k], 1e-13);
        assert_close(img[i], im2[k], 1e-13);
    }
    assert_true(fabs(im2[0]) > 0.1);
    assert_close(hypot(re2[0], im2[0]), 0.93, 1e-14);
    double M2[4], Mg[4];
    assert_int_equal(tt_shoot_lyapunov(2, J, M2, 0), 1);
    assert_int_equal(tt_shoot_lyapunov(2, J, Mg, 1), 1);
    for (int i = 0; i < 4; i++)
        assert_close(Mg[i], M2[i], 1e-12 * fabs(M2[0]));
    /* a singular matrix is refused by both */
    double S[4] = {1, 2, 2, 4};
    memcpy(A, S, sizeof A);
    assert_int_equal(tt_shoot_solve(2, A, b, s2, 0), 0);
    memcpy(A, S, sizeof A);
    assert_int_equal(tt_shoot_solve(2, A, b, sg, 1), 0);
}

static void algebra_n4_known_spectrum(void **state)
{
    (void)state;
    /* block diagonal: a rotation r e^(+-i a) and two real multipliers, mixed by a
     * similarity transform T (upper triangular, unit diagonal): J = T D T^-1 */
    enum { n = 4 };
    const double r = 0.9, a = 0.4, l2 = 0.5, l3 = -0.2;
    double D[n * n] = {r * cos(a), -r * sin(a), 0, 0, r * sin(a), r * cos(a), 0, 0,
                       0, 0, l2, 0, 0, 0, 0, l3};
    double T[n * n] = {1, 0.3, -0.2, 0.1, 0, 1, 0.5, -0.4, 0, 0, 1, 0.7, 0, 0, 0, 1};
    double Ti[n * n], TD[n * n], J[n * n];
    for (int c = 0; c < n; c++) { /* T^-1 column by column, by the solver */
        double A[n * n], e[n] = {0}, col[n];
        memcpy(A, T, sizeof A);
        e[c] = 1;
        assert_int_equal(tt_shoot_solve(n, A, e, col, 0), 1);
        for (int i = 0; i < n; i++)
            Ti[i * n + c] = col[i];
    }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            TD[i * n + j] = 0;
            for (int k = 0; k < n; k++)
                TD[i * n + j] += T[i * n + k] * D[k * n + j];
        }
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            J[i * n + j] = 0;
            for (int k = 0; k < n; k++)
                J[i * n + j] += TD[i * n + k] * Ti[k * n + j];
        }
    double re[n], im[n];
    assert_int_equal(tt_shoot_eigen(n, J, re, im, 0), 1);
    int complex = 0, got2 = 0, got3 = 0;
    for (int i = 0; i < n; i++) {
        if (fabs(im[i]) > 1e-9) {
            complex++;
            assert_close(hypot(re[i], im[i]), r, 1e-12);
            assert_close(fabs(atan2(im[i], re[i])), a, 1e-12);
        } else {
            got2 += fabs(re[i] - l2) < 1e-12;
            got3 += fabs(re[i] - l3) < 1e-12;
        }
    }
    assert_int_equal(complex, 2);
    assert_int_equal(got2, 1);
    assert_int_equal(got3, 1);
    /* the Lyapunov equation J^T M J - M = -I holds, and M is positive definite (its
     * quadratic form on the unit vectors and a mixed one is positive) */
    double M[n * n];
    assert_int_equal(tt_shoot_lyapunov(n, J, M, 0), 1);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double g = -M[i * n + j];
            for (int k = 0; k < n; k++)
                for (int l = 0; l < n; l++)
                    g += J[k * n + i] * M[k * n + l] * J[l * n + j];
            assert_close(g, i == j ? -1 : 0, 1e-10);
        }
    for (int i = 0; i < n; i++)
        assert_true(M[i * n + i] > 1);
}

/* The generic eigenvalues on a worker thread leave GSL's process-wide error handler
 * alone (src/solver/shooting_linalg.c): the handler this thread installs is the one it
 * reads back every time while the worker computes, and the spectrum is right. */
static atomic_int_fast8_t eigen_done;
static void handler_mark(const char *reason, const char *file, int line, int err)
{
    (void)reason, (void)file, (void)line, (void)err;
}

static void *eigen_worker(void *arg)
{
    int *bad = arg;
    /* a 3 x 3 upper triangle: its eigenvalues are its diagonal */
    const double J[9] = {0.5, 1, 2, 0, -0.25, 3, 0, 0, 0.125};
    for (int it = 0; it < 20000; it++) {
        double re[3], im[3];
        if (tt_shoot_eigen(3, J, re, im, 1) != 1)
            (*bad)++;
        double s = re[0] + re[1] + re[2], p = re[0] * re[1] * re[2];
        if (fabs(s - 0.375) > 1e-14 || fabs(p + 0.015625) > 1e-15)
            (*bad)++;
    }
    atomic_store(&eigen_done, 1);
    return NULL;
}

static void eigen_leaves_error_handler(void **st)
{
    (void)st;
    gsl_error_handler_t *old = gsl_set_error_handler(handler_mark);
    int bad = 0;
    long seen = 0, other = 0;
    atomic_store(&eigen_done, 0);
    pthread_t th;
    assert_int_equal(pthread_create(&th, NULL, eigen_worker, &bad), 0);
    while (!atomic_load(&eigen_done)) {
        other += gsl_set_error_handler(handler_mark) != handler_mark;
        seen++;
    }
    assert_int_equal(pthread_join(th, NULL), 0);
    gsl_set_error_handler(old);
    assert_int_equal(bad, 0);
    assert_true(seen > 0);
    if (other)
        fail_msg("GSL's error handler changed %ld times in %ld looks", other, seen);
}

TT_TEST_MAIN(cmocka_unit_test(free_fixed_point_is_the_analytic_steady_state),
             cmocka_unit_test(free_multipliers_are_analytic),
             cmocka_unit_test(standard_scene_agrees_with_settling),
             cmocka_unit_test(three_modes_converge_on_a_noisy_map),
             cmocka_unit_test(bistable_scene_shows_both_branches),
             cmocka_unit_test(generic_algebra_equals_closed_forms_at_n2),
             cmocka_unit_test(algebra_n4_known_spectrum),
             cmocka_unit_test(eigen_leaves_error_handler))
