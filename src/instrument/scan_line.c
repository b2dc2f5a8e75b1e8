/* One line of a scan on a tier: engage at its first pixel, settle, trace and retrace,
 * each phase's cycles run by the tier, the pixels' means into the images; and the
 * every-cycle tier's phases (see scan_private.h). */
#include "scan_private.h"

#include <math.h>
#include <stdlib.h>

#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

/* Phase lag in the lock-in's range, (-90, 270] degrees (see src/instrument/lockin.c). */
static double lag(double X, double Y)
{
    double ph = atan2(Y, X);
    return ph < -M_PI / 2 ? ph + 2 * M_PI : ph;
}

/* Engage at the line's first pixel: the material there on the sim, and, unless
 * continuous lines carry on from the last retrace, the feedback at that pixel's height,
 * the piezo at rest there, the tip and the lock-in on the free oscillation. */
static void engage(tt_scan *S, worker *W, long line, long nc, uint64_t kz, line_state *st)
{
    const tt_raster *R = &S->raster;
    double x, y, h0, topo;
    tt_raster_position(R, line, 0, nc, W->k0, &x, &y);
    if (S->plain)
        h0 = tt_surface_height(S->surface, x, y);
    else
        h0 = tt_scan_sample_at(S, &x, &y, tt_scan_clock_at(S, line, 0, nc, W->k0), &topo);
    st->current = S->uniform ? 0 : (size_t)tt_surface_material(S->surface, x, y);
    tt_scan_worker_contact(S, W, st->current);
    st->fb = W->fb;
    st->z_from = W->z_from;
    st->z_to = W->z_to;
    st->pz = W->pz;
    st->z_act = W->z_act;
    st->zn = W->zn;
    if (S->continuous && W->engaged)
        return;
    /* the z piezo's noise starts each line from its stationary distribution */
    st->zn = tt_noise_ou_first(&S->zn, kz);
    W->s_ref = S->setpoint;
    /* heights are reported against the surface's own zero, the piezo's range centred
     * on it; creep follows the whole line */
    const tt_feedback_params fp = {S->setpoint, S->kp, S->ki, S->z_range};
    tt_feedback_init(&st->fb, &fp, h0);
    st->z_from = st->z_to = st->z_act = st->fb.z;
    tt_piezo_init(&st->pz, &S->inst.piezo, st->fb.z,
                  (double)S->settle_cycles * S->cantilever.T + 1 / R->line_rate);
    tt_sim_reset_free(W->sim);
    tt_lockin_reset(W->lockin, S->cantilever.A0, S->cantilever.phi0);
    if (S->lockin.ratio2 > 0)
        tt_lockin_reset_second(W->lockin, S->cantilever.A2, S->cantilever.phi2);
}

/* A line finished: its state kept for the next (continuous lines), its pixels' means
 * into the images. */
static void line_done(const tt_scan *S, worker *W, long line, const line_state *st,
                      const pixel_acc *pix, const line_out *out)
{
    const tt_raster *R = &S->raster;
    W->engaged = 1;
    W->fb = st->fb;
    W->z_from = st->z_from;
    W->z_to = st->z_to;
    W->pz = st->pz;
    W->z_act = st->z_act;
    W->zn = st->zn;
    for (int dir = 0; dir < (R->retrace ? 2 : 1); dir++)
        for (long px = 0; px < R->pixels; px++) {
            const pixel_acc *a = &pix[(size_t)dir * (size_t)R->pixels + (size_t)px];
            for (int ch = 0; ch < TT_CH_COUNT; ch++) {
                /* lock-in channels come once per lock-in block, the rest per cycle */
                long cnt = tt_scan_channel_harmonic(ch) ? a->nblk : a->n;
                double v = cnt ? a->sum[ch] / (double)cnt : NAN;
                if (ch == TT_CH_ARTEFACT_INDEX)
                    v = cnt ? (a->sum[0] - a->sum[6]) / (double)cnt : NAN;
                else if (ch >= TT_CH_HARMONIC_PHASE_INDEX && ch < TT_CH_HARMONIC_PHASE_INDEX + NHARM &&
                         cnt)
                    v = lag(a->sum[ch], a->quad[ch - TT_CH_HARMONIC_PHASE_INDEX]) * 180 / M_PI;
                if (out->img[dir][ch] && ch != TT_CH_CERTAINTY_INDEX)
                    out->img[dir][ch][out->packed ? px : tt_raster_index(R, line, px)] = v;
            }
        }
}

