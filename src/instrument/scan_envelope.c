/* One scan line on the envelope tier (docs/dynamics.md, Tiers): the lock-in, the
 * feedback and the pixels see every cycle, as on the every-cycle tier, but where the
 * envelope moves slowly most cycles come from the cycle map's local linear model
 * (tiptap/solver/envelope.h) instead of an integration.
 *
 * Error control: the model runs in stretches of m cycles, each closed by a cycle
 * integrated from the model's state (a check). The model's prediction of that cycle
 * against the integration is the stretch's local error; within the tolerance the
 * stretch stands, the model is re-anchored on the check and m doubles; beyond it the
 * line rolls back to the stretch's start (lock-in, feedback, piezo, pixels, the
 * block's samples, the tip's state) and runs the stretch again at a quarter of its
 * length; a failure on the shortest stretch integrates every cycle through the check
 * and tries the model again after a wait. Every cycle is integrated at a material or
 * height edge (a cycle whose end's surface differs from its start's), when a cycle's
 * contact (touching or not, the flag at its start and end) differs from its
 * neighbours', at the start of each phase (settling, trace, retrace), and after a
 * failed check on the shortest stretch. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scan_private.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

enum {
    M_MIN = 4,       /* a stretch's first length, and the least after a failure */
    M_MAX = 1024,    /* its longest: the checks then cost about a thousandth of the cycles */
    WAIT_MIN = 16,   /* quiet integrated cycles before the model is tried */
    WAIT_MAX = 1024  /* the same after repeated failures (doubling) */
};

/* The surface at a cycle's start. */
typedef struct {
    long k;
    double h, topo;
    size_t mat;
} surf_pt;

/* What a line carries from cycle to cycle: what a rollback restores. */
typedef struct {
    long k; /* the next cycle of this phase */
    tt_feedback fb;
    double z_from, z_to, z_act;
    tt_piezo pz;
    size_t current; /* the material on the sim */
    double x[2];    /* the tip's state at cycle k's start: the sim's, or the model's */
    surf_pt ahead[2]; /* the surface at the next two cycles' starts (k < 0: none) */
    long cycles;
    double worst;
    int clamped;
} line_state;

/* One cycle's inputs, as scan.c's scan_line computes them. */
typedef struct {
    double ha, hb, topo, za, sa, sb;
    size_t mat, mat_next;
    int edge_next; /* the next cycle crosses an edge */
} cycle_in;

/* The line's fixed quantities. */
typedef struct {
    tt_scan *S;
    worker *W;
    long line, nc, ncyc;
    int phase, dir, P, N, piezo;
    double s_ref, tol, edge;
    pixel_acc *pix;
} line_ctx;

static size_t material_at(const tt_scan *S, double x, double y)
{
    return S->uniform ? 0 : (size_t)tt_surface_material(S->surface, x, y);
}

/* The surface at the start of cycle k: the height the apex meets, the true height and
 * the material (as scan.c's scan_line finds them). */
static void surface_at(const line_ctx *L, long k, double *h, double *topo, size_t *mat)
{
    const tt_scan *S = L->S;
    double x, y;
    tt_raster_position(&S->raster, L->line, L->dir, L->nc, L->phase ? k : 0, &x, &y);
    if (S->plain) {
        *h = *topo = S->flat ? 0 : tt_surface_height(S->surface, x, y);
    } else {
        double t = tt_scan_clock_at(S, L->line, L->phase, L->nc, L->phase ? k : 0);
        *h = tt_scan_sample_at(S, &x, &y, t, topo);
    }
    *mat = material_at(S, x, y);
}

/* The surface at cycle k's start, from the two found ahead when they hold it. */
static surf_pt surface_cached(const line_ctx *L, const line_state *st, long k)
{
    for (int i = 0; i < 2; i++)
        if (st->ahead[i].k == k)
            return st->ahead[i];
    surf_pt p = {.k = k};
    surface_at(L, k, &p.h, &p.topo, &p.mat);
    return p;
}

/* The inputs of cycle k (j: its place in the block); advances the piezo. The surface
 * is found one cycle further ahead than the cycle needs, so that a stretch closes its
 * check before a cycle that crosses an edge (edge_next), and kept for the next cycles. */
