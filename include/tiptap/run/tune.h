/* tiptap: the thermal tune (tiptap tune): the free, undriven cantilever's deflection
 * under its thermal force at the scene's [noise] temperature, recorded through the
 * detector (its [noise] detector floor added), its Welch-averaged power spectral density
 * and a damped-oscillator fit giving the resonance f, the quality factor Q and the
 * spring constant k by equipartition, each with its statistical uncertainty for the
 * record's length (docs/force-and-tune.md).
 *
 * One mode: the lever is a point mass, whose deflection is the tip's displacement, so
 * the optical-lever correction chi is 1 (k = chi^2 kB T / <x^2>). With [cantilever]
 * modes above 1 the lever is a beam read through an optical lever calibrated on the
 * static end load: the record is sum chi_n q_n, chi_n = tt_beam_slope(n) / 1.5 (0.9177,
 * 3.1872, 5.2324), and each mode's peak is fitted on its own window, k_n =
 * chi_n^2 kB T / <x_n*^2> (mode 1: 0.842 kB T / <x*^2> for the mode's own k_1; Butt and
 * Jaschke 1995's 0.817 is that times the static k's share 0.971).
 *
 * Ownership: tt_run_tune returns a table the caller frees; the scene is borrowed.
 */
#ifndef TIPTAP_RUN_TUNE_H
#define TIPTAP_RUN_TUNE_H

#include "tiptap/export.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/config/scene.h"
#include "tiptap/physics/cantilever.h"
#include "tiptap/run/run.h"
#include "tiptap/util/table.h"

TT_BEGIN_DECLS

/* One mode's fit. */
typedef struct {
    double f0, f0_err;           /* Hz */
    double Q, Q_err;
    double k, k_err;             /* chi^2 kB T / <x*^2> of the mode's peak, N/m */
    double chi;                  /* the detector's reading per tip deflection (1: a point mass) */
    double noise_factor;         /* <q^2> k / kB T the interpolated force gives */
    double chi2_dof;
    double fit_low, fit_high;    /* its window, Hz */
} tt_tune_mode;

typedef struct {
    double temperature;          /* K */
    double fs, bin_width;        /* sample rate and the spectrum's resolution, Hz */
    long segments;               /* Welch segments (Hann, half overlapping) */
    double averages;             /* the independent averages they are worth */
    double f0, f0_err;           /* fitted resonance, Hz, and its standard error */
    double Q, Q_err;
    double k, k_err;             /* chi^2 kB T / (pi P f0 Q / 2), N/m, and its error */
    double chi;                  /* the optical-lever correction used (1: a point mass) */
    double white, white_err;     /* the detector's floor, m^2/Hz one-sided (0 without) */
    double chi2_dof;             /* the fit's weighted residual per degree of freedom */
    double fit_low, fit_high;    /* the fit's window, Hz */
    double variance;             /* the record's mean square deflection, m^2 */
    double variance_err;         /* its statistical error, m^2 */
    double noise_factor;         /* <x^2> k / kB T the interpolated force gives (below 1) */
    long cycles;                 /* drive periods integrated */
    /* each mode's fit (1 .. TT_CANTILEVER_MODES_MAX; mode[0] repeats f0 .. fit_high above;
     * with several modes chi2_dof and fit_low, fit_high above are mode 1's) */
    int modes;
    tt_tune_mode mode[TT_CANTILEVER_MODES_MAX];
} tt_tune_result;

/* The free lever's mean square thermal deflection relative to kB T / k when the force
 * is drawn at points per drive period of frequency fd and linear between (its spectrum
 * 2 c kB T sinc^4(f dt), dt = 1 / (points fd)): the oscillator's |H|^2 weighted mean of
 * sinc^4, about sinc^4(f0 dt) for a sharp resonance. */
double tt_tune_noise_factor(double f0, double Q, double fd, int points);

/* Rows f (Hz), psd (m^2/Hz, one-sided), fit (m^2/Hz; NAN outside the fit's window) over
 * the spectrum's bins, and with several modes mode1 .. modeN (each mode's own fitted
 * density, no floor, NAN outside its window; fit then the whole model in every window); the
 * result as metadata and in *r when not NULL. [tune] read by tt_config_tune: TT_EINVAL
 * naming [noise] temperature when it is 0, [tune] duration when the record is too short
 * for the resolution, before anything runs. */
int tt_run_tune(const tt_scene *s, tt_table **out, tt_tune_result *r, tt_progress_fn progress, void *user);

TT_END_DECLS
#endif
