/* tiptap: the envelope tier's local model of the cycle map (docs/dynamics.md, Tiers).
 *
 * A drive cycle takes the stroboscopic state x = (d, d') at its start and the sample's
 * position s at its middle to the state one period later, P(x, s), and yields the
 * cycle's observables o(x, s): the deflection samples the lock-in reads, the peak
 * force, the greatest indentation and the tip-sample loss. Where the envelope moves
 * slowly, x and s stay close to where a cycle was last integrated (the anchor), and
 *
 *     P(x, s) = P(xa, sa) + dP/dx (x - xa) + dP/ds (s - sa) + O(|x - xa|^2 + |s - sa|^2)
 *
 * and likewise o: one cycle of the model costs a 2 x 3 and an (n + 3) x 3 product
 * instead of an integration, or (m + 3) x 3 when the caller needs only m linear
 * combinations of the samples (tt_envelope_reduce). Its Jacobians come from central
 * differences (6 cycles); each integrated cycle re-anchors the model, so the
 * second-order remainder stays small while the Jacobians are reused. The model is
 * iterated cycle by cycle, so it contracts as the true map does (its eigenvalues are
 * the Floquet multipliers): it is stable however strongly the contact damps, which an
 * extrapolation over many cycles would not be.
 *
 * Its error is measured, not assumed: tt_envelope_error compares the model's cycle
 * with an integrated one from the same state and sample, in units of the free
 * amplitude (velocities of w A0, forces of k A0, losses of the free loss per cycle),
 * as the stepper's tolerance is.
 *
 * Ownership: tt_envelope_alloc returns a handle freed by tt_envelope_free. It drives
 * the sim given to tt_envelope_build and keeps no pointer to it.
 */
#ifndef TIPTAP_ENVELOPE_H
#define TIPTAP_ENVELOPE_H

#include "tiptap/export.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

/* Observables after the n deflection samples of a cycle's vector. */
enum { TT_ENV_PEAK = 0, TT_ENV_INDENT = 1, TT_ENV_ETS = 2, TT_ENV_EXTRA = 3 };

typedef struct tt_envelope tt_envelope;

/* A model for n deflection samples per cycle. */
int tt_envelope_alloc(tt_envelope **out, const tt_cantilever *c, int n);
void tt_envelope_free(tt_envelope *e);
/* Observables per cycle: n + TT_ENV_EXTRA + the probes. */
int tt_envelope_size(const tt_envelope *e);

/* Probes (tiptap/solver/graze.h): np more observables after the TT_ENV_EXTRA ones, the
 * tip's position d at the sim's probe times (tt_sim_set_probes), so that the model
 * predicts the tip's path near its closest approach (the gap to the sample is then
 * taken from the sample's own position at those times, which the model's input, the
 * sample's position mid-cycle, does not fix). Call it after tt_envelope_alloc and before
 * tt_envelope_reduce and tt_envelope_use_second_order. */
int tt_envelope_set_probes(tt_envelope *e, int np);
int tt_envelope_probes(const tt_envelope *e);

/* Take the sample's travel within the cycle (sdot T) as a fourth input of the model, for
 * a sample whose travel changes from cycle to cycle by more than its position's smooth
 * course explains (the z piezo's noise): its Jacobian column costs 2 more cycles a build,
 * and the travel's offset from the anchor's counts in tt_envelope_reach. Without it the
 * model holds the travel at the anchor's. Call it before the model is first built. */
void tt_envelope_use_travel(tt_envelope *e);

/* Second order in the inputs, for noise that takes the inputs further from the anchor
 * than a linear model holds (docs/dynamics.md, "Noise on the envelope tier"): the
 * second derivatives from the build's cycles and one more cycle per pair of inputs (3
 * or 6), the Jacobians carried to each new anchor, the state's second-order part
 * carried by the caller (tt_envelope_predict2), and tt_envelope_error holding the
 * samples as the lock-in's components (the reduction's rows) rather than one by one.
 * Call it after tt_envelope_reduce and before the model is first built. */
int tt_envelope_use_second_order(tt_envelope *e);

