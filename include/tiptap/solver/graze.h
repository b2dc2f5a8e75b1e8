/* tiptap: grazing touches on the envelope tier (docs/dynamics.md, Tiers, "Grazing
 * touches on the envelope tier").
 *
 * A tip that grazes a sticky sample touches in some cycles and not in others (on the
 * polymer blend's matrix at 80 % setpoint: 1010100101...): the loss of one jump-in and
 * pull-off (Burnham et al.'s hysteresis, section 2.3) is more than one cycle needs, so
 * the amplitude alternates about the depth where the tip just reaches jump-in. The
 * cycle map is then piecewise smooth: smooth on each branch (touch, no touch), with a
 * jump between them, and on the touch branch singular where the touch begins, since the
 * time of jump-in moves as the square root of how far past it the tip would reach. Both
 * are handled by what the branches share: the path of the tip before it touches is the
 * free branch's, which the envelope tier's free model predicts to rounding (linear in
 * the state, its gaps at probe times around the closest approach among its
 * observables). From those gaps the model finds whether this cycle reaches jump-in and
 * when, t_c; the touch branch is then a smooth function of the state, the sample's
 * position and t_c (its error 1e-9 of the free amplitude over the blend's whole orbit),
 * fitted here by least squares, in the state and sample linearly and in t_c as a cubic,
 * to the touch cycles integrated lately.
 *
 * The state is the sim's, of n components (tt_sim_dim: d, d' for one mode); the fit's
 * features are 1, the state's n, the sample and the cubic in t_c (n + 5), and the star
 * moves each state component and the sample (2 (n + 1) cycles).
 *
 * Ownership: tt_graze_alloc returns a handle freed by tt_graze_free, every buffer it
 * uses allocated there. It owns the probe times and the buffer it gives a sim
 * (tt_graze_aim): it must outlive that sim's cycles, or the sim's probes be turned off
 * (tt_graze_disarm). States (n doubles) and output vectors are the caller's.
 */
#ifndef TIPTAP_GRAZE_H
#define TIPTAP_GRAZE_H

#include "tiptap/export.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

enum {
    TT_GRAZE_PROBES = 24, /* gaps probed around the closest approach per cycle */
    TT_GRAZE_FREE = 0,    /* a cycle that does not reach jump-in */
    TT_GRAZE_TOUCH = 1,   /* one that does, once */
    TT_GRAZE_UNSURE = 2   /* too close to call, or its touch begins outside the probes */
};

typedef struct tt_graze tt_graze;

/* For the sim's state and outputs of n + m values per cycle: the end state, then m
 * reduced observables
 * (the envelope tier's, tt_envelope_reduce_obs, without the probes) on the scales
 * scale[m], in which the fit's errors are measured, each to at least floor[m] of its
 * scale (both copied): a touch's peak force and greatest indentation are a maximum
 * sought on each step's samples, which scatters from one touch to the next by more
 * than the tolerance where the steps fall differently. */
int tt_graze_alloc(tt_graze **out, const tt_sim *sim, int m, const double *scale,
                   const double *floor);
void tt_graze_free(tt_graze *g);

/* Forget the touch cycles and the fit (a new phase, an edge, another material) and set
 * the material's jump-in penetration (m, tt_contact_jumpin). */
void tt_graze_reset(tt_graze *g, double jumpin);

/* Put the probes around the closest approach of a cycle, found from its n samples
 * (tt_sim_samples: their gap d - s), and give them to the sim: their times are fixed
 * from then on, and the free model must be built with them. 0 when the window does
 * not fit within one cycle (the sim's probes are then off). */
int tt_graze_aim(tt_graze *g, tt_sim *sim, const tt_sample *samples, int n);
/* Probe i's time from the cycle's start (s), once aimed. */
double tt_graze_probe_time(const tt_graze *g, int i);
/* Turn the sim's probes off. */
void tt_graze_disarm(tt_graze *g, tt_sim *sim);

