/* The thermal tune's Welch spectrum (FFTW) and its damped-oscillator fit (GSL
 * multifit_nlinear): see src/run/tune_private.h and docs/force-and-tune.md. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <fftw3.h>
#include <gsl/gsl_blas.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>

#include "tune_private.h"
#include "tiptap/util/error.h"

int tune_welch(const double *x, size_t n, double fs, size_t L, double *psd, long *segments,
               double *averages)
{
    double *in = fftw_alloc_real(L), *w = malloc(L * sizeof *w);
    fftw_complex *out = fftw_alloc_complex(L / 2 + 1);
    fftw_plan plan = in && out ? fftw_plan_dft_r2c_1d((int)L, in, out, FFTW_ESTIMATE) : NULL;
    if (!plan || !w) {
        if (plan)
            fftw_destroy_plan(plan);
        fftw_free(in);
        fftw_free(out);
        free(w);
        return tt_error_nomem("the tune's spectrum (%zu points a segment)", L);
    }
    double sw2 = 0;
    for (size_t i = 0; i < L; i++) {
        w[i] = 0.5 - 0.5 * cos(2 * M_PI * (double)i / (double)L); /* periodic Hann */
        sw2 += w[i] * w[i];
    }
    memset(psd, 0, (L / 2 + 1) * sizeof *psd);
    long K = 0;
    for (size_t s = 0; s + L <= n; s += L / 2, K++) {
        double mean = 0;
        for (size_t i = 0; i < L; i++)
            mean += x[s + i];
        mean /= (double)L;
        for (size_t i = 0; i < L; i++)
            in[i] = (x[s + i] - mean) * w[i];
        fftw_execute(plan);
        for (size_t k = 0; k <= L / 2; k++)
            psd[k] += out[k][0] * out[k][0] + out[k][1] * out[k][1];
    }
    /* one-sided: twice the two-sided density, but not at 0 and Nyquist */
    for (size_t k = 0; k <= L / 2; k++)
        psd[k] *= (k == 0 || k == L / 2 ? 1.0 : 2.0) / (fs * sw2 * (double)K);
    *segments = K;
    *averages = (double)K / (1 + 2.0 / 36.0 * (double)(K - 1) / (double)K);
    fftw_destroy_plan(plan);
    fftw_free(in);
    fftw_free(out);
    free(w);
    return TT_OK;
}

static double sinc(double x) { return x == 0 ? 1 : sin(M_PI * x) / (M_PI * x); }

/* The oscillator's one-sided density at f >= 0 under the interpolated force. */
static double oscillator(const tune_fit *m, double f)
{
    double u = f / m->f0, a = 1 - u * u, b = u / m->Q, s = sinc(f * m->dt);
    return s * s * s * s * m->P / (a * a + b * b);
}

double tune_model(const tune_fit *m, double f)
{
    /* sampled at fs without a filter, the density above Nyquist folds back: its images
     * at n fs +- f (two each side: the next are (1/5)^4 of the first) */
    double S = oscillator(m, f);
    for (int n = 1; n <= 2 && m->fs > 0; n++)
        S += oscillator(m, n * m->fs - f) + oscillator(m, n * m->fs + f);
    return S + m->W;
}

/* The data of a fit: bins, weights from the last model, the parameters' packing. */
typedef struct {
    const double *psd;
    size_t k0, k1;
    double df, sqrt_avg;
    const double *ref;      /* the previous model at the bins: the weights */
    const double *bg;       /* the fixed density under the model (NULL: none) */
    tune_fit base;
    int nparam;
} fit_data;

static void unpack(const fit_data *d, const gsl_vector *p, tune_fit *m)
{
    *m = d->base;
    m->P = exp(gsl_vector_get(p, 0));
    m->f0 = exp(gsl_vector_get(p, 1));
    m->Q = exp(gsl_vector_get(p, 2));
    m->W = d->nparam > 3 ? exp(gsl_vector_get(p, 3)) : 0;
}

/* Weighted residual (S - M) / M_ref sqrt(averages): each Welch bin's relative standard
 * deviation is 1 / sqrt(averages). */
static int residuals(const gsl_vector *p, void *data, gsl_vector *r)
{
    const fit_data *d = data;
    tune_fit m;
    unpack(d, p, &m);
    for (size_t k = d->k0; k <= d->k1; k++) {
        double M = tune_model(&m, (double)k * d->df);
        if (d->bg)
            M += d->bg[k - d->k0];
        gsl_vector_set(r, k - d->k0, (d->psd[k] - M) / d->ref[k - d->k0] * d->sqrt_avg);
    }
    return GSL_SUCCESS;
}