static void inputs(const line_ctx *L, line_state *st, long k, int j, cycle_in *in)
{
    const tt_scan *S = L->S;
    surf_pt a = surface_cached(L, st, k), b = surface_cached(L, st, k + 1), c = b;
    if (k + 1 < L->ncyc)
        c = surface_cached(L, st, k + 2);
    st->ahead[0] = b;
    st->ahead[1] = c;
    in->ha = a.h;
    in->topo = a.topo;
    in->mat = a.mat;
    in->hb = b.h;
    in->mat_next = b.mat;
    in->edge_next = c.mat != b.mat || fabs(c.h - b.h) > L->edge;
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
}

/* The surface at the cycle's end differs from its start's: the cycle crosses an edge,
 * and is integrated.
 * (A stretch also ends, with a check, where the sample has moved this far from the
 * anchor: a smooth slope, or a tip's rounded image of a step, which steepens into one.) */
static int edge_ahead(const line_ctx *L, const cycle_in *in)
{
    return in->mat_next != in->mat || fabs(in->hb - in->ha) > L->edge;
}

/* A cycle's observables into the block's samples and the pixel's sums. */
static void record(const line_ctx *L, long k, int j, const cycle_in *in, const double *obs)
{
    const tt_scan *S = L->S;
    const int N = L->N;
    memcpy(L->W->y + (size_t)j * (size_t)N, obs, (size_t)N * sizeof *obs);
    if (L->phase == 0)
        return;
    long px = tt_raster_pixel(&S->raster, L->dir, L->nc, k);
    pixel_acc *a = &L->pix[(size_t)L->dir * (size_t)S->raster.pixels + (size_t)px];
    a->sum[3] += obs[N + TT_ENV_PEAK];
    a->sum[4] += obs[N + TT_ENV_INDENT];
    a->sum[5] += obs[N + TT_ENV_ETS];
    a->sum[6] += in->topo;
    a->sum[0] += in->za;
    a->n++;
}

/* The end of a lock-in block: demodulate, update the feedback, and (trace, retrace)
 * add the lock-in's outputs to the pixel of the block's last cycle. */
static int block_end(const line_ctx *L, line_state *st, long b)
{
    tt_scan *S = L->S;
    tt_lockin *li = L->W->lockin;
    int rc = tt_lockin_push(li, L->W->y);
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
    long k = b * P + P - 1;
    if (k >= L->nc)
        k = L->nc - 1;
    long px = tt_raster_pixel(&S->raster, L->dir, L->nc, k);
    pixel_acc *a = &L->pix[(size_t)L->dir * (size_t)S->raster.pixels + (size_t)px];
    a->sum[1] += (A - S->setpoint) * P;
    a->sum[2] += ph * 180 / M_PI * P;
    a->nblk += P;
    for (int h = 2; h <= S->lockin.harmonics; h++) {
        double Ah = tt_lockin_amplitude(li, h), phh = tt_lockin_phase(li, h);
        a->sum[TT_CH_HARMONIC_INDEX + h - 2] += Ah * P;
        a->sum[TT_CH_HARMONIC_PHASE_INDEX + h - 2] += Ah * cos(phh) * P;
        a->quad[h - 2] += Ah * sin(phh) * P;
    }
    return TT_OK;
}

/* A point the line can return to: its state after a cycle, the lock-in's filter, the
 * block's samples so far and the sums of the pixels the next stretch can touch. */
typedef struct {
    line_state st;
    int contact;
    long p0, p1; /* saved pixels, p0 <= p1 (none: p0 > p1) */
    pixel_acc *pix;
} snapshot;