/* The line's fixed quantities. Engage: the rest separation of a free tip whose
 * amplitude the surface limits to the setpoint is about the setpoint; the feedback
 * then settles the rest. */
static line_ctx line_context(tt_scan *S, worker *W, long line)
{
    line_ctx L = {.S = S, .W = W, .line = line, .k0 = W->k0};
    L.P = S->lockin.periods_per_block;
    L.N = S->lockin.samples_per_period;
    L.nc = tt_raster_cycles_per_direction(&S->raster, S->cantilever.T);
    L.piezo = !tt_piezo_ideal(&S->inst.piezo);
    /* The model's error per cycle, relative to the free amplitude: held to ten times
     * the stepper's tolerance, below what the integration itself errs per cycle (13 to
     * 16 times the tolerance at 1e-8 on the standard scene, 5 to 20 times at 1e-6 and
     * 1e-7: one cycle against one at 1e-12 from the same state). The worker's own
     * model tolerance: the error estimate's companion line tightens the model with the
     * integration, or the model's error (at setpoint-10 100 times the integration's in
     * amplitude) would cancel out of the companion's difference */
    L.tol = W->model_tol;
    /* With noise on, the state and the sample wander from the anchor by the noise (the
     * thermal force alone moves the state by 1.25 pm a cycle, 2000 times the tolerance
     * at the default), and the model's error grows with the square of that reach: it is
     * held to 1e-3 of the reach as well at the default tolerance (proportional to it),
     * so the noise the model carries is right to 0.1 % (docs/dynamics.md, "Noise on the
     * envelope tier"). Without noise, the tolerance alone. */
    L.rel = S->noise.temperature > 0 || S->sd > 0 || S->zn.sd > 0 ? 5e5 * W->tolerance : 0;
    /* The noise that moves the state (thermal, z piezo) runs the model to second order,
     * whose inputs are held within 3e-3 of A0 of the anchor: beyond it the slow orbit's
     * curvature (the cycle map's second derivatives reach 30 / A0 on the edge sample's
     * stiff disks, against 1 - |mu| of 0.008) drives the model off in a stretch whose
     * last cycle still passes its check, and on stiff silicon at 300 K (the thermal
     * noise rings the stroboscopic state round the orbit by 2.5e-3 of A0 every 25
     * cycles) its third-order error, passed within the check's allowance, made the
     * height noise 8 % too large at 5e-3 (docs/dynamics.md, "Noise on the envelope
     * tier") */
    L.reach = tt_scan_second_order(S) ? 3e-3 : 0;
    /* and its derivatives, carried from anchor to anchor, hold within 2e-3 of A0 of
     * where they were taken (its third derivatives reach 3000 / A0^2 on that silicon,
     * and a model carried further missed its checks by a Jacobian a few per cent off):
     * past it the nearest kept model is recalled at a check (scan_envelope.c); between
     * checks a stretch past the reach switches to the kept model nearest, within the
     * reach, anchored where it was built */
    L.retake = tt_scan_second_order(S) ? 2e-3 : 0;
    L.edge = 1e-3 * S->A0;
    /* the noise of this line: keyed by (seed, line), counted in cycles from its start */
    L.kd = tt_noise_key(S->noise.seed, TT_NOISE_DETECTOR, line);
    L.kz = tt_noise_key(S->noise.seed, TT_NOISE_PIEZO, line);
    L.ke = tt_noise_key(S->noise.seed, TT_NOISE_ENVELOPE, line);
    return L;
}

