/* tiptap tune: the free lever's thermal deflection, its spectrum and the fit (see
 * include/tiptap/run/tune.h). */
#include "tiptap/run/tune.h"

#include <math.h>
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

/* The fit's first guesses from the spectrum: the highest bin above the lowest few, the
 * width at half its height, the level there. */
static void first_guess(const double *psd, size_t nb, double df, double W, tune_fit *m)
{
    size_t kp = 3;
    for (size_t k = 3; k < nb; k++)
        if (psd[k] > psd[kp])
            kp = k;
    size_t lo = kp, hi = kp;
    while (lo > 1 && psd[lo] - W > 0.5 * (psd[kp] - W))
        lo--;
    while (hi + 1 < nb && psd[hi] - W > 0.5 * (psd[kp] - W))
        hi++;
    m->f0 = (double)kp * df;
    m->Q = fmax(1, m->f0 / (fmax(1, (double)(hi - lo)) * df));
    m->P = fmax(psd[kp] - W, 1e-300) / (m->Q * m->Q);
    m->W = W;
}

int tt_run_tune(const tt_scene *s, tt_table **out, tt_tune_result *res, tt_progress_fn progress, void *user)
{
    tt_setup *st = NULL;
    tt_scene *copy = NULL;
    tt_tune_params p;
    tt_scan_noise noise;
    tt_sample *buf = NULL;
    double *x = NULL, *psd = NULL;
    tt_tune_result r = {.chi = 1};
    *out = NULL;
    int rc;
    if ((rc = tt_scene_locate(s, tt_config_tune(s, &p))) || (rc = run_setup(s, &copy, &st)) ||
        (rc = tt_config_noise(copy, tt_setup_solver(st), tt_setup_cantilever(st)->fd, &noise)))
        goto done;
    tt_cantilever c = *tt_setup_cantilever(st);
    const long n = p.samples_per_cycle, cycles = p.cycles;
    const double fs = (double)n * c.fd;
    const size_t N = (size_t)cycles * (size_t)n, L = p.segment;
    if (!(buf = calloc((size_t)n, sizeof *buf)) || !(x = malloc(N * sizeof *x)) ||
        !(psd = malloc((L / 2 + 1) * sizeof *psd))) {
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
    tt_sim_reset_free(sim);
    tt_sim_set_sample(sim, 1, 0);
    /* from the Boltzmann distribution, so that the record is stationary from its start */
    {
        const uint64_t k0 = tt_noise_key(noise.seed, TT_NOISE_THERMAL, 1);
        const double kT = TT_BOLTZMANN * noise.temperature;
        tt_sim_set_state(sim, sqrt(kT / c.k) * tt_noise_gauss(k0, 0), sqrt(kT / c.m) * tt_noise_gauss(k0, 1), 0);
    }
    const uint64_t kd = tt_noise_key(noise.seed, TT_NOISE_DETECTOR, 0);
    /* white noise of one-sided density n sampled at rate fs has variance n^2 fs / 2 */
    const double sd = noise.detector * sqrt(0.5 * fs);
    for (long i = 0; i < cycles && rc == TT_OK; i++) {
        tt_cycle cy;
        if (tt_cancel_requested()) {
            rc = tt_error(TT_EINTR, "interrupted: %ld of %ld drive periods finished", i, cycles);
            break;
        }
        if ((rc = tt_sim_cycle(sim, &cy)))
            break;
        for (long k = 0; k < n; k++) {
            size_t j = (size_t)i * (size_t)n + (size_t)k;
            x[j] = buf[k].d - buf[k].z + (sd > 0 ? sd * tt_noise_gauss(kd, (uint64_t)j) : 0);
        }
        if (progress && ((i + 1) % 1024 == 0 || i + 1 == cycles))
            progress(user, i + 1, cycles);
    }
    if (rc)
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
    tune_fit fit = {.dt = 1 / (c.fd * noise.points), .fs = fs};
    first_guess(psd, nb, r.bin_width, noise.detector > 0 ? psd[nb - nb / 16 - 1] : 0, &fit);
    /* the window: twenty half-widths f0 / 2Q either side of the peak, at most 0.95 f0;
     * with a detector floor on to 0.95 of Nyquist, where the floor shows */
    size_t k0 = 2, k1 = nb - 1;
    for (int pass = 0; pass < 2 && rc == TT_OK; pass++) {
        double w = fmin(0.95, 10 / fit.Q);
        k0 = (size_t)fmax(2, floor(fit.f0 * (1 - w) / r.bin_width));
        k1 = (size_t)fmin((double)nb - 1, ceil(fit.f0 * (1 + w) / r.bin_width));
        if (noise.detector > 0)
            k1 = (size_t)fmax((double)k1, 0.95 * (double)nb);
        rc = tune_fit_psd(psd, k0, k1, r.bin_width, r.averages, noise.detector > 0, &fit);
    }
    if (rc)
        goto done;
    const double kT = TT_BOLTZMANN * noise.temperature;
    r.f0 = fit.f0;
    r.f0_err = fit.f0 * sqrt(fit.cov[1][1]);
    r.Q = fit.Q;
    r.Q_err = fit.Q * sqrt(fit.cov[2][2]);
    r.white = fit.W;
    r.white_err = fit.W * sqrt(fit.cov[3][3]);
    r.chi2_dof = fit.chi2_dof;
    /* <x^2> of the mode = P pi f0 Q / 2 (the oscillator's integral); k = chi^2 kB T / <x^2> */
    r.k = r.chi * r.chi * kT / (fit.P * M_PI * fit.f0 * fit.Q / 2);
    double vk = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            vk += fit.cov[i][j]; /* ln k = const - ln P - ln f0 - ln Q */
    r.k_err = r.k * sqrt(vk);
    r.noise_factor = tt_tune_noise_factor(c.f0, c.Q, c.fd, noise.points);
    /* Var of the sample variance of a Gaussian record of length T: (2 / T) integral of
     * the autocovariance squared */
    r.variance_err = sqrt(2 * acov_square(&fit) * fs / (double)N);
    r.fit_low = (double)k0 * r.bin_width;
    r.fit_high = (double)k1 * r.bin_width;
    tt_table *t = tt_table_alloc(&t) == TT_OK ? t : NULL;
    if (!t || tt_table_add(t, "f", "Hz", 0) || tt_table_add(t, "psd", "m^2/Hz", 0) ||
        tt_table_add(t, "fit", "m^2/Hz", 0)) {
        tt_table_free(t);
        rc = tt_error_nomem("the tune's table");
        goto done;
    }
    *out = t;
    for (size_t k = 1; k < nb && rc == TT_OK; k++) {
        if ((rc = tt_table_row(t)))
            break;
        tt_table_set(t, 0, (double)k * r.bin_width);
        tt_table_set(t, 1, psd[k]);
        /* the fit where it was fitted */
        tt_table_set(t, 2, k >= k0 && k <= k1 ? tune_model(&fit, (double)k * r.bin_width) : NAN);
    }
    const struct {
        const char *key;
        double v;
    } meta[] = {{"temperature", r.temperature}, {"sample_rate", r.fs}, {"bin_width", r.bin_width},
                {"segments", (double)r.segments}, {"averages", r.averages}, {"f0", r.f0},
                {"f0_err", r.f0_err}, {"Q", r.Q}, {"Q_err", r.Q_err}, {"k", r.k}, {"k_err", r.k_err},
                {"chi", r.chi}, {"white", r.white}, {"white_err", r.white_err}, {"chi2_dof", r.chi2_dof},
                {"variance", r.variance}, {"variance_err", r.variance_err},
                {"noise_factor", r.noise_factor}, {"cycles", (double)r.cycles},
                {"fit_low", r.fit_low}, {"fit_high", r.fit_high}};
    for (size_t i = 0; i < sizeof meta / sizeof meta[0] && rc == TT_OK; i++)
        rc = run_meta_number(t, meta[i].key, meta[i].v);
done:
    if (res)
        *res = r;
    if (st) {
        tt_sim_set_sampling(tt_setup_sim(st), 0, NULL);
        tt_sim_set_thermal(tt_setup_sim(st), 0, 0);
    }
    free(buf);
    free(x);
    free(psd);
    tt_setup_free(st);
    tt_scene_free(copy);
    return rc;
}
