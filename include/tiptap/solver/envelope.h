/* tiptap: the envelope tier's local model of the cycle map (docs/dynamics.md, Tiers).
 *
 * A drive cycle takes the stroboscopic state x (the sim's n components, tt_sim_dim: d,
 * d' for one mode) at its start and the sample's position s at its middle to the state
 * one period later, P(x, s), and yields the cycle's observables o(x, s): the deflection
 * samples the lock-in reads, the peak force, the greatest indentation and the
 * tip-sample loss. Where the envelope moves slowly, x and s stay close to where a cycle
 * was last integrated (the anchor), and
 *
 *     P(x, s) = P(xa, sa) + dP/dx (x - xa) + dP/ds (s - sa) + O(|x - xa|^2 + |s - sa|^2)
 *
 * and likewise o: one cycle of the model costs an n x (n + 1) and an (m + 3) x (n + 1)
 * product instead of an integration, m the linear combinations of the samples the
 * caller needs (the lock-in's components). Its Jacobians come from central differences
 * (2 (n + 1) cycles); each integrated cycle re-anchors the model, so the second-order
 * remainder stays small while the Jacobians are reused. The model is iterated cycle by
 * cycle, so it contracts as the true map does (its eigenvalues are the Floquet
 * multipliers): it is stable however strongly the contact damps.
 *
 * Its error is measured, not assumed: tt_envelope_error compares the model's cycle
 * with an integrated one from the same state and sample, in units of the free
 * amplitude (positions of A0, velocities of w A0, forces of k A0, losses of k A0^2).
 *
 * A plan, as FFTW's: every choice (samples, probes, reduction, inputs, order, noise,
 * models kept) is a field of tt_envelope_params given to tt_envelope_alloc, which
 * allocates every buffer the model will use; nothing later allocates, so a build or a
 * prediction cannot run out of memory, and no call must come before another.
 *
 * Ownership: tt_envelope_alloc returns a handle freed by tt_envelope_free; it copies
 * the parameters (the reduction's rows included) and keeps no pointer to the sim it was
 * planned for or to the one tt_envelope_build drives. States x, x2, x1, x21 are arrays
 * of n doubles owned by the caller; observable vectors are the caller's too.
 */
#ifndef TIPTAP_ENVELOPE_H
#define TIPTAP_ENVELOPE_H

#include "tiptap/export.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

/* Observables after the deflection samples (or their m reductions) of a cycle's vector;
 * the probes, where planned, come after these. */
enum { TT_ENV_PEAK = 0, TT_ENV_INDENT = 1, TT_ENV_ETS = 2, TT_ENV_EXTRA = 3 };

typedef struct tt_envelope tt_envelope;

/* The plan's parameters (zero them, then set what is used). */
typedef struct {
    int samples;           /* deflection samples per cycle (> 0) */
    int probes;            /* tip positions at the sim's probe times (tt_sim_set_probes),
                            * observables after TT_ENV_EXTRA: a grazing tip's path near
                            * its closest approach (tiptap/solver/graze.h); 0: none */
    int reduced;           /* m: linear combinations of the samples the caller reads
                            * (tt_envelope_predict's TT_ENV_REDUCED); 0: none */
    const double *reduce;  /* their rows, m x samples (copied) */
    int travel;            /* the sample's travel within the cycle (sdot T) an input, for a
                            * sample whose travel changes from cycle to cycle (the z
                            * piezo's noise): 2 more cycles a build */
    int second_order;      /* second order in the inputs (docs/dynamics.md, "Noise on the
                            * envelope tier"): one more cycle a build per pair of inputs,
                            * the Jacobians carried to each new anchor */
    int kept;              /* second order: room for this many models kept for recall
                            * (tt_envelope_keep); 0: none */
    double psd;            /* the thermal force's two-sided PSD, N^2/Hz (0: none; one mode,
                            * with or without a law's states after its (d, d')) */
    double sd;             /* the detector's rms noise per sample, m (0: none; needs m) */
    int dim;               /* the state's components (0: the sim's now, tt_sim_dim): a plan
                            * for a law whose states the sim takes on later */
} tt_envelope_params;

/* What a build made of the model: usable, or why not (the caller integrates every cycle
 * until it builds again). Out of memory is no outcome: the plan allocated everything. */
typedef enum {
    TT_ENV_USABLE = 0,      /* every perturbed cycle ran on the anchor's branch */
    TT_ENV_CYCLE_FAILED,    /* a perturbed cycle could not be integrated (or was cancelled) */
    TT_ENV_OFF_BRANCH,      /* one touched the sample, or did not, otherwise than the
                             * anchor, or ended with another contact flag */
    TT_ENV_SINGULAR_FLOW,   /* the flow's Jacobian along the cycle is singular: no thermal
                             * covariance */
    TT_ENV_OUTCOMES
} tt_envelope_outcome;
/* The outcome's name, for messages ("usable", "cycle failed", ...). */
const char *tt_envelope_outcome_name(tt_envelope_outcome o);

/* A plan for the sim's state (tt_sim_dim components, or p->dim) on its cantilever.
 * TT_EINVAL for a parameter out of range (thermal noise on more than one mode, detector
 * noise without a reduction), TT_ENOMEM when the buffers cannot be had. */
int tt_envelope_alloc(tt_envelope **out, const tt_sim *sim, const tt_envelope_params *p);

/* The bytes tt_envelope_alloc would hold for p at p->dim components (0: 2), its kept
 * models included (a scan's memory estimate, one plan per state dimension per thread). */