int tt_scan_line_run(tt_scan *S, worker *W, long line, const line_out *out, scan_phase_fn run,
                     void *tier, long *cycles, double *worst, int *clamped)
{
    const tt_raster *R = &S->raster;
    line_ctx L = line_context(S, W, line);
    line_state st = {0};
    /* Continuous lines engage once and carry on from where the last retrace ended, with
     * no settling. */
    const int carry = S->continuous && W->engaged;
    engage(S, W, line, L.nc, L.kz, &st);
    L.s_ref = W->s_ref;
    int contact;
    tt_sim_get_x(W->sim, st.x, &contact);
    tt_sim_set_sampling(W->sim, L.N, W->samples);
    tt_sim_track_peaks(W->sim, (S->channels & (TT_CH_PEAK_FORCE | TT_CH_INDENTATION)) != 0);
    tt_sim_noise_key(W->sim, tt_noise_key(S->noise.seed, TT_NOISE_THERMAL, line));
    L.pix = calloc((size_t)R->pixels * 2, sizeof *L.pix);
    int rc = L.pix ? TT_OK : tt_error_nomem("the pixel sums of line %ld", line);
    /* Phase 0 settles at the first pixel; phases 1 and 2 are trace and retrace. */
    long settle_blocks = carry ? 0 : (S->settle_cycles + L.P - 1) / L.P;
    /* continuous lines retrace whether recorded or not: the next line starts there */
    int nphase = R->retrace || S->continuous ? 3 : 2;
    for (int phase = 0; phase < nphase && rc == TT_OK; phase++) {
        L.phase = phase;
        L.dir = phase == 2 ? 1 : 0;
        L.ncyc = phase == 0 ? settle_blocks * L.P : L.nc;
        st.k = phase == 1 ? L.k0 : 0;
        st.ahead[0].k = st.ahead[1].k = -1;
        rc = run(&L, &st, tier);
        if (phase == 0) /* what settling cost: the estimate's stretches each settle */
            W->settle_work = tt_scan_line_work(W, st.cycles);
    }
    if (rc == TT_SCAN_BUDGET) { /* the companion's share spent: its pixels so far count */
        W->budget_hit = 1;
        rc = TT_OK;
    }
    *cycles += st.cycles;
    if (st.worst > *worst)
        *worst = st.worst;
    *clamped |= st.clamped;
    if (rc == TT_OK)
        line_done(S, W, line, &st, L.pix, out);
    free(L.pix);
    return rc;
}

/* The cycle's deflection samples into the block's (j: its place in it), with the
 * detector's noise. */
static void block_samples(const line_ctx *L, const line_state *st, int j)
{
    const int N = L->N;
    const tt_sample *smp = L->W->samples;
    double *y = L->W->y + (size_t)j * (size_t)N;
    for (int q = 0; q < N; q++)
        y[q] = smp[q].d - smp[q].z;
    const double sd = L->S->sd;
    if (sd > 0)
        for (int q = 0; q < N; q++)
            y[q] += sd * tt_noise_gauss(L->kd, (uint64_t)st->cycles * (uint64_t)N + (uint64_t)q);
    /* mode 2's lock-in on the same deflection, on the sim's clock of its drive (the cycle
     * just integrated) */
    if (L->S->lockin.ratio2 > 0)
        tt_lockin_second_period(L->W->lockin, y,
                                tt_cantilever_drive2_turns(&L->S->cantilever, tt_sim_cycles(L->W->sim) - 1));
}

/* The every-cycle tier's cycles of one phase: each integrated. */
static int every_phase(const line_ctx *L, line_state *st, void *tier)
{
    (void)tier;
    while (st->k < L->ncyc) {
        cycle_in in;
        int rc = tt_scan_cycle_begin(L, st, &in);
        if (rc)
            return rc;
        tt_cycle cy;
        if ((rc = tt_scan_integrate(L, st, &in, &cy)))
            return rc;
        block_samples(L, st, in.j);
        if ((rc = tt_scan_cycle_end(L, st, &in, cy.peak_force, cy.max_indentation, cy.e_ts)))
            return rc;
    }
    return TT_OK;
}

int tt_scan_line_every(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                       long *integrated, double *worst, int *clamped)
{
    int rc = tt_scan_line_run(S, W, line, out, every_phase, NULL, cycles, worst, clamped);
    *integrated = *cycles;
    return rc;
}
