/* The generalised Maxwell sample (src/physics/contact_sls.c) and its surface's state
 * through the solver: relaxation under a held indentation and creep under a held load
 * follow the standard linear solid's exponentials, the free surface recovers on its
 * retardation time, a zero arm is the elastic law, and the energy balance closes with
 * the arms' loss booked as e_visc. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tt_test.h"
#include "solver/sim.h"
#include "tiptap/config/config.h"
#include "tiptap/config/scene.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

enum { NARM = 1 };
static const double K_E = 0.2e9, K_1 = 2e9, TAU = 1e-6, R_TIP = 10e-9;

static tt_contact *sls(double K1, double tau)
{
    tt_contact_params p = {TT_CONTACT_HERTZ, K_E, R_TIP, 0, 0.3e-9, NAN, 0, 0, NARM, {K1}, {tau}};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_OK);
    return c;
}

/* chi = delta sqrt(delta / R), the Hertz load's P = K R chi in length units. */
static double chi_of(double delta) { return delta * sqrt(delta / R_TIP); }

/* One classic RK4 step of the arm's state under the law's rate at a held delta. */
static void rk4_held(const tt_contact *c, double delta, double *q, double h)
{
    const tt_contact_law *L = tt_contact_law_of(c);
    double k[4], y, pw;
    L->rate(c, delta, 0, 1, q, &k[0], &pw);
    y = *q + 0.5 * h * k[0];
    L->rate(c, delta, 0, 1, &y, &k[1], &pw);
    y = *q + 0.5 * h * k[1];
    L->rate(c, delta, 0, 1, &y, &k[2], &pw);
    y = *q + h * k[2];
    L->rate(c, delta, 0, 1, &y, &k[3], &pw);
    *q += h / 6 * (k[0] + 2 * k[1] + 2 * k[2] + k[3]);
}

/* A held indentation: P(t) = R chi (K_e + K_1 exp(-t / tau)), from the glassy to the
 * relaxed load on the relaxation time. */
static void relaxation_under_held_indentation(void **state)
{
    (void)state;
    tt_contact *c = sls(K_1, TAU);
    assert_int_equal((int)tt_contact_law_of(c)->state_size, 1);
    const double delta = 2e-9, h = TAU / 1000;
    double q = 0, worst = 0;
    for (int i = 1; i <= 5000; i++) {
        rk4_held(c, delta, &q, h);
        double t = i * h, P = tt_contact_force(c, 0, delta, 0, 1, &q).conservative;
        double exact = R_TIP * chi_of(delta) * (K_E + K_1 * exp(-t / TAU));
        worst = fmax(worst, fabs(P - exact) / exact);
    }
    if (!(worst < 1e-10))
        fail_msg("relaxation off its exponential by %.3g (relative)", worst);
    tt_contact_free(c);
}

/* A held load F: chi(t) = F / (R K_e) - F / R (1 / K_e - 1 / K_g) exp(-t / tau_c), the
 * creep on the retardation time tau_c = tau K_g / K_e. The penetration that carries F
 * at each state is the load's inverse in chi. */
static void creep_under_held_load(void **state)
{
    (void)state;
    tt_contact *c = sls(K_1, TAU);
    const tt_contact_law *L = tt_contact_law_of(c);
    const double F = 5e-9, Kg = K_E + K_1, tc = TAU * Kg / K_E, h = tc / 1000;
    double q = 0, worst = 0;
    for (int i = 1; i <= 5000; i++) {
        double k[4], y[4] = {q}, pw;
        static const double a[4] = {0, 0.5, 0.5, 1};
        for (int j = 0; j < 4; j++) {
            if (j)
                y[j] = q + a[j] * h * k[j - 1];
            double chi = (F / R_TIP + K_1 * y[j]) / Kg, delta = cbrt(R_TIP * chi * chi);
            L->rate(c, delta, 0, 1, &y[j], &k[j], &pw);
        }
        q += h / 6 * (k[0] + 2 * k[1] + 2 * k[2] + k[3]);
        double chi = (F / R_TIP + K_1 * q) / Kg, t = i * h;
        double exact = F / (R_TIP * K_E) - F / R_TIP * (1 / K_E - 1 / Kg) * exp(-t / tc);
        worst = fmax(worst, fabs(chi - exact) / exact);
        double P = tt_contact_force(c, 0, cbrt(R_TIP * chi * chi), 0, 1, &q).conservative;
        assert_true(fabs(P - F) < 1e-9 * F);
    }
    if (!(worst < 1e-10))
        fail_msg("creep off its exponential by %.3g (relative)", worst);
    tt_contact_free(c);
}