static void snap_take(const line_ctx *L, const line_state *st, int contact, long stretch,
                      snapshot *sn)
{
    worker *W = L->W;
    const tt_raster *R = &L->S->raster;
    sn->st = *st;
    sn->contact = contact;
    tt_lockin_copy(W->lockin_save, W->lockin);
    memcpy(W->y_save, W->y, (size_t)L->P * (size_t)L->N * sizeof *W->y);
    sn->p0 = 1;
    sn->p1 = 0;
    if (L->phase == 0 || st->k >= L->ncyc)
        return;
    long k1 = st->k + stretch + L->P;
    if (k1 > L->ncyc - 1)
        k1 = L->ncyc - 1;
    long a = tt_raster_pixel(R, L->dir, L->nc, st->k), b = tt_raster_pixel(R, L->dir, L->nc, k1);
    sn->p0 = a < b ? a : b;
    sn->p1 = a < b ? b : a;
    const pixel_acc *src = L->pix + (size_t)L->dir * (size_t)R->pixels;
    memcpy(sn->pix, src + sn->p0, (size_t)(sn->p1 - sn->p0 + 1) * sizeof *sn->pix);
}

static void snap_restore(const line_ctx *L, const snapshot *sn, line_state *st)
{
    worker *W = L->W;
    tt_scan *S = L->S;
    *st = sn->st;
    tt_lockin_copy(W->lockin, W->lockin_save);
    memcpy(W->y, W->y_save, (size_t)L->P * (size_t)L->N * sizeof *W->y);
    if (sn->p0 <= sn->p1)
        memcpy(L->pix + (size_t)L->dir * (size_t)S->raster.pixels + sn->p0, sn->pix,
               (size_t)(sn->p1 - sn->p0 + 1) * sizeof *sn->pix);
    tt_sim_set_contact(W->sim, S->contacts[st->current], S->Qi[st->current]);
    tt_sim_set_state(W->sim, st->x[0], st->x[1], sn->contact);
}

/* The tier's controller within a phase. */
typedef struct {
    int model;       /* the model runs; else every cycle is integrated */
    long left;       /* model cycles before the stretch's check */
    long m;          /* the next stretch's length */
    long quiet, wait; /* integrated cycles without a change of contact or surface; needed */
    long redo;       /* integrate every cycle up to this one (a rolled-back stretch) */
    int prev_touch;
    int rebuild;     /* the Jacobians must be taken anew before the model runs */
    snapshot sn;
} controller;

/* Integrate cycle k from the sim's state: its observables and end state (st->x). */
static int integrate(const line_ctx *L, line_state *st, const cycle_in *in, tt_cycle *cy,
                     double *obs, int *c1, long *integrated)
{
    tt_scan *S = L->S;
    tt_sim *sim = L->W->sim;
    if (in->mat != st->current) {
        tt_sim_set_contact(sim, S->contacts[in->mat], S->Qi[in->mat]);
        st->current = in->mat;
    }
    tt_sim_set_sample(sim, in->sa, (in->sb - in->sa) / S->cantilever.T);
    int rc = tt_sim_cycle(sim, cy);
    if (rc)
        return rc;
    (*integrated)++;
    if (cy->residual_rel > st->worst)
        st->worst = cy->residual_rel;
    tt_envelope_observe(L->W->env, tt_sim_samples(sim), cy, obs);
    tt_sim_get_state(sim, &st->x[0], &st->x[1], c1);
    return TT_OK;
}

/* The check closing a stretch: cycle k integrated from the model's state, against the
 * model's own prediction of it. 1: the stretch stands (the model is re-anchored). */
static int check(const line_ctx *L, line_state *st, const cycle_in *in, double *obs,
                 long *integrated)
{
    tt_envelope *env = L->W->env;
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    const double x0[2] = {st->x[0], st->x[1]};
    const int c0 = tt_envelope_anchor_contact(env);
    double xp[2], *pred = obs + tt_envelope_size(env);
    tt_envelope_predict(env, x0, in->sa, sdot, xp, pred);
    tt_sim_set_state(L->W->sim, x0[0], x0[1], c0);
    tt_cycle cy;
    int c1;
    if (integrate(L, st, in, &cy, obs, &c1, integrated) != TT_OK) {
        /* a model state the cycle cannot be integrated from is a failed check: the
         * stretch is run again from its start, and at last every cycle */
        tt_error_clear();
        return 0;
    }
    double err = tt_envelope_error(env, xp, pred, st->x, obs);
    if (!(err <= L->tol) || c1 != c0 || tt_envelope_touched(&cy) != tt_envelope_anchor_touched(env))
        return 0;
    tt_envelope_anchor(env, x0, in->sa, sdot, st->x, &cy, obs);
    return 1;
}