/* A cycle's branch from its free path's tip positions d at the probes (TT_GRAZE_PROBES
 * of them, as tt_envelope_predict's TT_ENV_PROBES gives them), the sample at s0 at the cycle's
 * start moving at sdot. *tc: the time of jump-in from the cycle's
 * start (s); where the path does not reach jump-in, that of its closest approach, which
 * the touch branch tends to as the touch shrinks to nothing. *reach: the free path's
 * greatest penetration d - s (m), a free cycle's greatest indentation (not linear in
 * the state, as the time it is reached moves). */
int tt_graze_branch(const tt_graze *g, const double *d, double s0, double sdot, double *tc,
                    double *reach);

/* A touch cycle integrated from state x0 with the sample at s_mid (mid-cycle), its
 * jump-in at tc: its end state x1 and its m reduced observables. */
void tt_graze_add(tt_graze *g, const double *x0, double s_mid, double tc, const double *x1,
                  const double *red);
/* Touch cycles held for the fit (the latest 32; the star apart). */
int tt_graze_count(const tt_graze *g);
/* Whether a fit of the touch branch is in use; its outputs per cycle (n + m); the star's
 * cycles (2 (n + 1)). */
int tt_graze_fitted(const tt_graze *g);
int tt_graze_outputs(const tt_graze *g);
int tt_graze_star_size(const tt_graze *g);

/* The deepest touch held (the earliest jump-in): its start state and sample (mid-cycle),
 * from which the caller runs the star of six cycles that teach the fit the directions
 * the orbit does not take (within a stretch the sample hardly moves, and the touches
 * cluster where the state and t_c move together): each state component and the sample
 * moved by -+1e-4 of its scale (A0, w A0 for velocities), in cycles i = 0 to
 * tt_graze_star_size - 1 (input i / 2). 0 when none is held. */
int tt_graze_deepest(const tt_graze *g, double *x0, double *s_mid);
/* Whether the star is missing or farther from the latest touch in the sample than the
 * fit takes it (5e-3 of the free amplitude; fresh: farther than half the touches'
 * reach, 5e-4). */
int tt_graze_star_due(const tt_graze *g, int fresh);
/* Touches held within the fit's reach (1e-3 of the free amplitude) of the latest in the
 * sample: a fit needs 8. */
int tt_graze_near(const tt_graze *g);
/* Star cycle i (0 to tt_graze_star_size - 1), as tt_graze_add. */
void tt_graze_add_pair(tt_graze *g, int i, const double *x0, double s_mid, double tc,
                       const double *x1, const double *red);

/* Fit the touch branch to the cycles held whose sample is within 1e-3 of the free
 * amplitude of the latest's (the star within 5e-3): 1 when there are enough (8 and the
 * star) and the
 * fit reproduces each within tol (in the outputs' scales; w A0 for d', A0 for d); the
 * fit is then the one in use, else the last good one stays. */
int tt_graze_fit(tt_graze *g, double tol);
/* The touch branch's cycle from x with the sample at s_mid and jump-in at tc: end state
 * x1 and the m reduced observables. Needs a fit. */
void tt_graze_predict(const tt_graze *g, const double *x, double s_mid, double tc, double *x1,
                      double *red);
/* The difference of two versions of a touch cycle (end states, m reduced observables)
 * in units of tol of each output's scale (or its floor, where higher; A0 for positions,
 * w A0 for velocities): at most 1 within
 * the tolerance. */
double tt_graze_error(const tt_graze *g, const double *xa, const double *ra, const double *xb,
                      const double *rb, double tol);
/* Whether the fit in use covers a touch from state x with the sample at s_mid and
 * jump-in at tc: the sample within 1e-3 of the free amplitude of the cycles fitted, tc
 * and the state within their ranges (5 % of their spread beyond): a fit is not to be
 * followed far outside its data (its error there reached 1e-6 of the free amplitude,
 * against 1e-9 within). */
int tt_graze_covers(const tt_graze *g, const double *x, double s_mid, double tc);

TT_END_DECLS
#endif
