/* The implicit method (radau, Radau IIA of order 5): it converges at its order on a
 * smooth force law, and on a contact thousands of times stiffer than the cantilever
 * with heavy interaction damping it agrees with a tight dopri5 reference, keeps the
 * energy balance, and needs far fewer steps than dopri5 while the tip stays in contact. */
#include "tt_test.h"
#include "tt_laws.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"
#include "tiptap/solver/integrator.h"

/* ---- convergence: the tapping scene of test_convergence.c on a smooth law ---- */

static tt_cycle run_standard(const tt_contact *ct, double Qi, tt_method m, double tol, double *spc)
{
    return tt_run_tapping(ct, Qi, m, 0, tol, spc);
}

static void radau_converges_at_fifth_order(void **st)
{
    (void)st;
    /* An adaptive method has no step count to halve: its order shows as the slope of
     * the error against the steps it took, error ~ (steps per cycle)^-5. */
    double k3 = 3e18;
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc_custom(&ct, tt_cubic_load, tt_cubic_energy, &k3, 0, 0), TT_OK);
    tt_cycle ref = run_standard(ct, 10, TT_METHOD_DOPRI5, 1e-14, NULL);
    assert_true(ref.contact_fraction > 0.05);
    /* least-squares slopes of log error against log steps over six tolerances */
    enum { NT = 6 };
    double sx = 0, sxx = 0, sy[3] = {0, 0, 0}, sxy[3] = {0, 0, 0};
    for (int i = 0; i < NT; i++) {
        double tol = pow(10.0, -6 - i), n;
        tt_cycle cy = run_standard(ct, 10, TT_METHOD_RADAU, tol, &n);
        double e[3] = {fabs(cy.amplitude - ref.amplitude) / ref.amplitude, fabs(cy.phase - ref.phase),
                       fabs(cy.t_contact - ref.t_contact) / 3.33e-6};
        print_message("radau tol %.0e: %.1f steps per cycle, amplitude error %.3g, phase %.3g rad, "
                      "contact time %.3g of T\n",
                      tol, n, e[0], e[1], e[2]);
        double x = log(n);
        sx += x;
        sxx += x * x;
        for (int q = 0; q < 3; q++) {
            sy[q] += log(e[q]);
            sxy[q] += x * log(e[q]);
        }
    }
    double p[3];
    for (int q = 0; q < 3; q++)
        p[q] = -(NT * sxy[q] - sx * sy[q]) / (NT * sxx - sx * sx);
    print_message("radau observed order: amplitude %.2f phase %.2f contact time %.2f\n", p[0], p[1],
                  p[2]);
    for (int q = 0; q < 3; q++)
        assert_between(p[q], 4.5, 5.5);
    tt_contact_free(ct);
}

/* ---- a very stiff, heavily damped contact under a soft cantilever ---- */

typedef struct {
    tt_cycle last;
    double steps, rejected, max_residual;
} stiff_run;

/* 0.1 N/m, 10 kHz, Q 100, 20 nm free amplitude over a 1 TPa Hertz contact (R = 10 nm,
 * no adhesion) with Q_i = 0.03: in contact the load's stiffness is thousands of times
 * k_c and the interaction damping 33 m* w0. */
