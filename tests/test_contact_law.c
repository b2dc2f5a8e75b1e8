/* The contact law table (include/tiptap/physics/contact.h): each row gives the forces of
 * its law (Hertz, DMT, JKR, Maugis-Dugdale, custom) as the direct code paths do, the
 * conservative load of the law and the interaction damping apart as its dissipative part:
 * exactly c_i * rate in contact and exactly 0 out of it. */
#include "tt_test.h"
#include "tt_laws.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

static const double CI = 3.7e-7, RATE = -0.0123; /* kg/s and m/s, arbitrary */

/* The row's force, detail and energy agree with one another and with the load and
 * energy the contact gives through tt_contact_load and tt_contact_energy, bit for bit;
 * the dissipative part is c_i * rate in contact and 0 out of it, bit for bit. */
static void check_row(const tt_contact *c, double delta, int in)
{
    const tt_contact_law *law = tt_contact_law_of(c);
    double dPdd, a;
    double P = tt_contact_load(c, delta, in, &dPdd, &a);
    tt_contact_forces f = law->force(c, CI, delta, RATE, in, NULL);
    tt_contact_detail d;
    law->detail(c, CI, delta, RATE, in, NULL, &d);
    if (!(f.conservative == P && d.f.conservative == P && d.stiffness == dPdd && d.radius == a))
        fail_msg("%s at delta %.6g (in %d): force %.17g, detail %.17g (dP/dd %.17g, a %.17g), "
                 "load %.17g (%.17g, %.17g)", law->name, delta, in, f.conservative,
                 d.f.conservative, d.stiffness, d.radius, P, dPdd, a);
    assert_true(tt_contact_force(c, CI, delta, RATE, in, NULL).conservative == P);
    double want = in ? CI * RATE : 0.0;
    assert_true(f.dissipative == want);
    assert_true(d.f.dissipative == want);
    assert_true(d.damping == (in ? CI : 0.0));
    /* with no interaction damping nothing dissipates, in contact or not */
    assert_true(law->force(c, 0.0, delta, RATE, in, NULL).dissipative == 0.0);
    assert_true(law->energy(c, delta, in, NULL) == tt_contact_energy(c, delta, in));
}

/* Hertz (eq. 4): P = K sqrt(R) delta^(3/2), written as the law writes it, and nothing
 * out of contact; with w = 0 any model is Hertz. */
static void hertz_row(void **st)
{
    (void)st;
    tt_contact_params p = {TT_CONTACT_MAUGIS, 2e9, 10e-9, 0.0, 0.3e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_OK);
    const tt_contact_law *law = tt_contact_law_of(c);
    assert_string_equal(law->name, "hertz");
    assert_int_equal(law->state_size, 0);
    for (int i = -3; i <= 10; i++) {
        double delta = 0.37e-9 * i;
        for (int in = 0; in <= 1; in++) {
            check_row(c, delta, in);
            tt_contact_detail d;
            tt_contact_evaluate(c, CI, delta, RATE, in, NULL, &d);
            double ra = delta > 0 ? sqrt(p.R * delta) : 0;
            assert_true(d.f.conservative == (delta > 0 ? p.K * ra * delta : 0.0));
            assert_true(d.stiffness == (delta > 0 ? 1.5 * p.K * sqrt(p.R * delta) : 0.0));
            assert_true(d.radius == ra);
        }
    }
    tt_contact_free(c);
}

/* DMT (eq. 5) in normalised units: Delta = A^2, P = A^3 - 2 in contact; van der Waals
 * P = -2 xi^2 / (Delta - xi)^2 out of it (joined at (0, -2)). */
static void dmt_row(void **st)
{
    (void)st;
    const double xi = 0.3;
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_DMT, 0, xi), TT_OK);
    assert_string_equal(tt_contact_law_of(c)->name, "dmt");
    for (double A = 0.05; A < 30; A *= 1.3) {
        tt_contact_forces f = tt_contact_force(c, CI, A * A, RATE, 1, NULL);
        assert_close(f.conservative, A * A * A - 2, 1e-7 * fmax(1, A * A * A));
        assert_true(f.dissipative == CI * RATE);
        check_row(c, A * A, 1);
    }
    for (double D = -5; D <= 0.1; D += 0.05) {
        tt_contact_forces f = tt_contact_force(c, CI, D, RATE, 0, NULL);
        assert_close(f.conservative, -2 * xi * xi / ((D - xi) * (D - xi)), 1e-14);
        assert_true(f.dissipative == 0.0);
        check_row(c, D, 0);
    }
    tt_contact_free(c);
}

/* JKR (eq. 6): Delta = A^2 - 2/3 sqrt(6 A), P = A^3 - A sqrt(6 A) on the stable branch
 * (past the fold at A = (1/6)^(1/3)); no force out of contact. */
static void jkr_row(void **st)
{
    (void)st;
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_JKR, 0, 0.3), TT_OK);
    assert_string_equal(tt_contact_law_of(c)->name, "jkr");
    for (double A = 0.7; A < 30; A *= 1.3) {
        double r = sqrt(6 * A), D = A * A - 2.0 / 3.0 * r;
        tt_contact_forces f = tt_contact_force(c, CI, D, RATE, 1, NULL);
        assert_close(f.conservative, A * A * A - A * r, 1e-7 * fmax(1, A * A * A));
        assert_true(f.dissipative == CI * RATE);
        check_row(c, D, 1);
        check_row(c, D, 0);
        assert_true(tt_contact_force(c, CI, D, RATE, 0, NULL).conservative == 0.0);
    }
    tt_contact_free(c);
}