/* A cycle integrated while the model is off. The model comes back on it at once when
 * only a check failed (re-anchored, its Jacobians kept), and is built anew after an
 * edge, a change of contact or a failure on the shortest stretch, once the cycles have
 * been quiet long enough. 1: the model is on. */
static int full(const line_ctx *L, line_state *st, controller *c, const cycle_in *in, int edge,
                double *obs, long *integrated, int *rc)
{
    tt_sim *sim = L->W->sim;
    tt_envelope *env = L->W->env;
    double x0[2];
    int c0, c1;
    tt_sim_get_state(sim, &x0[0], &x0[1], &c0);
    tt_cycle cy;
    if ((*rc = integrate(L, st, in, &cy, obs, &c1, integrated)))
        return 0;
    int touch = tt_envelope_touched(&cy);
    int quiet = !edge && !in->edge_next && touch == c->prev_touch && c1 == c0;
    if (!quiet)
        c->rebuild = 1;
    quiet = quiet && st->k >= c->redo;
    c->quiet = quiet ? c->quiet + 1 : 0;
    c->prev_touch = touch;
    if (!quiet || st->k + 1 >= L->ncyc)
        return 0;
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    if (!c->rebuild && c0 == tt_envelope_anchor_contact(env) &&
        touch == tt_envelope_anchor_touched(env)) {
        tt_envelope_anchor(env, x0, in->sa, sdot, st->x, &cy, obs);
        return 1;
    }
    if (c->quiet < c->wait)
        return 0;
    if (tt_envelope_build(env, sim, x0, c0, in->sa, sdot, &cy, obs, integrated)) {
        c->rebuild = 0;
        return 1;
    }
    c->quiet = 0;
    c->wait = c->wait * 2 < WAIT_MAX ? c->wait * 2 : WAIT_MAX;
    return 0;
}

/* A failed check: back to the stretch's start. From there the model runs again on a
 * quarter of the stretch (a rejected step, retried shorter); a failure on the shortest
 * stretch integrates every cycle through k, and the model is built anew after a wait. */
static void fail(const line_ctx *L, line_state *st, controller *c, long k)
{
    snap_restore(L, &c->sn, st);
    if (c->m > M_MIN) {
        c->m = c->m / 4 > M_MIN ? c->m / 4 : M_MIN;
        c->left = c->m; /* the snapshot covers the shorter stretch too */
        return;
    }
    c->model = 0;
    c->quiet = 0;
    c->redo = k + 1;
    c->rebuild = 1;
    c->wait = c->wait * 2 < WAIT_MAX ? c->wait * 2 : WAIT_MAX;
}

/* The cycles of one phase. */
static int run_phase(const line_ctx *L, line_state *st, controller *c, long *integrated)
{
    double *obs = L->W->obs;
    int rc = TT_OK;
    c->model = 0;
    c->quiet = 0;
    c->prev_touch = -1;
    c->redo = 0;
    c->rebuild = 1;
    while (st->k < L->ncyc) {
        const long k = st->k;
        const int j = (int)(k % L->P);
        if ((k & 255) == 0 && tt_cancel_requested())
            return TT_EINTR;
        cycle_in in;
        inputs(L, st, k, j, &in);
        const int edge = edge_ahead(L, &in);
        int snap = 0;
        /* a model cycle, unless the stretch is done, this or the next cycle crosses an
         * edge, the sample is out of the anchor's reach, or it is the phase's last (the
         * next phase starts integrating from the sim's state): then a check */
        const double sdot = (in.sb - in.sa) / L->S->cantilever.T;
        if (c->model && c->left > 0 && !edge && !in.edge_next && in.mat == st->current &&
            k + 1 < L->ncyc &&
            fabs(tt_envelope_sample_offset(L->W->env, in.sa, sdot)) <= L->edge) {
            double x1[2];
            tt_envelope_predict(L->W->env, st->x, in.sa, sdot, x1, obs);
            st->x[0] = x1[0];
            st->x[1] = x1[1];
            c->left--;
        } else if (c->model) {
            if (!check(L, st, &in, obs, integrated)) {
                fail(L, st, c, k);
                continue;
            }
            c->m = 2 * c->m < M_MAX ? 2 * c->m : M_MAX;
            c->wait = WAIT_MIN;
            c->model = !edge && !in.edge_next;
            c->quiet = 0;
            snap = c->model;
        } else {
            c->model = snap = full(L, st, c, &in, edge, obs, integrated, &rc);
            if (rc)
                return rc;
        }
        record(L, k, j, &in, obs);
        st->cycles++;
        if ((j == L->P - 1 || k == L->ncyc - 1) && (rc = block_end(L, st, k / L->P)))
            return rc;
        st->k = k + 1;
        if (snap) {
            c->left = c->m;
            snap_take(L, st, tt_envelope_anchor_contact(L->W->env), c->left, &c->sn);
        }
    }
    return TT_OK;
}

