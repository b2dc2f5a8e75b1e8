/* The envelope tier's kept models (see include/tiptap/solver/envelope.h,
 * tt_envelope_keep_models): the derivatives of the cycle map taken at a few places of the
 * inputs, recalled where the inputs come back near one of them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envelope_private.h"
#include "tiptap/util/error.h"

enum { NBLOCK = 7 };

/* The sizes of a model's blocks: C, Cr, H, Hr, Lj, oa and ra. */
static void block_sizes(const tt_envelope *e, size_t sz[NBLOCK])
{
    const size_t nr = (size_t)e->m + TT_ENV_EXTRA + (size_t)e->np;
    sz[0] = (size_t)e->no * NIN;
    sz[1] = e->Cr ? nr * NIN : 0;
    sz[2] = e->H ? (2 + (size_t)e->no) * NPAIR : 0;
    sz[3] = e->Hr ? nr * NPAIR : 0;
    sz[4] = e->Lj ? (size_t)e->nn * (size_t)e->nn : 0;
    sz[5] = (size_t)e->no;
    sz[6] = e->ra ? nr : 0;
}

static void free_kept(tt_envelope *e)
{
    tt_envelope_own_views(e);
    for (int i = 0; i < e->nk; i++)
        free(e->kept[i].C);
    free(e->kept);
    free(e->korder);
    e->kept = NULL;
    e->korder = NULL;
    e->nk = e->ik = 0;
}

int tt_envelope_keep_models(tt_envelope *e, int k)
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
        return tt_error_nomem("the envelope tier's %d kept models", k);
    }
    for (e->nk = 0; e->nk < k; e->nk++) {
        tt_envelope_kept *m = &e->kept[e->nk];
        if (!(m->C = malloc(total * sizeof *m->C))) {
            free_kept(e);
            return tt_error_nomem("the envelope tier's %d kept models", k);
        }
        m->Cr = m->C + sz[0];
        m->H = m->Cr + sz[1];
        m->Hr = m->H + sz[2];
        m->Lj = m->Hr + sz[3];
        m->oa = m->Lj + sz[4];
        m->ra = m->oa + sz[5];
    }
    return TT_OK;
}

void tt_envelope_models_free(tt_envelope *e) { free_kept(e); }

void tt_envelope_forget(tt_envelope *e)
{
    tt_envelope_own_views(e); /* none points into the store that is reused */
    e->ik = 0;
    e->clock = 0;
    e->nmiss = 0;
}

/* Copies of the blocks in the mask (bit i: block i of block_sizes), one way or the other. */
enum { ALL = (1 << NBLOCK) - 1, JACOBIANS = 1 | 2, ANCHOR = 32 | 64 };
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
    m->xb[0] = e->xb[0];
    m->xb[1] = e->xb[1];
    m->sb = e->sb;
    m->tb = e->tb;
    m->contact = e->contact;
    m->touched = e->touched;
    m->tag = tag;
    m->used = ++e->clock;
    m->q[0] = m->xb[0] / e->L;
    m->q[1] = m->xb[1] / e->V;
    m->q[2] = m->sb / e->L;
    m->q[3] = e->nin > 3 ? m->tb / e->L : 0;
    m->key = key_of(m->contact, m->touched, tag);
    const int at = lower_bound(e, m->q[0]);
    memmove(e->korder + at + 1, e->korder + at, (size_t)(e->ik - at) * sizeof *e->korder);
    e->korder[at] = slot;
    e->ik++;
    m->x1[0] = e->x1[0];
    m->x1[1] = e->x1[1];
    memcpy(m->J, e->J, sizeof m->J);
    double *const to[NBLOCK] = {m->C, m->Cr, m->H, m->Hr, m->Lj, m->oa, m->ra};
    const double *const from[NBLOCK] = {e->C, e->Cr, e->Hv, e->Hrv, e->Ljv, e->oa, e->ra};
    copy_blocks(e, ALL, to, from);
}