static int stiff(double gap, tt_method m, double tol, int steps_per_cycle, stiff_run *r)
{
    tt_contact_params p = {TT_CONTACT_MAUGIS, 1e12, 10e-9, 0, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 0.1, 10e3, 100, 20e-9, 10e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.method = m;
    s.tolerance = tol;
    s.steps_per_cycle = steps_per_cycle;
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sim_set_contact(sim, ct, 0.03);
    tt_sim_set_sample(sim, gap, 0);
    /* 300 cycles from the free state (the transient decays over Q / pi = 32 cycles), so
     * that runs compare at the same cycle; the last 50 are measured. */
    int rc = TT_OK;
    memset(r, 0, sizeof *r);
    for (int i = 0; i < 300 && rc == TT_OK; i++) {
        rc = tt_sim_cycle(sim, &r->last);
        if (rc == TT_OK && i >= 250) {
            r->steps += r->last.steps / 50.0;
            r->rejected += r->last.rejected / 50.0;
            r->max_residual = fmax(r->max_residual, r->last.residual_rel);
        }
    }
    tt_sim_free(sim);
    tt_contact_free(ct);
    return rc;
}

static void radau_on_a_very_stiff_contact(void **st)
{
    (void)st;
    /* Intermittent contact at 15 nm rest separation: a brief, hard impact each cycle. */
    stiff_run ref, d5, ra;
    assert_int_equal(stiff(15e-9, TT_METHOD_DOPRI5, 1e-12, 0, &ref), TT_OK);
    assert_int_equal(stiff(15e-9, TT_METHOD_DOPRI5, 1e-8, 0, &d5), TT_OK);
    assert_int_equal(stiff(15e-9, TT_METHOD_RADAU, 1e-8, 0, &ra), TT_OK);
    double dPdd;
    tt_contact_params p = {TT_CONTACT_MAUGIS, 1e12, 10e-9, 0, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    (void)tt_contact_load(ct, ref.last.max_indentation, 1, &dPdd, NULL);
    tt_contact_free(ct);
    print_message("tapping, 15 nm: amplitude %.4f nm, phase %.3f deg, contact %.2f %% of the cycle, "
                  "contact stiffness %.0f k_c\n",
                  ref.last.amplitude * 1e9, ref.last.phase * 180 / M_PI,
                  100 * ref.last.contact_fraction, dPdd / 0.1);
    print_message("  steps per cycle at tolerance 1e-8: dopri5 %.1f (+%.1f rejected), radau %.1f "
                  "(+%.1f rejected)\n",
                  d5.steps, d5.rejected, ra.steps, ra.rejected);
    print_message("  radau: amplitude error %.2g of A0, phase %.2g rad, residual %.2g\n",
                  fabs(ra.last.amplitude - ref.last.amplitude) / 20e-9,
                  fabs(ra.last.phase - ref.last.phase), ra.max_residual);
    assert_true(dPdd > 1000 * 0.1);
    assert_true(ref.last.contact_fraction > 0);
    assert_true(isfinite(ra.last.amplitude) && isfinite(ra.last.phase));
    assert_close(ra.last.amplitude, ref.last.amplitude, 1e-6 * 20e-9);
    assert_close(ra.last.phase, ref.last.phase, 1e-5);
    assert_close(ra.last.e_ts, ref.last.e_ts, 1e-5 * ref.last.e_ts);
    assert_true(ra.max_residual < 1e-6);

    /* Pressed against the sample (1 nm past the rest position): the tip stays in contact,
     * where dopri5's steps are held by stability to the contact's time scale and radau's
     * only by accuracy. */
    assert_int_equal(stiff(-1e-9, TT_METHOD_DOPRI5, 1e-12, 0, &ref), TT_OK);
    assert_int_equal(stiff(-1e-9, TT_METHOD_DOPRI5, 1e-8, 0, &d5), TT_OK);
    assert_int_equal(stiff(-1e-9, TT_METHOD_RADAU, 1e-8, 0, &ra), TT_OK);
    print_message("in contact, -1 nm: amplitude %.4f nm, phase %.3f deg; steps per cycle at 1e-8: "
                  "dopri5 %.1f, radau %.1f\n",
                  ref.last.amplitude * 1e9, ref.last.phase * 180 / M_PI, d5.steps, ra.steps);
    print_message("  radau: amplitude error %.2g of A0, phase %.2g rad, residual %.2g\n",
                  fabs(ra.last.amplitude - ref.last.amplitude) / 20e-9,
                  fabs(ra.last.phase - ref.last.phase), ra.max_residual);
    assert_true(ref.last.contact_fraction > 1 - 1e-9);
    assert_close(ra.last.amplitude, ref.last.amplitude, 1e-8 * 20e-9);
    assert_close(ra.last.phase, ref.last.phase, 1e-6);
    assert_true(ra.max_residual < 1e-8);
    assert_true(ra.steps < d5.steps / 3);

    /* rk4 at 64 steps per cycle refuses such a contact (h w_contact about 6), and
     * points to both adaptive methods. */
    assert_int_equal(stiff(15e-9, TT_METHOD_RK4, 0, 64, &ra), TT_ENUM);
    print_message("rk4, 64 steps: %s\n", tt_error_message());
    assert_non_null(strstr(tt_error_message(), "use method = dopri5"));
    assert_non_null(strstr(tt_error_message(), "radau"));
}

/* ---- events with hysteresis: the loss per tap is the loop's area ---- */

static void radau_hysteresis_loss_is_the_loop_area(void **st)
{
    (void)st;
    /* test_tapping_energy.c's soft, sticky sample (lambda about 2.5): jump-in and
     * pull-off are located on the collocation polynomial. */
    tt_contact_params p = {TT_CONTACT_MAUGIS, 1e9, 10e-9, 0.1, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    const tt_contact_summary *sum = tt_contact_summary_of(ct);
    assert_true(sum->hysteresis);
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.method = TT_METHOD_RADAU;
    s.tolerance = 1e-10;
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sim_set_contact(sim, ct, NAN);
    tt_sim_set_sample(sim, 15e-9, 0);
    tt_cycle cy;
    int settled;
    long n;
    assert_int_equal(tt_sim_settle(sim, 30000, 1e-9, &cy, &settled, &n), TT_OK);
    assert_true(settled);
    assert_int_equal(cy.events, 2);
    assert_close(cy.e_ts, sum->loop_energy, 1e-6 * sum->loop_energy);
    assert_close(cy.e_drive, cy.e_damp + cy.e_ts, 1e-6 * cy.e_drive);
    tt_sim_free(sim);
    tt_contact_free(ct);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(radau_converges_at_fifth_order),
        cmocka_unit_test(radau_on_a_very_stiff_contact),
        cmocka_unit_test(radau_hysteresis_loss_is_the_loop_area),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
