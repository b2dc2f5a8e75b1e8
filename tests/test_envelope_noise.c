/* Noise on the envelope tier (docs/dynamics.md, "Noise on the envelope tier"): the cycle
 * map's linear-noise model of the thermal force gives the free cantilever's equipartition
 * (<d^2> = kB T / k, <d'^2> = kB T / m*); a scan with the full noise set (thermal,
 * detector, z piezo) skips cycles, and the noise in its images has the every-cycle tier's
 * statistics (per line the sd, the mean and the spectrum of height, error (amplitude -
 * setpoint) and phase over seeds) within sampling error; with the z piezo's noise alone (the same draws on
 * both tiers) the images' noise agrees to 1 % on stiff disks too; the images are the same
 * on one thread as on two. */
#include <math.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tt_noise_compare.h"
#include "tiptap/config/scene.h"
#include "tiptap/config/setup.h"
#include "tiptap/solver/envelope.h"
#include "tiptap/solver/noise.h"

enum { NS = 32 };

/* The model of a free cantilever (no sample) built on its steady cycle, iterated with the
 * thermal force's draws: the stationary variances of the state at the cycle's start
 * against equipartition, with standard errors from 40 batches (each many correlation
 * times Q / pi long). */
static void free_equipartition(double Q)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, Q, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    tt_solver s;
    tt_solver_default(&s);
    tt_sim *sim;
    assert_int_equal(tt_sim_alloc(&sim, &c, &s), TT_OK);
    tt_sample smp[NS];
    tt_sim_set_sampling(sim, NS, smp);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 1e-6, 0); /* a micrometre away: no force */
    tt_envelope *e;
    double R[NS];
    for (int q = 0; q < NS; q++)
        R[q] = 1.0 / NS;
    const double T = 300;
    const tt_envelope_params plan = {.samples = NS, .reduced = 1, .reduce = R,
                                     .psd = 2 * c.c * TT_BOLTZMANN * T};
    assert_int_equal(tt_envelope_alloc(&e, sim, &plan), TT_OK);
    assert_int_equal(tt_envelope_noise_size(e), 3);
    double x0[2];
    int c0;
    tt_sim_get_state(sim, &x0[0], &x0[1], &c0);
    tt_cycle cy;
    assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
    double *obs = malloc((size_t)tt_envelope_size(e) * sizeof *obs);
    tt_envelope_observe(e, smp, NULL, &cy, obs);
    long jac = 0;
    assert_int_equal(tt_envelope_build(e, sim, x0, c0, 1e-6, 0, &cy, obs, &jac), TT_ENV_USABLE);
    /* the steady cycle is the model's fixed point; the noise moves the state off it */
    double xs[2], red[1 + TT_ENV_EXTRA], x[2] = {x0[0], x0[1]};
    tt_envelope_predict(e, TT_ENV_REDUCED, x0, NULL, 1e-6, 0, xs, NULL, red);
    const uint64_t key = tt_noise_key(11, TT_NOISE_ENVELOPE, 0);
    enum { NB = 40 };
    const long burn = (long)(10 * Q), per = (long)(250 * Q);
    double bd[NB] = {0}, bv[NB] = {0};
    for (long n = 0; n < burn + NB * per; n++) {
        double x1[2], g[4], dx[2];
        tt_envelope_predict(e, TT_ENV_REDUCED, x, NULL, 1e-6, 0, x1, NULL, red);
        tt_noise_pair(key, 2 * (uint64_t)n, g);
        tt_noise_pair(key, 2 * (uint64_t)n + 1, g + 2);
        tt_envelope_noise(e, g, dx, red);
        x[0] = x1[0] + dx[0];
        x[1] = x1[1] + dx[1];
        if (n >= burn) {
            long b = (n - burn) / per;
            bd[b] += (x[0] - xs[0]) * (x[0] - xs[0]) / per;
            bv[b] += (x[1] - xs[1]) * (x[1] - xs[1]) / per;
        }
    }
    const double want[2] = {TT_BOLTZMANN * T / c.k, TT_BOLTZMANN * T / c.m};
    const double *bat[2] = {bd, bv};
    for (int i = 0; i < 2; i++) {
        double se, m = nc_batch_mean(bat[i], NB, &se);
        print_message("Q %g: <%s^2> / (kB T / %s) = %.4f +- %.4f\n", Q, i ? "d'" : "d", i ? "m" : "k",
                      m / want[i], se / want[i]);
        assert_true(se < 0.03 * want[i]);
        assert_close(m, want[i], 3.5 * se);
    }
    free(obs);
    tt_envelope_free(e);
    tt_sim_free(sim);
}

static void model_equipartition(void **st)
{
    (void)st;
    free_equipartition(50);
    free_equipartition(400);
}

/* The full noise set of tiptap bench (the z piezo's at its default bandwidth), and the z
 * piezo's alone. */
static const char *full_noise = "temperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n"
                                "z_piezo = 0.3 pm/sqrt(Hz)\n";
