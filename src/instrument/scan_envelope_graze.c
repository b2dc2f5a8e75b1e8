/* The envelope tier's grazing mode (tiptap/solver/graze.h; scan_envelope.c runs the
 * line): where the tip touches in some cycles and not in others, a model per branch. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scan_envelope_private.h"
#include "tiptap/physics/contact.h"
#include "tiptap/util/error.h"

/* Grazing touches (tiptap/solver/graze.h): where the tip touches in some cycles and
 * not in others, the free branch's model (its probes of the gap near the closest
 * approach among its observables) predicts whether a cycle reaches jump-in and when,
 * and the touch branch's model, fitted to the touch cycles integrated lately, gives a
 * touch cycle from its start, the sample and that time. Not with noise on: the thermal
 * and detector noise's linear response is that of one branch; the z piezo's moves the
 * sample by tens of picometres from cycle to cycle, enough to change a grazing cycle's
 * branch, and the branch models (first order, the touch fit linear in d, d', s) lack the
 * travel input and the second order the noisy model needs. There the cycles that
 * change contact are integrated, each one. */
int tt_scan_graze_possible(const line_ctx *L, const line_state *st)
{
    return L->W->graze && tt_sim_dim(L->W->sim) == L->W->graze_dim &&
           !tt_envelope_noise_size(L->W->env) && !(L->S->zn.sd > 0) &&
           isfinite(tt_contact_jumpin(L->S->contacts[st->current]));
}

/* A cycle on a branch of the grazing model: out of contact at its start and end, and
 * touching once (a jump-in and a pull-off) or not at all. */
int tt_scan_on_branch(const tt_cycle *cy, int c0, int c1)
{
    return c0 == 0 && c1 == 0 && cy->events == (tt_envelope_touched(cy) ? 2 : 0);
}

static void graze_enter(const line_ctx *L, const line_state *st, controller *c)
{
    c->graze = 1;
    c->free_ok = 0;
    c->quiet = 0;
    c->fails = 0;
    tt_graze_reset(L->W->graze, tt_contact_jumpin(L->S->contacts[st->current]));
}

void tt_scan_graze_leave(const line_ctx *L, controller *c)
{
    c->graze = 0;
    c->free_ok = 0;
    c->rebuild = 1;
    tt_graze_disarm(L->W->graze, L->W->sim);
}

/* A free cycle just integrated from x0 (the sim at its end): the probes aimed at its
 * closest approach, the cycle run again to read them, and the free model built on it.
 * 1: built. */
static int graze_build_free(const line_ctx *L, const cycle_in *in, const double *x0, double *obs)
{
    worker *W = L->W;
    tt_sim *sim = W->sim;
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    if (!tt_graze_aim(W->graze, sim, tt_sim_samples(sim), L->N))
        return 0;
    double x1[TT_SIM_DIM_MAX];
    int c1;
    tt_sim_get_x(sim, x1, &c1);
    tt_cycle cy;
    tt_sim_set_x(sim, x0, 0);
    tt_sim_set_sample(sim, in->sa, sdot);
    if (tt_sim_cycle(sim, &cy) != TT_OK) {
        tt_error_clear();
        tt_sim_set_x(sim, x1, c1);
        return 0;
    }
    tt_envelope_observe(W->env, tt_sim_samples(sim), tt_sim_probes(sim), &cy, obs);
    long jacobian = 0; /* its cycles are not the run's */
    return tt_envelope_build(W->env, sim, x0, 0, in->sa, sdot, &cy, obs, &jacobian) ==
           TT_ENV_USABLE;
}

/* The star of touch cycles about the deepest held (tt_graze_deepest), run from the
 * sim's state and put back: each state component (positions by 1e-4 A0, velocities by
 * 1e-4 w A0) and the sample (1e-4 A0) moved each way. 1: all touched once. */
static int graze_pair(const line_ctx *L, const cycle_in *in, double *obs, double *red)
{
    worker *W = L->W;
    tt_sim *sim = W->sim;
    const int nx = tt_sim_dim(sim);
    const double T = L->S->cantilever.T, sdot = (in->sb - in->sa) / T, A0 = L->S->A0;
    double h[TT_SIM_DIM_MAX + 1];
    for (int i = 0; i < nx; i++)
        h[i] = i % 2 ? 1e-4 * A0 * L->S->cantilever.wd : 1e-4 * A0;
    h[nx] = 1e-4 * A0;
    double x0[TT_SIM_DIM_MAX], smid, xs[TT_SIM_DIM_MAX], x1[TT_SIM_DIM_MAX], xp[TT_SIM_DIM_MAX];
    int cs, c1, ok = tt_graze_deepest(W->graze, x0, &smid);
    tt_sim_get_x(sim, xs, &cs);
    for (int i = 0; i < tt_graze_star_size(W->graze) && ok; i++) {
        double u[TT_SIM_DIM_MAX + 1] = {0};
        u[i / 2] = i % 2 ? h[i / 2] : -h[i / 2];
        for (int j = 0; j < nx; j++)
            xp[j] = x0[j] + u[j];
        const double ds = u[nx];
        tt_cycle cy;
        tt_sim_set_x(sim, xp, 0);
        tt_sim_set_sample(sim, smid + ds - 0.5 * sdot * T, sdot);
        if (tt_sim_cycle(sim, &cy) != TT_OK) {
            tt_error_clear();
            ok = 0;
            break;
        }
        tt_sim_get_x(sim, x1, &c1);
        ok = tt_scan_on_branch(&cy, 0, c1) && tt_envelope_touched(&cy);
        if (!ok)
            break;
        tt_envelope_observe(W->env, tt_sim_samples(sim), tt_sim_probes(sim), &cy, obs);
        tt_envelope_reduce_obs(W->env, obs, red);
        tt_graze_add_pair(W->graze, i, xp, smid + ds, cy.t_contact, x1, red);
    }
    tt_sim_set_x(sim, xs, cs);
    return ok;
}

