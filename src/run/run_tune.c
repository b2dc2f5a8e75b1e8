/* tiptap tune: the free lever's thermal deflection, its spectrum and the fit (see
 * include/tiptap/run/tune.h). */
#include "tiptap/run/tune.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run_common.h"
#include "tune_private.h"
#include "tiptap/config/config.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/config/setup.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

static double sinc4(double x)
{
    double s = x == 0 ? 1 : sin(M_PI * x) / (M_PI * x);
    return s * s * s * s;
}

double tt_tune_noise_factor(double f0, double Q, double fd, int points)
{
    /* the |H|^2-weighted mean of sinc^4 over 0 .. 40 f0, by the midpoint rule on a grid
     * fine against the resonance's width */
    const double dt = 1 / (fd * points), h = f0 / (Q * 64 > 64 ? Q * 64 : 64);
    double num = 0, den = 0;
    for (double f = 0.5 * h; f < 40 * f0; f += h) {
        double u = f / f0, a = 1 - u * u, b = u / Q, H2 = 1 / (a * a + b * b);
        num += H2 * sinc4(f * dt);
        den += H2;
    }
    return num / den;
}

/* (1/2) integral of the one-sided model's square over 0 .. 40 f0 (the floor left out): the
 * integral of the autocovariance's square, which sets the sample variance's error. */
static double acov_square(const tune_fit *m)
{
    const double h = m->f0 / (m->Q * 64 > 64 ? m->Q * 64 : 64);
    tune_fit o = *m;
    o.W = 0;
    o.fs = 0; /* the process itself, not its folded samples */
    double s = 0;
    for (double f = 0.5 * h; f < 40 * m->f0; f += h) {
        double v = tune_model(&o, f);
        s += v * v * h;
    }
    return 0.5 * s;
}

/* The detector's reading per tip deflection of mode i (0-based): 1 for the point mass;
 * a beam's slope at the tip against the static end load's 1.5 that calibrates it. */
static double lever_chi(const tt_cantilever *c, int i)
{
    return c->modes > 1 ? tt_beam_slope(i + 1) / 1.5 : 1;
}

/* The free lever's starting state from the Boltzmann distribution, each mode its own, so
 * that the record is stationary from its start. */
static void boltzmann_start(tt_sim *sim, const tt_cantilever *c, uint64_t key, double kT)
{
    if (c->modes <= 1) {
        tt_sim_set_state(sim, sqrt(kT / c->k) * tt_noise_gauss(key, 0), sqrt(kT / c->m) * tt_noise_gauss(key, 1), 0);
        return;
    }
    double X[TT_SIM_DIM_MAX];
    int contact;
    tt_sim_get_x(sim, X, &contact);
    for (int i = 0; i < c->modes; i++) {
        X[2 * i] = sqrt(kT / c->mode_k[i]) * tt_noise_gauss(key, (uint64_t)(2 * i));
        X[2 * i + 1] = sqrt(kT / c->mode_m[i]) * tt_noise_gauss(key, (uint64_t)(2 * i + 1));
    }
    tt_sim_set_x(sim, X, 0);
}

/* One mode's figures from its fit: k = chi^2 kB T / <x*^2>, <x*^2> = P pi f0 Q / 2 (the
 * oscillator's integral); ln k = const - ln P - ln f0 - ln Q sets its error. */
static void mode_figures(const tune_fit *fit, double chi, double kT, tt_tune_mode *m)
{
    m->f0 = fit->f0;
    m->f0_err = fit->f0 * sqrt(fit->cov[1][1]);
    m->Q = fit->Q;
    m->Q_err = fit->Q * sqrt(fit->cov[2][2]);
    m->chi = chi;
    m->k = chi * chi * kT / (fit->P * M_PI * fit->f0 * fit->Q / 2);
    double vk = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            vk += fit->cov[i][j];
    m->k_err = m->k * sqrt(vk);
    m->chi2_dof = fit->chi2_dof;
}

/* The one-mode fit: the window twenty half-widths f0 / 2Q either side of the peak, at
 * most 0.95 f0; with a detector floor on to 0.95 of Nyquist, where the floor shows. */