double tt_envelope_plan_bytes(const tt_envelope_params *p);
void tt_envelope_free(tt_envelope *e);
/* Observables per cycle: samples + TT_ENV_EXTRA + probes. */
int tt_envelope_size(const tt_envelope *e);

/* A cycle's observable vector from its samples (deflection d - z), results and the
 * tip's positions at the probes (NULL: not recorded, NAN). */
void tt_envelope_observe(const tt_envelope *e, const tt_sample *samples,
                         const tt_sample *probes, const tt_cycle *cy, double *obs);
/* An observable vector reduced: the m combinations, then TT_ENV_EXTRA and the probes. */
void tt_envelope_reduce_obs(const tt_envelope *e, const double *obs, double *red);

/* A cycle the caller just integrated, from state x0 (contact flag c0) with the sample at
 * s (at the cycle's start) moving at sdot, ended in the sim's present state with the
 * observables obs. Anchor the model there and take its derivatives by differences: the
 * sim is put back at the end of the unperturbed cycle (its sampling buffer is
 * overwritten). *cycles counts the cycles run. */
tt_envelope_outcome tt_envelope_build(tt_envelope *e, tt_sim *sim, const double *x0,
                                      int c0, double s, double sdot, const tt_cycle *cy,
                                      const double *obs, long *cycles);

/* Re-anchor on an integrated cycle from x0 ending in x1 (the Jacobians are kept; at
 * second order carried there). */
void tt_envelope_anchor(tt_envelope *e, const double *x0, double s, double sdot,
                        const double *x1, const tt_cycle *cy, const double *obs);

/* What a prediction gives: every observable (size), the reduced ones (m + TT_ENV_EXTRA),
 * or the probes alone. */
typedef enum { TT_ENV_ALL = 0, TT_ENV_REDUCED = 1, TT_ENV_PROBES = 2 } tt_envelope_view;

/* The model's cycle from x with the sample at s (cycle start) moving at sdot: end state
 * x1 and the view's outputs. x2: the state's second-order part, carried by the caller
 * (0 after an integrated cycle), and x21 the end state's; x2 NULL: the first-order
 * model (x21 not written). */
void tt_envelope_predict(const tt_envelope *e, tt_envelope_view view, const double *x,
                         const double *x2, double s, double sdot, double *x1,
                         double *x21, double *out);

/* The largest scaled difference between two versions of one cycle (model and
 * integration): end states and the view's outputs (TT_ENV_ALL or TT_ENV_REDUCED),
 * relative to the free amplitude. At second order with a reduction, TT_ENV_ALL holds
 * the samples as the lock-in's components. */
double tt_envelope_error(const tt_envelope *e, tt_envelope_view view, const double *xa,
                         const double *oa, const double *xb, const double *ob);

/* Noise: standard normal numbers a cycle's draw takes (n + m; 0: no noise), and a
 * cycle's noise from them: the end state's dx (n), the reduced samples' added to dc (m). */
int tt_envelope_noise_size(const tt_envelope *e);
void tt_envelope_noise(const tt_envelope *e, const double *g, double *dx, double *dc);

/* A new line: the kept models and the places missed forgotten, the noise's covariance
 * back to the free cantilever's, so that a line depends on no other line. */
void tt_envelope_reset(tt_envelope *e);

/* Kept models (second order, p->kept; docs/dynamics.md, "Noise on the envelope tier"):
 * keep the model just built under the caller's tag (a material), replacing the one
 * unused the longest when all room is taken. */
void tt_envelope_keep(tt_envelope *e, int tag);
/* The inputs' largest offset from where the present model's derivatives were taken (in
 * tt_envelope_reach's units). */
double tt_envelope_model_reach(const tt_envelope *e, const double *x, double s,
                               double sdot);
/* Make the kept model nearest to the inputs, within `within` of where its derivatives
 * were taken, with the contact flag, touch and tag given, the present one. 1: recalled;
 * the caller then anchors it on an integrated cycle (tt_envelope_anchor). 0: none. */
int tt_envelope_recall(tt_envelope *e, const double *x, double s, double sdot,
                       int contact, int touched, int tag, double within);
/* The same with the present anchor's contact flag and touch, anchored where it was
 * built: it predicts on from there with no cycle integrated. 1: switched; 0: none is
 * near enough, and the present model is as it was. */
int tt_envelope_switch(tt_envelope *e, const double *x, double s, double sdot, int tag,
                       double within);
/* Whether the inputs come back within `within` of a place where the caller found no kept
 * model near (tagged as given) among the last 64 such places: 1, a place worth a model
 * of its own; 0, and this place is noted. */
int tt_envelope_revisit(tt_envelope *e, const double *x, double s, double sdot, int tag,
                        double within);

/* Whether a cycle touched the sample; the anchor's touch and start contact flag. */
int tt_envelope_touched(const tt_cycle *cy);
int tt_envelope_anchor_touched(const tt_envelope *e);
int tt_envelope_anchor_contact(const tt_envelope *e);
/* How far the sample at s moving at sdot is from the anchor's (mid-cycle), m. */
double tt_envelope_sample_offset(const tt_envelope *e, double s, double sdot);
/* How far a cycle's inputs (state x, sample at s moving at sdot) are from the anchor's,
 * the largest in units of the free amplitude (positions, s) and of w A0 (velocities). */
double tt_envelope_reach(const tt_envelope *e, const double *x, double s, double sdot);

TT_END_DECLS
#endif
