/* The envelope tier's kept models (see include/tiptap/solver/envelope.h,
 * the plan's kept): the derivatives of the cycle map taken at a few places of the
 * inputs, recalled where the inputs come back near one of them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envelope_private.h"
#include "tiptap/util/error.h"

enum { NBLOCK = 11 };

/* The sizes of a model's blocks: J, xb, x1, q, C, Cr, H, Hr, Lj, oa and ra. */
static void block_sizes(const tt_envelope *e, size_t sz[NBLOCK])
{
    const size_t nr = (size_t)e->nr, ni = (size_t)e->ni, nx = (size_t)e->nx;
    const size_t npair = (size_t)e->npair;
    sz[0] = nx * ni;
    sz[1] = sz[2] = nx;
    sz[3] = ni;
    sz[4] = (size_t)e->no * ni;
    sz[5] = e->m > 0 ? nr * ni : 0;
    sz[6] = e->second ? (nx + (size_t)e->no) * npair : 0;
    sz[7] = e->second ? nr * npair : 0;
    sz[8] = e->psd > 0 || e->sd > 0 ? (size_t)e->nn * (size_t)e->nn : 0;
    sz[9] = (size_t)e->no;
    sz[10] = e->m > 0 ? nr : 0;
}

size_t tt_envelope_model_doubles(const tt_envelope *e)
{
    size_t sz[NBLOCK], total = 0;
    block_sizes(e, sz);
    for (int i = 0; i < NBLOCK; i++)
        total += sz[i];
    return total;
}

static void free_kept(tt_envelope *e)
{
    tt_envelope_own_views(e);
    for (int i = 0; i < e->nk; i++)
        free(e->kept[i].J);
    free(e->kept);
    free(e->korder);
    e->kept = NULL;
    e->korder = NULL;
    e->nk = e->ik = 0;
}

int tt_envelope_models_alloc(tt_envelope *e, int k)
{
    free_kept(e);
    if (k <= 0)
        return TT_OK;
    size_t sz[NBLOCK], total = 0;
    block_sizes(e, sz);
    for (int i = 0; i < NBLOCK; i++)
        total += sz[i];
    e->kept = calloc((size_t)k, sizeof *e->kept);
    e->korder = calloc((size_t)k, sizeof *e->korder);
    if (!e->kept || !e->korder) {
        free_kept(e);
        return TT_ENOMEM;
    }
    for (e->nk = 0; e->nk < k; e->nk++) {
        tt_envelope_kept *m = &e->kept[e->nk];
        if (!(m->J = malloc(total * sizeof *m->J))) {
            free_kept(e);
            return TT_ENOMEM;
        }
        double **const to[NBLOCK] = {&m->J, &m->xb, &m->x1, &m->q, &m->C, &m->Cr,
                                     &m->H, &m->Hr, &m->Lj, &m->oa, &m->ra};
        for (int i = 1; i < NBLOCK; i++)
            *to[i] = *to[i - 1] + sz[i - 1];
    }
    return TT_OK;
}

void tt_envelope_models_free(tt_envelope *e) { free_kept(e); }

void tt_envelope_reset(tt_envelope *e)
{
    /* the noise's covariance back to the free cantilever's */
    if (e->Lf)
        memcpy(e->Lj, e->Lf, (size_t)e->nn * (size_t)e->nn * sizeof *e->Lj);
    tt_envelope_own_views(e); /* none points into the store that is reused */
    e->ik = 0;
    e->clock = 0;
    e->nmiss = 0;
}

/* Copies of the blocks in the mask (bit i: block i of block_sizes), one way or the other. */
enum { ALL = (1 << NBLOCK) - 1, JACOBIANS = 1 | 16 | 32, ANCHOR = 4 | 512 | 1024 };
static void copy_blocks(const tt_envelope *e, int mask, double *const to[NBLOCK],
                        const double *const from[NBLOCK])
{
    size_t sz[NBLOCK];
    block_sizes(e, sz);
    for (int i = 0; i < NBLOCK; i++)
        if (mask & (1 << i) && sz[i])
            memcpy(to[i], from[i], sz[i] * sizeof *to[i]);
}

/* The search's key of a model: its contact flag, touch and tag. */
static int key_of(int contact, int touched, int tag)
{
    return tag * 4 + (contact ? 2 : 0) + (touched ? 1 : 0);
}

