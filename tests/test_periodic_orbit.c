/* Periodic orbits of more than one cycle (tt_sim_settle_orbit, docs/dynamics.md,
 * Settling): the standard cantilever (40 N/m, 300 kHz, Q 400, 20 nm) over the polymer
 * blend's soft, sticky matrix (100 MPa, 60 mJ/m^2, Q_i 10) at 6 nm jumps in three
 * cycles out of four. Its approach row says period 4, and its dissipation is the mean
 * of the four cycles (one of which dissipates nothing), which agrees with the energy
 * the drive feeds in (Cleveland's relation); before, the row was one cycle of the
 * orbit (0 aJ) with settled = 0. A steady point (the stiff disks) keeps period 1 and
 * the same numbers, bit for bit, as tt_sim_settle gives; a point whose orbit is not
 * found within max_cycles is the mean over its last cycles, and both are warned of. */
#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/run/run.h"
#include "tiptap/run/sweep.h"
#include "tiptap/util/error.h"
#include "tiptap/util/warning.h"

static const char *blend =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\n"
    "quality_factor = 400\nfree_amplitude = 20 nm\ndrive = base\n"
    "[tip]\nradius = 10 nm\nyoungs_modulus = 169 GPa\npoisson_ratio = 0.27\n"
    "[material matrix]\nyoungs_modulus = 100 MPa\npoisson_ratio = 0.49\n"
    "adhesion_energy = 60 mJ/m^2\ninteratomic_distance = 0.3 nm\n"
    "interaction_quality_factor = 10\n"
    "[material disk]\nyoungs_modulus = 3 GPa\npoisson_ratio = 0.35\n"
    "adhesion_energy = 40 mJ/m^2\ninteratomic_distance = 0.3 nm\n";

/* The blend with [approach] keys, and a free amplitude other than 20 nm (A0 > 0). */
static tt_scene *scene_A0(const char *approach, const char *A0)
{
    char text[2048];
    snprintf(text, sizeof text, "%s[approach]\n%s", blend, approach);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "blend"), TT_OK);
    if (A0) {
        char set[64];
        snprintf(set, sizeof set, "cantilever.free_amplitude=%s", A0);
        assert_int_equal(tt_scene_set(s, set), TT_OK);
    }
    return s;
}

static tt_scene *scene(const char *approach) { return scene_A0(approach, NULL); }

/* Warnings heard on this thread: how many of each of two categories, the last text. */
typedef struct {
    int settle, validity;
    char message[1024];
} heard;

static void hear(const char *category, const char *message, void *data)
{
    heard *h = data;
    if (strcmp(category, TT_WARN_SETTLE) == 0) {
        h->settle++;
        snprintf(h->message, sizeof h->message, "%s", message);
    } else if (strcmp(category, TT_WARN_VALIDITY) == 0)
        h->validity++;
}

/* A one-point approach's table, the warnings it raised in *h. */
static tt_table *approach_A0(const char *keys, const char *A0, heard *h)
{
    tt_scene *s = scene_A0(keys, A0);
    tt_table *t = NULL;
    memset(h, 0, sizeof *h);
    tt_warning_sink old = tt_warning_push(hear, h);
    assert_int_equal(tt_run_approach(s, &t, NULL, NULL), TT_OK);
    tt_warning_pop(old);
    tt_scene_free(s);
    assert_int_equal(tt_table_rows(t), 1);
    return t;
}

static tt_table *approach(const char *keys, heard *h) { return approach_A0(keys, NULL, h); }

static double cell(const tt_table *t, const char *name)
{
    long c = tt_table_find(t, name);
    if (c < 0)
        fail_msg("no column %s", name);
    return tt_table_numbers(t, (size_t)c)[0];
}

/* The energy the drive feeds in per cycle less the cantilever's own damping of the
 * fundamental, for a deflection fundamental of amplitude A and lag phi (rad) under the
 * base drive z = a_d cos(w t) (docs/physics.md): E_drive = pi A a_d (k sin phi - c w
 * cos phi), and the damping pi c w A^2 of a harmonic motion. At resonance, where a_d =
 * A0 / Q, this is Cleveland et al.'s pi k A^2 / Q (A0 / A sin phi - 1) less pi k A A0
 * cos(phi) / Q^2 (0.1 % of it here). */
