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
    for (int i = 0; i < e->nk; i++)
        free(e->kept[i].C);
    free(e->kept);
    free(e->kq);
    free(e->kkey);
    e->kept = NULL;
    e->kq = NULL;
    e->kkey = NULL;
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
    e->kq = calloc(4 * (size_t)k, sizeof *e->kq);
    e->kkey = calloc((size_t)k, sizeof *e->kkey);
    if (!e->kept || !e->kq || !e->kkey) {
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
    e->ik = 0;
    e->clock = 0;
    e->nmiss = 0;
}

/* Copies of the model's derivatives and noise factor (the first n blocks: 5), and of the
 * cycle its anchor holds (7), one way or the other. */
static void copy_blocks(const tt_envelope *e, int n, double *const to[NBLOCK],
                        const double *const from[NBLOCK])
{
    size_t sz[NBLOCK];
    block_sizes(e, sz);
    for (int i = 0; i < n; i++)
        if (sz[i])
            memcpy(to[i], from[i], sz[i] * sizeof *to[i]);
}

/* The search's key of a model: its contact flag, touch and tag. */
static int key_of(int contact, int touched, int tag)
{
    return tag * 4 + (contact ? 2 : 0) + (touched ? 1 : 0);
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
    } else {
        e->ik++;
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
    double *q = e->kq + 4 * (size_t)slot;
    q[0] = m->xb[0] / e->L;
    q[1] = m->xb[1] / e->V;
    q[2] = m->sb / e->L;
    q[3] = e->nin > 3 ? m->tb / e->L : 0;
    e->kkey[slot] = key_of(m->contact, m->touched, tag);
    m->x1[0] = e->x1[0];
    m->x1[1] = e->x1[1];
    memcpy(m->J, e->J, sizeof m->J);
    double *const to[NBLOCK] = {m->C, m->Cr, m->H, m->Hr, m->Lj, m->oa, m->ra};
    const double *const from[NBLOCK] = {e->C, e->Cr, e->H, e->Hr, e->Lj, e->oa, e->ra};
    copy_blocks(e, NBLOCK, to, from);
}

double tt_envelope_model_reach(const tt_envelope *e, const double x[2], double s, double sdot)
{
    return tt_envelope_distance(e, e->xb, e->sb, e->tb, x, s, sdot);
}

/* The kept model nearest to the inputs, within `within` of where its derivatives were
 * taken (tt_envelope_distance, on the inputs scaled beforehand), with the contact flag,
 * touch and tag given; -1: none. */
static int nearest(const tt_envelope *e, const double x[2], double s, double sdot, int contact,
                   int touched, int tag, double within)
{
    const int key = key_of(contact, touched, tag);
    const double u0 = x[0] / e->L, u1 = x[1] / e->V, u2 = (s + 0.5 * sdot * e->T) / e->L,
                 u3 = e->nin > 3 ? sdot * e->T / e->L : 0;
    int best = -1;
    double dbest = within;
    for (int i = 0; i < e->ik; i++) {
        if (e->kkey[i] != key)
            continue;
        const double *q = e->kq + 4 * (size_t)i;
        double d = fabs(u0 - q[0]);
        if (d > dbest)
            continue;
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

/* Kept model i made the present one: its derivatives and noise factor (nb = 5), or
 * those and the cycle integrated where they were taken as the anchor (nb = NBLOCK). */
static void install(tt_envelope *e, int i, int nb)
{
    tt_envelope_kept *m = &e->kept[i];
    m->used = ++e->clock;
    memcpy(e->J, m->J, sizeof e->J);
    double *const to[NBLOCK] = {e->C, e->Cr, e->H, e->Hr, e->Lj, e->oa, e->ra};
    const double *const from[NBLOCK] = {m->C, m->Cr, m->H, m->Hr, m->Lj, m->oa, m->ra};
    copy_blocks(e, nb, to, from);
    e->xa[0] = e->xb[0] = m->xb[0];
    e->xa[1] = e->xb[1] = m->xb[1];
    e->sa = e->sb = m->sb;
    e->ta = e->tb = m->tb;
    if (nb == NBLOCK) {
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
        install(e, i, 5);
    return i >= 0;
}

int tt_envelope_switch(tt_envelope *e, const double x[2], double s, double sdot, int tag,
                       double within)
{
    const int i = nearest(e, x, s, sdot, e->contact, e->touched, tag, within);
    if (i >= 0)
        install(e, i, NBLOCK);
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
