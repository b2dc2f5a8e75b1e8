/* The per-cycle steps of a scan line that the every-cycle tier (scan_line.c) and the
 * envelope tier (scan_envelope.c) share: a cycle's inputs, its integration, its
 * per-cycle channels and the lock-in block's end (see scan_private.h). */
#include <math.h>

#include "scan_private.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

/* The surface at cycle k's start, from the two found ahead when they hold it. */
static surf_pt surface_cached(const line_ctx *L, const line_state *st, long k)
{
    for (int i = 0; i < 2; i++)
        if (st->ahead[i].k == k)
            return st->ahead[i];
    return tt_scan_surface_at(L, k);
}

int tt_scan_cycle_begin(const line_ctx *L, line_state *st, cycle_in *in)
{
    const tt_scan *S = L->S;
    const long k = st->k;
    const int j = (int)(k % L->P);
    if ((k & 255) == 0 && tt_cancel_requested())
        return TT_EINTR;
    const worker *W = L->W;
    if (W->budget > 0 &&
        (W->budget_cycles ? st->cycles : tt_scan_line_work(W, st->cycles)) >= W->budget)
        return TT_SCAN_BUDGET;
    in->k = k;
    in->j = j;
    surf_pt a = surface_cached(L, st, k), b = surface_cached(L, st, k + 1), c = b;
    if (k + 1 < L->ncyc)
        c = surface_cached(L, st, k + 2);
    st->ahead[0] = b;
    st->ahead[1] = c;
    in->ha = a.h;
    in->topo = a.topo;
    in->dil = a.dil;
    in->mat = a.mat;
    in->geo = a.geo;
    in->hb = b.h;
    in->mat_next = b.mat;
    in->edge_next = c.mat != b.mat || fabs(c.h - b.h) > L->edge;
    /* The z piezo moves linearly from the last output to the new one over the block
     * after an update, so the sample never jumps; the sample follows the piezo's actual
     * height, the height channel records the command, as an instrument's does. */
    const double P = L->P;
    in->za = st->z_from + (st->z_to - st->z_from) * (double)j / P;
    double zb = st->z_from + (st->z_to - st->z_from) * (double)(j + 1) / P;
    double pa = in->za, pb = zb;
    if (L->piezo) {
        pa = st->z_act;
        pb = st->z_act = tt_piezo_advance(&st->pz, zb, S->cantilever.T);
    }
    in->sa = L->s_ref - in->ha + pa;
    in->sb = L->s_ref - in->hb + pb;
    /* The z piezo's noise moves the sample too (its height, not the command): exact at the
     * cycle's start and end, linear between; the step's normal is a function of (seed,
     * line, cycle), so a stretch run again draws the same. */
    in->zn = 0;
    if (S->zn.sd > 0) {
        in->sa += st->zn;
        in->zn = 0.5 * st->zn;
        st->zn = tt_noise_ou_next(&S->zn, L->kz, (uint64_t)st->cycles + 1, st->zn);
        in->sb += st->zn;
        in->zn += 0.5 * st->zn;
    }
    return TT_OK;
}

int tt_scan_integrate(const line_ctx *L, line_state *st, const cycle_in *in, tt_cycle *cy)
{
    tt_scan *S = L->S;
    tt_sim *sim = L->W->sim;
    if (in->mat != st->current || in->geo != st->geo) {
        int rc = tt_scan_geometry_use(S, L->W, in->mat, in->geo);
        if (rc)
            return rc;
        st->current = in->mat;
        st->geo = in->geo;
    }
    tt_sim_set_sample(sim, in->sa, (in->sb - in->sa) / S->cantilever.T);
    int rc = tt_sim_cycle(sim, cy);
    if (rc)
        return rc;
    if (cy->residual_rel > st->worst)
        st->worst = cy->residual_rel;
    st->loss[0] = cy->e_hyst;
    st->loss[1] = cy->e_ci;
    st->loss[2] = cy->e_visc;
    st->loss_fresh = 1;
    return TT_OK;
}

