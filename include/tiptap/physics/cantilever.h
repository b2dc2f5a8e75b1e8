/* tiptap: the point-mass cantilever and its drive (Burnham et al. eqs. 1, 2; docs/physics.md).
 *
 * Tip position d, base z, sample surface s on one axis pointing into the sample.
 *   m* d'' + c (d' - z') + k (d - z) = -P(d - s) - c_i (d' - s') [in contact] + F(t)
 * with m* = k / w0^2 and c = m* w0 / Q (the standard quality factor; Burnham et al.'s
 * 2/sqrt(2 + 4 Q^2) differs by under 0.1 % for Q >= 10).
 * Base drive (Burnham et al.'s): z = a_d cos(w t), F = 0. Force drive: z = 0,
 * F = F0 cos(w t). The drive strength is derived from the free amplitude A0 of the
 * deflection y = d - z at the drive frequency, so both drives give the same free
 * oscillation y = A0 cos(w t - phi0), phi0 = the lag, 90 degrees at resonance.
 *
 * Plain struct, no ownership.
 */
#ifndef TIPTAP_CANTILEVER_H
#define TIPTAP_CANTILEVER_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef enum { TT_DRIVE_BASE = 0, TT_DRIVE_FORCE = 1 } tt_drive;

/* The flexural modes a cantilever may carry (docs/physics.md, "Eigenmodes"). */
enum { TT_CANTILEVER_MODES_MAX = 3 };

typedef struct {
    /* given */
    double k;        /* spring constant, N/m */
    double f0;       /* resonance frequency, Hz */
    double Q;        /* quality factor */
    double A0;       /* free deflection amplitude at the drive frequency, m */
    double fd;       /* drive frequency, Hz */
    tt_drive drive;
    /* derived by tt_cantilever_init */
    double w0, wd;   /* rad/s */
    double m;        /* effective mass, kg */
    double c;        /* damping coefficient, kg/s */
    double a_d;      /* base drive amplitude, m (base drive) */
    double F0;       /* force drive amplitude, N (force drive) */
    double phi0;     /* free phase lag of y behind the drive, rad */
    double T;        /* drive period, s */
    /* the further flexural modes (tt_cantilever_set_modes; 0 or 1: the point mass).
     * Each mode n is a tip-normalised Euler-Bernoulli mode, its deflection q_n added to
     * the tip: m_n q_n'' + c_n q_n' + k_n q_n = F_tip + g_n m_n w^2 z (base drive). Index 0
     * repeats the point mass's k, f0, Q. */
    int modes;
    double mode_k[TT_CANTILEVER_MODES_MAX], mode_f[TT_CANTILEVER_MODES_MAX];
    double mode_Q[TT_CANTILEVER_MODES_MAX];
    double mode_m[TT_CANTILEVER_MODES_MAX], mode_c[TT_CANTILEVER_MODES_MAX];
    double mode_base[TT_CANTILEVER_MODES_MAX]; /* g_n: base drive's inertial coupling */
    /* mode 2's own drive, bimodal AM-AM (tt_cantilever_set_drive2; A2 = 0: none): a
     * second sinusoid of the same kind as the first (base or force) at fd2 */
    double A2;        /* the free deflection's amplitude at fd2, m */
    double fd2, wd2;  /* Hz, rad/s */
    double ratio2;    /* fd2 / fd: mode 2's drive periods per period of the first */
    double a_d2;      /* base amplitude, m, signed so that its force on mode 2 is +cos */
    double F02;       /* force amplitude, N (force drive) */
    double phi2;      /* the free deflection's lag behind that force, rad */
} tt_cantilever;

/* Fill the derived constants; TT_EINVAL with a message on non-physical input. */
int tt_cantilever_init(tt_cantilever *c, double k, double f0, double Q, double A0, double fd,
                       tt_drive drive);

/* Give the cantilever `modes` flexural modes (1 .. TT_CANTILEVER_MODES_MAX): f, k and Q
 * of modes 2.. at index 1.. (NULL or a NAN entry: the Euler-Bernoulli default of a
 * rectangular beam, f_n = f_1 (b_n / b_1)^2, k_n = k_1 (f_n / f_1)^2, Q_n = Q_1 f_n / f_1).
 * Call after tt_cantilever_init; TT_EINVAL with a message on non-physical input. */
int tt_cantilever_set_modes(tt_cantilever *c, int modes, const double *f, const double *k,
                            const double *Q);

/* Drive mode 2 as well (bimodal AM-AM, docs/physics.md "Bimodal imaging"): a second
 * sinusoid of the first drive's kind at fd2 (NAN: mode 2's resonance) whose free
 * deflection, all modes summed, has amplitude A2 (m) at fd2. Needs modes >= 2; call after
 * tt_cantilever_set_modes; TT_EINVAL with a message on non-physical input. */
int tt_cantilever_set_drive2(tt_cantilever *c, double A2, double fd2);

/* The second drive's phase at the start of drive period n of the first, in turns in
 * [0, 1): frac(n fd2 / fd), the one clock the equation of motion and the second lock-in
 * share. */
double tt_cantilever_drive2_turns(const tt_cantilever *c, long n);

/* The free deflection's complex response at angular frequency w to a unit drive of the
 * cantilever's kind (base: 1 m; force: 1 N), every mode summed: y = Re(R e^{i w t}). */
void tt_cantilever_response_modes(const tt_cantilever *c, double w, double *re, double *im);

/* Euler-Bernoulli constants of a clamped-free rectangular beam's mode n (1-based, up to
 * TT_CANTILEVER_MODES_MAX): the root b_n of cos b cosh b = -1, the optical lever's slope
 * per tip deflection phi_n'(L) L / phi_n(L), and the base drive's coupling
 * Gamma_n / Gamma_1 (Gamma_n = phi_n(L) int phi_n / int phi_n^2). NAN out of range. */
double tt_beam_root(int n);
double tt_beam_slope(int n);
double tt_beam_base_coupling(int n);

/* Steady free response of the deflection at angular frequency w to the configured
 * drive strength: amplitude (m) and lag (rad), from the transfer function. */
void tt_cantilever_response(const tt_cantilever *c, double w, double *amp, double *lag);

TT_END_DECLS
#endif