/* A touch integrated from x0 to x1 (its reduced observables in c->red) joins the touch
 * model's cycles, the star about the deepest is run anew when the sample has moved from
 * it, and the model is fitted again (c->red and c->pred are overwritten). */
static void graze_learn(const line_ctx *L, controller *c, const cycle_in *in, const double *x0,
                        const tt_cycle *cy, const double *x1)
{
    tt_graze *g = L->W->graze;
    tt_graze_add(g, x0, sample_mid(in), cy->t_contact, x1, c->red);
    /* no fit while the sample moves too fast for 8 touches within its reach (a
     * transient), and the star run anew only where it is missing, or stale and the fit
     * fails without it */
    if (!c->free_ok || tt_graze_near(g) < 8)
        return;
    if (tt_graze_star_due(g, 0))
        graze_pair(L, in, c->pred, c->red);
    if (!tt_graze_fit(g, 2 * L->tol) && tt_graze_star_due(g, 1)) {
        graze_pair(L, in, c->pred, c->red);
        tt_graze_fit(g, 2 * L->tol);
    }
}

/* A cycle integrated in the grazing mode while the model is off, from x0 to st->x: a
 * free one anchors the free model (or builds it, once the cycles have been quiet long
 * enough), a touch one joins the touch model's fit. 1: both models are ready. */
int tt_scan_graze_full(const line_ctx *L, line_state *st, controller *c, const cycle_in *in,
                      const double *x0, const tt_cycle *cy, double *obs, int branch)
{
    worker *W = L->W;
    if (!c->graze)
        graze_enter(L, st, c);
    /* a tip that keeps to one branch while the model is off taps (or flies) as the one
     * model of a smooth map follows it */
    if (!branch || c->same >= WAIT_MIN * 4) {
        tt_scan_graze_leave(L, c);
        c->quiet = 0;
        return 0;
    }
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T;
    c->quiet = st->k >= c->redo ? c->quiet + 1 : 0;
    if (tt_envelope_touched(cy)) {
        tt_envelope_reduce_obs(W->env, obs, c->red);
        graze_learn(L, c, in, x0, cy, st->x);
    } else if (c->free_ok) {
        tt_envelope_anchor(W->env, x0, in->sa, sdot, st->x, cy, obs);
    } else if (c->quiet >= c->wait) {
        c->free_ok = graze_build_free(L, in, x0, c->pred);
    }
    if (st->k + 1 >= L->ncyc)
        return 0;
    return c->free_ok && tt_graze_fitted(W->graze) && c->quiet >= c->wait;
}

/* A free cycle's greatest indentation, where tracked, from its probes. */
static void free_indent(const line_ctx *L, double *red, double reach)
{
    double *x = red + tt_lockin_components(L->W->lockin);
    if (!isnan(x[TT_ENV_INDENT]))
        x[TT_ENV_INDENT] = reach;
}

/* The branch of a cycle from the tip's state x with the sample at s0 at its start
 * moving at sdot, and whether the model can follow it: a free cycle, or a touch the
 * fit covers. */
static int graze_call(const line_ctx *L, lookahead *la, const double *x, double s0,
                      double sdot, double *tc, double *reach, int *b)
{
    worker *W = L->W;
    const int nx = tt_sim_dim(W->sim);
    /* a model cycle calls its successor's branch as it ends: the next cycle's call is
     * the same when its inputs are */
    int same = la->valid && la->s0 == s0 && la->sdot == sdot;
    for (int i = 0; i < nx && same; i++)
        same = la->x[i] == x[i];
    if (!same) {
        double d[TT_GRAZE_PROBES], x1[TT_SIM_DIM_MAX];
        tt_envelope_predict(W->env, TT_ENV_PROBES, x, NULL, s0, sdot, x1, NULL, d);
        la->b = tt_graze_branch(W->graze, d, s0, sdot, &la->tc, &la->reach);
        la->ok = la->b == TT_GRAZE_FREE ||
                 (la->b == TT_GRAZE_TOUCH &&
                  tt_graze_covers(W->graze, x, s0 + 0.5 * sdot * L->S->cantilever.T, la->tc));
        memcpy(la->x, x, (size_t)nx * sizeof *x);
        la->s0 = s0;
        la->sdot = sdot;
        la->valid = 1;
    }
    *b = la->b;
    *tc = la->tc;
    *reach = la->reach;
    return la->ok;
}

