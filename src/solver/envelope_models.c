/* The envelope tier's kept models (see include/tiptap/solver/envelope.h,
 * tt_envelope_keep_models): the derivatives of the cycle map taken at a few places of the
 * inputs, recalled where the inputs come back near one of them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envelope_private.h"
#include "tiptap/util/error.h"

/* The sizes of a model's blocks: C, Cr, H, Hr and Lj. */
static void block_sizes(const tt_envelope *e, size_t sz[5])
{
    const size_t nr = (size_t)e->m + TT_ENV_EXTRA + (size_t)e->np;
    sz[0] = (size_t)e->no * NIN;
    sz[1] = e->Cr ? nr * NIN : 0;
    sz[2] = e->H ? (2 + (size_t)e->no) * NPAIR : 0;
    sz[3] = e->Hr ? nr * NPAIR : 0;
    sz[4] = e->Lj ? (size_t)e->nn * (size_t)e->nn : 0;
}

static void free_kept(tt_envelope *e)
{
    for (int i = 0; i < e->nk; i++)
        free(e->kept[i].C);
    free(e->kept);
    e->kept = NULL;
    e->nk = e->ik = 0;
}

int tt_envelope_keep_models(tt_envelope *e, int k)
{
    free_kept(e);
    if (k <= 0)
        return TT_OK;
    size_t sz[5], total = 0;
    block_sizes(e, sz);
    for (int i = 0; i < 5; i++)
        total += sz[i];
    e->kept = calloc((size_t)k, sizeof *e->kept);
    if (!e->kept)
        return tt_error_nomem("the envelope tier's %d kept models", k);
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
    }
    return TT_OK;
}

void tt_envelope_models_free(tt_envelope *e) { free_kept(e); }

void tt_envelope_forget(tt_envelope *e)
{
    e->ik = 0;
    e->clock = 0;
}

/* Copies of the model's derivatives and noise factor, one way or the other. */
static void copy_blocks(const tt_envelope *e, double *const to[5], const double *const from[5])
{
    size_t sz[5];
    block_sizes(e, sz);
    for (int i = 0; i < 5; i++)
        if (sz[i])
            memcpy(to[i], from[i], sz[i] * sizeof *to[i]);
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
    memcpy(m->J, e->J, sizeof m->J);
    double *const to[5] = {m->C, m->Cr, m->H, m->Hr, m->Lj};
    const double *const from[5] = {e->C, e->Cr, e->H, e->Hr, e->Lj};
    copy_blocks(e, to, from);
}

double tt_envelope_model_reach(const tt_envelope *e, const double x[2], double s, double sdot)
{
    return tt_envelope_distance(e, e->xb, e->sb, e->tb, x, s, sdot);
}

int tt_envelope_recall(tt_envelope *e, const double x[2], double s, double sdot, int contact,
                       int touched, int tag, double within)
{
    int best = -1;
    double dbest = within;
    for (int i = 0; i < e->ik; i++) {
        const tt_envelope_kept *m = &e->kept[i];
        if (m->contact != contact || m->touched != touched || m->tag != tag)
            continue;
        const double d = tt_envelope_distance(e, m->xb, m->sb, m->tb, x, s, sdot);
        if (d <= dbest) {
            dbest = d;
            best = i;
        }
    }
    if (best < 0)
        return 0;
    tt_envelope_kept *m = &e->kept[best];
    m->used = ++e->clock;
    memcpy(e->J, m->J, sizeof e->J);
    double *const to[5] = {e->C, e->Cr, e->H, e->Hr, e->Lj};
    const double *const from[5] = {m->C, m->Cr, m->H, m->Hr, m->Lj};
    copy_blocks(e, to, from);
    /* the derivatives belong to the place they were taken at: the caller's anchor
     * carries them from there (tt_envelope_anchor) */
    e->xa[0] = e->xb[0] = m->xb[0];
    e->xa[1] = e->xb[1] = m->xb[1];
    e->sa = e->sb = m->sb;
    e->ta = e->tb = m->tb;
    e->contact = m->contact;
    e->touched = m->touched;
    e->built = 1;
    return 1;
}