/* Kept models, for noise whose reach of the inputs outruns one model's (docs/dynamics.md,
 * "Noise on the envelope tier"): the second-order model holds near where its
 * derivatives were taken, and noise brings the inputs back near the same places again
 * and again. Room for k models (0: none kept), each its derivatives, its thermal
 * noise's factor and the cycle its build integrated (a few kB). The envelope owns them;
 * a model recalled or switched to is used from the store, its Jacobians copied, its
 * second derivatives and noise factor read where they are kept (until a build or
 * tt_envelope_forget). Call it after tt_envelope_use_second_order and
 * tt_envelope_set_noise. */
int tt_envelope_keep_models(tt_envelope *e, int k);
/* Forget the kept models (a new line, whose cycles must not depend on another's). */
void tt_envelope_forget(tt_envelope *e);
/* Keep the model just built (tt_envelope_build, second order) under the caller's tag
 * (a material), replacing the one unused the longest when all room is taken. */
void tt_envelope_keep(tt_envelope *e, int tag);
/* The inputs' largest offset from where the present model's derivatives were taken (in
 * tt_envelope_reach's units). */
double tt_envelope_model_reach(const tt_envelope *e, const double x[2], double s, double sdot);
/* Make the kept model nearest to the inputs, within `within` of where its derivatives
 * were taken, with the contact flag, touch and tag given, the present one. 1: recalled;
 * the caller then anchors it on an integrated cycle (tt_envelope_anchor), which carries
 * its derivatives there, before it predicts. 0: none is near enough. */
int tt_envelope_recall(tt_envelope *e, const double x[2], double s, double sdot, int contact,
                       int touched, int tag, double within);
/* Make the kept model nearest to the inputs, within `within` of where its derivatives
 * were taken, with the present anchor's contact flag and touch and the tag given, the
 * present one, anchored where it was built (on the cycle its build integrated there):
 * the model predicts on from there with no cycle integrated. 1: switched; 0: none is
 * near enough, and the present model is as it was. */
int tt_envelope_switch(tt_envelope *e, const double x[2], double s, double sdot, int tag,
                       double within);
/* Whether the inputs come back within `within` of a place where the caller found no kept
 * model near (tagged as given) among the last 64 such places: 1, a place worth a model
 * of its own; 0, and this place is noted. Forgotten with the kept models. */
int tt_envelope_revisit(tt_envelope *e, const double x[2], double s, double sdot, int tag,
                        double within);

/* A cycle's observable vector from its samples (deflection d - z) and results. */
void tt_envelope_observe(const tt_envelope *e, const tt_sample *samples, const tt_cycle *cy,
                         double *obs);

/* A cycle the caller just integrated, from state x0 (contact flag c0) with the sample at
 * s (at the cycle's start) moving at sdot, ended in the sim's present state with the
 * observables obs. Anchor the model there and take its Jacobians by central
 * differences: 6 more cycles, each from x0 or s perturbed, and the sim is put back at
 * the end of the unperturbed cycle (its sampling buffer is overwritten). Returns 1
 * when the model is usable: every perturbed cycle ran and touched the sample, or did
 * not, as the unperturbed one did, and ended with its contact flag. *cycles counts the
 * cycles run. A failing cycle is no error here: the caller integrates every cycle. */
int tt_envelope_build(tt_envelope *e, tt_sim *sim, const double x0[2], int c0, double s,
                      double sdot, const tt_cycle *cy, const double *obs, long *cycles);

/* The tip's positions at the probes (NULL: not recorded, NAN) into obs after the
 * TT_ENV_EXTRA observables. */
void tt_envelope_observe_probes(const tt_envelope *e, const tt_sample *probes, double *obs);

/* Re-anchor on an integrated cycle (the Jacobians are kept). x1: its end state. */
void tt_envelope_anchor(tt_envelope *e, const double x0[2], double s, double sdot,
                        const double x1[2], const tt_cycle *cy, const double *obs);

/* The model's cycle from x with the sample at s moving at sdot: end state x1 and the
 * observables obs. */
void tt_envelope_predict(const tt_envelope *e, const double x[2], double s, double sdot,
                         double x1[2], double *obs);

/* The same for a second-order model (tt_envelope_use_second_order): x is the state, x2
 * its second-order part (0 after an integrated cycle); x21 the end state's. Without
 * second order, or before it is built, x21 is 0 and the prediction tt_envelope_predict's
 * (which is this with x2 = 0). */
