/* Closed-loop imaging: raster, lock-in, feedback and per-pixel channels
 * (see include/tiptap/instrument/scan.h). */
#include "tiptap/instrument/scan.h"
#include "scan_private.h"

#include <math.h>
#include <stdio.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tiptap/solver/noise.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/util/clock.h"

static const struct {
    const char *name, *unit;
} channel_info[TT_CH_COUNT] = {
    {"height", "m"},     {"error", "m"},       {"phase", "deg"},       {"peak_force", "N"},
    {"indentation", "m"}, {"dissipation", "J"}, {"topography", "m"},   {"amplitude", "m"},
    {"harmonic2", "m"},  {"harmonic3", "m"},   {"harmonic4", "m"},     {"harmonic5", "m"},
    {"harmonic6", "m"},  {"harmonic7", "m"},   {"harmonic8", "m"},
    {"harmonic2_phase", "deg"}, {"harmonic3_phase", "deg"}, {"harmonic4_phase", "deg"},
    {"harmonic5_phase", "deg"}, {"harmonic6_phase", "deg"}, {"harmonic7_phase", "deg"},
    {"harmonic8_phase", "deg"}, {"artefact", "m"},
};

const char *tt_scan_channel_name(int i) { return i >= 0 && i < TT_CH_COUNT ? channel_info[i].name : "?"; }
const char *tt_scan_channel_unit(int i) { return i >= 0 && i < TT_CH_COUNT ? channel_info[i].unit : "?"; }
int tt_scan_channel_count(void) { return TT_CH_COUNT; }

int tt_scan_channel_harmonic(int i)
{
    if (i == 1 || i == 2 || i == 7)
        return 1;
    if (i >= TT_CH_HARMONIC_INDEX && i < TT_CH_HARMONIC_INDEX + NHARM)
        return i - TT_CH_HARMONIC_INDEX + 2;
    if (i >= TT_CH_HARMONIC_PHASE_INDEX && i < TT_CH_HARMONIC_PHASE_INDEX + NHARM)
        return i - TT_CH_HARMONIC_PHASE_INDEX + 2;
    return 0;
}

int tt_scan_channels_parse(const char *text, unsigned *mask, char *why, size_t len)
{
    *mask = 0;
    const char *p = text;
    while (*p) {
        while (*p == ' ' || *p == ',' || *p == '\t')
            p++;
        if (!*p)
            break;
        const char *e = p;
        while (*e && *e != ',' && *e != ' ' && *e != '\t')
            e++;
        int found = -1;
        for (int i = 0; i < TT_CH_COUNT; i++)
            if (strlen(channel_info[i].name) == (size_t)(e - p) &&
                strncmp(channel_info[i].name, p, (size_t)(e - p)) == 0)
                found = i;
        if (found < 0) {
            snprintf(why, len,
                     "unknown channel '%.*s'; channels are height, error, amplitude, phase, "
                     "peak_force, indentation, dissipation, topography, harmonic2 to harmonic%d, "
                     "harmonic2_phase to harmonic%d_phase, artefact",
                     (int)(e - p), p, TT_CH_HARMONIC_MAX, TT_CH_HARMONIC_MAX);
            return -1;
        }
        *mask |= 1u << found;
        p = e;
    }
    if (!*mask) {
        snprintf(why, len, "no channel named");
        return -1;
    }
    return 0;
}

/* Every material's force law, built before any line runs. */
static int build_contacts(tt_scan *S, const tt_material *m, size_t n)
{
    S->nmaterials = n;
    S->contacts = calloc(n, sizeof *S->contacts);
    S->Qi = calloc(n, sizeof *S->Qi);
    S->contact_R = calloc(n, sizeof *S->contact_R);
    S->names = calloc(n, sizeof *S->names);
    S->indent = calloc(n, sizeof *S->indent);
    if (!S->contacts || !S->Qi || !S->contact_R || !S->names || !S->indent)
        return tt_error_nomem("the force laws of %zu materials", n);
    for (size_t i = 0; i < n; i++) {
        S->Qi[i] = m[i].Qi;
        S->contact_R[i] = m[i].contact.R;
        S->indent[i] = -INFINITY;
        snprintf(S->names[i], sizeof S->names[i], "%s", m[i].name);
        if (tt_contact_alloc(&S->contacts[i], &m[i].contact)) {
            char why[512];
            snprintf(why, sizeof why, "%s", tt_error_message());
            return tt_error(TT_EINVAL, "[material %s]: %s", m[i].name, why);
        }
    }
    return TT_OK;
}