static double cleveland(const tt_cantilever *c, double A, double phi)
{
    return M_PI * A * c->a_d * (c->k * sin(phi) - c->c * c->wd * cos(phi)) - M_PI * c->c * c->wd * A * A;
}

static void matrix_at_6nm_is_a_period_4_orbit(void **st)
{
    (void)st;
    heard h;
    tt_table *t = approach("from = 6 nm\nto = 6 nm\npoints = 1\n", &h);
    double A = cell(t, "amplitude"), phi = cell(t, "phase") * M_PI / 180, E = cell(t, "dissipated");
    /* the orbit, cycle by cycle, from the free oscillation at 6 nm: 3000 cycles (the
     * transient falls as exp(-pi n / Q), 1e-10 of it by then), then ten periods */
    tt_scene *s = scene("");
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_sim *sim = tt_setup_sim(su);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 6e-9, 0);
    enum { N = 40 };
    tt_cycle c[N];
    for (int i = 0; i < 3000; i++)
        assert_int_equal(tt_sim_cycle(sim, &c[0]), TT_OK);
    double mean = 0, least = INFINITY, most = 0;
    for (int i = 0; i < N; i++) {
        assert_int_equal(tt_sim_cycle(sim, &c[i]), TT_OK);
        mean += c[i].e_ts / N;
        least = fmin(least, c[i].e_ts);
        most = fmax(most, c[i].e_ts);
    }
    double two = 0; /* it repeats every 4 cycles, not every 2 */
    for (int i = 4; i < N; i++) {
        assert_close(c[i].amplitude, c[i - 4].amplitude, 1e-6 * 20e-9);
        two = fmax(two, fabs(c[i].amplitude - c[i - 2].amplitude));
    }
    assert_true(two > 1e-3 * 20e-9);
    double E_cl = cleveland(tt_setup_cantilever(su), A, phi);
    print_message("period %g, settled %g after %g cycles: amplitude %.6g nm, phase %.6g deg; "
                  "dissipated %.6g aJ (cycles %.4g to %.4g aJ, mean %.6g aJ); Cleveland %.6g aJ\n",
                  cell(t, "period"), cell(t, "settled"), cell(t, "cycles"), A * 1e9, phi * 180 / M_PI,
                  E * 1e18, least * 1e18, most * 1e18, mean * 1e18, E_cl * 1e18);
    assert_true(cell(t, "period") == 4);
    assert_true(cell(t, "settled") == 1);
    assert_true(least == 0 && most > 10e-18); /* one cycle of the four misses the sample */
    /* the row is the mean over the orbit, not one of its cycles */
    assert_close(E, mean, 1e-5 * mean);
    /* and agrees with the drive's energy balance, to the harmonics' share of the
     * cantilever's damping, which Cleveland's relation leaves out */
    assert_close(E, E_cl, 1e-3 * E);
    /* the warning names the point and its period */
    assert_int_equal(h.settle, 1);
    assert_non_null(strstr(h.message, "z = 6 (period 4) nm"));
    tt_setup_free(su);
    tt_scene_free(s);
    tt_table_free(t);
}

static void matrix_at_3_5nm_with_10nm_is_a_period_3_orbit(void **st)
{
    (void)st;
    heard h;
    tt_table *t = approach_A0("from = 3.5 nm\nto = 3.5 nm\npoints = 1\n", "10 nm", &h);
    double A = cell(t, "amplitude"), phi = cell(t, "phase") * M_PI / 180, E = cell(t, "dissipated");
    tt_scene *s = scene_A0("", "10 nm");
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    double E_cl = cleveland(tt_setup_cantilever(su), A, phi);
    print_message("period %g: amplitude %.6g nm, phase %.6g deg, dissipated %.6g aJ, Cleveland %.6g aJ\n",
                  cell(t, "period"), A * 1e9, phi * 180 / M_PI, E * 1e18, E_cl * 1e18);
    assert_true(cell(t, "period") == 3);
    assert_close(E, E_cl, 1e-3 * E);
    tt_setup_free(su);
    tt_scene_free(s);
    tt_table_free(t);
}

