/* Lock-in demodulation over whole drive periods with FFTW, then a low-pass filter
 * (see include/tiptap/instrument/lockin.h). */
#include "tiptap/instrument/lockin.h"

#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

#define MAXH 16
#define MAXORDER 8

struct tt_lockin {
    tt_lockin_params p;
    int n;                  /* samples per block */
    double *in;
    fftw_complex *out;
    fftw_plan plan;
    double alpha;           /* filter coefficient per block */
    double X[MAXORDER][MAXH], Y[MAXORDER][MAXH]; /* filter stages */
    double rawX[MAXH], rawY[MAXH], mean;
    int nc;                 /* components per period: 1 + 2 harmonics */
    double *R;              /* nc x samples_per_period: one period's samples to them */
    /* the second reference (ratio2 > 0): its cascade stepped per sample, the block's sums
     * of its products and the last block's raw result */
    double alpha2, X2[MAXORDER], Y2[MAXORDER], sumX2, sumY2, rawX2, rawY2;
    long n2;
};

/* The matrix of tt_lockin_transform: the mean, then per harmonic (2 / N) cos and sin of
 * h w t at the samples, so that a block's transform is the mean of its periods'. */
static int component_matrix(tt_lockin *l)
{
    const int N = l->p.samples_per_period;
    l->nc = 1 + 2 * l->p.harmonics;
    l->R = malloc((size_t)l->nc * (size_t)N * sizeof *l->R);
    if (!l->R)
        return -1;
    for (int q = 0; q < N; q++) {
        l->R[q] = 1.0 / N;
        for (int h = 1; h <= l->p.harmonics; h++) {
            /* the angle reduced to one turn first, exact in integers */
            double a = 2 * M_PI * (double)((long)h * q % N) / N;
            l->R[(size_t)(2 * h - 1) * (size_t)N + (size_t)q] = 2.0 / N * cos(a);
            l->R[(size_t)(2 * h) * (size_t)N + (size_t)q] = 2.0 / N * sin(a);
        }
    }
    return 0;
}

int tt_lockin_alloc(tt_lockin **out, const tt_lockin_params *p)
{
    *out = NULL;
    if (!(p->drive_frequency > 0) || p->samples_per_period < 8 || p->periods_per_block < 1 ||
        p->harmonics < 1 || p->harmonics > MAXH || p->filter_order < 1 || p->filter_order > MAXORDER ||
        !(p->time_constant >= 0))
        return tt_error(TT_EINVAL, "lock-in: invalid parameters");
    if (2 * p->harmonics >= p->samples_per_period)
        return tt_error(TT_EINVAL, "lock-in: %d harmonics need more than %d samples per period",
                        p->harmonics, 2 * p->harmonics);
    tt_lockin *l = calloc(1, sizeof *l);
    if (!l)
        return tt_error_nomem("the lock-in");
    l->p = *p;
    l->n = p->samples_per_period * p->periods_per_block;
    l->in = fftw_alloc_real((size_t)l->n);
    l->out = fftw_alloc_complex((size_t)l->n / 2 + 1);
    if (!l->in || !l->out) {
        tt_lockin_free(l);
        return tt_error_nomem("the lock-in's block of %d samples", p->samples_per_period * p->periods_per_block);
    }
    /* FFTW's planner is not thread-safe; execution on separate arrays is. */
#pragma omp critical(tt_fftw_planner)
    l->plan = fftw_plan_dft_r2c_1d(l->n, l->in, l->out, FFTW_ESTIMATE);
    if (!l->plan) {
        tt_lockin_free(l);
        return tt_error(TT_ENOMEM, "lock-in: no FFTW plan");
    }
    if (component_matrix(l)) {
        tt_lockin_free(l);
        return tt_error_nomem("the lock-in's block of %d samples", p->samples_per_period * p->periods_per_block);
    }
    double Tb = p->periods_per_block / p->drive_frequency;
    /* exact discretisation of a first-order section for a block-held input */
    l->alpha = p->time_constant > 0 ? 1 - exp(-Tb / p->time_constant) : 1.0;
    if (p->ratio2 > 0) {
        if (!isfinite(p->ratio2) || 2 * p->ratio2 >= p->samples_per_period / 2.0) {
            tt_lockin_free(l);
            return tt_error(TT_EINVAL, "lock-in: a second reference at %g times the drive needs more "
                                       "than %g samples per period (its mixing's sum frequency below "
                                       "the samples' Nyquist frequency)", p->ratio2, 4 * p->ratio2);
        }
        double ts = 1 / (p->drive_frequency * p->samples_per_period);
        l->alpha2 = p->time_constant > 0 ? 1 - exp(-ts / p->time_constant) : 1.0;
    }
    *out = l;
    return TT_OK;
}