static int fit_one(const double *psd, size_t nb, const tt_tune_result *r, int with_floor, tune_fit *fit,
                   size_t *k0, size_t *k1)
{
    int rc = TT_OK;
    for (int pass = 0; pass < 2 && rc == TT_OK; pass++) {
        double w = fmin(0.95, 10 / fit->Q);
        *k0 = (size_t)fmax(2, floor(fit->f0 * (1 - w) / r->bin_width));
        *k1 = (size_t)fmin((double)nb - 1, ceil(fit->f0 * (1 + w) / r->bin_width));
        if (with_floor)
            *k1 = (size_t)fmax((double)*k1, 0.95 * (double)nb);
        rc = tune_fit_psd(psd, *k0, *k1, r->bin_width, r->averages, with_floor, NULL, fit);
    }
    return rc;
}

/* The whole fitted model at f: every mode's density and the floor. */
static double whole_model(const tune_fit *fit, int modes, double W, double f)
{
    double v = W;
    for (int i = 0; i < modes; i++) {
        tune_fit o = fit[i];
        o.W = 0;
        v += tune_model(&o, f);
    }
    return v;
}

/* The table: f, psd, fit; with several modes fit the whole model in every window and
 * each mode's own density in its own. */
static int tune_table(tt_table **out, const double *psd, size_t nb, double df, const tune_fit *fit, int modes,
                      const size_t *k0, const size_t *k1)
{
    tt_table *t = tt_table_alloc(&t) == TT_OK ? t : NULL;
    int rc = !t || tt_table_add(t, "f", "Hz", 0) || tt_table_add(t, "psd", "m^2/Hz", 0) ||
             tt_table_add(t, "fit", "m^2/Hz", 0);
    static const char *names[TT_CANTILEVER_MODES_MAX] = {"mode1", "mode2", "mode3"};
    for (int i = 0; modes > 1 && i < modes && !rc; i++)
        rc = tt_table_add(t, names[i], "m^2/Hz", 0);
    if (rc) {
        tt_table_free(t);
        return tt_error_nomem("the tune's table");
    }
    *out = t;
    const double W = fit[modes - 1].W;
    for (size_t k = 1; k < nb && rc == TT_OK; k++) {
        if ((rc = tt_table_row(t)))
            break;
        const double f = (double)k * df;
        tt_table_set(t, 0, f);
        tt_table_set(t, 1, psd[k]);
        if (modes == 1) {
            /* the fit where it was fitted */
            tt_table_set(t, 2, k >= k0[0] && k <= k1[0] ? tune_model(&fit[0], f) : NAN);
            continue;
        }
        int in = 0;
        for (int i = 0; i < modes; i++) {
            tune_fit o = fit[i];
            o.W = 0;
            int here = k >= k0[i] && k <= k1[i];
            in |= here;
            tt_table_set(t, 3 + (size_t)i, here ? tune_model(&o, f) : NAN);
        }
        tt_table_set(t, 2, in ? whole_model(fit, modes, W, f) : NAN);
    }
    return rc;
}

/* The result's figures as the table's metadata; modes 2.. as f0_2, Q_2, k_2 and so on. */
static int tune_meta(tt_table *t, const tt_tune_result *r)
{
    const struct {
        const char *key;
        double v;
    } meta[] = {{"temperature", r->temperature}, {"sample_rate", r->fs}, {"bin_width", r->bin_width},
                {"segments", (double)r->segments}, {"averages", r->averages}, {"f0", r->f0},
                {"f0_err", r->f0_err}, {"Q", r->Q}, {"Q_err", r->Q_err}, {"k", r->k}, {"k_err", r->k_err},
                {"chi", r->chi}, {"white", r->white}, {"white_err", r->white_err}, {"chi2_dof", r->chi2_dof},
                {"variance", r->variance}, {"variance_err", r->variance_err},
                {"noise_factor", r->noise_factor}, {"cycles", (double)r->cycles},
                {"fit_low", r->fit_low}, {"fit_high", r->fit_high}};
    int rc = TT_OK;
    for (size_t i = 0; i < sizeof meta / sizeof meta[0] && rc == TT_OK; i++)
        rc = run_meta_number(t, meta[i].key, meta[i].v);
    if (r->modes > 1 && rc == TT_OK)
        rc = run_meta_number(t, "modes", r->modes);
    for (int n = 1; n < r->modes && rc == TT_OK; n++) {
        const tt_tune_mode *m = &r->mode[n];
        const double v[] = {m->f0, m->f0_err, m->Q, m->Q_err, m->k, m->k_err, m->chi, m->noise_factor,
                            m->chi2_dof, m->fit_low, m->fit_high};
        static const char *keys[] = {"f0", "f0_err", "Q", "Q_err", "k", "k_err", "chi", "noise_factor",
                                     "chi2_dof", "fit_low", "fit_high"};
        for (size_t i = 0; i < sizeof v / sizeof v[0] && rc == TT_OK; i++) {
            char key[32];
            snprintf(key, sizeof key, "%s_%d", keys[i], n + 1);
            rc = run_meta_number(t, key, v[i]);
        }
    }
    return rc;
}