double tt_envelope_model_reach(const tt_envelope *e, const double x[2], double s, double sdot)
{
    return tt_envelope_distance(e, e->xb, e->sb, e->tb, x, s, sdot);
}

/* The kept model nearest to the inputs, within `within` of where its derivatives were
 * taken (tt_envelope_distance, on the inputs scaled beforehand), with the contact flag,
 * touch and tag given; -1: none. Only the models within reach in the first input are
 * looked at, from the order by it. */
static int nearest(const tt_envelope *e, const double x[2], double s, double sdot, int contact,
                   int touched, int tag, double within)
{
    const int key = key_of(contact, touched, tag);
    const double u0 = x[0] / e->L, u1 = x[1] / e->V, u2 = (s + 0.5 * sdot * e->T) / e->L,
                 u3 = e->nin > 3 ? sdot * e->T / e->L : 0;
    int best = -1;
    double dbest = within;
    for (int j = lower_bound(e, u0 - within); j < e->ik; j++) {
        const int i = e->korder[j];
        const double *q = e->kept[i].q;
        if (q[0] > u0 + dbest)
            break;
        if (e->kept[i].key != key)
            continue;
        double d = fabs(u0 - q[0]);
        const double d1 = fabs(u1 - q[1]), d2 = fabs(u2 - q[2]), d3 = fabs(u3 - q[3]);
        d = d1 > d ? d1 : d;
        d = d2 > d ? d2 : d;
        d = d3 > d ? d3 : d;
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
    memcpy(e->J, m->J, sizeof e->J);
    double *const to[NBLOCK] = {e->C, e->Cr, NULL, NULL, NULL, e->oa, e->ra};
    const double *const from[NBLOCK] = {m->C, m->Cr, NULL, NULL, NULL, m->oa, m->ra};
    copy_blocks(e, anchor ? JACOBIANS | ANCHOR : JACOBIANS, to, from);
    e->Hv = m->H;
    e->Hrv = m->Hr;
    e->Ljv = m->Lj;
    e->xa[0] = e->xb[0] = m->xb[0];
    e->xa[1] = e->xb[1] = m->xb[1];
    e->sa = e->sb = m->sb;
    e->ta = e->tb = m->tb;
    if (anchor) {
        e->x1[0] = m->x1[0];
        e->x1[1] = m->x1[1];
    }
    e->contact = m->contact;
    e->touched = m->touched;
    e->built = 1;
}

int tt_envelope_recall(tt_envelope *e, const double x[2], double s, double sdot, int contact,
                       int touched, int tag, double within)
{
    const int i = nearest(e, x, s, sdot, contact, touched, tag, within);
    /* the derivatives belong to the place they were taken at: the caller's anchor
     * carries them from there (tt_envelope_anchor) */
    if (i >= 0)
        install(e, i, 0);
    return i >= 0;
}

int tt_envelope_switch(tt_envelope *e, const double x[2], double s, double sdot, int tag,
                       double within)
{
    const int i = nearest(e, x, s, sdot, e->contact, e->touched, tag, within);
    if (i >= 0)
        install(e, i, 1);
    return i >= 0;
}

int tt_envelope_revisit(tt_envelope *e, const double x[2], double s, double sdot, int tag,
                        double within)
{
    const int n = e->nmiss < MISSES ? e->nmiss : MISSES;
    for (int i = 0; i < n; i++) {
        const tt_envelope_miss *m = &e->miss[i];
        if (m->tag == tag && tt_envelope_distance(e, m->x, m->s, m->t, x, s, sdot) <= within)
            return 1;
    }
    tt_envelope_miss *m = &e->miss[e->nmiss++ % MISSES];
    m->x[0] = x[0];
    m->x[1] = x[1];
    m->s = s + 0.5 * sdot * e->T;
    m->t = sdot * e->T;
    m->tag = tag;
    return 0;
}