/* The first place in korder whose model's first scaled input is at least u0. */
static int lower_bound(const tt_envelope *e, double u0)
{
    int lo = 0, hi = e->ik;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (e->kept[e->korder[mid]].q[0] < u0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* Slot's place in korder taken out (n: the models in the order). */
static void order_remove(tt_envelope *e, int slot, int n)
{
    for (int i = 0; i < n; i++)
        if (e->korder[i] == slot) {
            memmove(e->korder + i, e->korder + i + 1, (size_t)(n - 1 - i) * sizeof *e->korder);
            return;
        }
}

void tt_envelope_keep(tt_envelope *e, int tag)
{
    if (!e->nk || !e->built)
        return;
    int slot = e->ik;
    if (slot == e->nk) { /* all in use: the one unused the longest goes */
        for (int i = slot = 0; i < e->nk; i++)
            if (e->kept[i].used < e->kept[slot].used)
                slot = i;
        order_remove(e, slot, e->ik);
        e->ik--;
    }
    tt_envelope_kept *m = &e->kept[slot];
    m->sb = e->sb;
    m->tb = e->tb;
    m->contact = e->contact;
    m->touched = e->touched;
    m->tag = tag;
    m->used = ++e->clock;
    for (int i = 0; i < e->nx; i++)
        m->q[i] = e->xb[i] / e->xs[i];
    m->q[e->nx] = m->sb / e->L;
    m->q[e->nx + 1] = e->nin > e->nx + 1 ? m->tb / e->L : 0;
    m->key = key_of(m->contact, m->touched, tag);
    const int at = lower_bound(e, m->q[0]);
    memmove(e->korder + at + 1, e->korder + at, (size_t)(e->ik - at) * sizeof *e->korder);
    e->korder[at] = slot;
    e->ik++;
    double *const to[NBLOCK] = {m->J, m->xb, m->x1, NULL, m->C, m->Cr,
                                m->H, m->Hr, m->Lj, m->oa, m->ra};
    const double *const from[NBLOCK] = {e->J, e->xb, e->x1, NULL, e->C, e->Cr,
                                        e->Hv, e->Hrv, e->Ljv, e->oa, e->ra};
    copy_blocks(e, ALL & ~8, to, from);
}

double tt_envelope_model_reach(const tt_envelope *e, const double *x, double s, double sdot)
{
    return tt_envelope_distance(e, e->xb, e->sb, e->tb, x, s, sdot);
}

/* The kept model nearest to the inputs, within `within` of where its derivatives were
 * taken (tt_envelope_distance, on the inputs scaled beforehand), with the contact flag,
 * touch and tag given; -1: none. Only the models within reach in the first input are
 * looked at, from the order by it. */
static int nearest(const tt_envelope *e, const double *x, double s, double sdot, int contact,
                   int touched, int tag, double within)
{
    const int key = key_of(contact, touched, tag), nx = e->nx, nq = e->ni;
    double u[NIN_MAX];
    for (int i = 0; i < nx; i++)
        u[i] = x[i] / e->xs[i];
    u[nx] = (s + 0.5 * sdot * e->T) / e->L;
    u[nx + 1] = e->nin > nx + 1 ? sdot * e->T / e->L : 0;
    int best = -1;
    double dbest = within;
    for (int j = lower_bound(e, u[0] - within); j < e->ik; j++) {
        const int i = e->korder[j];
        const double *q = e->kept[i].q;
        if (q[0] > u[0] + dbest)
            break;
        if (e->kept[i].key != key)
            continue;
        double d = fabs(u[0] - q[0]);
        for (int k = 1; k < nq; k++) {
            const double dk = fabs(u[k] - q[k]);
            d = dk > d ? dk : d;
        }
        if (d <= dbest) {
            dbest = d;
            best = i;
        }
    }
    return best;
}

/* Kept model i made the present one: its Jacobians copied (the anchor carries them), its
 * second derivatives and noise factor in use where they are, and with anchor set, the
 * cycle integrated where they were taken as the anchor. */
static void install(tt_envelope *e, int i, int anchor)
{
    tt_envelope_kept *m = &e->kept[i];
    m->used = ++e->clock;
    double *const to[NBLOCK] = {e->J, NULL, e->x1, NULL, e->C, e->Cr,
                                NULL, NULL, NULL, e->oa, e->ra};
    const double *const from[NBLOCK] = {m->J, NULL, m->x1, NULL, m->C, m->Cr,
                                        NULL, NULL, NULL, m->oa, m->ra};
    copy_blocks(e, anchor ? JACOBIANS | ANCHOR : JACOBIANS, to, from);
    e->Hv = m->H;
    e->Hrv = m->Hr;
    e->Ljv = m->Lj;
    memcpy(e->xa, m->xb, (size_t)e->nx * sizeof *e->xa);
    memcpy(e->xb, m->xb, (size_t)e->nx * sizeof *e->xb);
    e->sa = e->sb = m->sb;
    e->ta = e->tb = m->tb;
    e->contact = m->contact;
    e->touched = m->touched;
    e->built = 1;
}

int tt_envelope_recall(tt_envelope *e, const double *x, double s, double sdot, int contact,
                       int touched, int tag, double within)
{
    const int i = nearest(e, x, s, sdot, contact, touched, tag, within);
    /* the derivatives belong to the place they were taken at: the caller's anchor
     * carries them from there (tt_envelope_anchor) */
    if (i >= 0)
        install(e, i, 0);
    return i >= 0;
}

int tt_envelope_switch(tt_envelope *e, const double *x, double s, double sdot, int tag,
                       double within)
{
    const int i = nearest(e, x, s, sdot, e->contact, e->touched, tag, within);
    if (i >= 0)
        install(e, i, 1);
    return i >= 0;
}

int tt_envelope_revisit(tt_envelope *e, const double *x, double s, double sdot, int tag,
                        double within)
{
    const int n = e->nmiss < MISSES ? e->nmiss : MISSES;
    for (int i = 0; i < n; i++) {
        const tt_envelope_miss *m = &e->miss[i];
        if (m->tag == tag && tt_envelope_distance(e, m->x, m->s, m->t, x, s, sdot) <= within)
            return 1;
    }
    tt_envelope_miss *m = &e->miss[e->nmiss++ % MISSES];
    memcpy(m->x, x, (size_t)e->nx * sizeof *x);
    m->s = s + 0.5 * sdot * e->T;
    m->t = sdot * e->T;
    m->tag = tag;
    return 0;
}