int tt_scan_piezo_noise(const tt_scan_noise *n, const tt_cantilever *c, tt_noise_ou *zn)
{
    *zn = (tt_noise_ou){0, 0, 0};
    if (n->z_piezo > 0 && tt_noise_ou_init(zn, n->z_piezo, n->z_bandwidth, c->T))
        return tt_error(TT_EINVAL, "[noise] z_piezo_bandwidth: %g Hz is not above 0 and at most "
                                   "half the drive frequency (%g Hz)",
                        n->z_bandwidth, 0.5 * c->fd);
    return TT_OK;
}

/* Copy the parameters; the lock-in demodulates only up to the highest harmonic a
 * channel records, since nothing else reads the rest. */
static int take_params(tt_scan *S, const tt_scan_params *p)
{
    S->cantilever = p->cantilever;
    S->solver = p->solver;
    S->raster = p->raster;
    S->channels = p->channels;
    S->settle_cycles = p->settle_cycles;
    S->profile_line = p->profile_line < 0 ? S->raster.lines / 2 : p->profile_line;
    if (S->profile_line >= S->raster.lines)
        return tt_error(TT_EINVAL, "[scan] profile_line: %ld is past the last line (%ld)",
                        S->profile_line, S->raster.lines - 1);
    S->noise = p->noise;
    S->continuous = p->continuous;
    /* white noise of one-sided density n sampled at rate fs has variance n^2 fs / 2 */
    S->sd = p->noise.detector * sqrt(0.5 * p->lockin.samples_per_period / p->cantilever.T);
    int rc = tt_scan_piezo_noise(&p->noise, &p->cantilever, &S->zn);
    if (rc)
        return rc;
    S->lockin = p->lockin;
    S->lockin.drive_frequency = p->cantilever.fd;
    S->lockin.harmonics = 1;
    for (int c = 0; c < TT_CH_COUNT; c++)
        if ((S->channels & (1u << c)) && tt_scan_channel_harmonic(c) > S->lockin.harmonics)
            S->lockin.harmonics = tt_scan_channel_harmonic(c);
    if (S->lockin.harmonics > p->lockin.harmonics)
        return tt_error(TT_EINVAL, "[scan] channels: harmonic%d needs [lockin] harmonics = %d or more (it is %d)",
                        S->lockin.harmonics, S->lockin.harmonics, p->lockin.harmonics);
    S->setpoint = p->feedback.setpoint;
    S->kp = p->feedback.kp;
    S->ki = p->feedback.ki;
    S->z_range = p->feedback.z_range;
    S->A0 = p->cantilever.A0;
    S->inst = p->instrument;
    const tt_instrument_params *in = &p->instrument;
    S->plain = p->tip.kind == TT_TIP_POINT && in->tilt_x == 0 && in->tilt_y == 0 &&
               in->drift_x == 0 && in->drift_y == 0 && in->drift_z == 0 &&
               tt_piezo_ideal(&in->piezo);
    if (p->nmaterials < 1)
        return tt_error(TT_EINVAL, "a scan needs at least one material");
    return TT_OK;
}

/* The dilated surface over the scan area and as far as drift carries the sample, on a
 * grid (where one is needed) a quarter of the finest of the pixel pitch, the line pitch
 * and the tip radius, but no finer than a sixteenth of the pixel: the grid's cost grows
 * as step^-4 (its nodes and the footprint's nodes each step^-2), and a sharper tip
 * would otherwise buy detail far finer than the image shows at that price (a cone over
 * 200 nm spheres, 64 pixels: 0.4 s at R = 10 nm, 6 s at 5 nm; docs/surfaces.md). */
static int make_dilation(tt_scan *S, const tt_tip_shape *tip)
{
    const tt_raster *R = &S->raster;
    double t = (double)R->lines / R->line_rate;
    double mx = fabs(S->inst.drift_x) * t, my = fabs(S->inst.drift_y) * t;
    double fast = (R->fast_y ? R->size_y : R->size_x) / (double)R->pixels;
    double slow = (R->fast_y ? R->size_x : R->size_y) / (double)R->lines;
    double pitch = fmin(fast, slow), dx = fmax(fmin(pitch, tip->radius) / 4, pitch / 16);
    return tt_dilation_alloc(&S->dilation, S->surface, tip, -mx, -my, R->size_x + mx,
                             R->size_y + my, dx);
}