static void steady_point_is_unchanged(void **st)
{
    (void)st;
    /* the stiff disks at 10 nm, settled (no shooting): the row is the last cycle of
     * tt_sim_settle from the same start, bit for bit */
    heard h;
    tt_table *t = approach("from = 10 nm\nto = 10 nm\npoints = 1\nmaterial = disk\nsteady = settle\n", &h);
    tt_scene *s = scene("");
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 1), TT_OK);
    tt_sim *sim = tt_setup_sim(su);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 10e-9, 0);
    tt_cycle c;
    int settled;
    long n;
    assert_int_equal(tt_sim_settle(sim, 20000, 1e-7, &c, &settled, &n), TT_OK);
    assert_true(settled);
    assert_true(cell(t, "period") == 1);
    assert_true(cell(t, "cycles") == (double)n);
    assert_true(cell(t, "amplitude") == c.amplitude);
    assert_true(cell(t, "phase") == c.phase * 180 / M_PI);
    assert_true(cell(t, "dissipated") == c.e_ts);
    assert_true(cell(t, "peak_force") == c.peak_force);
    assert_int_equal(h.settle, 0);
    tt_setup_free(su);
    tt_scene_free(s);
    tt_table_free(t);
}

static void orbit_not_found_is_a_window_mean(void **st)
{
    (void)st;
    /* at 8 nm the matrix's orbit has period 27, found within about 600 cycles: in 100
     * none is, and the row is the mean over the last 64 of them */
    tt_scene *s = scene("");
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_sim *sim = tt_setup_sim(su);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 8e-9, 0);
    tt_cycle c[100], got;
    for (int i = 0; i < 100; i++)
        assert_int_equal(tt_sim_cycle(sim, &c[i]), TT_OK);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 8e-9, 0);
    tt_settle_result r;
    assert_int_equal(tt_sim_settle_orbit(sim, 100, 1e-7, &got, &r), TT_OK);
    assert_int_equal(r.settled, 0);
    assert_int_equal(r.period, 0);
    assert_int_equal(r.window, TT_SETTLE_WINDOW);
    assert_int_equal(r.cycles, 100);
    double e = 0, X = 0, Y = 0;
    for (int i = 100 - TT_SETTLE_WINDOW; i < 100; i++) {
        e += c[i].e_ts / TT_SETTLE_WINDOW;
        X += c[i].amplitude * cos(c[i].phase) / TT_SETTLE_WINDOW;
        Y += c[i].amplitude * sin(c[i].phase) / TT_SETTLE_WINDOW;
    }
    assert_close(got.e_ts, e, 1e-12 * e);
    assert_close(got.amplitude, hypot(X, Y), 1e-12 * 20e-9);
    /* and the approach says so */
    heard h;
    tt_table *t = approach("from = 8 nm\nto = 8 nm\npoints = 1\nmax_cycles = 100\nsteady = settle\n", &h);
    assert_true(cell(t, "period") == 0);
    assert_true(cell(t, "settled") == 0);
    assert_int_equal(h.settle, 1);
    assert_non_null(strstr(h.message, "1 of 1 points found no period up to 64 cycles"));
    assert_non_null(strstr(h.message, "z = 8 nm"));
    assert_non_null(strstr(h.message, "last 64 cycles"));
    tt_table_free(t);
    tt_setup_free(su);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(matrix_at_6nm_is_a_period_4_orbit),
        cmocka_unit_test(matrix_at_3_5nm_with_10nm_is_a_period_3_orbit),
        cmocka_unit_test(steady_point_is_unchanged),
        cmocka_unit_test(orbit_not_found_is_a_window_mean),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