/* The standard cantilever (40 N/m, 300 kHz, Q 400, 20 nm) over contact c, the sample
 * at rest separation s, at tolerance 1e-10 (the elastic run's own energy residual is
 * 4e-6 of the free loss at 1e-8 on this soft sample, 9e-8 at 1e-10). */
static tt_sim *cantilever(const tt_contact *c, double s, tt_method m)
{
    tt_cantilever cl;
    assert_int_equal(tt_cantilever_init(&cl, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver sv;
    tt_solver_default(&sv);
    sv.method = m;
    sv.steps_per_cycle = 4096;
    sv.tolerance = 1e-10;
    tt_sim *S;
    assert_int_equal(tt_sim_alloc(&S, &cl, &sv), TT_OK);
    tt_sim_set_contact(S, c, NAN);
    tt_sim_set_sample(S, s, 0);
    return S;
}

/* The arm's state that holds the free surface at depression u0, the tip out of
 * contact: chi_f = K_1 q / K_g. */
static void press_surface(tt_sim *S, double u0)
{
    double x[3];
    int contact;
    tt_sim_get_x(S, x, &contact);
    x[2] = chi_of(u0) * (K_E + K_1) / K_1;
    tt_sim_set_x(S, x, 0);
}

/* A surface pressed in and left alone, the tip oscillating far above it: its
 * depression u follows u^(3/2) = u0^(3/2) exp(-t / tau_c) (chi_f decays so), sampled
 * through two cycles, on each method. */
static void free_surface_recovers(void **state)
{
    (void)state;
    const tt_method methods[3] = {TT_METHOD_DOPRI5, TT_METHOD_RK4, TT_METHOD_RADAU};
    for (int k = 0; k < 3; k++) {
        tt_contact *c = sls(K_1, TAU);
        tt_sim *S = cantilever(c, 200e-9, methods[k]);
        assert_int_equal(tt_sim_dim(S), 3);
        const double Kg = K_E + K_1, tc = TAU * Kg / K_E, u0 = 1.5e-9;
        press_surface(S, u0);
        enum { NS = 64 };
        tt_sample smp[NS];
        tt_sim_set_sampling(S, NS, smp);
        double worst = 0;
        for (int cyc = 0; cyc < 2; cyc++) {
            tt_cycle out;
            assert_int_equal(tt_sim_cycle(S, &out), TT_OK);
            assert_true(out.contact_fraction == 0);
            for (int i = 0; i < NS; i++) {
                double e = pow(u0, 1.5) * exp(-smp[i].t / tc);
                worst = fmax(worst, fabs(pow(smp[i].u, 1.5) - e) / e);
            }
        }
        if (!(worst < 1e-6))
            fail_msg("%s: the free surface's recovery off its exponential by %.3g (relative)",
                     tt_method_name(methods[k]), worst);
        tt_sim_free(S);
        tt_contact_free(c);
    }
}

/* dopri5's free flight advances the arm's state exactly (exp(A tau), src/solver/
 * flight.c): a surface recovering under the tip far above follows u^(3/2) = u0^(3/2)
 * exp(-t / tau_c) to 1e-9 in the flight's few steps a cycle, and ends where dopri5's
 * own steps put it (the flight kept off by tracking the extremes) within their
 * tolerance. */
static void flight_recovery_exact(void **state)
{
    (void)state;
    const double Kg = K_E + K_1, tc = TAU * Kg / K_E, u0 = 1.5e-9;
    double end[2], worst[2] = {0, 0};
    long steps[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        tt_contact *c = sls(K_1, TAU);
        tt_sim *S = cantilever(c, 200e-9, TT_METHOD_DOPRI5);
        tt_sim_track_extremes(S, k);
        tt_sim_reset_free(S);
        press_surface(S, u0);
        enum { NS = 64 };
        tt_sample smp[NS];
        tt_sim_set_sampling(S, NS, smp);
        for (int cyc = 0; cyc < 2; cyc++) {
            tt_cycle out;
            assert_int_equal(tt_sim_cycle(S, &out), TT_OK);
            steps[k] += out.steps;
            for (int i = 0; i < NS; i++) {
                double e = pow(u0, 1.5) * exp(-smp[i].t / tc);
                worst[k] = fmax(worst[k], fabs(pow(smp[i].u, 1.5) - e) / e);
            }
        }
        double x[3];
        int contact;
        tt_sim_get_x(S, x, &contact);
        end[k] = x[2];
        tt_sim_free(S);
        tt_contact_free(c);
    }
    if (!(worst[0] < 1e-9))
        fail_msg("the flight's recovery off its exponential by %.3g (relative)", worst[0]);
    /* the flight's steps are T / 8 at most (one free period is one drive period here) */
    if (!(steps[0] <= 2 * 9 && steps[0] < steps[1]))
        fail_msg("%ld flight steps against dopri5's %ld in two cycles", steps[0], steps[1]);
    if (!(fabs(end[0] - end[1]) <= 1e-9 * end[1]))
        fail_msg("the flight's state %.17g against dopri5's %.17g", end[0], end[1]);
}

/* One arm of zero modulus and a relaxation time past any run is the Hertz law: each
 * cycle's figures as the elastic run's, to the solver's tolerance (the two differ in
 * the rounding of the load and in the elastic run's free flight; 1e-7 of the peak force
 * at tolerance 1e-10, 3e-6 at 1e-8: the integration's error, not the law's). */
static void zero_arm_is_elastic(void **state)
{
    (void)state;
    tt_contact_params pe = {TT_CONTACT_HERTZ, K_E, R_TIP, 0, 0.3e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ce, *cs = sls(0, 1e300);
    assert_int_equal(tt_contact_alloc(&ce, &pe), TT_OK);
    tt_sim *Se = cantilever(ce, 17e-9, TT_METHOD_DOPRI5), *Ss = cantilever(cs, 17e-9, TT_METHOD_DOPRI5);
    double worst = 0;
    for (int i = 0; i < 60; i++) {
        tt_cycle a, b;
        assert_int_equal(tt_sim_cycle(Se, &a), TT_OK);
        assert_int_equal(tt_sim_cycle(Ss, &b), TT_OK);
        worst = fmax(worst, fabs(a.amplitude - b.amplitude) / a.amplitude);
        worst = fmax(worst, fabs(a.phase - b.phase));
        worst = fmax(worst, fabs(a.mean - b.mean) / a.amplitude);
        if (a.contact_fraction > 0)
            worst = fmax(worst, fabs(a.peak_force - b.peak_force) / a.peak_force);
        assert_true(b.e_visc == 0);
        assert_int_equal(a.events, b.events);
    }
    if (!(worst < 1e-6))
        fail_msg("a zero arm differs from the elastic law by %.3g", worst);
    tt_sim_free(Se);
    tt_sim_free(Ss);
    tt_contact_free(ce);
    tt_contact_free(cs);
}

/* Tapping the standard linear solid: every cycle's energy balance closes with the arms'
 * loss booked as e_visc (positive, the tip-sample loss's whole but the interaction
 * damping's), on each method. */
static void energy_balance_closes(void **state)
{
    (void)state;
    const tt_method methods[3] = {TT_METHOD_DOPRI5, TT_METHOD_RK4, TT_METHOD_RADAU};
    for (int k = 0; k < 3; k++) {
        tt_contact *c = sls(K_1, 0.3e-6);
        tt_sim *S = cantilever(c, 17e-9, methods[k]);
        tt_sim_set_contact(S, c, 30);
        double worst = 0, visc = 0;
        for (int i = 0; i < 80; i++) {
            tt_cycle out;
            assert_int_equal(tt_sim_cycle(S, &out), TT_OK);
            worst = fmax(worst, out.residual_rel);
            if (out.contact_fraction > 0) {
                assert_true(out.e_visc > 0);
                assert_true(fabs(out.e_ts - out.e_visc - out.e_ci - out.e_hyst) <= 1e-12 * out.e_ts);
                assert_true(fabs(out.e_hyst) < 1e-6 * out.e_visc);
                visc += out.e_visc;
            }
        }
        assert_true(visc > 0);
        if (!(worst < 1e-6))
            fail_msg("%s: energy residual %.3g of the free loss", tt_method_name(methods[k]), worst);
        tt_sim_free(S);
        tt_contact_free(c);
    }
}

/* Bad arms are refused before anything is built. */
static void bad_arms_refused(void **state)
{
    (void)state;
    tt_contact *c;
    tt_contact_params p = {TT_CONTACT_HERTZ, K_E, R_TIP, 0, 0.3e-9, NAN, 0, 0, 1, {-1}, {TAU}};
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
    p.arm_modulus[0] = K_1;
    p.arm_time[0] = 0;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
    p.arm_time[0] = TAU;
    p.viscosity = 1;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
    p.viscosity = 0;
    p.model = TT_CONTACT_MAUGIS;
    p.w = 0.05;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
    p.arms = 5;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_EINVAL);
    tt_error_clear();
}

/* A scene's arms are checked with one line naming the file, section and key: materials
 * (scan 0) or the scan's tier (scan 1). */
static void expect_scene_error(const char *text, int scan, const char *fragment)
{
    tt_scene *s = tt_scene_alloc();
    tt_error_clear();
    assert_int_equal(tt_scene_load_string(s, text, "t.ini"), TT_OK);
    int rc;
    if (scan) {
        tt_scan_params p;
        rc = tt_config_scan(s, &p);
        if (rc == TT_OK)
            tt_config_scan_free(&p);
    } else {
        tt_material *m = NULL;
        size_t n = 0;
        rc = tt_config_materials(s, &m, &n);
        free(m);
    }
    const char *msg = tt_error_message();
    if (rc == TT_OK || !strstr(msg, "t.ini: [") || !strstr(msg, fragment) || strchr(msg, '\n'))
        fail_msg("%s -> '%s' (wanted one line with '%s')", text, rc ? msg : "accepted", fragment);
    tt_scene_free(s);
    tt_error_clear();
}

static void scene_arms_refused(void **state)
{
    (void)state;
    const char *arm = "[material p]\nmodel = hertz\narm1_modulus = 1 GPa\n";
    expect_scene_error(arm, 0, "arm1_modulus: needs arm1_relaxation_time");
    expect_scene_error("[material p]\nmodel = hertz\narm2_modulus = 1 GPa\narm2_relaxation_time = 1 us\n",
                       0, "arm1 is missing");
    expect_scene_error("[material p]\nadhesion_energy = 50 mJ/m^2\narm1_modulus = 1 GPa\n"
                       "arm1_relaxation_time = 1 us\n", 0, "the Hertz law alone");
    /* every tier takes the arms: the envelope tier (the default) plans the arm's state
     * as an input (tests/test_envelope_arms.c), the averaged tier tabulates its periodic
     * cycle (tests/test_averaged_arms.c); two modes run every cycle only */
    const char *sls = "[material p]\nmodel = hertz\narm1_modulus = 1 GPa\narm1_relaxation_time = 1 us\n";
    const char *tiers[3] = {"every", "envelope", "averaged"};
    for (int i = 0; i < 3; i++) {
        char text[256];
        snprintf(text, sizeof text, "%s[solver]\ntier = %s\n", sls, tiers[i]);
        tt_scene *s = tt_scene_alloc();
        assert_int_equal(tt_scene_load_string(s, text, "t.ini"), TT_OK);
        tt_scan_params p;
        assert_int_equal(tt_config_scan(s, &p), TT_OK);
        tt_config_scan_free(&p);
        tt_scene_free(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(relaxation_under_held_indentation),
        cmocka_unit_test(creep_under_held_load),
        cmocka_unit_test(free_surface_recovers),
        cmocka_unit_test(flight_recovery_exact),
        cmocka_unit_test(zero_arm_is_elastic),
        cmocka_unit_test(energy_balance_closes),
        cmocka_unit_test(bad_arms_refused),
        cmocka_unit_test(scene_arms_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
