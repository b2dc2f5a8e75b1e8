/* Closed-loop imaging: the scan made from its parameters, its lines run on the line
 * engine's workers (scan_worker.c) in parallel or one at a time, and its results
 * (see include/tiptap/instrument/scan.h). */
#include "tiptap/instrument/scan.h"
#include "scan_engine.h"

#include <math.h>
#include <stdio.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

/* Every material's force law, built before any line runs. */
static int build_contacts(tt_scan *S, const tt_material *m, size_t n)
{
    S->nmaterials = n;
    S->contacts = calloc(n, sizeof *S->contacts);
    S->Qi = calloc(n, sizeof *S->Qi);
    S->contact_R = calloc(n, sizeof *S->contact_R);
    S->contact_p = calloc(n, sizeof *S->contact_p);
    S->names = calloc(n, sizeof *S->names);
    S->indent = calloc(n, sizeof *S->indent);
    if (!S->contacts || !S->Qi || !S->contact_R || !S->contact_p || !S->names || !S->indent)
        return tt_error_nomem("the force laws of %zu materials", n);
    for (size_t i = 0; i < n; i++) {
        S->Qi[i] = m[i].Qi;
        S->contact_R[i] = m[i].contact.R;
        S->contact_p[i] = m[i].contact;
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
    S->lockin.ratio2 = p->cantilever.A2 > 0 ? p->cantilever.ratio2 : 0.0;
    if ((S->channels & (TT_CH_AMPLITUDE2 | TT_CH_PHASE2)) && !(S->lockin.ratio2 > 0))
        return tt_error(TT_EINVAL, "[scan] channels: amplitude_2 and phase_2 need mode 2 driven "
                                   "([cantilever] mode2_free_amplitude)");
    if (S->lockin.ratio2 > 0 && S->solver.tier != TT_TIER_EVERY)
        return tt_error(TT_EINVAL, "[solver] tier: %s does not serve mode 2's drive (bimodal "
                                   "imaging runs every cycle): set tier = every",
                        tt_tier_name(S->solver.tier));
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
    if (p->local_geometry && S->solver.tier != TT_TIER_EVERY)
        return tt_error(TT_EINVAL, "[tip] contact_geometry: local runs on the every-cycle tier "
                                   "only: expected [solver] tier = every (it is %s)",
                        tt_tier_name(S->solver.tier));
    /* the differences a twentieth of the tip's radius apart: finer than the contact
     * (a Hertz contact 1 nm deep under 10 nm is 3 nm across), and a sphere of r read to
     * about (R / 20 r)^2 (docs/surfaces.md) */
    S->geo_step = 1.0 / 20;
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
    double pitch = fmin(fast, slow), dx = fmax(fmin(pitch, tip->radius) / 4, pitch / 16), b[4];
    S->tip = *tip;
    tt_raster_bounds(R, b); /* a rotated or moved scan visits another box of the sample */
    return tt_dilation_alloc_contacts(&S->dilation, S->surface, tip, b[0] - mx, b[1] - my, b[2] + mx,
                                      b[3] + my, dx, S->local);
}

/* The certainty channel is the surface's, not the run's: filled once, at each pixel's
 * centre, and left alone by the lines. */
static void fill_certainty(tt_scan *S)
{
    const tt_raster *R = &S->raster;
    for (int r = 0; r < 2; r++)
        for (long line = 0; S->img[r][TT_CH_CERTAINTY_INDEX] && line < R->lines; line++)
            for (long px = 0; px < R->pixels; px++) {
                double x, y;
                tt_raster_position(R, line, 0, 2 * R->pixels, 2 * px + 1, &x, &y);
                S->img[r][TT_CH_CERTAINTY_INDEX][tt_raster_index(R, line, px)] =
                    tt_surface_certainty(S->surface, x, y);
            }
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
    S->local = p->local_geometry && !S->flat; /* a flat's geometry is the flat law's */
    if (p->tip.kind != TT_TIP_POINT && !S->flat && (rc = make_dilation(S, &p->tip))) {
        tt_scan_free(S);
        return rc;
    }
    size_t n = (size_t)S->raster.pixels * (size_t)S->raster.lines;
    const unsigned held = S->channels | tt_scan_kept_channels(p);
    for (int r = 0; r < (S->raster.retrace ? 2 : 1); r++)
        for (int c = 0; c < TT_CH_COUNT; c++) {
            if (!(held & (1u << c)))
                continue;
            S->img[r][c] = malloc(n * sizeof(double));
            if (!S->img[r][c]) {
                tt_scan_free(S);
                return tt_error_nomem("the scan's images of %zu pixels", n);
            }
            for (size_t i = 0; i < n; i++)
                S->img[r][c][i] = NAN;
        }
    fill_certainty(S);
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
    free(S->contact_p);
    free(S->names);
    free(S->indent);
    free(S);
}

/* A line's totals into the scan's; 1 when it finished (counted done once). */
static int line_account(tt_scan *S, long line, int rc, const line_tally *t)
{
    S->cycles += t->cycles;
    S->integrated += t->integrated;
    S->work += t->work;
    S->settle_work += t->settle_work;
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
        rc = tt_scan_worker_alloc(S, &W[i], &S->solver);
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
            int lrc = tt_scan_worker_line(S, w, line, NULL, line == S->watch_line ? S->watch : NULL, &t);
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
    for (int i = 0; i < threads; i++) {
        merge_indent(S, &W[i]);
        long tables;
        S->laws_built += tt_scan_geometry_built(&W[i], &tables);
        S->tables_built += tables;
    }
    for (int i = 0; i < threads; i++)
        tt_scan_worker_free(&W[i]);
    free(W);
    return rc;
}

int tt_scan_step_prepare(tt_scan *S)
{
    if (S->step)
        return TT_OK;
    S->step = malloc(sizeof *S->step);
    if (!S->step)
        return tt_error_nomem("the scan's stepping workspace");
    int rc = tt_scan_worker_alloc(S, S->step, &S->solver);
    if (rc) {
        tt_scan_worker_free(S->step);
        free(S->step);
        S->step = NULL;
    }
    return rc;
}

int tt_scan_step(tt_scan *S, long line, tt_scan_scope *scope)
{
    if (line < 0 || line >= S->raster.lines)
        return tt_error(TT_EINVAL, "line %ld: the scan's lines are 0 to %ld", line, S->raster.lines - 1);
    int rc = tt_scan_step_prepare(S);
    if (rc)
        return rc;
    line_tally t;
    rc = tt_scan_worker_line(S, S->step, line, NULL, scope, &t);
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
const tt_cantilever *tt_scan_cantilever(const tt_scan *S) { return &S->cantilever; }
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
void tt_scan_averaged_marks_clear(tt_scan *S)
{
    S->collapsed = S->outside = 0;
    S->collapse_line = S->collapse_px = -1;
}
double tt_scan_error_estimate(const tt_scan *S) { return S->worst_residual; }
long tt_scan_contact_laws_built(const tt_scan *S, long *tables)
{
    long t = 0, n = S->step ? tt_scan_geometry_built(S->step, &t) : 0;
    if (tables)
        *tables = S->tables_built + t;
    return S->laws_built + n;
}
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
    if (channel < 0 || channel >= TT_CH_COUNT || retrace < 0 || retrace > 1 ||
        !(S->channels & (1u << channel)))
        return NULL; /* one kept for the estimate alone (tt_scan_kept_channels) too */
    return S->img[retrace][channel];
}

unsigned tt_scan_kept_channels(const tt_scan_params *p)
{
    const double pixels = (double)p->raster.pixels * (double)p->raster.lines;
    return pixels <= TT_SCAN_KEPT_PIXELS ? (TT_CH_HEIGHT | TT_CH_ERROR | TT_CH_PHASE) & ~p->channels : 0;
}

double tt_scan_instrument_time(const tt_scan *S)
{
    return (double)S->raster.lines / S->raster.line_rate;
}
