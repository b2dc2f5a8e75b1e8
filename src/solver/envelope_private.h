/* The envelope tier's model (tiptap/solver/envelope.h): its state, shared by envelope.c
 * (the plan, the model and its anchor), envelope_models.c (the models kept for recall)
 * and envelope_noise.c (the noise's covariance). */
#ifndef TIPTAP_ENVELOPE_PRIVATE_H
#define TIPTAP_ENVELOPE_PRIVATE_H

#include <math.h>

#include "tiptap/solver/envelope.h"

/* Inputs of the model: the state's nx components at the cycle start, the sample's
 * position mid-cycle and, where planned (travel), the sample's travel within the cycle:
 * ni = nx + 2 places, the first nin in use. The largest, for arrays on the stack. */
enum { NIN_MAX = TT_SIM_DIM_MAX + 2 };

/* A model kept for recall (envelope_models.c): the derivatives as taken at xb, sb, tb,
 * and the cycle integrated there (its end state x1, observables oa, reduced ra). */
typedef struct {
    double sb, tb;
    int contact, touched, tag;
    int key;           /* and its contact flag, touch and tag in one key */
    long used;         /* when it was last kept or recalled: the oldest is replaced */
    /* in one block: J (nx x ni), xb, x1 (nx), q (ni: xb over its scales, sb and tb over
     * L, for the search), then C, Cr, H, Hr, Lj, oa, ra as the model's */
    double *J, *xb, *x1, *q, *C, *Cr, *H, *Hr, *Lj, *oa, *ra;
} tt_envelope_kept;

/* Places where no kept model was near (tt_envelope_revisit), the last MISSES of them. */
enum { MISSES = 64 };
typedef struct {
    double x[TT_SIM_DIM_MAX], s, t;
    int tag;
} tt_envelope_miss;

struct tt_envelope {
    int nx;               /* the state's components (tt_sim_dim) */
    int nmode;            /* of them the modes' (d, d') pairs; the law's states after */
    int ni, npair;        /* input places (nx + 2) and their pairs */
    int n, no;            /* samples per cycle; observables (n + TT_ENV_EXTRA + np) */
    int np;               /* probes of the gap */
    double T, L, V;       /* period; length and velocity scales (A0, w A0) */
    double mass, w0, sig; /* the cantilever's effective mass, resonance and decay rate */
    double *xs;           /* per state component: its scale (L for positions, V for
                           * velocities: even and odd components) */
    double *hs;           /* per input (the state's components, the sample, the travel):
                           * the build's step (tt_envelope_build) */
    double *oscale;       /* per observable: its scale */
    /* the anchor: a cycle integrated from xa with the sample at sa (mid-cycle) */
    double *xa, sa, ta, *x1;
    int contact, touched;
    int nin;              /* inputs in use: nx + 1, or nx + 2 with the travel */
    int generic;          /* the prediction's generic kernels for one mode too (set by
                           * tests/test_envelope_plan.c only, which checks they agree) */
    /* second order: the second derivatives of the end state and of the observables, by
     * input pair (npair per output, outputs by rows: the end state's nx, then the
     * observables'), and of the reduced observables; built: they belong to the present
     * Jacobians */
    int second, built;
    double *H, *Hr;
    /* the second derivatives and the noise factor in use, read only: the model's own (H,
     * Hr, Lj) or a kept one's (tt_envelope_switch, _recall), which are not copied */
    const double *Hv, *Hrv, *Ljv;
    double *oa;
    /* Jacobians: of the end state (nx x ni, by rows) and of the observables, by input */
    double *J;
    double *C;            /* no x ni, by columns (the prediction's loop vectorises) */
    /* the samples reduced: m x n rows R; the anchor's reduced observables ra (nr = m +
     * TT_ENV_EXTRA + np) and their Jacobian Cr, by columns */
    int m, nr;
    double *R, *ra, *Cr;
    /* noise: the thermal force's two-sided PSD and the detector's per-sample rms; the
     * states at the samples of the 2 nx cycles perturbed in each state component (the
     * flow's Jacobian along the cycle; one mode, a law's states after it); the lower
     * Cholesky factor, by rows, of the
     * joint covariance of the end state's and the reduced samples' noise per cycle (nn
     * = nx + m) */
    double psd, sd;
    int nn;
    double *trk, *Lj, *phi; /* phi: the flow's Jacobian at the samples and the end */
    double *Lf;             /* Lj for the free cantilever, until a model is built */
    /* scratch for a build and the covariance, sized by the plan */
    double *work;
    /* the inputs where the present derivatives were taken (built or recalled), and the
     * models kept for recall: nk of them, the first ik in use */
    double *xb, sb, tb;
    tt_envelope_kept *kept;
    int *korder;     /* the kept models in use by their first scaled input, ascending */
    int nk, ik;
    long clock;
    tt_envelope_miss miss[MISSES];
    int nmiss; /* misses recorded (the ring holds the last MISSES) */
};

/* The place of the input pair (i, j), i <= j, among the npair second derivatives. */
static inline int tt_envelope_pair(const tt_envelope *e, int i, int j)
{
    return i * e->ni - i * (i - 1) / 2 + (j - i);
}

/* The model's own second derivatives and noise factor in use (after a build, or before
 * the kept ones they may point into change). */
static inline void tt_envelope_own_views(tt_envelope *e)
{
    e->Hv = e->H;
    e->Hrv = e->Hr;
    e->Ljv = e->Lj;
}

/* The noise (envelope_noise.c): the scratch it needs (doubles of e->work); the free
 * cantilever's factor into the buffers the plan allocated; for a build, the flow's
 * Jacobian at the cycle's samples from the cycles perturbed by h in d and d' (e->trk),
 * and the thermal force's and detector's joint covariance factored into e->Lj (0: a
 * singular flow). */
size_t tt_envelope_noise_work(const tt_envelope *e);
void tt_envelope_noise_plan(tt_envelope *e);
void tt_envelope_flow_measured(tt_envelope *e, const double *h);
int tt_envelope_thermal_covariance(tt_envelope *e);

/* The kept models' storage (envelope_models.c): allocated for the plan, freed. */
int tt_envelope_models_alloc(tt_envelope *e, int k);
/* The doubles one kept model holds, from the plan's dimensions. */
size_t tt_envelope_model_doubles(const tt_envelope *e);
void tt_envelope_models_free(tt_envelope *e);

/* The largest offset of the inputs (x, s at the cycle's start moving at sdot) from the
 * place (xr, sr mid-cycle, tr the travel): each state component over its scale, the
 * sample's and, where it is an input, the travel's over A0. */
static inline double tt_envelope_distance(const tt_envelope *e, const double *xr, double sr,
                                          double tr, const double *x, double s, double sdot)
{
    double u = fabs(x[0] - xr[0]) / e->xs[0];
    for (int i = 1; i < e->nx; i++)
        u = fmax(u, fabs(x[i] - xr[i]) / e->xs[i]);
    if (e->nin > e->nx + 1)
        u = fmax(u, fabs(sdot * e->T - tr) / e->L);
    return fmax(u, fabs(s + 0.5 * sdot * e->T - sr) / e->L);
}

#endif