static const char *z_noise = "z_piezo = 0.3 pm/sqrt(Hz)\n";

/* The soft polymer around stiff disks (30 GPa, no loss), the lines through their
 * centres, so that each taps both: on the disks the z piezo's noise takes the model
 * furthest (docs/dynamics.md, "Noise on the envelope tier"). */
static const char *blend = "[material disk]\nyoungs_modulus = 30 GPa\npoisson_ratio = 0.3\n"
                           "adhesion_energy = 40 mJ/m^2\n"
                           "[surface]\ntype = flat\nmap = disks\nmap_materials = polymer, disk\n"
                           "map_period = 500 nm\nmap_radius = 150 nm\n";

/* Flat silicon (100 GPa, the teaching grating's; stripes of it alone, as a uniform map
 * scans the scene's first material): a stiff contact, where the thermal
 * force rings the state round the orbit by 2.5e-3 of A0 and the cycle map's third
 * derivatives reach 3000 / A0^2, so that the model holds only near where its
 * derivatives were taken (kept models, recalled; docs/dynamics.md, "Noise on the
 * envelope tier"). */
static const char *silicon = "[material silicon]\nreduced_modulus = 100 GPa\n"
                             "adhesion_energy = 20 mJ/m^2\ninteratomic_distance = 0.3 nm\n"
                             "[surface]\ntype = flat\nmap = stripes\nmap_materials = silicon, silicon\n";
static const char *thermal = "temperature = 300 K\n";
static const char *arms = "[material polymer]\nadhesion_energy = 0 J/m^2\nyoungs_modulus = 500 MPa\n"
                          "poisson_ratio = 0.4\narm1_modulus = 500 MPa\narm1_relaxation_time = 1 us\n";
static const char *arms_noise = "temperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n";

/* The model on a standard linear solid (thermal_arms' sample), its second order (the
 * noise's) and its first (the noise-free scans'): its map's column for the arm's state,
 * against cycles integrated from the state moved by 10 fm either way. The state (chi
 * units, contact_sls.c) is about 7 pm on the free flight, where the surface's depression
 * (R chi^2)^(1/3) is clipped at 0: the second order's old step of 1e-3 of A0 (20 pm)
 * crossed that and took dd/dq at 0.34 of its value, dd'/dq at 0.67 and the lock-in's
 * cosine and sine at 0.39 and 0.61, which biased the images' phase noise 5 % high
 * (thermal_arms); the first order's old 1e-4 of A0 (2 pm) took dd/dq 1.2 % off. */
static void arm_columns(int second)
{
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, nc_polymer_base(), "base.ini"), TT_OK);
    assert_int_equal(tt_scene_load_string(sc, arms, "arms.ini"), TT_OK);
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, sc), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_sim *sim = tt_setup_sim(su);
    assert_int_equal(tt_sim_dim(sim), 3);
    tt_sample smp[NS];
    tt_sim_set_sampling(sim, NS, smp);
    const double s = 15e-9; /* 15.6 nm of amplitude */
    tt_sim_set_sample(sim, s, 0);
    tt_cycle cy;
    for (int i = 0; i < 3000; i++)
        assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
    double R[3 * NS];
    for (int q = 0; q < NS; q++) {
        R[q] = 1.0 / NS;
        R[NS + q] = 2.0 / NS * cos(2 * M_PI * q / NS);
        R[2 * NS + q] = 2.0 / NS * sin(2 * M_PI * q / NS);
    }
    const double psd = 2 * tt_setup_cantilever(su)->c * TT_BOLTZMANN * 300;
    const tt_envelope_params plan = {.samples = NS, .reduced = 3, .reduce = R,
                                     .second_order = second, .psd = second ? psd : 0};
    tt_envelope *e;
    assert_int_equal(tt_envelope_alloc(&e, sim, &plan), TT_OK);
    double x0[3], x1[3];
    int c0, c1;
    tt_sim_get_x(sim, x0, &c0);
    assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
    assert_true(tt_envelope_touched(&cy));
    tt_sim_get_x(sim, x1, &c1);
    double *obs = malloc((size_t)tt_envelope_size(e) * sizeof *obs);
    tt_envelope_observe(e, smp, NULL, &cy, obs);
    long jac = 0;
    assert_int_equal(tt_envelope_build(e, sim, x0, c0, s, 0, &cy, obs, &jac), TT_ENV_USABLE);
    /* (d, d', q, mean, cos, sin) at x0 -+ h in q: the model's and the integrated */
    const double h = 1e-14;
    double model[2][6], exact[2][6], red[3 + TT_ENV_EXTRA];
    for (int k = 0; k < 2; k++) {
        double x[3] = {x0[0], x0[1], x0[2] + (k ? -h : h)};
        tt_envelope_predict(e, TT_ENV_REDUCED, x, NULL, s, 0, model[k], NULL, red);
        memcpy(model[k] + 3, red, 3 * sizeof *red);
        tt_sim_set_x(sim, x, c0);
        tt_sim_set_sample(sim, s, 0);
        assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
        tt_sim_get_x(sim, exact[k], &c1);
        tt_envelope_observe(e, smp, NULL, &cy, obs);
        tt_envelope_reduce_obs(e, obs, red);
        memcpy(exact[k] + 3, red, 3 * sizeof *red);
    }
    static const char *name[6] = {"d", "d'", "q", "mean", "cos", "sin"};
    double worst = 0;
    for (int i = 0; i < 6; i++) {
        const double m = (model[0][i] - model[1][i]) / (2 * h), x = (exact[0][i] - exact[1][i]) / (2 * h);
        print_message("order %d: d %s / dq: model %.6g, integrated %.6g (%+.2e)\n", second ? 2 : 1,
                      name[i], m, x, m / x - 1);
        /* measured within 3e-4 (the mean's; 1.2e-4 the rest) */
        worst = fmax(worst, fabs(m / x - 1));
    }
    assert_true(worst < 2e-3);
    free(obs);
    tt_envelope_free(e);
    tt_setup_free(su);
    tt_scene_free(sc);
}

