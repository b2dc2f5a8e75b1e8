/* The scan's line engine: a worker made for a solver setting (its sim, lock-in and the
 * tier the setting runs on here), retuned to a change of noise, and one line run on its
 * tier (see scan_engine.h). */
#include "scan_private.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/solver/noise.h"
#include "tiptap/util/clock.h"
#include "tiptap/util/error.h"

void tt_scan_worker_free(worker *W)
{
    tt_sim_free(W->sim);
    tt_lockin_free(W->lockin);
    free(W->samples);
    free(W->y);
    for (int n = 0; n <= TT_SIM_DIM_MAX; n++)
        tt_envelope_free(W->envs[n]);
    tt_graze_free(W->graze);
    tt_lockin_free(W->lockin_save);
    free(W->y_save);
    free(W->obs);
    free(W->indent);
    tt_scan_geometry_free(W);
}

/* The averaged tier takes the drive, the damping and the tip-sample force for small
 * against the cantilever's own forces at the drive frequency (Krylov-Bogoliubov): below
 * Q 30 (a liquid's Q 1 gave NaN before this bound) or with the drive more than 5 % from
 * resonance (the detuning k - m w^2 over a tenth of k; at twice and half the resonance
 * its images were wrong by 100 nm) the scan runs on the envelope tier instead. */
static int averaged_allowed(const tt_cantilever *c)
{
    double detune = 1 - (c->fd / c->f0) * (c->fd / c->f0);
    return c->Q >= 30 && fabs(detune) <= 0.1;
}

int tt_scan_averaged_tier(const tt_scan_params *p)
{
    return p->solver.tier == TT_TIER_AVERAGED && averaged_allowed(&p->cantilever);
}

int tt_scan_envelope_tier(const tt_scan_params *p)
{
    int tier = p->solver.tier == TT_TIER_AVERAGED && !averaged_allowed(&p->cantilever)
                   ? TT_TIER_ENVELOPE
                   : p->solver.tier;
    return tier == TT_TIER_ENVELOPE;
}

/* Whether a solver setting runs on the averaged tier here. */
int tt_scan_averaged_usable(const tt_scan *S, const tt_solver *solver)
{
    return solver->tier == TT_TIER_AVERAGED && averaged_allowed(&S->cantilever);
}

/* Whether a solver setting runs on the envelope tier here (the averaged tier's
 * fallback included). It runs at any Q and with any noise: above Q 3000 its checks bound a
 * stretch's drift (scan_envelope.c); at low Q the map contracts within a few cycles and
 * the model follows it (Q 10, 3, 1 and 0.3 skipped 89 to 98 % of the cycles within
 * their estimates; a fallback below Q 30 was a guess, never measured); thermal and
 * detector noise run on it to first order, the z piezo's (smooth below its bandwidth)
 * as the sample's position it is (docs/dynamics.md, "Noise on the envelope tier"). */
int tt_scan_envelope_usable(const tt_scan *S, const tt_solver *solver)
{
    int tier = solver->tier == TT_TIER_AVERAGED && !tt_scan_averaged_usable(S, solver) ? TT_TIER_ENVELOPE
                                                                              : solver->tier;
    return tier == TT_TIER_ENVELOPE;
}

/* The envelope tier's models kept per thread with noise that moves the state, 7 kB each
 * on the standard lock-in: a line of the teaching grating at 300 K builds a few hundred
 * (with 64 kept its lines took 9 % more instructions) */
enum { KEPT_MODELS = 512 };

/* The envelope tier's plan for this scan's lock-in and noise (tiptap/solver/envelope.h):
 * the model's cycles give the lock-in its per-period components, not samples (a few
 * dozen multiply-adds a cycle instead of n products and a transform); the gaps around
 * the closest approach, from which a grazing tip's branch and the time of its jump-in
 * are predicted (tiptap/solver/graze.h); the z piezo's noise moves the sample within
 * each cycle by a travel of its own (about pi n fc sqrt(2 T) rms), an input of the
 * model as the sample's position is; noise that moves the state takes the model to
 * second order, with models kept for recall, as the noise brings the state back near
 * the same places; the noise to first order: the thermal force's PSD (2 c kB T) and the
 * detector's per-sample rms (the sim integrates without the thermal force). */
static tt_envelope_params plan_of(const tt_lockin_params *lk, const tt_lockin *l,
                                  const tt_cantilever *c, const tt_scan_noise *nz, double zn_sd,
                                  double sd)
{
    tt_envelope_params p = {0};
    p.samples = lk->samples_per_period;
    p.probes = TT_GRAZE_PROBES;
    p.reduced = tt_lockin_components(l);
    p.reduce = tt_lockin_component_matrix(l);
    p.travel = zn_sd > 0;
    p.second_order = nz->temperature > 0 || zn_sd > 0; /* tt_scan_second_order's */
    p.kept = p.second_order ? KEPT_MODELS : 0;
    p.psd = 2 * c->c * TT_BOLTZMANN * nz->temperature;
    p.sd = sd;
    return p;
}