void tt_lockin_free(tt_lockin *l)
{
    if (!l)
        return;
#pragma omp critical(tt_fftw_planner)
    {
        if (l->plan)
            fftw_destroy_plan(l->plan);
    }
    fftw_free(l->in);
    fftw_free(l->out);
    free(l->R);
    free(l);
}

void tt_lockin_reset(tt_lockin *l, double amplitude, double phase)
{
    memset(l->X, 0, sizeof l->X);
    memset(l->Y, 0, sizeof l->Y);
    for (int k = 0; k < l->p.filter_order; k++) {
        l->X[k][0] = amplitude * cos(phase);
        l->Y[k][0] = amplitude * sin(phase);
    }
    l->rawX[0] = amplitude * cos(phase);
    l->rawY[0] = amplitude * sin(phase);
}

void tt_lockin_copy(tt_lockin *dst, const tt_lockin *src)
{
    memcpy(dst->X, src->X, sizeof dst->X);
    memcpy(dst->Y, src->Y, sizeof dst->Y);
    memcpy(dst->rawX, src->rawX, sizeof dst->rawX);
    memcpy(dst->rawY, src->rawY, sizeof dst->rawY);
    dst->mean = src->mean;
    memcpy(dst->X2, src->X2, sizeof dst->X2);
    memcpy(dst->Y2, src->Y2, sizeof dst->Y2);
    dst->sumX2 = src->sumX2;
    dst->sumY2 = src->sumY2;
    dst->rawX2 = src->rawX2;
    dst->rawY2 = src->rawY2;
    dst->n2 = src->n2;
}

/* One block's raw results (the fundamental and harmonics: in-phase X, quadrature Y)
 * through the filter. */
static void filter(tt_lockin *l, const double *X, const double *Y)
{
    for (int h = 0; h < l->p.harmonics; h++) {
        double x = X[h], y = Y[h];
        l->rawX[h] = x;
        l->rawY[h] = y;
        for (int k = 0; k < l->p.filter_order; k++) {
            l->X[k][h] += l->alpha * (x - l->X[k][h]);
            l->Y[k][h] += l->alpha * (y - l->Y[k][h]);
            x = l->X[k][h];
            y = l->Y[k][h];
        }
    }
}

/* The block's end for the second reference: its raw result, the mean of the block's
 * products (kept from the last block when none came). */
static void second_close(tt_lockin *l)
{
    if (l->n2 > 0) {
        l->rawX2 = l->sumX2 / (double)l->n2;
        l->rawY2 = l->sumY2 / (double)l->n2;
    }
    l->sumX2 = l->sumY2 = 0;
    l->n2 = 0;
}

void tt_lockin_second_period(tt_lockin *l, const double *samples, double turns)
{
    const int N = l->p.samples_per_period, order = l->p.filter_order;
    const double a = l->alpha2, step = l->p.ratio2 / N;
    for (int q = 0; q < N; q++) {
        /* the phase in turns reduced before the angle: exact for any period count */
        double t = turns + step * q;
        double ang = 2 * M_PI * (t - floor(t));
        double x = 2 * samples[q] * cos(ang), y = 2 * samples[q] * sin(ang);
        l->sumX2 += x;
        l->sumY2 += y;
        for (int k = 0; k < order; k++) {
            l->X2[k] += a * (x - l->X2[k]);
            l->Y2[k] += a * (y - l->Y2[k]);
            x = l->X2[k];
            y = l->Y2[k];
        }
    }
    l->n2 += N;
}

