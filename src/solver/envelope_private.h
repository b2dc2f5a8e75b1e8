/* The envelope tier's model (tiptap/solver/envelope.h): its state, shared by envelope.c
 * (the model and its anchor) and envelope_models.c (the models kept for recall). */
#ifndef TIPTAP_ENVELOPE_PRIVATE_H
#define TIPTAP_ENVELOPE_PRIVATE_H

#include <math.h>

#include "tiptap/solver/envelope.h"

/* Inputs of the model: d, d' at the cycle start, the sample's position mid-cycle and,
 * where the caller asks for it (tt_envelope_use_travel), the sample's travel within the
 * cycle. */
enum { NIN = 4, NPAIR = NIN * (NIN + 1) / 2 };

/* A model kept for recall (envelope_models.c): the derivatives as taken at xb, sb, tb,
 * and the cycle integrated there (its end state x1, observables oa, reduced ra). */
typedef struct {
    double xb[2], sb, tb, x1[2];
    double q[4];       /* for the search: xb over L and V, sb and tb over L */
    int contact, touched, tag;
    int key;           /* and its contact flag, touch and tag in one key */
    long used;         /* when it was last kept or recalled: the oldest is replaced */
    double J[2][NIN];
    double *C, *Cr, *H, *Hr, *Lj, *oa, *ra; /* as the model's, in one block */
} tt_envelope_kept;

/* Places where no kept model was near (tt_envelope_revisit), the last MISSES of them. */
enum { MISSES = 64 };
typedef struct {
    double x[2], s, t;
    int tag;
} tt_envelope_miss;

struct tt_envelope {
    int n, no;            /* samples per cycle; observables (n + TT_ENV_EXTRA + np) */
    int np;               /* probes of the gap (tt_envelope_set_probes) */
    double T, L, V;       /* period; length and velocity scales (A0, w A0) */
    double mass, w0, sig; /* the cantilever's effective mass, resonance and decay rate */
    double *oscale;       /* per observable: its scale */
    /* the anchor: a cycle integrated from xa with the sample at sa (mid-cycle) */
    double xa[2], sa, ta, x1[2];
    int contact, touched;
    int nin;              /* inputs in use: 3, or 4 with the travel */
    /* second order (tt_envelope_use_second_order): the second derivatives of the end
     * state and of the observables, by input pair (NPAIR per output, outputs by rows:
     * the end state's 2, then the observables'), and of the reduced observables;
     * built: they belong to the present Jacobians */
    int second, built;
    double *H, *Hr;
    /* the second derivatives and the noise factor in use, read only: the model's own (H,
     * Hr, Lj) or a kept one's (tt_envelope_switch, _recall), which are not copied */
    const double *Hv, *Hrv, *Ljv;
    double *oa;
    /* Jacobians: of the end state and of the observables, by input */
    double J[2][NIN];
    double *C;            /* no x NIN, by columns (the prediction's loop vectorises) */
    /* the samples reduced (tt_envelope_reduce): m x n rows R; the anchor's reduced
     * observables ra (nr = m + TT_ENV_EXTRA + np) and their Jacobian Cr, by columns */
    int m;
    double *R, *ra, *Cr;
    /* noise (tt_envelope_set_noise): the thermal force's two-sided PSD and the
     * detector's per-sample rms; the tip's states at the samples of the four cycles
     * perturbed in d and d' (the flow's Jacobian along the cycle); the lower Cholesky
     * factors, by rows, of the joint covariance of the end state's and the reduced
     * samples' noise per cycle (nn = 2 + m; thermal and detector) and of the
     * detector's alone (m) */
    double psd, sd;
    int nn;
    double *trk, *Lj, *Ld, *phi; /* phi: the flow's Jacobian at the samples and the end */
    double *Lf;                  /* Lj for the free cantilever, until a model is built */
    /* the inputs where the present derivatives were taken (built or recalled), and the
     * models kept for recall (tt_envelope_keep_models): nk of them, the first ik in use */
    double xb[2], sb, tb;
    tt_envelope_kept *kept;
    int *korder;     /* the kept models in use by their first scaled input, ascending */
    int nk, ik;
    long clock;
    tt_envelope_miss miss[MISSES];
    int nmiss; /* misses recorded (the ring holds the last MISSES) */
};

/* The model's own second derivatives and noise factor in use (after a build, or before
 * the kept ones they may point into change). */
static inline void tt_envelope_own_views(tt_envelope *e)
{
    e->Hv = e->H;
    e->Hrv = e->Hr;
    e->Ljv = e->Lj;
}

/* The noise's covariance (envelope_noise.c), for a build: the flow's Jacobian at the
 * cycle's samples from the cycles perturbed by h in d and d' (e->trk), and the thermal
 * force's and detector's joint covariance factored into e->Lj (0: out of memory, or a
 * singular flow). */
void tt_envelope_flow_measured(tt_envelope *e, const double h[NIN]);
int tt_envelope_thermal_covariance(tt_envelope *e);

/* The kept models' storage freed (tt_envelope_free). */
void tt_envelope_models_free(tt_envelope *e);

/* The largest offset of the inputs (x, s at the cycle's start moving at sdot) from the
 * place (xr, sr mid-cycle, tr the travel): d over A0, d' over w A0, the sample's and,
 * where it is an input, the travel's over A0. */
static inline double tt_envelope_distance(const tt_envelope *e, const double xr[2], double sr,
                                          double tr, const double x[2], double s, double sdot)
{
    double u = fmax(fabs(x[0] - xr[0]) / e->L, fabs(x[1] - xr[1]) / e->V);
    if (e->nin > 3)
        u = fmax(u, fabs(sdot * e->T - tr) / e->L);
    return fmax(u, fabs(s + 0.5 * sdot * e->T - sr) / e->L);
}

#endif