int tt_scan_alloc(tt_scan **out, const tt_scan_params *p)
{
    *out = NULL;
    tt_scan *S = calloc(1, sizeof *S);
    if (!S)
        return tt_error_nomem("the scan");
    int rc;
    if ((rc = take_params(S, p)) ||
        (rc = tt_surface_alloc(&S->surface, &p->surface, p->materials, p->nmaterials,
                               S->raster.size_x, S->raster.size_y)) ||
        (rc = build_contacts(S, p->materials, p->nmaterials))) {
        tt_scan_free(S);
        return rc;
    }
    S->uniform = tt_surface_uniform(S->surface);
    S->flat = tt_surface_flat(S->surface);
    if (p->tip.kind != TT_TIP_POINT && !S->flat && (rc = make_dilation(S, &p->tip))) {
        tt_scan_free(S);
        return rc;
    }
    size_t n = (size_t)S->raster.pixels * (size_t)S->raster.lines;
    for (int r = 0; r < (S->raster.retrace ? 2 : 1); r++)
        for (int c = 0; c < TT_CH_COUNT; c++) {
            if (!(S->channels & (1u << c)))
                continue;
            S->img[r][c] = malloc(n * sizeof(double));
            if (!S->img[r][c]) {
                tt_scan_free(S);
                return tt_error_nomem("the scan's images of %zu pixels", n);
            }
            for (size_t i = 0; i < n; i++)
                S->img[r][c][i] = NAN;
        }
    S->collapse_line = S->collapse_px = -1;
    S->watch_line = -1;
    S->line_done = calloc((size_t)S->raster.lines, 1);
    if (!S->line_done) {
        tt_scan_free(S);
        return tt_error_nomem("the scan's %ld lines", S->raster.lines);
    }
    *out = S;
    return TT_OK;
}

void tt_scan_free(tt_scan *S)
{
    if (!S)
        return;
    if (S->step)
        tt_scan_worker_free(S->step);
    free(S->step);
    for (int r = 0; r < 2; r++)
        for (int c = 0; c < TT_CH_COUNT; c++)
            free(S->img[r][c]);
    free(S->line_done);
    tt_dilation_free(S->dilation);
    tt_surface_free(S->surface);
    for (size_t i = 0; i < S->nmaterials && S->avg; i++)
        tt_averaged_free(S->avg[i]);
    free(S->avg);
    for (size_t i = 0; i < S->nmaterials && S->contacts; i++)
        tt_contact_free(S->contacts[i]);
    free(S->contacts);
    free(S->Qi);
    free(S->contact_R);
    free(S->names);
    free(S->indent);
    free(S);
}