void tt_lockin_reset_second(tt_lockin *l, double amplitude, double phase)
{
    for (int k = 0; k < MAXORDER; k++) {
        l->X2[k] = amplitude * cos(phase);
        l->Y2[k] = amplitude * sin(phase);
    }
    l->rawX2 = amplitude * cos(phase);
    l->rawY2 = amplitude * sin(phase);
    l->sumX2 = l->sumY2 = 0;
    l->n2 = 0;
}

int tt_lockin_push(tt_lockin *l, const double *samples)
{
    memcpy(l->in, samples, (size_t)l->n * sizeof(double));
    fftw_execute(l->plan);
    double scale = 2.0 / l->n, X[MAXH], Y[MAXH];
    l->mean = l->out[0][0] / l->n;
    for (int h = 1; h <= l->p.harmonics; h++) {
        int bin = h * l->p.periods_per_block;
        /* y = A cos(h w t - phi) = A cos(phi) cos + A sin(phi) sin; the transform's
         * bin holds (X - iY) n / 2 */
        X[h - 1] = l->out[bin][0] * scale;
        Y[h - 1] = -l->out[bin][1] * scale;
    }
    filter(l, X, Y);
    second_close(l);
    return TT_OK;
}

int tt_lockin_components(const tt_lockin *l) { return l->nc; }
const double *tt_lockin_component_matrix(const tt_lockin *l) { return l->R; }

void tt_lockin_transform(const tt_lockin *l, const double *samples, double *c)
{
    const int N = l->p.samples_per_period;
    for (int i = 0; i < l->nc; i++) {
        const double *r = l->R + (size_t)i * (size_t)N;
        double sum = 0;
        for (int q = 0; q < N; q++)
            sum += r[q] * samples[q];
        c[i] = sum;
    }
}

int tt_lockin_push_components(tt_lockin *l, const double *c)
{
    const int P = l->p.periods_per_block, nc = l->nc;
    double X[MAXH], Y[MAXH], mean = 0;
    for (int h = 0; h < l->p.harmonics; h++)
        X[h] = Y[h] = 0;
    for (int j = 0; j < P; j++) {
        const double *cj = c + (size_t)j * (size_t)nc;
        mean += cj[0];
        for (int h = 0; h < l->p.harmonics; h++) {
            X[h] += cj[2 * h + 1];
            Y[h] += cj[2 * h + 2];
        }
    }
    l->mean = mean / P;
    for (int h = 0; h < l->p.harmonics && P > 1; h++) { /* one period: its own, exactly */
        X[h] /= P;
        Y[h] /= P;
    }
    filter(l, X, Y);
    second_close(l);
    return TT_OK;
}

static double lag(double X, double Y)
{
    double ph = atan2(Y, X);
    return ph < -M_PI / 2 ? ph + 2 * M_PI : ph; /* continuous through 90 and 180 degrees */
}

double tt_lockin_amplitude(const tt_lockin *l, int h)
{
    int o = l->p.filter_order - 1;
    return hypot(l->X[o][h - 1], l->Y[o][h - 1]);
}

double tt_lockin_phase(const tt_lockin *l, int h)
{
    int o = l->p.filter_order - 1;
    return lag(l->X[o][h - 1], l->Y[o][h - 1]);
}

double tt_lockin_raw_amplitude(const tt_lockin *l, int h) { return hypot(l->rawX[h - 1], l->rawY[h - 1]); }
double tt_lockin_raw_phase(const tt_lockin *l, int h) { return lag(l->rawX[h - 1], l->rawY[h - 1]); }
double tt_lockin_mean(const tt_lockin *l) { return l->mean; }

double tt_lockin_second_amplitude(const tt_lockin *l)
{
    int o = l->p.filter_order - 1;
    return hypot(l->X2[o], l->Y2[o]);
}

double tt_lockin_second_phase(const tt_lockin *l)
{
    int o = l->p.filter_order - 1;
    return lag(l->X2[o], l->Y2[o]);
}

double tt_lockin_second_raw_amplitude(const tt_lockin *l) { return hypot(l->rawX2, l->rawY2); }
double tt_lockin_second_raw_phase(const tt_lockin *l) { return lag(l->rawX2, l->rawY2); }