/* A Hann window's adjacent bins are correlated (power correlation 4/9, and 1/36 two
 * apart), so the fit's bins are not independent: the covariance of a smooth fit grows
 * by 1 + 2 (4/9 + 1/36) = 35/18. */
#define HANN_BIN_CORRELATION (35.0 / 18.0)

int tune_fit_psd(const double *psd, size_t k0, size_t k1, double df, double averages, int floor,
                 const double *bg, tune_fit *m)
{
    const size_t nb = k1 - k0 + 1, np = floor ? 4 : 3;
    if (k1 <= k0 || nb < np + 2)
        return tt_error(TT_ENUM, "the tune's fit: too few bins (%zu) in its window", nb);
    double *ref = malloc(nb * sizeof *ref);
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    gsl_multifit_nlinear_workspace *ws = gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, nb, np);
    gsl_vector *p = gsl_vector_alloc(np);
    gsl_matrix *cov = gsl_matrix_alloc(np, np);
    int rc = TT_OK;
    if (!ref || !ws || !p || !cov) {
        rc = tt_error_nomem("the tune's fit");
        goto done;
    }
    fit_data d = {psd, k0, k1, df, sqrt(averages), ref, bg, *m, (int)np};
    gsl_vector_set(p, 0, log(m->P));
    gsl_vector_set(p, 1, log(m->f0));
    gsl_vector_set(p, 2, log(m->Q));
    if (floor)
        gsl_vector_set(p, 3, log(m->W > 0 ? m->W : 1e-40));
    gsl_multifit_nlinear_fdf fdf = {.f = residuals, .df = NULL, .fvv = NULL, .n = nb, .p = np, .params = &d};
    /* weights from the model of the previous pass (fixed within a pass: minimising
     * ((S - M) / M)^2 with M free would bias the level by 1 / averages) */
    for (int pass = 0; pass < 4 && rc == TT_OK; pass++) {
        tune_fit cur;
        unpack(&d, p, &cur);
        for (size_t k = k0; k <= k1; k++)
            ref[k - k0] = pass == 0 ? fmax(psd[k], 1e-300)
                                    : tune_model(&cur, (double)k * df) + (bg ? bg[k - k0] : 0);
        int info;
        gsl_multifit_nlinear_init(p, &fdf, ws);
        int st = gsl_multifit_nlinear_driver(200, 1e-10, 1e-10, 1e-10, NULL, NULL, &info, ws);
        if (st != GSL_SUCCESS && st != GSL_EMAXITER)
            rc = tt_error(TT_ENUM, "the tune's fit did not converge: %s", gsl_strerror(st));
        else
            gsl_vector_memcpy(p, gsl_multifit_nlinear_position(ws));
    }
    if (rc == TT_OK) {
        unpack(&d, p, m);
        gsl_multifit_nlinear_covar(gsl_multifit_nlinear_jac(ws), 0.0, cov);
        memset(m->cov, 0, sizeof m->cov);
        for (size_t i = 0; i < np; i++)
            for (size_t j = 0; j < np; j++)
                m->cov[i][j] = gsl_matrix_get(cov, i, j) * HANN_BIN_CORRELATION;
        double chi2;
        gsl_blas_ddot(gsl_multifit_nlinear_residual(ws), gsl_multifit_nlinear_residual(ws), &chi2);
        m->chi2_dof = chi2 / (double)(nb - np);
        m->nparam = (int)np;
        if (!(m->f0 > 0 && m->Q > 0 && m->P > 0) || !isfinite(m->cov[0][0]))
            rc = tt_error(TT_ENUM, "the tune's fit failed (f0 %g Hz, Q %g)", m->f0, m->Q);
    }
done:
    free(ref);
    if (ws)
        gsl_multifit_nlinear_free(ws);
    gsl_vector_free(p);
    gsl_matrix_free(cov);
    return rc;
}

void tune_first_guess(const double *psd, size_t lo_bin, size_t hi_bin, double df, double W, tune_fit *m)
{
    size_t kp = lo_bin;
    for (size_t k = lo_bin; k < hi_bin; k++)
        if (psd[k] > psd[kp])
            kp = k;
    size_t lo = kp, hi = kp;
    while (lo > 1 && psd[lo] - W > 0.5 * (psd[kp] - W))
        lo--;
    while (hi + 1 < hi_bin && psd[hi] - W > 0.5 * (psd[kp] - W))
        hi++;
    m->f0 = (double)kp * df;
    m->Q = fmax(1, m->f0 / (fmax(1, (double)(hi - lo)) * df));
    m->P = fmax(psd[kp] - W, 1e-300) / (m->Q * m->Q);
    m->W = W;
}