/* Engage as scan.c's scan_line does (tt_scan_engage); the tip's state is the model's
 * first input. */
static void engage(tt_scan *S, worker *W, long line, long nc, line_state *st)
{
    scan_carry e;
    tt_scan_engage(S, W, line, nc, &e);
    st->current = e.current;
    st->fb = e.fb;
    st->z_from = e.z_from;
    st->z_to = e.z_to;
    st->pz = e.pz;
    st->z_act = e.z_act;
    int contact;
    tt_sim_get_state(W->sim, &st->x[0], &st->x[1], &contact);
}

int tt_scan_line_envelope(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          long *integrated, double *worst, int *clamped)
{
    const tt_raster *R = &S->raster;
    line_ctx L = {.S = S, .W = W, .line = line};
    L.P = S->lockin.periods_per_block;
    L.N = S->lockin.samples_per_period;
    L.nc = tt_raster_cycles_per_direction(R, S->cantilever.T);
    L.piezo = !tt_piezo_ideal(&S->inst.piezo);
    L.s_ref = S->setpoint;
    /* The model's error per cycle, relative to the free amplitude: held to ten times
     * the stepper's tolerance, below what the integration itself errs per cycle (13 to
     * 16 times the tolerance at 1e-8 on the standard scene, 5 to 20 times at 1e-6 and
     * 1e-7: one cycle against one at 1e-12 from the same state) */
    L.tol = 10 * S->solver.tolerance;
    L.edge = 1e-3 * S->A0;
    line_state st = {0};
    const int carry = S->continuous && W->engaged; /* no settling then */
    engage(S, W, line, L.nc, &st);
    tt_sim_set_sampling(W->sim, L.N, W->samples);
    tt_sim_track_peaks(W->sim, (S->channels & (TT_CH_PEAK_FORCE | TT_CH_INDENTATION)) != 0);
    controller c = {.m = M_MIN, .wait = WAIT_MIN};
    L.pix = calloc((size_t)R->pixels * 2, sizeof *L.pix);
    c.sn.pix = calloc((size_t)R->pixels, sizeof *c.sn.pix);
    int rc = L.pix && c.sn.pix ? TT_OK : tt_error(TT_ENOMEM, "out of memory");
    long settle_blocks = carry ? 0 : (S->settle_cycles + L.P - 1) / L.P;
    int nphase = R->retrace || S->continuous ? 3 : 2;
    for (int phase = 0; phase < nphase && rc == TT_OK; phase++) {
        L.phase = phase;
        L.dir = phase == 2 ? 1 : 0;
        L.ncyc = phase == 0 ? settle_blocks * L.P : L.nc;
        st.k = 0;
        st.ahead[0].k = st.ahead[1].k = -1;
        rc = run_phase(&L, &st, &c, integrated);
    }
    *cycles += st.cycles;
    if (st.worst > *worst)
        *worst = st.worst;
    *clamped |= st.clamped;
    if (rc == TT_OK) {
        scan_carry e = {st.fb, st.z_from, st.z_to, st.z_act, st.pz, st.current};
        tt_scan_line_done(S, W, line, &e, L.pix, out);
    }
    free(L.pix);
    free(c.sn.pix);
    return rc;
}
