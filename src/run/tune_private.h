/* The thermal tune's spectrum and fit (tune_spectrum.c), private to src/run. */
#ifndef TIPTAP_RUN_TUNE_PRIVATE_H
#define TIPTAP_RUN_TUNE_PRIVATE_H

#include <stddef.h>

/* Welch's estimate of the one-sided PSD (m^2/Hz) of x[0..n) sampled at fs: Hann segments
 * of length L (even), each half overlapping the last, mean removed from each; psd[0..L/2]
 * (caller's), *segments, *averages (the independent averages the overlapped segments are
 * worth: K / (1 + 2 (1/6)^2 (K - 1) / K), Welch 1967). TT_ENOMEM. */
int tune_welch(const double *x, size_t n, double fs, size_t L, double *psd, long *segments,
               double *averages);

/* The fit's model and result. */
typedef struct {
    double P, f0, Q, W;    /* the oscillator's zero-frequency density, resonance, Q, floor */
    double dt;             /* the thermal force's point spacing (sinc^4 factor) */
    double fs;             /* the sample rate (the images above Nyquist fold back) */
    double cov[4][4];      /* covariance of (ln P, ln f0, ln Q, ln W) */
    double chi2_dof;
    int nparam;            /* 3: no floor fitted (W = 0), 4 with it */
} tune_fit;

/* The model at f: sinc^4(f dt) P / ((1 - u^2)^2 + (u / Q)^2), u = f / f0, with its
 * images at n fs -+ f (n = 1, 2) folded back by the sampling, plus W. */
double tune_model(const tune_fit *m, double f);

/* Fit psd over bins [k0, k1] (bin width df, averages the Welch estimate's), with the
 * floor when floor is set, over bg[0 .. k1 - k0] (a fixed density the model sits on: the
 * other modes' and a floor fitted elsewhere; NULL: none); m holds the starting values
 * and dt. TT_ENUM when it fails. */
int tune_fit_psd(const double *psd, size_t k0, size_t k1, double df, double averages, int floor,
                 const double *bg, tune_fit *m);

/* The fit's first guesses from the spectrum's bins [lo_bin, hi_bin): the highest bin,
 * the width at half its height above the floor W, the level there. */
void tune_first_guess(const double *psd, size_t lo_bin, size_t hi_bin, double df, double W, tune_fit *m);

/* Fit each of `modes` peaks on its own window, the other modes' fitted densities and the
 * floor held under it, sweeping the modes three times; f_guess[i]: where mode i's peak
 * is looked for (within a factor 1.3). fit[i] holds dt and fs on entry (W the floor's
 * first guess), the fit on return, k0[i] .. k1[i] its window; with floor set the highest
 * mode's window runs on to 0.95 of Nyquist and fits the floor. A status. */
int tune_fit_modes(const double *psd, size_t nb, double df, double averages, int with_floor, int modes,
                   const double *f_guess, tune_fit *fit, size_t *k0, size_t *k1);

#endif