/* Record the free lever's detector reading: sum chi_n q_n and the floor. */
static int record(tt_sim *sim, const tt_cantilever *c, const tt_sample *buf, const double *q, long n,
                  long cycles, double sd, uint64_t kd, double *x, tt_progress_fn progress, void *user)
{
    const int modes = c->modes > 1 ? c->modes : 1;
    double chi[TT_CANTILEVER_MODES_MAX];
    for (int i = 0; i < modes; i++)
        chi[i] = lever_chi(c, i);
    int rc = TT_OK;
    for (long i = 0; i < cycles && rc == TT_OK; i++) {
        tt_cycle cy;
        if (tt_cancel_requested())
            return tt_error(TT_EINTR, "interrupted: %ld of %ld drive periods finished", i, cycles);
        if ((rc = tt_sim_cycle(sim, &cy)))
            break;
        for (long k = 0; k < n; k++) {
            size_t j = (size_t)i * (size_t)n + (size_t)k;
            double v = buf[k].d - buf[k].z;
            if (q) {
                v = 0;
                for (int m = 0; m < modes; m++)
                    v += chi[m] * q[(size_t)k * (size_t)modes + (size_t)m];
            }
            x[j] = v + (sd > 0 ? sd * tt_noise_gauss(kd, (uint64_t)j) : 0);
        }
        if (progress && ((i + 1) % 1024 == 0 || i + 1 == cycles))
            progress(user, i + 1, cycles);
    }
    return rc;
}