/* Maugis-Dugdale (eq. 7) at the curve's own points, below and above the fold's onset
 * (lambda = 0.938), in normalised and in physical units. */
static void maugis_row(void **st)
{
    (void)st;
    const double lambdas[] = {0.3, 2.0};
    for (int k = 0; k < 2; k++) {
        tt_contact *c;
        assert_int_equal(tt_contact_alloc_normalised(&c, TT_CONTACT_MAUGIS, lambdas[k], 0.3), TT_OK);
        assert_string_equal(tt_contact_law_of(c)->name, "maugis");
        const tt_contact_summary *s = tt_contact_summary_of(c);
        int n = 0;
        for (double e = 1e-4; e < 10; e *= 1.2) {
            double m = 1 + e, A, D, P, A2, D2, P2;
            tt_contact_maugis_point(lambdas[k], m, &A, &D, &P);
            tt_contact_maugis_point(lambdas[k], m * 1.0001, &A2, &D2, &P2);
            if (!(D2 < D) || D <= s->jumpout_delta + 1e-6)
                continue; /* the unstable branch: Delta falls as A grows (m falls) */
            tt_contact_detail d;
            tt_contact_evaluate(c, CI, D, RATE, 1, NULL, &d);
            assert_close(d.f.conservative, P, 1e-7 * fmax(1, fabs(P)));
            assert_close(d.radius, A, 1e-7 * fmax(1, A));
            assert_true(d.f.dissipative == CI * RATE);
            check_row(c, D, 1);
            n++;
        }
        assert_true(n > 10);
        for (double D = -3; D < s->jumpin_delta; D += 0.1)
            check_row(c, D, 0);
        tt_contact_free(c);
    }
    /* physical units: the same row scales by F* and d* */
    tt_contact_params p = {TT_CONTACT_MAUGIS, 1e9, 20e-9, 0.05, 0.3e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_OK);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    for (int i = 0; i < 40; i++) {
        double delta = s->depth_scale * (-2 + 0.25 * i);
        check_row(c, delta, 1);
        check_row(c, delta, 0);
    }
    tt_contact_free(c);
}

/* The caller's law: its load and stiffness as given, no radius, the damping the table's. */
static void custom_row(void **st)
{
    (void)st;
    double k3 = 4e25;
    tt_contact *c;
    assert_int_equal(tt_contact_alloc_custom(&c, tt_cubic_load, tt_cubic_energy, &k3, 0, 0), TT_OK);
    assert_string_equal(tt_contact_law_of(c)->name, "custom");
    for (int i = -2; i <= 8; i++) {
        double delta = 0.25e-9 * i, dP;
        double P = tt_cubic_load(delta, 1, &dP, &k3);
        for (int in = 0; in <= 1; in++) {
            tt_contact_detail d;
            tt_contact_evaluate(c, CI, delta, RATE, in, NULL, &d);
            assert_true(d.f.conservative == P);
            assert_true(d.stiffness == dP);
            assert_true(d.radius == 0.0);
            check_row(c, delta, in);
        }
    }
    tt_contact_free(c);
}

/* The solver's force at a sample (tt_sim_force): the law's load plus c_i = m* w0 / Q_i
 * times the penetration rate v - s' in contact, the load alone out of it. */
static void sim_force_is_the_rows(void **st)
{
    (void)st;
    tt_contact_params p = {TT_CONTACT_HERTZ, 2e9, 10e-9, 0.0, 0.3e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *c;
    assert_int_equal(tt_contact_alloc(&c, &p), TT_OK);
    tt_cantilever cl;
    tt_cantilever_init(&cl, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE);
    tt_solver sv;
    tt_solver_default(&sv);
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &cl, &sv), TT_OK);
    const double Qi = 10, sdot = 1e-6;
    tt_sim_set_contact(sim, c, Qi);
    tt_sim_set_sample(sim, 0, sdot);
    const double ci = cl.m * cl.w0 / Qi, delta = 1e-9, v = 0.3;
    tt_sample smp = {.d = delta, .v = v, .contact = 1, .f = NAN};
    double a, load = p.K * sqrt(p.R * delta) * delta;
    assert_close(tt_sim_force(sim, &smp, &a), load + ci * (v - sdot), 1e-12 * load);
    assert_close(a, sqrt(p.R * delta), 1e-20);
    smp.contact = 0;
    assert_close(tt_sim_force(sim, &smp, &a), load, 1e-12 * load);
    tt_sim_free(sim);
    tt_contact_free(c);
}

/* Every model has its row, named as [material] model names it, and no state yet. */
static void rows_by_model(void **st)
{
    (void)st;
    const tt_contact_model models[] = {TT_CONTACT_MAUGIS, TT_CONTACT_HERTZ, TT_CONTACT_DMT,
                                       TT_CONTACT_JKR};
    for (int i = 0; i < 4; i++) {
        tt_contact *c;
        assert_int_equal(tt_contact_alloc_normalised(&c, models[i], 1.0, 0.3), TT_OK);
        const tt_contact_law *law = tt_contact_law_of(c);
        assert_string_equal(law->name, tt_contact_model_name(models[i]));
        assert_int_equal(law->state_size, 0);
        tt_contact_model back;
        assert_int_equal(tt_contact_model_parse(law->name, &back), 0);
        assert_int_equal(back, models[i]);
        tt_contact_free(c);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(hertz_row),  cmocka_unit_test(dmt_row),    cmocka_unit_test(jkr_row),
        cmocka_unit_test(maugis_row), cmocka_unit_test(custom_row), cmocka_unit_test(rows_by_model),
        cmocka_unit_test(sim_force_is_the_rows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