/* A model cycle in the grazing mode. 0 when the model cannot follow this cycle or the
 * next (too close to call, or a touch outside the fit): the stretch then ends with a
 * check on this cycle, so that the next starts from an integrated state and is
 * integrated as it is (c->exact). */
int tt_scan_graze_step(const line_ctx *L, line_state *st, controller *c, const cycle_in *in,
                      double *obs)
{
    worker *W = L->W;
    const double T = L->S->cantilever.T, sdot = (in->sb - in->sa) / T;
    double tc, reach, x1[TT_SIM_DIM_MAX];
    int b;
    if (!graze_call(L, &c->la, st->x, in->sa, sdot, &tc, &reach, &b))
        return 0;
    if (b == TT_GRAZE_FREE) {
        tt_envelope_predict(W->env, TT_ENV_REDUCED, st->x, NULL, in->sa, sdot, x1, NULL, obs);
        free_indent(L, obs, reach);
    } else {
        tt_graze_predict(W->graze, st->x, sample_mid(in), tc, x1, obs);
    }
    if (!graze_call(L, &c->la, x1, in->sb, sdot, &tc, &reach, &b))
        return 0;
    memcpy(st->x, x1, (size_t)tt_sim_dim(W->sim) * sizeof *x1);
    return 1;
}

/* The check closing a stretch in the grazing mode: cycle k integrated from the model's
 * state against the model of the branch it took (a branch the probes called otherwise
 * fails it). Touch cycles join the touch model's fit, passed or not. As check. */
check_outcome tt_scan_graze_check(const line_ctx *L, line_state *st, const cycle_in *in,
                                  double *obs, controller *c, int *rc)
{
    worker *W = L->W;
    tt_envelope *env = W->env;
    const double sdot = (in->sb - in->sa) / L->S->cantilever.T, smid = sample_mid(in);
    double x0[TT_SIM_DIM_MAX];
    memcpy(x0, st->x, sizeof x0);
    const int exact = c->exact;
    double gaps[TT_GRAZE_PROBES], tc, reach, xp[TT_SIM_DIM_MAX];
    tt_envelope_predict(env, TT_ENV_PROBES, x0, NULL, in->sa, sdot, xp, NULL, gaps);
    const int b = tt_graze_branch(W->graze, gaps, in->sa, sdot, &tc, &reach);
    tt_sim_set_x(W->sim, x0, 0);
    tt_cycle cy;
    int c1, irc = tt_scan_env_integrate(L, st, in, &cy, obs, &c1, c);
    if (irc == TT_EINTR) {
        *rc = irc;
        return CHECK_FAILED;
    }
    if (irc != TT_OK) {
        tt_error_clear();
        return CHECK_FAILED;
    }
    const int touch = tt_envelope_touched(&cy);
    if (!tt_scan_on_branch(&cy, 0, c1))
        return CHECK_FAILED;
    tt_envelope_reduce_obs(env, obs, c->red);
    if (exact) { /* from an integrated state: nothing to check, all to learn */
        if (touch) {
            graze_learn(L, c, in, x0, &cy, st->x);
        } else {
            tt_envelope_anchor(env, x0, in->sa, sdot, st->x, &cy, obs);
        }
        return CHECK_EXACT;
    }
    const int nr = tt_graze_outputs(W->graze) - tt_sim_dim(W->sim);
    if (touch) {
        if (b == TT_GRAZE_FREE || !isfinite(tc) || !tt_graze_fitted(W->graze)) {
            graze_learn(L, c, in, x0, &cy, st->x);
            return CHECK_FAILED;
        }
        tt_graze_predict(W->graze, x0, smid, tc, xp, c->pred);
    } else {
        if (b == TT_GRAZE_TOUCH)
            return CHECK_FAILED;
        double x1[TT_SIM_DIM_MAX];
        tt_envelope_predict(env, TT_ENV_REDUCED, x0, NULL, in->sa, sdot, xp, NULL, c->pred);
        free_indent(L, c->pred, reach);
        tt_envelope_predict(env, TT_ENV_PROBES, x0, NULL, in->sa, sdot, x1, NULL, c->pred + nr);
    }
    /* a touch's peak force and indentation to their floors (tt_graze_alloc) */
    double gerr = tt_scan_env_drift(L, c->m) * (touch ? tt_graze_error(W->graze, xp, c->pred, st->x, c->red, L->tol)
                        : tt_envelope_error(env, TT_ENV_REDUCED, xp, c->pred, st->x, c->red) / L->tol);
    if (touch) /* learnt from, passed or not */
        graze_learn(L, c, in, x0, &cy, st->x);
    if (!(gerr <= 1))
        return CHECK_FAILED;
    if (!touch)
        tt_envelope_anchor(env, x0, in->sa, sdot, st->x, &cy, obs);
    return CHECK_PASSED;
}