int tt_run_tune(const tt_scene *s, tt_table **out, tt_tune_result *res, tt_progress_fn progress, void *user)
{
    tt_setup *st = NULL;
    tt_scene *copy = NULL;
    tt_tune_params p;
    tt_scan_noise noise;
    tt_sample *buf = NULL;
    double *x = NULL, *psd = NULL, *q = NULL;
    tt_tune_result r = {.chi = 1, .modes = 1};
    *out = NULL;
    int rc;
    if ((rc = tt_scene_locate(s, tt_config_tune(s, &p))) || (rc = run_setup(s, &copy, &st)) ||
        (rc = tt_config_noise(copy, tt_setup_solver(st), tt_setup_cantilever(st)->fd, &noise)))
        goto done;
    tt_cantilever c = *tt_setup_cantilever(st);
    const int modes = c.modes > 1 ? c.modes : 1;
    const long n = p.samples_per_cycle, cycles = p.cycles;
    const double fs = (double)n * c.fd;
    const size_t N = (size_t)cycles * (size_t)n, L = p.segment;
    if (!(buf = calloc((size_t)n, sizeof *buf)) || !(x = malloc(N * sizeof *x)) ||
        !(psd = malloc((L / 2 + 1) * sizeof *psd)) ||
        (modes > 1 && !(q = malloc((size_t)n * (size_t)modes * sizeof *q)))) {
        rc = tt_error_nomem("the tune's record (%zu samples)", N);
        goto done;
    }
    /* the free lever: undriven, nothing under the tip */
    tt_sim *sim = tt_setup_sim(st);
    c.a_d = 0;
    c.F0 = 0;
    tt_sim_set_cantilever(sim, &c);
    tt_sim_set_contact(sim, NULL, NAN);
    if ((rc = tt_sim_set_thermal(sim, noise.temperature, noise.points)))
        goto done;
    tt_sim_noise_key(sim, tt_noise_key(noise.seed, TT_NOISE_THERMAL, 0));
    tt_sim_set_sampling(sim, (int)n, buf);
    tt_sim_set_mode_sampling(sim, q);
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 1, 0);
    const double kT = TT_BOLTZMANN * noise.temperature;
    boltzmann_start(sim, &c, tt_noise_key(noise.seed, TT_NOISE_THERMAL, 1), kT);
    /* white noise of one-sided density n sampled at rate fs has variance n^2 fs / 2 */
    const double sd = noise.detector * sqrt(0.5 * fs);
    if ((rc = record(sim, &c, buf, q, n, cycles, sd, tt_noise_key(noise.seed, TT_NOISE_DETECTOR, 0), x,
                     progress, user)))
        goto done;
    r.cycles = cycles;
    r.temperature = noise.temperature;
    r.fs = fs;
    r.bin_width = fs / (double)L;
    {
        double m = 0, v = 0;
        for (size_t j = 0; j < N; j++)
            m += x[j];
        m /= (double)N;
        for (size_t j = 0; j < N; j++)
            v += (x[j] - m) * (x[j] - m);
        r.variance = v / (double)N;
    }
    if ((rc = tune_welch(x, N, fs, L, psd, &r.segments, &r.averages)))
        goto done;
    /* the floor's first guess: the density near Nyquist, where the oscillator's is
     * (f0 / f)^4 smaller */
    const size_t nb = L / 2;
    const int with_floor = noise.detector > 0;
    tune_fit fit[TT_CANTILEVER_MODES_MAX];
    size_t k0[TT_CANTILEVER_MODES_MAX] = {2}, k1[TT_CANTILEVER_MODES_MAX] = {nb - 1};
    for (int i = 0; i < modes; i++)
        fit[i] = (tune_fit){.dt = 1 / (c.fd * noise.points), .fs = fs, .W = with_floor ? psd[nb - nb / 16 - 1] : 0};
    if (modes == 1) {
        tune_first_guess(psd, 3, nb, r.bin_width, fit[0].W, &fit[0]);
        rc = fit_one(psd, nb, &r, with_floor, &fit[0], &k0[0], &k1[0]);
    } else {
        /* each peak looked for near the scene's frequency of its mode */
        double fg[TT_CANTILEVER_MODES_MAX];
        for (int i = 0; i < modes; i++)
            fg[i] = c.mode_f[i];
        rc = tune_fit_modes(psd, nb, r.bin_width, r.averages, with_floor, modes, fg, fit, k0, k1);
    }
    if (rc)
        goto done;
    r.modes = modes;
    double acov = 0;
    for (int i = 0; i < modes; i++) {
        tt_tune_mode *m = &r.mode[i];
        mode_figures(&fit[i], lever_chi(&c, i), kT, m);
        m->noise_factor = tt_tune_noise_factor(i ? c.mode_f[i] : c.f0, i ? c.mode_Q[i] : c.Q, c.fd, noise.points);
        m->fit_low = (double)k0[i] * r.bin_width;
        m->fit_high = (double)k1[i] * r.bin_width;
        /* the modes' peaks apart, their cross terms in C^2 are left out */
        acov += acov_square(&fit[i]);
    }
    const tt_tune_mode *m1 = &r.mode[0];
    r.f0 = m1->f0, r.f0_err = m1->f0_err, r.Q = m1->Q, r.Q_err = m1->Q_err;
    r.k = m1->k, r.k_err = m1->k_err, r.chi = m1->chi, r.chi2_dof = m1->chi2_dof;
    r.noise_factor = m1->noise_factor, r.fit_low = m1->fit_low, r.fit_high = m1->fit_high;
    r.white = fit[modes - 1].W;
    r.white_err = fit[modes - 1].W * sqrt(fit[modes - 1].cov[3][3]);
    /* Var of the sample variance of a Gaussian record of length T: (2 / T) integral of
     * the autocovariance squared */
    r.variance_err = sqrt(2 * acov * fs / (double)N);
    if ((rc = tune_table(out, psd, nb, r.bin_width, fit, modes, k0, k1)) == TT_OK)
        rc = tune_meta(*out, &r);
done:
    if (res)
        *res = r;
    if (st) {
        tt_sim_set_sampling(tt_setup_sim(st), 0, NULL);
        tt_sim_set_mode_sampling(tt_setup_sim(st), NULL);
        tt_sim_set_thermal(tt_setup_sim(st), 0, 0);
    }
    free(buf);
    free(x);
    free(psd);
    free(q);
    tt_setup_free(st);
    tt_scene_free(copy);
    return rc;
}
