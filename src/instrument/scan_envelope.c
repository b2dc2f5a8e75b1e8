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
 * failed check on the shortest stretch. Where the tip grazes, scan_envelope_graze.c
 * runs a model per branch; the controller's decisions are counted per thread
 * (tiptap/instrument/scan_envelope_stops.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scan_envelope_private.h"
#include "tiptap/instrument/scan_envelope_stops.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

/* The controller's decisions, counted per thread (tiptap/instrument/scan_envelope_stops.h). */
static _Thread_local long stops[TT_ENV_STOPS];

void tt_scan_envelope_stops(long counts[TT_ENV_STOPS])
{
    memcpy(counts, stops, sizeof stops);
}

void tt_scan_envelope_stops_reset(void) { memset(stops, 0, sizeof stops); }

const char *tt_scan_envelope_stop_name(int i)
{
    static const char *const names[TT_ENV_STOPS] = {
        "model", "check_pass", "check_error", "check_contact", "check_touch", "check_cycle",
        "shortest", "full", "full_edge", "full_change", "full_redo", "full_wait", "full_graze",
        "end_sample", "end_reach", "build"};
    return i >= 0 && i < TT_ENV_STOPS ? names[i] : "?";
}


/* The surface at the cycle's end differs from its start's: the cycle crosses an edge,
 * and is integrated.
 * (A stretch also ends, with a check, where the sample has moved this far from the
 * anchor: a smooth slope, or a tip's rounded image of a step, which steepens into one.) */
static int edge_ahead(const line_ctx *L, const cycle_in *in)
{
    return in->mat_next != in->mat || fabs(in->hb - in->ha) > L->edge;
}

/* Noise on the envelope tier (docs/dynamics.md, "Noise on the envelope tier"): every
 * cycle, integrated or the model's, is run without the thermal force, and gets the
 * thermal force's linear response in its end state and lock-in components and the
 * detector's noise in its components, from normals that are a pure function of (seed,
 * line, cycle): a stretch run again after a rollback, and the error estimate's
 * companion line, draw what the run drew. */
enum { NOISE_MAX = TT_SIM_DIM_MAX + 1 + 2 * 16 + 1 };

/* The cycle's noise added to its components and its end state st->x. */
static void add_noise(const line_ctx *L, line_state *st, double *comp)
{
    const tt_envelope *env = L->W->env;
    const int nn = tt_envelope_noise_size(env);
    if (!nn)
        return;
    double g[NOISE_MAX + 1], dx[TT_SIM_DIM_MAX];
    const uint64_t base = (uint64_t)st->cycles * (uint64_t)((nn + 1) / 2);
    for (int i = 0; i < nn && i < NOISE_MAX; i += 2)
        tt_noise_pair(L->ke, base + (uint64_t)(i / 2), g + i);
    tt_envelope_noise(env, g, dx, comp);
    for (int i = 0; i < tt_sim_dim(L->W->sim); i++)
        st->x[i] += dx[i];
}

/* A cycle's observables into the block's and the pixel's sums, with its noise; the
 * cycle ends (tt_scan_cycle_end). The block keeps each period as the lock-in's
 * components (tt_lockin_transform): obs holds them already after a model cycle
 * (reduced), else the cycle's samples, whose end state is then where the sim goes on. */
static int record(const line_ctx *L, line_state *st, const cycle_in *in, const double *obs,
                  int reduced)
{
    const tt_lockin *li = L->W->lockin;
    const int nc = tt_lockin_components(li);
    double *slot = L->W->y + (size_t)in->j * (size_t)nc;
    if (reduced)
        memcpy(slot, obs, (size_t)nc * sizeof *obs);
    else
        tt_lockin_transform(li, obs, slot);
    if (tt_envelope_noise_size(L->W->env)) {
        add_noise(L, st, slot);
        if (!reduced) {
            tt_sim *sim = L->W->sim;
            int cf;
            double x[TT_SIM_DIM_MAX];
            tt_sim_get_x(sim, x, &cf);
            tt_sim_set_x(sim, st->x, cf);
        }
    }
    const double *x = obs + (reduced ? nc : L->N);
    return tt_scan_cycle_end(L, st, in, x[TT_ENV_PEAK], x[TT_ENV_INDENT], x[TT_ENV_ETS]);
}


static void snap_take(const line_ctx *L, const line_state *st, int contact, long stretch,
                      snapshot *sn)
{
    worker *W = L->W;
    const tt_raster *R = &L->S->raster;
    sn->st = *st;
    sn->contact = contact;
    tt_lockin_copy(W->lockin_save, W->lockin);
    memcpy(W->y_save, W->y, (size_t)L->P * (size_t)L->N * sizeof *W->y);
    if (W->indent)
        memcpy(sn->indent, W->indent, L->S->nmaterials * sizeof *W->indent);
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
    /* a rolled-back stretch's greatest indentation is not the line's: its cycles run
     * again */
    if (W->indent)
        memcpy(W->indent, sn->indent, S->nmaterials * sizeof *W->indent);
    if (sn->p0 <= sn->p1)
        memcpy(L->pix + (size_t)L->dir * (size_t)S->raster.pixels + sn->p0, sn->pix,
               (size_t)(sn->p1 - sn->p0 + 1) * sizeof *sn->pix);
    tt_scan_worker_contact(S, W, st->current);
    tt_sim_set_x(W->sim, st->x, sn->contact);
}




/* The model is too far from where its derivatives were taken for a cycle from x0 that
 * touched (or began in contact): a nearer kept one is looked for. A free cycle's map is
 * linear in the state and blind to the sample, so its derivatives carry exactly (a
 * parachuting tip's sample moves by 6e-3 of A0 a cycle as the loop reaches for the
 * surface). */
static int far_off(const line_ctx *L, const double *x0, const cycle_in *in, int touched,
                   int c0)
{
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    return L->retake > 0 && (touched || c0) &&
           tt_envelope_model_reach(L->W->env, x0, in->sa, sdot) > L->retake;
}

/* With noise that moves the state (L->retake > 0), the second-order model holds near
 * where its derivatives were taken: on an integrated cycle from x0 (contact flag c0)
 * the kept model nearest to its inputs, within L->retake of them, with its contact and
 * touch and on its material, is made the present one (before the caller anchors it
 * there, which carries its derivatives). A check recalls only, never builds: a build
 * costs 15 to 22 cycles, and where the state sweeps through new places (a transient
 * after an edge) a model carried on passes its checks as before; the builds of full()
 * (after a failure, or on a cycle integrated anyway) fill the store. 1: recalled. */
static int recall(const line_ctx *L, const line_state *st, const controller *c,
                  const cycle_in *in, const double *x0, int c0, const tt_cycle *cy)
{
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    /* after two failures in a row the model is built anew, not recalled */
    return c->fails < 2 && tt_envelope_recall(L->W->env, x0, in->sa, sdot, c0,
                                               tt_envelope_touched(cy), (int)st->current,
                                               L->retake);
}

/* No kept model near an integrated cycle from x0: whether the state has missed near
 * there before (a place it comes back to, worth a model of its own) rather than passing
 * through once, as a transient after an edge does (tt_envelope_revisit). */
static int worth_a_model(const line_ctx *L, const line_state *st, const cycle_in *in,
                         const double *x0)
{
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    return tt_envelope_revisit(L->W->env, x0, in->sa, sdot, (int)st->current, L->retake);
}

/* The check closing a stretch: cycle k integrated from the model's state, against the
 * model's own prediction of it (CHECK_FAILED also when the run was cancelled, *rc =
 * TT_EINTR). */
static check_outcome check(const line_ctx *L, line_state *st, const cycle_in *in, double *obs,
                           controller *c, int *rc)
{
    tt_envelope *env = L->W->env;
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    double x0[TT_SIM_DIM_MAX];
    memcpy(x0, st->x, sizeof x0);
    const int c0 = tt_envelope_anchor_contact(env);
    double xp[TT_SIM_DIM_MAX], xp2[TT_SIM_DIM_MAX], *pred = obs + tt_envelope_size(env);
    tt_envelope_predict(env, TT_ENV_ALL, x0, st->x2, in->sa, sdot, xp, xp2, pred);
    tt_sim_set_x(L->W->sim, x0, c0);
    tt_cycle cy;
    int c1;
    int irc = tt_scan_env_integrate(L, st, in, &cy, obs, &c1, c);
    if (irc == TT_EINTR) {
        *rc = irc;
        return CHECK_FAILED;
    }
    if (irc != TT_OK) {
        /* a model state the cycle cannot be integrated from is a failed check: the
         * stretch is run again from its start, and at last every cycle */
        tt_error_clear();
        stops[TT_ENV_CHECK_CYCLE]++;
        return CHECK_FAILED;
    }
    if (L->W->env != env) {
        /* the cycle took the tip onto a law of another dimension: that plan's model is
         * built there anew */
        c->rebuild = 1;
        return CHECK_MODEL_OFF;
    }
    double err = tt_envelope_error(env, TT_ENV_ALL, xp, pred, st->x, obs) * tt_scan_env_drift(L, c->m);
    /* a grown bound's stretch is held to what one within the fixed reach may err */
    const double far = tt_envelope_reach(env, x0, in->sa, sdot);
    const double allow = L->tol + L->rel * (c->bound > 1 ? fmin(far, L->reach) : far);
    if (!(err <= allow) || c1 != c0 || tt_envelope_touched(&cy) != tt_envelope_anchor_touched(env)) {
        c->bound = fmax(1, 0.5 * c->bound);
        stops[c1 != c0 ? TT_ENV_CHECK_CONTACT
              : tt_envelope_touched(&cy) != tt_envelope_anchor_touched(env) ? TT_ENV_CHECK_TOUCH
                                                                           : TT_ENV_CHECK_ERROR]++;
        return CHECK_FAILED;
    }
    stops[TT_ENV_CHECK_PASS]++;
    /* A stretch the bounds ended whose error is an eighth of what a stretch within the
     * fixed bounds may err (the second-order model's error grows with the cube of the
     * reach) lets the next one run twice as far, as a step-size controller does: where
     * the loop's oscillation moves the sample past the fixed 20 pm in a cycle, the bound,
     * not an error, had stopped the model (docs/dynamics.md, "Why it integrates") */
    if (c->bounded && err <= 0.125 * (L->tol + L->rel * L->reach))
        c->bound = fmin(BOUND_MAX, 2 * c->bound);
    c->smooth = sample_mid(in) - in->zn;
    if (far_off(L, x0, in, tt_envelope_touched(&cy), c0) && !recall(L, st, c, in, x0, c0, &cy) &&
        worth_a_model(L, st, in, x0)) {
        /* no kept model near a place the state comes back to: one is built here, for
         * the stretches to switch to (a transient after an edge sweeps through places
         * once, and builds none) */
        long jacobian = 0; /* its cycles are not the run's */
        if (tt_envelope_build(env, L->W->sim, x0, c0, in->sa, sdot, &cy, obs, &jacobian) !=
            TT_ENV_USABLE) {
            c->rebuild = 1;
            return CHECK_MODEL_OFF;
        }
        tt_envelope_keep(env, (int)st->current);
        return CHECK_PASSED;
    }
    tt_envelope_anchor(env, x0, in->sa, sdot, st->x, &cy, obs);
    return CHECK_PASSED;
}

/* A cycle integrated while the model is off. The model comes back on it at once when
 * only a check failed (re-anchored, its Jacobians kept), and is built anew after an
 * edge, a change of contact or a failure on the shortest stretch, once the cycles have
 * been quiet long enough. 1: the model is on. */
static int full(const line_ctx *L, line_state *st, controller *c, const cycle_in *in, int edge,
                double *obs, int *rc)
{
    tt_sim *sim = L->W->sim;
    tt_envelope *const was = L->W->env;
    double x0[TT_SIM_DIM_MAX];
    int c0, c1;
    tt_sim_get_x(sim, x0, &c0);
    tt_cycle cy;
    stops[TT_ENV_FULL]++;
    if ((*rc = tt_scan_env_integrate(L, st, in, &cy, obs, &c1, c)))
        return 0;
    /* the plan of the law the cycle ended on (another dimension's after a material
     * edge, whose model is built anew: the edge is no calm cycle) */
    tt_envelope *env = L->W->env;
    if (env != was)
        c->rebuild = 1;
    int touch = tt_envelope_touched(&cy);
    /* a tip that touches in one cycle and not in the next, both on a branch, grazes */
    const int calm = !edge && !in->edge_next;
    const int branch = calm && tt_scan_graze_possible(L, st) && tt_scan_on_branch(&cy, c0, c1);
    const int alternates = branch && c->prev_branch && touch != c->prev_touch;
    c->prev_branch = branch;
    if (c->graze || alternates) {
        c->same = touch == c->prev_touch ? c->same + 1 : 0;
        c->prev_touch = touch;
        stops[TT_ENV_FULL_GRAZE]++;
        return tt_scan_graze_full(L, st, c, in, x0, &cy, obs, branch);
    }
    int quiet = calm && touch == c->prev_touch && c1 == c0;
    if (!quiet || st->k < c->redo)
        stops[!calm ? TT_ENV_FULL_EDGE : !quiet ? TT_ENV_FULL_CHANGE : TT_ENV_FULL_REDO]++;
    if (!quiet)
        c->rebuild = 1;
    quiet = quiet && st->k >= c->redo;
    c->quiet = quiet ? c->quiet + 1 : 0;
    c->prev_touch = touch;
    if (!quiet || st->k + 1 >= L->ncyc)
        return 0;
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    const int same = !c->rebuild && c0 == tt_envelope_anchor_contact(env) &&
                     touch == tt_envelope_anchor_touched(env);
    /* a model gone too far is recalled nearer or, this cycle being integrated anyway,
     * built here at once where the state comes back (elsewhere, a transient's place, it
     * is anchored here as it is); a kept model near enough needs no wait after a change
     * either: the map is the same wherever the line is */
    const int far = same && far_off(L, x0, in, touch, c0);
    if ((same && !far) || (L->retake > 0 && recall(L, st, c, in, x0, c0, &cy)) ||
        (far && !worth_a_model(L, st, in, x0))) {
        tt_envelope_anchor(env, x0, in->sa, sdot, st->x, &cy, obs);
        c->smooth = sample_mid(in) - in->zn;
        c->rebuild = 0;
        return 1;
    }
    if (!far && c->quiet < c->wait) {
        stops[TT_ENV_FULL_WAIT]++;
        return 0;
    }
    stops[TT_ENV_BUILD]++;
    long jacobian = 0; /* its cycles are not the run's */
    c->smooth = sample_mid(in) - in->zn;
    if (tt_envelope_build(env, sim, x0, c0, in->sa, sdot, &cy, obs, &jacobian) == TT_ENV_USABLE) {
        tt_envelope_keep(env, (int)st->current);
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
    /* a stretch that the reach bound ended early is retried on a quarter of what it ran
     * (a fast transient's, a few cycles, fails as the shortest at once, rather than
     * again at the same cycle) */
    const long len = L->reach > 0 && c->ran < c->m ? c->ran : c->m;
    c->ran = 0;
    if (len > M_MIN) {
        c->m = len / 4 > M_MIN ? len / 4 : M_MIN;
        c->left = c->m; /* the snapshot covers the shorter stretch too */
        return;
    }
    c->model = 0;
    stops[TT_ENV_SHORTEST]++;
    c->quiet = 0;
    c->redo = k + 1;
    if (c->graze) {
        /* the free model is built anew after a second failure in a row; the touch
         * model learns from every touch integrated */
        if (++c->fails >= 2) {
            c->free_ok = 0;
            c->fails = 0;
        }
        c->wait = c->wait * 2 < WAIT_MAX ? c->wait * 2 : WAIT_MAX;
        return;
    }
    /* With noise on, a short stretch fails where the noise took the state too far for
     * the model (its error grows with the square of the reach), not where the Jacobians
     * went stale: the model is anchored again on the next cycle, twice in a row before
     * they are taken anew after a wait. */
    if (L->rel > 0 && c->fails < 2) {
        c->fails++;
        return;
    }
    c->rebuild = 1;
    c->wait = c->wait * 2 < WAIT_MAX ? c->wait * 2 : WAIT_MAX;
}

/* model_step with noise that moves the state (thermal, z piezo): the second-order model,
 * its part of the state carried beside it, within its reach of the anchor (L->reach);
 * the sample's reach from the anchor counts its smooth course only, the z piezo's noise
 * being an input the model takes, held by the check's error (docs/dynamics.md, "Noise on
 * the envelope tier"). Past the reach the kept model nearest to the inputs, within the
 * reach of where it was built, takes over from its own anchor, and the expansion
 * starts anew there: the noise rings the state round an orbit many times the reach
 * wide (0.7 nm on the edge sample's disks, every 100 cycles), and the models built on
 * it tile it. Never grazing (graze_possible). */
static int model_step2(const line_ctx *L, line_state *st, controller *c,
                       const cycle_in *in, double sdot, double *obs)
{
    tt_envelope *env = L->W->env;
    if (!(fabs(sample_mid(in) - in->zn - c->smooth) <= L->edge * c->bound)) {
        stops[TT_ENV_END_SAMPLE]++;
        c->bounded = 1;
        return 0;
    }
    const double reach = L->reach * c->bound;
    if (!(tt_envelope_reach(env, st->x, in->sa, sdot) <= reach)) {
        if (!tt_envelope_switch(env, st->x, in->sa, sdot, (int)st->current, reach)) {
            stops[TT_ENV_END_REACH]++;
            c->bounded = 1;
            return 0;
        }
        memset(st->x2, 0, sizeof st->x2);
    }
    double x1[TT_SIM_DIM_MAX], x21[TT_SIM_DIM_MAX];
    tt_envelope_predict(env, TT_ENV_REDUCED, st->x, st->x2, in->sa, sdot, x1, x21, obs);
    const int nx = tt_sim_dim(L->W->sim);
    memcpy(st->x, x1, (size_t)nx * sizeof *x1);
    memcpy(st->x2, x21, (size_t)nx * sizeof *x21);
    return 1;
}

/* A model cycle, unless the stretch is done, this or the next cycle crosses an edge,
 * the sample is out of the anchor's reach, or it is the phase's last (the next phase
 * starts integrating from the sim's state): then a check. 1: the model ran the cycle,
 * its samples reduced to the lock-in's components in obs. */
static int model_step(const line_ctx *L, line_state *st, controller *c,
                      const cycle_in *in, int edge, double *obs)
{
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    if (!c->model || c->left <= 0 || edge || in->edge_next || in->mat != st->current ||
        in->k + 1 >= L->ncyc)
        return 0;
    if (L->reach > 0)
        return model_step2(L, st, c, in, sdot, obs);
    if (!(fabs(tt_envelope_sample_offset(L->W->env, in->sa, sdot)) <= L->edge)) {
        stops[TT_ENV_END_SAMPLE]++;
        return 0;
    }
    if (c->graze)
        return tt_scan_graze_step(L, st, c, in, obs);
    double x1[TT_SIM_DIM_MAX];
    tt_envelope_predict(L->W->env, TT_ENV_REDUCED, st->x, NULL, in->sa, sdot, x1, NULL, obs);
    memcpy(st->x, x1, (size_t)tt_sim_dim(L->W->sim) * sizeof *x1);
    return 1;
}

/* The cycles of one phase. */
static int run_phase(const line_ctx *L, line_state *st, controller *c)
{
    double *obs = L->W->obs;
    int rc = TT_OK;
    if (c->graze)
        tt_scan_graze_leave(L, c);
    c->model = 0;
    c->quiet = 0;
    c->prev_touch = -1;
    c->prev_branch = 0;
    c->redo = 0;
    c->rebuild = 1;
    while (st->k < L->ncyc) {
        cycle_in in;
        if ((rc = tt_scan_cycle_begin(L, st, &in)))
            return rc;
        const int edge = edge_ahead(L, &in);
        int snap = 0, reduced = model_step(L, st, c, &in, edge, obs);
        check_outcome pass = CHECK_FAILED;
        if (reduced) {
            stops[TT_ENV_MODEL]++;
            c->left--;
            c->ran++;
        } else if (c->model) {
            pass = c->graze ? tt_scan_graze_check(L, st, &in, obs, c, &rc) : check(L, st, &in, obs, c, &rc);
            if (pass == CHECK_FAILED) {
                if (rc)
                    return rc;
                fail(L, st, c, in.k);
                continue;
            }
            if (pass == CHECK_PASSED) /* a check, not a cycle from an integrated state */
                c->m = 2 * c->m < M_MAX ? 2 * c->m : M_MAX;
            /* with the reach bound, a transient's stretches pass a cycle or two before
             * the Jacobians go stale: the wait is reset only by one that held */
            if (!(L->reach > 0) || c->ran >= WAIT_MIN)
                c->wait = WAIT_MIN;
            c->fails = 0;
            c->model = pass != CHECK_MODEL_OFF && !edge && !in.edge_next;
            c->quiet = 0;
            snap = c->model;
        } else {
            c->model = snap = full(L, st, c, &in, edge, obs, &rc);
            if (rc)
                return rc;
        }
        if ((rc = record(L, st, &in, obs, reduced)))
            return rc;
        c->exact = !reduced;
        if (snap) {
            c->left = c->m;
            c->ran = 0;
            c->bounded = 0;
            snap_take(L, st, tt_envelope_anchor_contact(L->W->env), c->left, &c->sn);
        }
    }
    return TT_OK;
}

/* The envelope tier's cycles of one phase (a scan_phase_fn; tier: the controller). */
static int envelope_phase(const line_ctx *L, line_state *st, void *tier)
{
    controller *c = tier;
    free(c->seen);
    c->nseen = L->ncyc;
    c->seen = calloc((size_t)(L->ncyc > 0 ? L->ncyc : 1), 1);
    if (!c->seen)
        return tt_error_nomem("the envelope tier's record of %ld cycles", L->ncyc);
    return run_phase(L, st, c);
}

int tt_scan_line_envelope(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          long *integrated, double *worst, int *clamped)
{
    controller c = {.m = M_MIN, .wait = WAIT_MIN, .bound = 1};
    for (int n = 0; n <= TT_SIM_DIM_MAX; n++) /* a line's cycles depend on no other line's */
        if (W->envs[n])
            tt_envelope_reset(W->envs[n]);
    c.sn.pix = calloc((size_t)S->raster.pixels, sizeof *c.sn.pix);
    c.sn.indent = malloc((S->nmaterials ? S->nmaterials : 1) * sizeof *c.sn.indent);
    c.red = malloc(2 * (size_t)tt_envelope_size(W->env) * sizeof *c.red);
    c.pred = c.red ? c.red + tt_envelope_size(W->env) : NULL;
    if (!c.sn.pix || !c.red || !c.sn.indent) {
        free(c.sn.pix);
        free(c.sn.indent);
        free(c.red);
        return tt_error_nomem("the envelope tier's pixels of a line ([scan] pixels = %ld)", S->raster.pixels);
    }
    int rc = tt_scan_line_run(S, W, line, out, envelope_phase, &c, cycles, worst, clamped);
    *integrated += c.integrated;
    tt_graze_disarm(W->graze, W->sim);
    free(c.seen);
    free(c.sn.pix);
    free(c.sn.indent);
    free(c.red);
    return rc;
}