void tt_envelope_predict2(const tt_envelope *e, const double x[2], const double x2[2], double s,
                          double sdot, double x1[2], double x21[2], double *obs);

/* Reduce the model's deflection samples to m linear combinations of them, R (m x n, by
 * rows; copied), for a caller that needs only those (the lock-in's per-period
 * components, tiptap/instrument/lockin.h): tt_envelope_predict_reduced then costs
 * (m + 3) x 3 instead of (n + 3) x 3. Call it before the model is first built. */
int tt_envelope_reduce(tt_envelope *e, int m, const double *R);

/* tt_envelope_predict with the samples reduced: red holds the m reduced values, then
 * the TT_ENV_EXTRA observables. Needs tt_envelope_reduce. */
void tt_envelope_predict_reduced(const tt_envelope *e, const double x[2], double s, double sdot,
                                 double x1[2], double *red);

/* The model's probes alone (np tip positions, m) from x with the sample at s moving at sdot,
 * to first order in d, d' and s: neither the travel (tt_envelope_use_travel) nor the
 * second order is taken, as the grazing model that reads them runs only without noise. */
void tt_envelope_predict_probes(const tt_envelope *e, const double x[2], double s, double sdot,
                                double *g);
/* An observable vector reduced as tt_envelope_reduce asks: the m combinations, then the
 * TT_ENV_EXTRA observables and the probes as they are. */
void tt_envelope_reduce_obs(const tt_envelope *e, const double *obs, double *red);

/* tt_envelope_predict2 with the samples reduced. */
void tt_envelope_predict2_reduced(const tt_envelope *e, const double x[2], const double x2[2],
                                  double s, double sdot, double x1[2], double x21[2], double *red);

/* Noise of the model's cycles (docs/dynamics.md, "Noise on the envelope tier"): the
 * thermal force (two-sided PSD psd, N^2/Hz; 0: none) and detector noise of rms sd (m)
 * on each deflection sample, both to first order, as a draw per cycle of the end
 * state's noise and the reduced samples' (jointly Gaussian, covariance from the
 * flow's Jacobian along the anchor's cycle, taken by tt_envelope_build; the free
 * cantilever's until a model is built). Call it after tt_envelope_reduce; the cycles
 * tt_envelope_build runs must be noiseless. */
int tt_envelope_set_noise(tt_envelope *e, double psd, double sd);
/* Back to the free cantilever's covariance (a line's start, so that a line's noise does
 * not depend on the lines its thread ran before). */
void tt_envelope_noise_reset(tt_envelope *e);
/* Standard normal numbers a cycle's draw takes (2 + m; 0: no noise). */
int tt_envelope_noise_size(const tt_envelope *e);
/* A cycle's noise from the normals g: the end state's dx, the reduced samples' added to
 * dc (m). */
void tt_envelope_noise(const tt_envelope *e, const double *g, double dx[2], double *dc);
/* The detector's noise alone added to the reduced samples dc, from the normals g (m). */
void tt_envelope_detector_noise(const tt_envelope *e, const double *g, double *dc);

/* The largest scaled difference between two versions of one cycle (model and
 * integration): end states and observables, relative to the free amplitude. */
double tt_envelope_error(const tt_envelope *e, const double xa[2], const double *oa,
                         const double xb[2], const double *ob);

/* The same for two reduced versions (tt_envelope_reduce_obs), the combinations in units
 * of the free amplitude. */
double tt_envelope_error_reduced(const tt_envelope *e, const double xa[2], const double *ra,
                                 const double xb[2], const double *rb);

/* Whether a cycle touched the sample; the anchor's touch and start contact flag. */
int tt_envelope_touched(const tt_cycle *cy);
int tt_envelope_anchor_touched(const tt_envelope *e);
int tt_envelope_anchor_contact(const tt_envelope *e);
/* How far the sample at s moving at sdot is from the anchor's (mid-cycle), m. */
double tt_envelope_sample_offset(const tt_envelope *e, double s, double sdot);
/* How far a cycle's inputs (state x, sample at s moving at sdot) are from the anchor's,
 * the largest in units of the free amplitude (d, s) and of w A0 (d'). */
double tt_envelope_reach(const tt_envelope *e, const double x[2], double s, double sdot);

TT_END_DECLS
#endif
