/* The thermal tune's fit of several flexural modes: each peak on its own window, the
 * others' fitted densities and the floor held under it (see src/run/tune_private.h and
 * docs/force-and-tune.md, "Several modes"). */
#include <math.h>
#include <stdlib.h>

#include "tune_private.h"
#include "tiptap/util/error.h"

/* The other modes' densities (their images folded in, no floor) and, unless this window
 * fits it, the floor W: what mode n's peak sits on over bins [k0, k1]. */
static void background(const tune_fit *fit, int modes, int n, size_t k0, size_t k1, double df, double W,
                       double *bg)
{
    for (size_t k = k0; k <= k1; k++) {
        double b = W;
        for (int i = 0; i < modes; i++) {
            if (i == n)
                continue;
            tune_fit o = fit[i];
            o.W = 0;
            b += tune_model(&o, (double)k * df);
        }
        bg[k - k0] = b;
    }
}

/* Mode n's window: twenty half-widths either side of its peak, at most 0.95 f_n, never
 * past the geometric mean of its neighbours' frequencies; the floor's on to 0.95 of
 * Nyquist. */
static void window(const tune_fit *fit, int modes, int n, size_t nb, double df, int with_floor, size_t *k0,
                   size_t *k1)
{
    double w = fmin(0.95, 10 / fit[n].Q), lo = fit[n].f0 * (1 - w), hi = fit[n].f0 * (1 + w);
    if (n > 0)
        lo = fmax(lo, sqrt(fit[n - 1].f0 * fit[n].f0));
    if (n + 1 < modes)
        hi = fmin(hi, sqrt(fit[n].f0 * fit[n + 1].f0));
    *k0 = (size_t)fmax(2, floor(lo / df));
    *k1 = (size_t)fmin((double)nb - 1, ceil(hi / df));
    if (with_floor && n + 1 == modes)
        *k1 = (size_t)fmax((double)*k1, 0.95 * (double)nb);
}

int tune_fit_modes(const double *psd, size_t nb, double df, double averages, int with_floor, int modes,
                   const double *f_guess, tune_fit *fit, size_t *k0, size_t *k1)
{
    double *bg = malloc(nb * sizeof *bg), W = with_floor ? fit[0].W : 0;
    if (!bg)
        return tt_error_nomem("the tune's fit of %d modes", modes);
    for (int n = 0; n < modes; n++) {
        size_t a = (size_t)fmax(3, floor(f_guess[n] / 1.3 / df));
        size_t b = (size_t)fmin((double)nb, ceil(f_guess[n] * 1.3 / df));
        tune_first_guess(psd, a, b > a + 1 ? b : a + 2, df, W, &fit[n]);
    }
    int rc = TT_OK;
    for (int sweep = 0; sweep < 3 && rc == TT_OK; sweep++)
        for (int n = modes - 1; n >= 0 && rc == TT_OK; n--) {
            int fits_floor = with_floor && n + 1 == modes;
            window(fit, modes, n, nb, df, with_floor, &k0[n], &k1[n]);
            background(fit, modes, n, k0[n], k1[n], df, fits_floor ? 0 : W, bg);
            fit[n].W = fits_floor ? W : 0;
            if ((rc = tune_fit_psd(psd, k0[n], k1[n], df, averages, fits_floor, bg, &fit[n])))
                break;
            if (fits_floor)
                W = fit[n].W;
        }
    free(bg);
    return rc;
}