static tt_envelope_params envelope_plan(const tt_scan *S, const worker *W)
{
    return plan_of(&S->lockin, W->lockin, &S->cantilever, &S->noise, S->zn.sd, S->sd);
}

double tt_scan_envelope_plans_bytes(const tt_scan_params *p)
{
    tt_lockin *l;
    if (!tt_scan_envelope_tier(p))
        return 0;
    if (tt_lockin_alloc(&l, &p->lockin)) { /* refused later, by tt_scan_alloc */
        tt_error_clear();
        return 0;
    }
    /* as tt_scan_alloc sets the detector's per-sample rms; the z piezo's noise moves the
     * sample wherever it has a density */
    double sd = p->noise.detector * sqrt(0.5 * p->lockin.samples_per_period / p->cantilever.T);
    tt_envelope_params e = plan_of(&p->lockin, l, &p->cantilever, &p->noise,
                                   p->noise.z_piezo > 0 ? 1.0 : 0.0, sd);
    const int modes = 2 * (p->cantilever.modes > 1 ? p->cantilever.modes : 1);
    int seen[TT_SIM_DIM_MAX + 1] = {0};
    double bytes = 0;
    /* a plan per state dimension (envelope_plans): the modes', and a law's states after
     * them (a relaxation arm's one each, contact_sls.c) */
    for (size_t i = 0; i < p->nmaterials; i++) {
        int n = modes + p->materials[i].contact.arms;
        if (n <= TT_SIM_DIM_MAX && !seen[n]) {
            seen[n] = 1;
            e.dim = n;
            bytes += tt_envelope_plan_bytes(&e);
        }
    }
    tt_lockin_free(l);
    return bytes;
}

/* The plans, one per state dimension the sim takes (its own now, and each material's
 * law's after the modes'), all made up front: a line never allocates. */
static int envelope_plans(const tt_scan *S, worker *W)
{
    tt_envelope_params plan = envelope_plan(S, W);
    const int n0 = tt_sim_dim(W->sim), modes = 2 * (S->cantilever.modes > 1 ? S->cantilever.modes : 1);
    for (size_t i = 0; i <= S->nmaterials; i++) {
        const int n = i == 0 ? n0
                             : modes + (int)tt_contact_law_of(S->contacts[i - 1])->state_size;
        if (n < 1 || n > TT_SIM_DIM_MAX)
            return tt_error(TT_EINVAL, "[material %s]: a state of %d components (at most %d)",
                            S->names[i - 1], n, TT_SIM_DIM_MAX);
        plan.dim = n;
        int rc = W->envs[n] ? TT_OK : tt_envelope_alloc(&W->envs[n], W->sim, &plan);
        if (rc)
            return rc;
    }
    W->env = W->envs[n0];
    return TT_OK;
}

static int envelope_alloc(tt_scan *S, worker *W)
{
    size_t n = (size_t)S->lockin.samples_per_period * (size_t)S->lockin.periods_per_block;
    int rc = envelope_plans(S, W);
    W->graze_dim = tt_sim_dim(W->sim);
    if (!rc) {
        const int m = tt_lockin_components(W->lockin);
        double *scale = calloc(2 * ((size_t)m + TT_ENV_EXTRA), sizeof *scale);
        if (!scale)
            return tt_error_nomem("a scan thread's envelope tier");
        double *floor = scale + m + TT_ENV_EXTRA;
        const tt_cantilever *c = &S->cantilever;
        for (int i = 0; i < m; i++)
            scale[i] = c->A0;
        scale[m + TT_ENV_PEAK] = c->k * c->A0;
        scale[m + TT_ENV_INDENT] = c->A0;
        scale[m + TT_ENV_ETS] = c->k * c->A0 * c->A0;
        /* a touch's peak force and greatest indentation scatter from one grazing touch
         * to the next by up to 4e-5 k A0 and 1e-6 A0 (the maximum sought on each step's
         * samples; the blend's matrix): held to 1e-4 and 1e-5 of their scales, 8 pN and
         * 0.2 pm on the standard cantilever, which a pixel's hundreds of cycles average */
        floor[m + TT_ENV_PEAK] = 1e-4;
        floor[m + TT_ENV_INDENT] = 1e-5;
        rc = tt_graze_alloc(&W->graze, W->sim, m + TT_ENV_EXTRA, scale, floor);
        free(scale);
    }
    if (!rc)
        rc = tt_lockin_alloc(&W->lockin_save, &S->lockin);
    if (rc)
        return rc;
    W->y_save = calloc(n, sizeof *W->y_save);
    W->obs = calloc(2 * (size_t)tt_envelope_size(W->env), sizeof *W->obs);
    if (!W->y_save || !W->obs)
        return tt_error_nomem("a scan thread's envelope tier");
    return TT_OK;
}

/* The averaged tier's tables, once per scan (before any thread runs a line): every
 * material's, with the harmonics the lock-in keeps. */