void tt_scan_worker_free(worker *W)
{
    tt_sim_free(W->sim);
    tt_lockin_free(W->lockin);
    free(W->samples);
    free(W->y);
    tt_envelope_free(W->env);
    tt_graze_free(W->graze);
    tt_lockin_free(W->lockin_save);
    free(W->y_save);
    free(W->obs);
    free(W->indent);
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
static int averaged_usable(const tt_scan *S, const tt_solver *solver)
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
static int envelope_usable(const tt_scan *S, const tt_solver *solver)
{
    int tier = solver->tier == TT_TIER_AVERAGED && !averaged_usable(S, solver) ? TT_TIER_ENVELOPE
                                                                              : solver->tier;
    return tier == TT_TIER_ENVELOPE;
}

/* The envelope tier's models kept per thread with noise that moves the state, 7 kB each
 * on the standard lock-in: a line of the teaching grating at 300 K builds a few hundred
 * (with 64 kept its lines took 9 % more instructions) */
enum { KEPT_MODELS = 512 };

/* Noise that moves the tip's state (the thermal force, the z piezo's) takes the envelope
 * tier's model to second order (tiptap/solver/envelope.h); the detector's does not. */
static int second_order(const tt_scan *S)
{
    return S->noise.temperature > 0 || S->zn.sd > 0;
}

/* What the envelope model's shape follows from the noise: 1, the travel as an input (z
 * piezo noise); 2, second order. */
static int model_shape(const tt_scan *S)
{
    return (S->zn.sd > 0 ? 1 : 0) | (second_order(S) ? 2 : 0);
}

static int envelope_alloc(tt_scan *S, worker *W)
{
    W->env_shape = model_shape(S);
    size_t n = (size_t)S->lockin.samples_per_period * (size_t)S->lockin.periods_per_block;
    int rc = tt_envelope_alloc(&W->env, &S->cantilever, S->lockin.samples_per_period);
    /* the gaps around the closest approach, from which a grazing tip's branch and the
     * time of its jump-in are predicted (tiptap/solver/graze.h) */
    if (!rc)
        rc = tt_envelope_set_probes(W->env, TT_GRAZE_PROBES);
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
        rc = tt_graze_alloc(&W->graze, &S->cantilever, m + TT_ENV_EXTRA, scale, floor);
        free(scale);
    }
    if (!rc)
        rc = tt_lockin_alloc(&W->lockin_save, &S->lockin);
    if (rc)
        return rc;
    /* the model's cycles give the lock-in its per-period components, not samples: a few
     * dozen multiply-adds a cycle instead of n products and a transform */
    rc = tt_envelope_reduce(W->env, tt_lockin_components(W->lockin),
                            tt_lockin_component_matrix(W->lockin));
    if (rc)
        return rc;
    /* the z piezo's noise moves the sample within each cycle by a travel of its own
     * (about pi n fc sqrt(2 T) rms): an input of the model, as the sample's position is */
    if (S->zn.sd > 0)
        tt_envelope_use_travel(W->env);
    if (second_order(S) && (rc = tt_envelope_use_second_order(W->env)))
        return rc;
    /* noise to first order in the model's cycles: the thermal force's PSD (2 c kB T) and
     * the detector's per-sample rms; the sim integrates without the thermal force */
    const tt_cantilever *c = &S->cantilever;
    rc = tt_envelope_set_noise(W->env, 2 * c->c * TT_BOLTZMANN * S->noise.temperature, S->sd);
    /* the second-order model holds near where its derivatives were taken, and the noise
     * brings the state back near the same places: models kept for recall */
    if (!rc && second_order(S))
        rc = tt_envelope_keep_models(W->env, KEPT_MODELS);
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
static int averaged_tables(tt_scan *S)
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
    const int env = envelope_usable(S, &S->solver);
    if (W->averaged)
        return TT_OK; /* noiseless (docs/dynamics.md, Averaged) */
    /* the model's inputs and order follow the noise: made anew when they change */
    if (W->env && (!env || W->env_shape != model_shape(S))) {
        tt_envelope_free(W->env);
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
    if (!W->env)
        return envelope_alloc(S, W);
    return tt_envelope_set_noise(W->env, 2 * S->cantilever.c * TT_BOLTZMANN * S->noise.temperature,
                                 S->sd);
}

static int worker_alloc(tt_scan *S, worker *W, const tt_solver *solver)
{
    memset(W, 0, sizeof *W);
    W->tolerance = solver->tolerance;
    W->model_tol = 10 * solver->tolerance;
    int rc;
    if ((rc = tt_sim_alloc(&W->sim, &S->cantilever, solver)) ||
        (rc = tt_sim_set_thermal(W->sim, envelope_usable(S, solver) ? 0 : S->noise.temperature,
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
    if (averaged_usable(S, solver)) {
        W->averaged = 1;
        return averaged_tables(S);
    }
    return envelope_usable(S, solver) ? envelope_alloc(S, W) : TT_OK;
}


/* Phase lag in the lock-in's range, (-90, 270] degrees (see src/instrument/lockin.c). */
static double lag(double X, double Y)
{
    double ph = atan2(Y, X);
    return ph < -M_PI / 2 ? ph + 2 * M_PI : ph;
}

/* The instrument's clock (tt_instrument_params) at the start of cycle k of phase 0
 * (settling: the line's start), 1 (trace) or 2 (retrace). */
double tt_scan_clock_at(const tt_scan *S, long line, int phase, long nc, long k)
{
    double half = 0.5 / S->raster.line_rate, t = (double)line / S->raster.line_rate;
    if (phase == 0)
        return t;
    return t + (phase == 2 ? half : 0) + half * (double)k / (double)nc;
}

/* The sample under raster position (x, y) at time t: *x, *y become the surface's point
 * there (drift); returns the height the apex meets (dilated, tilted, drifted in z) and
 * the true height in *topo. */
double tt_scan_sample_at(const tt_scan *S, double *x, double *y, double t, double *topo)
{
    const tt_instrument_params *in = &S->inst;
    *x -= in->drift_x * t;
    *y -= in->drift_y * t;
    *topo = S->flat ? 0 : tt_surface_height(S->surface, *x, *y);
    double h = S->dilation ? tt_dilation_height(S->dilation, *x, *y) : *topo;
    return h + in->tilt_x * *x + in->tilt_y * *y + in->drift_z * t;
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
    tt_sim_set_contact(W->sim, S->contacts[st->current], S->Qi[st->current]);
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
                else if (ch >= TT_CH_HARMONIC_PHASE_INDEX && cnt)
                    v = lag(a->sum[ch], a->quad[ch - TT_CH_HARMONIC_PHASE_INDEX]) * 180 / M_PI;
                if (out->img[dir][ch])
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
    L.reach = second_order(S) ? 3e-3 : 0;
    /* and its derivatives, carried from anchor to anchor, hold within 2e-3 of A0 of
     * where they were taken (its third derivatives reach 3000 / A0^2 on that silicon,
     * and a model carried further missed its checks by a Jacobian a few per cent off):
     * past it the nearest kept model is recalled at a check (scan_envelope.c); between
     * checks a stretch past the reach switches to the kept model nearest, within the
     * reach, anchored where it was built */
    L.retake = second_order(S) ? 2e-3 : 0;
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
    tt_sim_get_state(W->sim, &st.x[0], &st.x[1], &contact);
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

/* One line on the worker's tier. */
static int run_line(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                    long *integrated, double *worst, int *clamped)
{
    if (W->env)
        return tt_scan_line_envelope(S, W, line, out, cycles, integrated, worst, clamped);
    if (W->averaged)
        return tt_scan_line_averaged(S, W, line, out, cycles, worst, clamped);
    int rc = tt_scan_line_run(S, W, line, out, every_phase, NULL, cycles, worst, clamped);
    *integrated = *cycles;
    return rc;
}

/* What one line added to the scan's totals. */
typedef struct {
    long cycles, integrated;
    double worst;
    int clamped;
} line_tally;

/* One line on worker W into the scan's images, recording into W->scope when it is set
 * (the scope is closed after the line); tally receives what the line ran. */
static int scan_line(tt_scan *S, worker *W, long line, tt_scan_scope *scope, line_tally *t)
{
    line_out images;
    memcpy(images.img, S->img, sizeof images.img);
    images.packed = 0;
    memset(t, 0, sizeof *t);
    int rc = scope ? tt_scan_scope_begin(scope, S, line) : TT_OK;
    if (rc)
        return rc;
    W->scope = scope;
    rc = run_line(S, W, line, &images, &t->cycles, &t->integrated, &t->worst, &t->clamped);
    W->scope = NULL;
    if (scope)
        tt_scan_scope_end(scope, rc == TT_OK);
    return rc;
}

/* A line's totals into the scan's; 1 when it finished (counted done once). */
static int line_account(tt_scan *S, long line, int rc, const line_tally *t)
{
    S->cycles += t->cycles;
    S->integrated += t->integrated;
    if (t->worst > S->worst_residual)
        S->worst_residual = t->worst;
    S->clamped |= t->clamped;
    if (rc != TT_OK)
        return 0;
    if (!S->line_done[line]) {
        S->line_done[line] = 1;
        S->lines_done++;
    }
    return 1;
}

/* The greatest indentation of each material from a worker's: the same whichever
 * worker ran which line. */
static void merge_indent(tt_scan *S, const worker *W)
{
    for (size_t m = 0; W->indent && m < S->nmaterials; m++)
        if (W->indent[m] > S->indent[m])
            S->indent[m] = W->indent[m];
}

int tt_scan_run(tt_scan *S, int threads, void (*progress)(void *user, long done, long total),
                void *user)
{
    if (threads <= 0)
        threads = omp_get_max_threads();
    if (threads > S->raster.lines)
        threads = (int)S->raster.lines;
    if (threads < 1 || S->continuous)
        threads = 1; /* continuous lines follow one another */
    worker *W = calloc((size_t)threads, sizeof *W);
    if (!W)
        return tt_error_nomem("%d scan threads", threads);
    int rc = TT_OK;
    for (int i = 0; i < threads && rc == TT_OK; i++)
        rc = worker_alloc(S, &W[i], &S->solver);
    if (rc == TT_OK) {
        S->status = TT_OK;
        long total = S->raster.lines;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (long line = 0; line < total; line++) {
            int failed;
#pragma omp atomic read
            failed = S->status;
            if (failed || S->line_done[line] || tt_cancel_requested())
                continue;
            worker *w = &W[omp_get_thread_num()];
            line_tally t;
            int lrc = scan_line(S, w, line, line == S->watch_line ? S->watch : NULL, &t);
#pragma omp critical(tt_scan_result)
            {
                if (line_account(S, line, lrc, &t)) {
                    if (progress)
                        progress(user, S->lines_done, total);
                } else if (lrc != TT_EINTR && S->status == TT_OK) {
                    snprintf(S->message, sizeof S->message, "line %ld: %s", line, tt_error_message());
                    S->status = lrc;
                }
            }
        }
        if (S->status != TT_OK)
            rc = tt_error(S->status, "%s", S->message);
        else if (S->lines_done < S->raster.lines)
            rc = tt_error(TT_EINTR, "interrupted after %ld of %ld lines", S->lines_done,
                          S->raster.lines);
    }
    for (int i = 0; i < threads; i++)
        merge_indent(S, &W[i]);
    for (int i = 0; i < threads; i++)
        tt_scan_worker_free(&W[i]);
    free(W);
    return rc;
}

int tt_scan_step(tt_scan *S, long line, tt_scan_scope *scope)
{
    if (line < 0 || line >= S->raster.lines)
        return tt_error(TT_EINVAL, "line %ld: the scan's lines are 0 to %ld", line, S->raster.lines - 1);
    if (!S->step) {
        S->step = malloc(sizeof *S->step);
        if (!S->step)
            return tt_error_nomem("the scan's stepping workspace");
        int rc = worker_alloc(S, S->step, &S->solver);
        if (rc) {
            tt_scan_worker_free(S->step);
            free(S->step);
            S->step = NULL;
            return rc;
        }
    }
    line_tally t;
    int rc = scan_line(S, S->step, line, scope, &t);
    line_account(S, line, rc, &t);
    merge_indent(S, S->step);
    return rc;
}

void tt_scan_disengage(tt_scan *S)
{
    if (S->step)
        S->step->engaged = 0;
}

int tt_scan_line_values(const tt_scan *S, int ch, int retrace, long line, double *out)
{
    const double *img = tt_scan_image(S, ch, retrace);
    if (!img || line < 0 || line >= S->raster.lines)
        return tt_error(TT_EINVAL, "no %s image of line %ld (%s)", tt_scan_channel_name(ch), line,
                        img ? "no such line" : "channel not recorded");
    for (long px = 0; px < S->raster.pixels; px++)
        out[px] = img[tt_raster_index(&S->raster, line, px)];
    return TT_OK;
}

/* One companion line on a solver setting: height, amplitude and phase of trace and
 * retrace into buf (6 blocks of pixels: [channel][direction]), stopped after budget
 * cycles (0: none); *hit says it stopped there, *ran counts its cycles. */
static int companion_line(tt_scan *S, const tt_solver *solver, long line, long budget, long k0,
                          double *buf, int *hit, long *ran)
{
    worker W;
    line_out out = {{{0}}, 1};
    long px = S->raster.pixels, cycles = 0, integrated = 0;
    double worst = 0;
    int clamped = 0;
    for (long i = 0; i < 6 * px; i++)
        buf[i] = NAN; /* pixels the budget left out stay NaN */
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < (S->raster.retrace ? 2 : 1); r++)
            out.img[r][c] = buf + (size_t)(2 * c + r) * (size_t)px;
    int rc = worker_alloc(S, &W, solver);
    /* The tight line's model is held ten times tighter than the run's, as its steps are
     * (a hundred times: see tt_companion_solver), so that the difference of the two is
     * the run's error, the model's included; a hundred times tighter is below what the
     * grazing touches' model can follow (1e-9 of A0 over the blend's orbit), and the
     * tight line would integrate every grazing cycle at 1e-10 (16 G instructions, a
     * fifth of the README job's) */
    W.model_tol = fmax(W.model_tol, S->solver.tolerance);
    W.budget = budget;
    W.k0 = k0;
    if (!rc)
        rc = run_line(S, &W, line, &out, &cycles, &integrated, &worst, &clamped);
    *hit = W.budget_hit;
    *ran = cycles;
    tt_scan_worker_free(&W);
    return rc;
}

/* A hundred times tighter (rk4: four times the steps, 16 times at its order of 2 on
 * contact), so that the difference of the two runs is the run's own error even where
 * the error does not fall with the tolerance: on the bistable scene the envelope
 * model's error control changes course between 1e-9 and 1e-10, and the amplitude moved
 * 3.5 times more from 1e-9 to 1e-10 than from 1e-8 to 1e-9. Not below 1e-14, where the
 * steps' rounding takes over. */
tt_solver tt_companion_solver(const tt_solver *s)
{
    tt_solver t = *s;
    t.tolerance = fmax(s->tolerance / 100, fmin(s->tolerance, 1e-14));
    t.steps_per_cycle = s->steps_per_cycle <= 2500000 ? 4 * s->steps_per_cycle : 10000000;
    return t;
}

/* The companion's cycles: a fifth of the scan's cost, counted as the cycles the scan
 * integrated. On the every-cycle tier each of the companion's costs what its tighter
 * setting asks (dopri5's steps grow as the tolerance to the -1/5, 2.5 times at a
 * hundredth; rk4 runs four times the steps); on the envelope tier a cycle the scan
 * integrated cost 17 to 21 us with its model's work (the README's main job, the
 * teaching scene), a companion cycle 4 to 17 us, so one counts as one. 0 (no bound)
 * where the scan integrated none (the averaged tier). */
static long companion_budget(const tt_scan *S, const tt_solver *tight)
{
    double per = S->solver.method == TT_METHOD_RK4
                     ? (double)tight->steps_per_cycle / (double)S->solver.steps_per_cycle
                     : pow(S->solver.tolerance / tight->tolerance, 0.2);
    if (!(per >= 1) || envelope_usable(S, &S->solver))
        per = 1;
    return S->integrated > 0 ? (long)(TT_ESTIMATE_SHARE * (double)S->integrated / per) : 0;
}

/* Where the image is hardest: the largest height step between neighbouring pixels of
 * the trace (of trace and retrace when the companion covers whole lines, reach >= the
 * pixels), its line, and the first pixel of the stretch of reach pixels the companion
 * runs, the step a quarter into it. The profile line from its start where no line has
 * a step (a flat image, or no height channel). */
static long hardest_line(const tt_scan *S, long reach, double *step, long *first)
{
    const tt_raster *R = &S->raster;
    const int dirs = reach >= R->pixels && R->retrace ? 2 : 1;
    long best = S->profile_line, at = 0;
    double top = 0;
    for (long l = 0; l < R->lines; l++) {
        if (!S->line_done[l])
            continue;
        for (int r = 0; r < dirs && S->img[r][0]; r++) {
            const double *h = S->img[r][0];
            for (long i = 1; i < R->pixels; i++) {
                double d = fabs(h[tt_raster_index(R, l, i)] - h[tt_raster_index(R, l, i - 1)]);
                if (d > top) {
                    top = d;
                    best = l;
                    at = i;
                }
            }
        }
    }
    *step = top;
    *first = 0;
    if (reach < R->pixels) {
        *first = at - reach / 4 > 0 ? at - reach / 4 : 0;
        if (*first + reach > R->pixels)
            *first = R->pixels - reach;
    }
    return best;
}

int tt_scan_estimate_error(tt_scan *S, tt_scan_error *e)
{
    memset(e, 0, sizeof *e);
    const tt_raster *R = &S->raster;
    const long px = R->pixels;
    const int dirs = R->retrace ? 2 : 1;
    double *buf = calloc((size_t)(12 * px), sizeof *buf);
    if (!buf)
        return tt_error_nomem("the companion line's profile");
    double c0 = tt_clock(TT_CLOCK_PROCESS);
    tt_solver tight = tt_companion_solver(&S->solver);
    /* the averaged tier's error is its model's, which no tolerance moves: its companion
     * is the envelope tier at the run's tolerance (as accurate as every cycle) */
    const int avg = averaged_usable(S, &S->solver);
    if (avg) {
        tight = S->solver;
        tight.tier = TT_TIER_ENVELOPE;
    }
    int trc = avg ? averaged_tables(S) : TT_OK;
    if (trc) {
        free(buf);
        return trc;
    }
    /* Lines that do not carry on from one another are each a function of the line alone
     * (the noise keyed by line, the envelope model forgotten): the image's own line is
     * what the run's setting gives, and only the tight line runs. Continuous lines start
     * where the last one ended, so the run's setting runs again beside it, from the
     * same engage, on half the budget each. */
    int rerun = S->continuous || avg;
    for (int c = 0; c < 3; c++) /* and where the image lacks a channel it compares */
        for (int r = 0; r < dirs; r++)
            rerun |= !S->img[r][c];
    const long nc = tt_raster_cycles_per_direction(R, S->cantilever.T);
    const long settle = (S->settle_cycles + S->lockin.periods_per_block - 1) /
                        S->lockin.periods_per_block * S->lockin.periods_per_block;
    long budget = companion_budget(S, &tight);
    /* A stretch inside the line engages there, not where the image's line reached it
     * from the line's start (its noise counted from another cycle, its feedback fresh):
     * the run's setting runs the same stretch beside it, each on half the budget. The
     * trace's pixels the budget reaches, less the one it stops in: */
    long full = (long)((double)(budget - settle) / (double)nc * (double)px) - 1;
    if (budget > 0 && full < px)
        rerun = 1;
    if (rerun)
        budget /= 2;
    long reach = budget > 0 ? (long)((double)(budget - settle) / (double)nc * (double)px) - 1 : 2 * px;
    if (budget > 0 && reach < 2) {
        /* a scan of a line or two: the fifth does not reach past the companion's
         * settling, and the whole line runs (e->cycles says what it cost) */
        budget = 0;
        reach = 2 * px;
    }
    double step = 0;
    long first = 0;
    long line = S->lines_done > 0 ? hardest_line(S, reach, &step, &first) : S->profile_line;
    /* the stretch's first cycle: the first whole cycle of its first pixel */
    const long k0 = (first * nc + px - 1) / px;
    int rc[2] = {TT_OK, TT_OK}, hit[2] = {0, 0};
    long ran[2] = {0, 0};
    char why[2][512]; /* a worker thread's message is its own: carried back here */
#pragma omp parallel for num_threads(2) schedule(static, 1) if (rerun)
    for (int k = 0; k < 2; k++) {
        if (k == 0 && !rerun) { /* the image's own line */
            for (int c = 0; c < 3; c++)
                for (int r = 0; r < dirs; r++)
                    for (long i = 0; i < px; i++)
                        buf[(size_t)(2 * c + r) * (size_t)px + (size_t)i] =
                            S->img[r][c][tt_raster_index(R, line, i)];
            continue;
        }
        rc[k] = companion_line(S, k ? &tight : &S->solver, line, budget, k0,
                               buf + (size_t)(6 * k * px), &hit[k], &ran[k]);
        snprintf(why[k], sizeof why[k], "%s", rc[k] ? tt_error_message() : "");
    }
    for (int k = 0; k < 2; k++)
        if (rc[k]) {
            free(buf);
            return tt_error(rc[k], "the companion line at tolerance %g: %s",
                            k ? tight.tolerance : S->solver.tolerance, why[k]);
        }
    const int partial = hit[0] || hit[1];
    double max[3] = {0}, sum[3] = {0};
    const double scale[3] = {1, 1 / S->A0, 1};
    long n = 0;
    for (int r = 0; r < (partial ? 1 : dirs); r++)
        for (long i = r ? 0 : first; i < px; i++) {
            /* a line stopped by its budget: the trace's pixels before the one it stopped in */
            if (partial && (i + 1 >= px || isnan(buf[(size_t)(6 * px + 1 + i)]) ||
                            (rerun && isnan(buf[(size_t)(1 + i)]))))
                break;
            for (int c = 0; c < 3; c++) {
                double a = buf[(size_t)((2 * c + r) * px + i)], b = buf[(size_t)((6 + 2 * c + r) * px + i)];
                double d = fabs(a - b) * scale[c];
                if (!(d <= max[c]))
                    max[c] = d; /* a NaN (a pixel without data) stays visible */
                sum[c] += d * d;
            }
            n++;
        }
    free(buf);
    if (n == 0)
        return tt_error(TT_EINVAL, "the companion line compared no pixel");
    /* the difference stands for the run's error to within a tenth; twice it covers that
     * and the other lines, which the companion did not run */
    e->height_max = 2 * max[0];
    e->height_rms = 2 * sqrt(sum[0] / (double)n);
    e->amplitude_max = 2 * max[1];
    e->amplitude_rms = 2 * sqrt(sum[1] / (double)n);
    e->phase_max = 2 * max[2];
    e->phase_rms = 2 * sqrt(sum[2] / (double)n);
    e->line = line;
    e->tolerance = tight.tolerance;
    e->pixels = n;
    e->pixels_line = dirs * px;
    e->step = step;
    e->first = first;
    e->cycles = ran[0] + ran[1];
    e->seconds = tt_clock(TT_CLOCK_PROCESS) - c0;
    return TT_OK;
}

long tt_scan_xres(const tt_scan *S) { return S->raster.fast_y ? S->raster.lines : S->raster.pixels; }
long tt_scan_yres(const tt_scan *S) { return S->raster.fast_y ? S->raster.pixels : S->raster.lines; }
long tt_scan_lines(const tt_scan *S) { return S->raster.lines; }
int tt_scan_fast_y(const tt_scan *S) { return S->raster.fast_y; }
double tt_scan_size_x(const tt_scan *S) { return S->raster.size_x; }
double tt_scan_size_y(const tt_scan *S) { return S->raster.size_y; }
unsigned tt_scan_channels(const tt_scan *S) { return S->channels; }
int tt_scan_has_retrace(const tt_scan *S) { return S->raster.retrace; }
long tt_scan_lines_done(const tt_scan *S) { return S->lines_done; }
long tt_scan_profile_line(const tt_scan *S) { return S->profile_line; }
long tt_scan_cycles(const tt_scan *S) { return S->cycles; }
const tt_solver *tt_scan_solver(const tt_scan *S) { return &S->solver; }
long tt_scan_cycles_integrated(const tt_scan *S) { return S->integrated; }
double tt_scan_averaged_build_seconds(const tt_scan *S) { return S->avg_seconds; }
double tt_scan_averaged_table_error(const tt_scan *S) { return S->avg_error; }
long tt_scan_averaged_outside(const tt_scan *S) { return S->outside; }

long tt_scan_averaged_collapsed(const tt_scan *S, long *line, long *pixel)
{
    if (line)
        *line = S->collapse_line;
    if (pixel)
        *pixel = S->collapse_px;
    return S->collapsed;
}
double tt_scan_error_estimate(const tt_scan *S) { return S->worst_residual; }
int tt_scan_clamped(const tt_scan *S) { return S->clamped; }
const tt_dilation *tt_scan_dilation(const tt_scan *S) { return S->dilation; }
size_t tt_scan_materials(const tt_scan *S) { return S->nmaterials; }
const char *tt_scan_material_name(const tt_scan *S, size_t i) { return S->names[i]; }

int tt_scan_contact_extent(const tt_scan *S, size_t i, tt_contact_extent *e)
{
    e->indentation = S->indent[i] > -INFINITY ? S->indent[i] : NAN;
    e->radius = NAN;
    e->tip_radius = S->contact_R[i];
    if (!(e->indentation > 0))
        return 0;
    tt_contact_load(S->contacts[i], e->indentation, 1, NULL, &e->radius);
    return tt_contact_beyond_validity(e->radius, e->indentation, e->tip_radius);
}

const double *tt_scan_image(const tt_scan *S, int channel, int retrace)
{
    if (channel < 0 || channel >= TT_CH_COUNT || retrace < 0 || retrace > 1)
        return NULL;
    return S->img[retrace][channel];
}

double tt_scan_instrument_time(const tt_scan *S)
{
    return (double)S->raster.lines / S->raster.line_rate;
}
