/* The system's generic n-mode kernels (src/solver/system.c) equal the one-mode elastic
 * system's specialised ones bit for bit at n = 2: the right-hand side and the energy at
 * scattered states, and whole cycles run on either plan. */
#include <stdlib.h>

#include "tt_test.h"
#include "solver/sim.h"
#include "tiptap/physics/contact.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

/* The standard cantilever (40 N/m, 300 kHz, Q 400, 20 nm) over an adhesive Maugis
 * contact (K 1 GPa, R 10 nm, w 0.1 J/m^2) with interaction damping. */
static tt_sim *standard(tt_contact **ct, tt_drive drive, tt_method m)
{
    tt_contact_params p = {TT_CONTACT_MAUGIS, 1e9, 10e-9, 0.1, 0.3e-9, NAN, 0, 0, 0, {0}, {0}};
    assert_int_equal(tt_contact_alloc(ct, &p), TT_OK);
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, drive), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    s.method = m;
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sim_set_contact(sim, *ct, 30);
    tt_sim_set_sample(sim, 15e-9, 2e-6);
    return sim;
}

static void assert_same_bits(const double *a, const double *b, int n, const char *what)
{
    for (int i = 0; i < n; i++)
        if (memcmp(&a[i], &b[i], sizeof a[i]) != 0)
            fail_msg("%s[%d]: specialised %.17g, generic %.17g", what, i, a[i], b[i]);
}

static void kernels_equal_at_n2(void **state)
{
    (void)state;
    const tt_drive drives[2] = {TT_DRIVE_BASE, TT_DRIVE_FORCE};
    srand(29);
    for (int k = 0; k < 2; k++) {
        tt_contact *ct;
        tt_sim *S = standard(&ct, drives[k], TT_METHOD_DOPRI5);
        assert_int_equal(S->sys.n, 2);
        assert_ptr_equal(S->sys.rhs, tt_sim_rhs);
        for (int i = 0; i < 2000; i++) {
            double Y[NY], Fs[NY], Fg[NY];
            for (int j = 0; j < NY; j++)
                Y[j] = (double)rand() / RAND_MAX - 0.5;
            Y[Y_D] = 15e-9 + 25e-9 * ((double)rand() / RAND_MAX - 0.5); /* on both sides */
            Y[Y_V] = 40.0 * ((double)rand() / RAND_MAX - 0.5);
            double tau = S->c.T * rand() / RAND_MAX;
            int in = rand() & 1;
            tt_sim_rhs(S, tau, Y, in, Fs);
            tt_system_rhs_n(S, tau, Y, in, Fg);
            assert_same_bits(Fs, Fg, NY, "rhs");
            double Es = tt_sim_energy(S, tau, Y, in), Eg = tt_system_energy_n(S, tau, Y, in);
            assert_same_bits(&Es, &Eg, 1, "energy");
        }
        tt_sim_free(S);
        tt_contact_free(ct);
    }
}

/* 40 cycles from the free state on each plan: every cycle's figures the same bits. */
static void run(tt_method m, int generic, int noise, tt_cycle *out, int n)
{
    tt_contact *ct;
    tt_sim *S = standard(&ct, TT_DRIVE_BASE, m);
    if (generic)
        tt_system_plan(S, 1);
    if (noise) {
        assert_int_equal(tt_sim_set_thermal(S, 300, 64), TT_OK);
        tt_sim_noise_key(S, tt_noise_key(7, 0, 0));
    }
    tt_sim_reset_free(S);
    for (int i = 0; i < n; i++)
        assert_int_equal(tt_sim_cycle(S, &out[i]), TT_OK);
    tt_sim_free(S);
    tt_contact_free(ct);
}

static void cycles_equal_on_either_plan(void **state)
{
    (void)state;
    enum { N = 40 };
    const tt_method methods[3] = {TT_METHOD_DOPRI5, TT_METHOD_RK4, TT_METHOD_RADAU};
    for (int k = 0; k < 3; k++)
        for (int noise = 0; noise < 2; noise++) {
            tt_cycle a[N], b[N];
            run(methods[k], 0, noise, a, N);
            run(methods[k], 1, noise, b, N);
            assert_true(a[N - 1].events > 0); /* the tip taps */
            for (int i = 0; i < N; i++)
                if (memcmp(&a[i], &b[i], sizeof a[i]) != 0)
                    fail_msg("%s%s: cycle %d differs (amplitude %.17g against %.17g)",
                             tt_method_name(methods[k]), noise ? " with noise" : "", i,
                             a[i].amplitude, b[i].amplitude);
        }
}

/* The n-component state accessors carry the one-mode state as (d, v): what set_x puts in,
 * get_x and get_state read back, and a cycle from either setter ends the same. */
static void state_of_dimension_n(void **state)
{
    (void)state;
    tt_contact *ct, *ct_b;
    tt_sim *a = standard(&ct, TT_DRIVE_BASE, TT_METHOD_DOPRI5);
    tt_sim *b = standard(&ct_b, TT_DRIVE_BASE, TT_METHOD_DOPRI5);
    assert_int_equal(tt_sim_dim(a), 2);
    double x[TT_SIM_DIM_MAX] = {16e-9, -0.01}, y[TT_SIM_DIM_MAX], d, v;
    int contact;
    tt_sim_set_x(a, x, 0);
    tt_sim_get_x(a, y, &contact);
    tt_sim_get_state(a, &d, &v, &contact);
    assert_true(y[0] == x[0] && y[1] == x[1] && d == x[0] && v == x[1] && contact == 0);
    tt_sim_set_state(b, x[0], x[1], 0);
    tt_cycle ca, cb;
    assert_int_equal(tt_sim_cycle(a, &ca), TT_OK);
    assert_int_equal(tt_sim_cycle(b, &cb), TT_OK);
    assert_memory_equal(&ca, &cb, sizeof ca);
    tt_sim_get_x(a, x, &contact);
    tt_sim_get_state(b, &d, &v, &contact);
    assert_true(x[0] == d && x[1] == v);
    tt_sim_free(a);
    tt_sim_free(b);
    tt_contact_free(ct);
    tt_contact_free(ct_b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(kernels_equal_at_n2),
        cmocka_unit_test(cycles_equal_on_either_plan),
        cmocka_unit_test(state_of_dimension_n),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