int tt_scan_averaged_tables(tt_scan *S)
{
    if (S->avg)
        return TT_OK;
    double t0 = tt_clock(TT_CLOCK_THREAD);
    S->avg = calloc(S->nmaterials, sizeof *S->avg);
    if (!S->avg)
        return tt_error_nomem("the averaged tier's tables of %zu materials", S->nmaterials);
    for (size_t i = 0; i < S->nmaterials; i++) {
        int rc = tt_averaged_alloc(&S->avg[i], &S->cantilever, S->contacts[i], S->Qi[i],
                                   S->lockin.harmonics);
        if (rc)
            return rc;
        double e = tt_averaged_table_error(S->avg[i]);
        if (e > S->avg_error)
            S->avg_error = e;
    }
    S->avg_seconds = tt_clock(TT_CLOCK_THREAD) - t0; /* with the check */
    return TT_OK;
}

int tt_scan_worker_retune(tt_scan *S, worker *W)
{
    const int env = tt_scan_envelope_usable(S, &S->solver);
    if (W->averaged)
        return TT_OK; /* its noise read from S at each block (scan_averaged.c) */
    /* the model's plan follows the noise: made anew for the new noise (a line's model
     * starts afresh anyway, tt_envelope_reset) */
    if (W->env) {
        for (int n = 0; n <= TT_SIM_DIM_MAX; n++) {
            tt_envelope_free(W->envs[n]);
            W->envs[n] = NULL;
        }
        tt_graze_free(W->graze); /* envelope_alloc makes a new one when the tier returns */
        tt_lockin_free(W->lockin_save);
        free(W->y_save);
        free(W->obs);
        W->env = NULL;
        W->graze = NULL;
        W->lockin_save = NULL;
        W->y_save = W->obs = NULL;
    }
    int rc = tt_sim_set_thermal(W->sim, env ? 0 : S->noise.temperature, S->noise.points);
    if (rc || !env)
        return rc;
    return envelope_alloc(S, W);
}

int tt_scan_worker_alloc(tt_scan *S, worker *W, const tt_solver *solver)
{
    memset(W, 0, sizeof *W);
    W->tolerance = solver->tolerance;
    W->model_tol = 10 * solver->tolerance;
    int rc;
    /* the averaged tier integrates only where its slow flow fails, at its own looser
     * tolerance, and adds the thermal force as its slow flow takes it (scan_averaged.c) */
    const int avg = tt_scan_averaged_usable(S, solver);
    const tt_solver own = avg ? tt_scan_averaged_solver(solver) : *solver;
    if ((rc = tt_sim_alloc(&W->sim, &S->cantilever, &own)) ||
        (rc = tt_sim_set_thermal(W->sim, avg || tt_scan_envelope_usable(S, solver) ? 0 : S->noise.temperature,
                                 S->noise.points)) ||
        (rc = tt_lockin_alloc(&W->lockin, &S->lockin)))
        return rc;
    size_t n = (size_t)S->lockin.samples_per_period * (size_t)S->lockin.periods_per_block;
    W->samples = calloc(n, sizeof *W->samples);
    W->y = calloc(n, sizeof *W->y);
    W->indent = malloc(S->nmaterials * sizeof *W->indent);
    if (!W->samples || !W->y || !W->indent)
        return tt_error_nomem("a scan thread's lock-in samples");
    for (size_t i = 0; i < S->nmaterials; i++)
        W->indent[i] = -INFINITY;
    if (tt_scan_averaged_usable(S, solver)) {
        W->averaged = 1;
        return tt_scan_averaged_tables(S);
    }
    return tt_scan_envelope_usable(S, solver) ? envelope_alloc(S, W) : TT_OK;
}

int tt_scan_worker_line(tt_scan *S, worker *W, long line, const line_out *out,
                        tt_scan_scope *scope, line_tally *t)
{
    line_out images;
    if (!out) {
        memcpy(images.img, S->img, sizeof images.img);
        images.packed = 0;
        out = &images;
    }
    memset(t, 0, sizeof *t);
    int rc = scope ? tt_scan_scope_begin(scope, S, line) : TT_OK;
    if (rc)
        return rc;
    W->scope = scope;
    W->work0 = tt_sim_work(W->sim);
    W->settle_work = 0;
    if (W->env)
        rc = tt_scan_line_envelope(S, W, line, out, &t->cycles, &t->integrated, &t->worst,
                                   &t->clamped);
    else if (W->averaged)
        rc = tt_scan_line_averaged(S, W, line, out, &t->cycles, &t->integrated, &t->worst,
                                   &t->clamped);
    else
        rc = tt_scan_line_every(S, W, line, out, &t->cycles, &t->integrated, &t->worst,
                                &t->clamped);
    t->work = tt_scan_line_work(W, t->cycles);
    t->settle_work = W->settle_work;
    W->scope = NULL;
    if (scope)
        tt_scan_scope_end(scope, rc == TT_OK);
    return rc;
}
