/* tiptap: is the feedback loop oscillating? Judged from a line's full-rate record (the
 * scope: tiptap/instrument/scan_scope.h), not from the pixel means, which average a
 * ring of one period a pixel away (docs/imaging.md, "The scope").
 *
 * The ring: the error signal swings to alternate sides of zero, each swing beyond a
 * threshold (five times the record's own block-to-block noise, and at least 1 % of the
 * setpoint), the swings evenly spaced (each half period within a factor 1.6 of their
 * median). The loop oscillates when such a run lasts three periods (six swings) or
 * more: a loop of damping ratio 0.3 or more rings fewer than three swings after an
 * edge, one of 0.1 (or an unstable one) many more.
 *
 * What it measures of the loop, from the longest ring: its frequency f (the swings'
 * spacing) and decay per half period r (the median ratio of successive swing peaks),
 * hence the closed loop's dominant pole p = -sigma + i 2 pi f with sigma = -2 f ln r.
 * The loop is modelled as the PI controller C(s) = kp + ki / s acting on the plant
 * g e^(-s d) / ((1 + s tau_A) (1 + s tau_f)^n): the lock-in's n low-pass sections of
 * time constant tau_f and the block's delay d = periods_per_block / fd (half a block
 * to demodulate, half a block of z ramp), both known, and two unknowns: the plant gain
 * g = |dA/ds| (how much the amplitude changes per metre of separation, about 1 in hard
 * tapping) and the amplitude's time constant tau_A (Q / (pi f0) for a free cantilever,
 * its amplitude bandwidth pi f0 / Q; shorter in contact, where the surface limits the
 * amplitude at once as it comes closer). The pole solves 1 + L(p) = 0: its phase
 * condition gives tau_A, its magnitude g. With them, the suggested ki is the one that
 * gives the model a 60 degree phase margin (kp kept), a loop that settles an edge with
 * about 10 % overshoot; the phase margin of the present gains is reported too. A ring
 * the model cannot match even with tau_A = 0 (more lag in the filter and the delay
 * alone than the ring shows) leaves tau_A at 0 and model_phase off -180 deg.
 *
 * Ownership: plain structs, nothing allocated.
 */
#ifndef TIPTAP_SCAN_OSCILLATION_H
#define TIPTAP_SCAN_OSCILLATION_H

#include "tiptap/export.h"
#include "tiptap/instrument/scan_scope.h"

TT_BEGIN_DECLS

/* The loop the record came from (tt_scan_loop fills it from a scan). */
typedef struct {
    double tau_a;          /* the amplitude's time constant, s (tt_scan_loop: the free
                            * cantilever's, Q / (pi f0)) */
    double fd;             /* drive frequency, Hz */
    double time_constant;  /* the lock-in filter's, s */
    int filter_order;
    int periods_per_block;
    double kp, ki;         /* the gains the record ran with */
    double setpoint;       /* m */
} tt_loop;

/* The scan's loop as it stands now (its present gains, the free tau_A). */
void tt_scan_loop(const tt_scan *s, tt_loop *loop);

typedef struct {
    int rings;              /* 1: the loop oscillates (the ring below lasts three periods or more) */
    int retrace;            /* the direction of the longest ring */
    double t_start, t_end;  /* its span on the instrument's clock, s */
    double periods;         /* its length in periods */
    double frequency;       /* Hz */
    double decay;           /* ratio of successive swings (per half period; >= 1: growing) */
    double damping;         /* the damping ratio of the pole: -ln r / sqrt(pi^2 + ln^2 r) */
    double error_peak;      /* the largest swing of the error in it, m */
    double z_peak_to_peak;  /* of z about the surface the tip follows over it, m */
    double threshold;       /* the swing threshold, m */
    double noise;           /* the error's block-to-block noise (rms), m */
    /* the model (measured only where a ring of two swings or more was found: else NaN) */
    double plant_gain;      /* g, dimensionless */
    double amplitude_time;  /* tau_A, s */
    double model_phase;     /* the model's phase at the pole, deg (-180: matched) */
    double phase_margin;    /* of the present gains on the model, deg */
    double ki_suggested;    /* 1/s (Hz), for a 60 deg phase margin */
} tt_oscillation;

/* Checks both directions of the record. TT_EINVAL when the record holds no line. */
int tt_scan_oscillation(const tt_scan_scope *sc, const tt_loop *loop, tt_oscillation *o);

/* The model's phase margin (deg) of integral gain ki (kp as in loop) for plant gain g,
 * and the integral gain that gives phase margin pm (deg; NaN where none does). */
double tt_loop_phase_margin(const tt_loop *loop, double g, double ki);
double tt_loop_ki_for_margin(const tt_loop *loop, double g, double pm);

TT_END_DECLS
#endif