/* A cycle's loss per mechanism into its pixel's sums: an integrated cycle's own; a
 * model cycle (the envelope tier's model predicts the total alone) its total split as
 * the last integrated cycle's was, so that the three still add up to it. */
static void loss_sums(line_state *st, double ets, pixel_acc *a)
{
    double *sum = a->sum + TT_CH_LOSS_INDEX;
    if (st->loss_fresh) {
        for (int i = 0; i < 3; i++)
            sum[i] += st->loss[i];
        return;
    }
    const double total = st->loss[0] + st->loss[1] + st->loss[2];
    for (int i = 0; i < 3; i++)
        sum[i] += total != 0 ? ets * (st->loss[i] / total) : 0.0;
}

/* The sums of the pixel that cycle k of this direction falls in. */
static pixel_acc *pixel_of(const line_ctx *L, long k)
{
    const tt_raster *R = &L->S->raster;
    long px = tt_raster_pixel(R, L->dir, L->nc, k);
    return &L->pix[(size_t)L->dir * (size_t)R->pixels + (size_t)px];
}

int tt_scan_block_end(const line_ctx *L, line_state *st, long b)
{
    tt_scan *S = L->S;
    tt_lockin *li = L->W->lockin;
    /* the envelope and averaged tiers keep the block's periods as the lock-in's
     * components */
    int rc = L->W->env || L->W->averaged ? tt_lockin_push_components(li, L->W->y)
                                          : tt_lockin_push(li, L->W->y);
    if (rc)
        return rc;
    const int P = L->P;
    double A = tt_lockin_amplitude(li, 1), ph = tt_lockin_phase(li, 1);
    st->z_from = st->z_to;
    st->z_to = tt_feedback_update(&st->fb, A, P * S->cantilever.T);
    if (st->fb.clamped)
        st->clamped = 1;
    if (L->phase == 0)
        return TT_OK;
    if (L->W->scope)
        tt_scan_scope_put(L, st, b, A, ph);
    /* the block's lock-in outputs belong to the pixel of its last cycle */
    long k = b * P + P - 1;
    pixel_acc *a = pixel_of(L, k < L->nc ? k : L->nc - 1);
    a->sum[1] += (A - S->setpoint) * P;
    a->sum[2] += ph * 180 / M_PI * P;
    a->sum[7] += A * P;
    a->nblk += P;
    if (S->lockin.ratio2 > 0) {
        a->sum[TT_CH_AMPLITUDE2_INDEX] += tt_lockin_second_amplitude(li) * P;
        a->sum[TT_CH_PHASE2_INDEX] += tt_lockin_second_phase(li) * 180 / M_PI * P;
    }
    for (int h = 2; h <= S->lockin.harmonics; h++) {
        double Ah = tt_lockin_amplitude(li, h), phh = tt_lockin_phase(li, h);
        a->sum[TT_CH_HARMONIC_INDEX + h - 2] += Ah * P;
        /* a harmonic's phase is averaged as a vector: near zero amplitude it is noise,
         * and a plain mean across its wrap would be meaningless */
        a->sum[TT_CH_HARMONIC_PHASE_INDEX + h - 2] += Ah * cos(phh) * P;
        a->quad[h - 2] += Ah * sin(phh) * P;
    }
    return TT_OK;
}

int tt_scan_cycle_end(const line_ctx *L, line_state *st, const cycle_in *in, double peak,
                      double indent, double ets)
{
    if (L->phase > 0) {
        pixel_acc *a = pixel_of(L, in->k);
        a->sum[3] += peak;
        a->sum[4] += indent;
        a->sum[5] += ets;
        a->sum[6] += in->topo;
        a->sum[TT_CH_DILATION_INDEX] += in->dil;
        a->sum[0] += in->za;
        a->n++;
        if (indent > L->W->indent[in->mat]) /* NaN when not tracked: left out */
            L->W->indent[in->mat] = indent;
        loss_sums(st, ets, a);
    }
    st->loss_fresh = 0;
    st->cycles++;
    st->k = in->k + 1;
    if (in->j == L->P - 1 || in->k == L->ncyc - 1)
        return tt_scan_block_end(L, st, in->k / L->P);
    return TT_OK;
}