static void arm_state_jacobian(void **st)
{
    (void)st;
    arm_columns(1);
    arm_columns(0);
}

/* The envelope tier's noise against the every-cycle tier's (tt_noise_compare.h); the
 * envelope tier integrates under half the cycles. */
static void compare_tiers(const char *what, const char *sample, const char *noise, int seeds,
                          double slack, double mean_slack)
{
    assert_true(nc_compare_tiers(nc_polymer_base(), what, sample, noise, "envelope", seeds, slack,
                                 mean_slack) < 0.5);
}

/* The full noise set (thermal, detector, z piezo) on the soft polymer over 16 seeds:
 * the noise's statistics within their sampling error. */
static void statistics_match(void **st)
{
    (void)st;
    compare_tiers("full noise set, polymer", "", full_noise, 16, 0, 0);
}

/* The z piezo's noise alone on the blend over 4 seeds: both tiers draw the same noise,
 * so the images' noise agrees to the model's error: its sd within 1 % and its mean
 * within 1 % of that sd (measured: the sd 0.1 % in height, 0.8 % in phase; the height's mean
 * 0.03 pm, 0.25 % of its sd). */
static void z_piezo_blend(void **st)
{
    (void)st;
    compare_tiers("z piezo noise, blend", blend, z_noise, 4, 0.01, 0.01);
}

/* The thermal noise alone on stiff silicon over 10 seeds: the noise's sd and spectrum
 * within their sampling error (a model carried 5e-3 of A0 from its anchor made the
 * height's sd 8 % too large on silicon, 3.5 standard errors). Its mean within 0.3 of
 * its sd: the linear-noise approximation leaves out the mean shift that the thermal
 * force's curvature through the impact gives within a cycle (measured 0.2 sd, 0.05 pm;
 * 0.26 sd before the kept models). */
static void thermal_silicon(void **st)
{
    (void)st;
    compare_tiers("thermal noise, silicon", silicon, thermal, 10, 0, 0.3);
}

/* examples/viscoelastic-blend/arms.ini's standard linear solid (the surface's
 * depression a state after (d, d'), on the plan of dimension 3) with its thermal and
 * detector noise, over 6 seeds: the thermal force kicks the tip alone and the surface
 * follows through the whole state's flow (envelope_noise.c), so the noise's sd and
 * spectrum agree within their sampling error, its mean within 0.3 of its sd (as on
 * silicon: the linear-noise approximation's mean shift). Measured over 32 seeds: the
 * sd 0.3 +- 1.1 % high in height, 1.0 +- 1.3 % in error and 2.0 +- 1.1 % in phase
 * (5.0 +- 1.2 % before the arm's state got its own step). Six seeds cannot tell that
 * 5 % apart from sampling error: arm_state_jacobian is the test that catches it. */
static void thermal_arms(void **st)
{
    (void)st;
    compare_tiers("thermal and detector noise, SLS", arms, arms_noise, 6, 0, 0.3);
}

/* The same noise on one thread as on two: the draws are a function of (seed, line,
 * cycle), not of the thread. */
static void threads_agree(void **st)
{
    (void)st;
    tt_scan_assert_threads_agree(nc_polymer_base(),
                                 "[scan]\nline_rate = 20 Hz\n[noise]\nseed = 3\n"
                                 "temperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n"
                                 "z_piezo = 0.3 pm/sqrt(Hz)\n",
                                 NC_CH, 1);
}

TT_TEST_MAIN(cmocka_unit_test(model_equipartition),
             cmocka_unit_test(arm_state_jacobian),
             cmocka_unit_test(statistics_match),
             cmocka_unit_test(z_piezo_blend),
             cmocka_unit_test(thermal_silicon),
             cmocka_unit_test(thermal_arms),
             cmocka_unit_test(threads_agree))
