/* The work-precision study of the solvers (see include/tiptap/instrument/accuracy.h). */
#include "tiptap/instrument/accuracy.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/util/clock.h"
#include "tiptap/util/phase.h"

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* Half decades: the step between neighbours is small enough that "ten times more
 * accurate" lands near a measured setting. */
static const double dopri5_tolerances[] = {1e-4, 3e-5, 1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8,
                                           1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11};
static const double averaged_tolerance[] = {1e-8};
static const double rk4_steps[] = {32, 64, 128, 256, 512, 1024, 2048};

/* One row per method and tier: a new method joins the study here. The envelope tier's
 * error control follows the same tolerance (tiptap/solver/envelope.h), so its ladder is
 * dopri5's. */
static const tt_accuracy_ladder ladders[] = {
    {TT_METHOD_DOPRI5, "tolerance", dopri5_tolerances, COUNT(dopri5_tolerances), TT_TIER_EVERY, NULL},
    {TT_METHOD_DOPRI5, "tolerance", dopri5_tolerances, COUNT(dopri5_tolerances), TT_TIER_ENVELOPE,
     "envelope"},
    {TT_METHOD_RK4, "steps_per_cycle", rk4_steps, COUNT(rk4_steps), TT_TIER_EVERY, NULL},
    {TT_METHOD_RADAU, "tolerance", dopri5_tolerances, COUNT(dopri5_tolerances), TT_TIER_EVERY, NULL},
    /* the averaged tier has no knob: one row, its model's error on the line */
    {TT_METHOD_DOPRI5, "tolerance", averaged_tolerance, 1, TT_TIER_AVERAGED, "averaged"},
};

const tt_accuracy_ladder *tt_accuracy_ladders(size_t *count)
{
    *count = COUNT(ladders);
    return ladders;
}

const char *tt_accuracy_ladder_name(const tt_accuracy_ladder *l)
{
    return l->name ? l->name : tt_method_name(l->method);
}

static const tt_accuracy_observable point_obs[] = {
    {"amplitude_err_rel", "amplitude error (relative)"},
    {"phase_err_deg", "phase error (deg)"},
    {"mean_err_m", "mean deflection error (m)"},
    {"peak_force_err_rel", "peak force error (relative)"},
    {"dissipation_err_rel", "dissipation error (relative)"},
};
static const tt_accuracy_observable line_obs[] = {
    {"height_err_max_m", "largest height error (m)"},
    {"height_err_rms_m", "RMS height error (m)"},
    {"phase_err_max_deg", "largest phase error (deg)"},
    {"phase_err_rms_deg", "RMS phase error (deg)"},
};

void tt_accuracy_params_default(tt_accuracy_params *p)
{
    memset(p, 0, sizeof *p);
    p->kind = TT_ACCURACY_AUTO;
    p->point = NAN;
    p->cycles = 0;
    p->line_pixels = 8;
    p->repeats = 3;
    p->repeat_below = 0.5;
    p->ref_tolerance = 1e-13;
    p->check_tolerance = 1e-12;
    p->ladders = NULL;
    p->nladders = 0;
}

/* What one run produced. */
typedef struct {
    tt_cycle last;     /* point: the last cycle */
    double prev_amp;   /* point: the amplitude of the cycle before */
    double *profile;   /* line: heights (m), then phases (deg), trace then retrace */
    double seconds, cpu_seconds, steps_per_cycle, residual_rel, integrated;
} run_result;

struct tt_accuracy {
    tt_accuracy_kind kind;
    tt_accuracy_params p;
    tt_cantilever cantilever;
    tt_solver solver;      /* the setting of the run under way (the default's at first) */
    tt_contact *contact;   /* point: the force law, built once */
    double Qi;
    tt_scan_params scan;   /* line: the segment; its own copy of the materials */
    tt_material *materials;
    double z;          /* point: rest separation */
    long cycles;
    double A0;
    size_t nprofile;   /* line: values per channel's profile (trace and retrace) */
    tt_accuracy_row *rows;
    size_t nrows, next;
    int pass;          /* 1: every row computed; 2..repeats: cheap rows timed again */
    run_result ref;
    int ref_done;
};

/* A solver's accuracy knob by the name of its [solver] key: a method joins the study
 * with its ladder row and, for a new knob, a row here. */
static int set_knob(tt_solver *sv, const char *knob, double value)
{
    if (strcmp(knob, "tolerance") == 0)
        sv->tolerance = value;
    else if (strcmp(knob, "steps_per_cycle") == 0)
        sv->steps_per_cycle = (int)value;
    else
        return tt_error(TT_EINVAL, "the accuracy study knows no solver knob '%s'", knob);
    return TT_OK;
}

static double get_knob(const tt_solver *sv, const char *knob)
{
    return strcmp(knob, "steps_per_cycle") == 0 ? (double)sv->steps_per_cycle : sv->tolerance;
}

/* What a row runs: its ladder's method, tier, knob and name. */
typedef struct {
    tt_method method;
    tt_tier tier;
    const char *knob, *name;
} row_kind;

static row_kind kind_of(const tt_accuracy_ladder *l)
{
    row_kind k = {l->method, l->tier, l->knob, tt_accuracy_ladder_name(l)};
    return k;
}

static int same_kind(row_kind a, row_kind b)
{
    return a.method == b.method && a.tier == b.tier && strcmp(a.knob, b.knob) == 0;
}

static int add_row(tt_accuracy *A, tt_accuracy_role role, row_kind k, double value, int is_default)
{
    tt_accuracy_row *r = realloc(A->rows, (A->nrows + 1) * sizeof *r);
    if (!r)
        return tt_error_nomem("the accuracy study's rows");
    A->rows = r;
    r = &A->rows[A->nrows++];
    memset(r, 0, sizeof *r);
    r->role = role;
    r->method = k.method;
    r->tier = k.tier;
    r->knob = k.knob;
    r->name = k.name;
    r->value = value;
    r->is_default = is_default;
    r->run_time = r->cpu_time = r->steps_per_cycle = r->residual_rel = r->primary = NAN;
    r->integrated = NAN;
    for (int i = 0; i < TT_ACCURACY_MAX_OBS; i++)
        r->err[i] = NAN;
    return TT_OK;
}

/* The subject's own setting: its method and tier, the value of that method's knob, and
 * the name of the ladder it belongs on (the envelope tier's, or the method's). */
static int own_setting(const tt_solver *own, tt_tier tier, const tt_accuracy_ladder *lad,
                       size_t nlad, row_kind *k, double *value)
{
    k->method = own->method;
    k->tier = tier;
    k->knob = NULL;
    k->name = tier == TT_TIER_EVERY ? tt_method_name(own->method) : tt_tier_name(tier);
    *value = NAN;
    size_t n;
    const tt_accuracy_ladder *all = tt_accuracy_ladders(&n);
    for (size_t i = 0; i < nlad && !k->knob; i++)
        if (lad[i].method == own->method && lad[i].tier == tier)
            *k = kind_of(&lad[i]);
    for (size_t i = 0; i < n && !k->knob; i++)
        if (all[i].method == own->method)
            k->knob = all[i].knob;
    if (!k->knob)
        return tt_error(TT_EINVAL, "the accuracy study has no ladder for method %s",
                        tt_method_name(own->method));
    *value = get_knob(own, k->knob);
    return TT_OK;
}

/* Rows: reference, floor, then the ladders, with the subject's setting marked on its
 * ladder, or put where it falls between two values when it is not one of them. */
static int plan(tt_accuracy *A)
{
    const tt_accuracy_ladder *lad = A->p.ladders;
    size_t nlad = A->p.nladders;
    if (!lad)
        lad = tt_accuracy_ladders(&nlad);
    int line = A->kind == TT_ACCURACY_LINE;
    /* a point has no tiers: the subject's setting is judged on every cycle there */
    tt_tier tier = line ? A->solver.tier : TT_TIER_EVERY;
    row_kind dk, ref = {TT_METHOD_DOPRI5, TT_TIER_EVERY, "tolerance", "dopri5"};
    double dval;
    int rc, kept = 0;
    if ((rc = own_setting(&A->solver, tier, lad, nlad, &dk, &dval)) ||
        (rc = add_row(A, TT_ACCURACY_REFERENCE, ref, A->p.ref_tolerance, 0)) ||
        (rc = add_row(A, TT_ACCURACY_FLOOR, ref, A->p.check_tolerance, 0)))
        return rc;
    int placed = 0;
    for (size_t l = 0; l < nlad; l++) {
        const tt_accuracy_ladder *L = &lad[l];
        if (L->tier != TT_TIER_EVERY && !line)
            continue;
        kept++;
        const double *v = L->values;
        size_t n = L->nvalues, pos = n + 1; /* n + 1: the default is not added here */
        if (same_kind(kind_of(L), dk) && !placed) {
            pos = n;
            for (size_t i = 0; i < n; i++)
                if (v[i] == dval)
                    pos = n + 1;
            for (size_t i = 1; i < n && pos == n; i++)
                if ((dval - v[i - 1]) * (dval - v[i]) < 0)
                    pos = i;
            if (pos == n && n >= 2 && (dval - v[0]) * (v[1] - v[0]) < 0)
                pos = 0;
        }
        for (size_t i = 0; i <= n; i++) {
            if (i == pos) {
                if ((rc = add_row(A, TT_ACCURACY_SETTING, dk, dval, 1)))
                    return rc;
                placed = 1;
            }
            if (i == n)
                break;
            int is_def = !placed && same_kind(kind_of(L), dk) && v[i] == dval;
            if ((rc = add_row(A, TT_ACCURACY_SETTING, kind_of(L), v[i], is_def)))
                return rc;
            placed |= is_def;
        }
    }
    if (!kept)
        return tt_error(TT_EINVAL, "the ladders chosen are of the envelope or averaged tier, which a steady "
                                   "point does not have (it is judged on scan lines)");
    /* a method left out of the ladders still has its own setting judged */
    if (!placed && (rc = add_row(A, TT_ACCURACY_SETTING, dk, dval, 1)))
        return rc;
    return TT_OK;
}

/* The line segment: the scan's first pixels of its middle line, with its pixel size
 * and its time per pixel, so that a pixel sees what it would see in the full scan. */
static int make_segment(tt_accuracy *A, const tt_scan_params *scan)
{
    tt_raster r = scan->raster;
    long P = A->p.line_pixels;
    if (P < 2)
        return tt_error(TT_EINVAL, "a scan line needs at least 2 pixels (got %ld)", P);
    A->materials = malloc(scan->nmaterials * sizeof *A->materials);
    if (!A->materials)
        return tt_error_nomem("the accuracy study's %zu materials", scan->nmaterials);
    memcpy(A->materials, scan->materials, scan->nmaterials * sizeof *A->materials);
    A->scan = *scan;
    A->scan.materials = A->materials;
    double frac = (double)P / (double)r.pixels;
    A->scan.raster.pixels = P;
    A->scan.raster.lines = 1;
    A->scan.raster.line_rate = r.line_rate / frac;
    if (r.fast_y)
        A->scan.raster.size_y = r.size_y * frac;
    else
        A->scan.raster.size_x = r.size_x * frac;
    A->scan.profile_line = -1;
    A->scan.channels = TT_CH_HEIGHT | TT_CH_PHASE;
    A->nprofile = (size_t)P * (r.retrace ? 2 : 1);
    return TT_OK;
}

int tt_accuracy_alloc(tt_accuracy **out, const tt_accuracy_subject *subject,
                      const tt_accuracy_params *p)
{
    *out = NULL;
    tt_accuracy *A = calloc(1, sizeof *A);
    if (!A)
        return tt_error_nomem("the accuracy study");
    A->p = *p;
    A->cantilever = subject->cantilever;
    A->solver = subject->solver;
    int rc = TT_OK;
    if (!(A->p.repeats >= 1))
        A->p.repeats = 1;
    if (!(A->p.ref_tolerance > 0 && A->p.check_tolerance > A->p.ref_tolerance)) {
        rc = tt_error(TT_EINVAL, "the check reference's tolerance must be looser than the reference's");
        goto fail;
    }
    A->kind = p->kind;
    if (A->kind == TT_ACCURACY_AUTO)
        A->kind = (!isfinite(p->point) && subject->has_scan) ? TT_ACCURACY_LINE : TT_ACCURACY_POINT;
    const tt_cantilever *c = &subject->cantilever;
    A->A0 = c->A0;
    if (A->kind == TT_ACCURACY_LINE) {
        if (!subject->has_scan) {
            rc = tt_error(TT_EINVAL, "a scan line study needs a scan");
            goto fail;
        }
        if ((rc = make_segment(A, &subject->scan)))
            goto fail;
    } else {
        A->cycles = p->cycles > 0 ? p->cycles : (long)ceil(c->Q * log(1e8) / M_PI);
        if (A->cycles < 10)
            A->cycles = 10;
        A->z = p->point;
        if (!isfinite(A->z))
            A->z = isfinite(subject->approach_point) ? subject->approach_point : 0.8 * c->A0;
        A->Qi = subject->material.Qi;
        if (tt_contact_alloc(&A->contact, &subject->material.contact)) {
            char why[512];
            snprintf(why, sizeof why, "%s", tt_error_message());
            rc = tt_error(TT_EINVAL, "[material %s]: %s", subject->material.name, why);
            goto fail;
        }
    }
    if ((rc = plan(A)))
        goto fail;
    A->pass = 1;
    *out = A;
    return TT_OK;
fail:
    tt_accuracy_free(A);
    return rc;
}

void tt_accuracy_free(tt_accuracy *A)
{
    if (!A)
        return;
    tt_contact_free(A->contact);
    free(A->materials);
    free(A->ref.profile);
    free(A->rows);
    free(A);
}

/* Point: the free steady state at the separation, then the same cycles for every
 * setting; only the integration is timed. */
static int run_point(tt_accuracy *A, run_result *res)
{
    tt_sim *sim = NULL;
    int rc;
    if ((rc = tt_sim_alloc(&sim, &A->cantilever, &A->solver)))
        return rc;
    tt_sim_set_contact(sim, A->contact, A->Qi);
    tt_sim_set_sample(sim, A->z, 0);
    tt_sim_reset_free(sim);
    long steps = 0;
    double worst = 0, amp = NAN;
    tt_cycle cy;
    memset(&cy, 0, sizeof cy);
    double t0 = tt_clock(TT_CLOCK_WALL), c0 = tt_clock(TT_CLOCK_PROCESS);
    for (long n = 0; n < A->cycles; n++) {
        if ((n & 255) == 0 && tt_cancel_requested()) {
            rc = tt_error(TT_EINTR, "interrupted");
            break;
        }
        res->prev_amp = amp;
        if ((rc = tt_sim_cycle(sim, &cy)))
            break;
        amp = cy.amplitude;
        steps += cy.steps;
        if (cy.residual_rel > worst)
            worst = cy.residual_rel;
    }
    res->seconds = tt_clock(TT_CLOCK_WALL) - t0;
    res->cpu_seconds = tt_clock(TT_CLOCK_PROCESS) - c0;
    tt_sim_free(sim);
    if (rc)
        return rc;
    res->last = cy;
    res->steps_per_cycle = (double)steps / (double)A->cycles;
    res->residual_rel = worst;
    return TT_OK;
}

/* Line: the segment scanned on one thread; surface generation is not timed. */
static int run_line(tt_accuracy *A, run_result *res)
{
    tt_scan *scan = NULL;
    A->scan.solver = A->solver;
    int rc = tt_scan_alloc(&scan, &A->scan);
    if (rc)
        return rc;
    double t0 = tt_clock(TT_CLOCK_WALL), c0 = tt_clock(TT_CLOCK_PROCESS);
    rc = tt_scan_run(scan, 1, NULL, NULL);
    res->seconds = tt_clock(TT_CLOCK_WALL) - t0;
    res->cpu_seconds = tt_clock(TT_CLOCK_PROCESS) - c0;
    if (!rc) {
        free(res->profile);
        res->profile = malloc(2 * A->nprofile * sizeof *res->profile);
        if (!res->profile)
            rc = tt_error_nomem("the accuracy study's profile of %zu pixels", 2 * A->nprofile);
    }
    if (!rc) {
        /* height then phase, each trace then retrace (channel indices: the bit's place) */
        int dirs = tt_scan_has_retrace(scan) ? 2 : 1, ch[2] = {0, 2};
        size_t P = A->nprofile / (size_t)dirs;
        for (int c = 0; c < 2; c++)
            for (int r = 0; r < dirs; r++) {
                const double *img = tt_scan_image(scan, ch[c], r);
                memcpy(res->profile + (size_t)c * A->nprofile + (size_t)r * P, img, P * sizeof *img);
            }
        res->steps_per_cycle = NAN;
        res->residual_rel = tt_scan_error_estimate(scan);
        res->integrated = (double)tt_scan_cycles_integrated(scan) / (double)tt_scan_cycles(scan);
    }
    tt_scan_free(scan);
    return rc;
}

static int run_setting(tt_accuracy *A, const tt_accuracy_row *row, run_result *res)
{
    A->solver.method = row->method;
    A->solver.tier = row->tier;
    int rc = set_knob(&A->solver, row->knob, row->value);
    if (rc)
        return rc;
    return A->kind == TT_ACCURACY_LINE ? run_line(A, res) : run_point(A, res);
}

/* |a - b| relative to |ref|, or to scale when ref is zero. */
static double rel(double a, double b, double ref, double scale)
{
    double d = fabs(a - b);
    return d / (fabs(ref) > 0 ? fabs(ref) : scale);
}

static void compare(tt_accuracy *A, tt_accuracy_row *row, const run_result *res)
{
    if (A->kind == TT_ACCURACY_LINE) {
        for (int c = 0; c < 2; c++) {
            const double *a = res->profile + (size_t)c * A->nprofile;
            const double *b = A->ref.profile + (size_t)c * A->nprofile;
            double mx = 0, ss = 0;
            for (size_t i = 0; i < A->nprofile; i++) {
                /* phases wrap: a lag of 359.9 deg is 0.1 deg from one of 0 */
                double d = c ? tt_phase_diff_deg(a[i], b[i]) : fabs(a[i] - b[i]);
                if (!(d <= mx))
                    mx = d; /* NaN wins: a failed pixel is no accuracy */
                ss += d * d;
            }
            row->err[c ? TT_ACCURACY_PHASE_MAX : TT_ACCURACY_HEIGHT_MAX] = mx;
            row->err[c ? TT_ACCURACY_PHASE_RMS : TT_ACCURACY_HEIGHT_RMS] = sqrt(ss / (double)A->nprofile);
        }
        row->primary = row->err[TT_ACCURACY_HEIGHT_MAX] / A->A0;
        return;
    }
    const tt_cycle *c = &res->last, *r = &A->ref.last;
    const tt_cantilever *cl = &A->cantilever;
    double dphi = remainder(c->phase - r->phase, 2 * M_PI);
    row->err[0] = rel(c->amplitude, r->amplitude, r->amplitude, A->A0);
    row->err[1] = fabs(dphi) * 180 / M_PI;
    row->err[2] = fabs(c->mean - r->mean);
    /* no force at all (a free cantilever): relative to the force of the free deflection */
    row->err[3] = rel(c->peak_force, r->peak_force, r->peak_force, cl->k * A->A0);
    /* no tip-sample loss at all (a conservative force): relative to the free loss */
    row->err[4] = rel(c->e_ts, r->e_ts, r->e_ts, M_PI * cl->c * cl->wd * A->A0 * A->A0);
    row->primary = row->err[0];
}

int tt_accuracy_done(const tt_accuracy *A) { return A->next >= A->nrows; }

int tt_accuracy_pass(const tt_accuracy *A) { return A->pass; }

/* Move to the next unit of work: the next row in the first pass; in the later timing
 * passes, the next finished row cheap enough to be timed again. */
static void advance(tt_accuracy *A)
{
    A->next++;
    for (;;) {
        if (A->next >= A->nrows) {
            if (A->pass >= A->p.repeats)
                return;
            A->pass++;
            A->next = 0;
            continue;
        }
        const tt_accuracy_row *r = &A->rows[A->next];
        if (A->pass == 1 || (r->status == TT_OK && r->run_time < A->p.repeat_below))
            return;
        A->next++;
    }
}

/* A later pass: the same run again, for its time only (its numbers do not change). */
static int retime(tt_accuracy *A, tt_accuracy_row *row)
{
    run_result res = {0};
    int rc = run_setting(A, row, &res);
    free(res.profile);
    if (rc == TT_EINTR)
        return rc;
    if (rc)
        return tt_error(rc, "%s %s %g failed when timed again: %s", tt_method_name(row->method),
                        row->knob, row->value, tt_error_message());
    row->run_time = fmin(row->run_time, res.seconds);
    row->cpu_time = fmin(row->cpu_time, res.cpu_seconds);
    row->runs++;
    advance(A);
    return TT_OK;
}

int tt_accuracy_iterate(tt_accuracy *A, const tt_accuracy_row **out)
{
    if (tt_accuracy_done(A))
        return tt_error(TT_EINVAL, "the accuracy study is complete");
    tt_accuracy_row *row = &A->rows[A->next];
    *out = row;
    if (A->pass > 1)
        return retime(A, row);
    run_result res = {0};
    int rc = run_setting(A, row, &res);
    if (rc == TT_EINTR || (rc && row->role == TT_ACCURACY_REFERENCE)) {
        free(res.profile);
        if (rc != TT_EINTR)
            rc = tt_error(rc, "the reference run (dopri5, tolerance %g) failed: %s", row->value,
                          tt_error_message());
        return rc;
    }
    if (rc) {
        row->status = rc;
        snprintf(row->message, sizeof row->message, "%s", tt_error_message());
        free(res.profile);
        tt_error_clear();
        advance(A);
        return TT_OK;
    }
    row->run_time = res.seconds;
    row->cpu_time = res.cpu_seconds;
    row->runs = 1;
    row->steps_per_cycle = res.steps_per_cycle;
    row->residual_rel = res.residual_rel;
    row->integrated = A->kind == TT_ACCURACY_LINE ? res.integrated : NAN;
    if (row->role == TT_ACCURACY_REFERENCE) {
        A->ref = res;
        A->ref_done = 1;
    }
    compare(A, row, &res);
    if (row->role != TT_ACCURACY_REFERENCE)
        free(res.profile);
    advance(A);
    return TT_OK;
}

tt_accuracy_kind tt_accuracy_kind_of(const tt_accuracy *A) { return A->kind; }

size_t tt_accuracy_observables(const tt_accuracy *A, const tt_accuracy_observable **obs)
{
    if (A->kind == TT_ACCURACY_LINE) {
        *obs = line_obs;
        return COUNT(line_obs);
    }
    *obs = point_obs;
    return COUNT(point_obs);
}

size_t tt_accuracy_rows(const tt_accuracy *A) { return A->nrows; }

const tt_accuracy_row *tt_accuracy_row_at(const tt_accuracy *A, size_t i)
{
    return i < A->nrows ? &A->rows[i] : NULL;
}

/* Rows with their numbers: all of them after the first pass. */
static size_t computed(const tt_accuracy *A) { return A->pass > 1 ? A->nrows : A->next; }

/* The loosest setting of a ladder from which on every tighter one meets the target:
 * a lucky cancellation of errors at one loose setting is no setting to recommend. */
static const tt_accuracy_row *reliable(const tt_accuracy *A, const char *name, double target)
{
    const tt_accuracy_row *pick = NULL;
    for (size_t i = 0; i < computed(A); i++) {
        const tt_accuracy_row *r = &A->rows[i];
        if (r->role != TT_ACCURACY_SETTING || strcmp(r->name, name) != 0)
            continue;
        if (r->status == TT_OK && r->primary <= target) {
            if (!pick)
                pick = r;
        } else {
            pick = NULL;
        }
    }
    return pick;
}

static double cost(const tt_accuracy *A, const tt_accuracy_row *r)
{
    return A->p.cpu_clock ? r->cpu_time : r->run_time;
}

const tt_accuracy_row *tt_accuracy_cheapest(const tt_accuracy *A, const char *name, double target)
{
    const tt_accuracy_row *best = NULL;
    for (size_t i = 0; i < computed(A); i++) {
        const tt_accuracy_row *r = &A->rows[i];
        if (r->role != TT_ACCURACY_SETTING || (name && strcmp(r->name, name) != 0))
            continue;
        const tt_accuracy_row *c = reliable(A, r->name, target);
        if (c && (!best || cost(A, c) < cost(A, best)))
            best = c;
    }
    return best;
}

const tt_accuracy_row *tt_accuracy_default_row(const tt_accuracy *A)
{
    for (size_t i = 0; i < A->nrows; i++)
        if (A->rows[i].is_default)
            return &A->rows[i];
    return NULL;
}

double tt_accuracy_point(const tt_accuracy *A) { return A->kind == TT_ACCURACY_POINT ? A->z : NAN; }
long tt_accuracy_cycles(const tt_accuracy *A) { return A->cycles; }
long tt_accuracy_line_pixels(const tt_accuracy *A)
{
    return A->kind == TT_ACCURACY_LINE ? A->p.line_pixels : 0;
}
double tt_accuracy_free_amplitude(const tt_accuracy *A) { return A->A0; }

const tt_cycle *tt_accuracy_reference_cycle(const tt_accuracy *A)
{
    return (A->ref_done && A->kind == TT_ACCURACY_POINT) ? &A->ref.last : NULL;
}

double tt_accuracy_reference_drift(const tt_accuracy *A)
{
    if (!A->ref_done || A->kind != TT_ACCURACY_POINT)
        return NAN;
    return fabs(A->ref.last.amplitude - A->ref.prev_amp) / A->A0;
}

const double *tt_accuracy_reference_profile(const tt_accuracy *A, size_t *n)
{
    if (!A->ref_done || A->kind != TT_ACCURACY_LINE) {
        *n = 0;
        return NULL;
    }
    *n = 2 * A->nprofile;
    return A->ref.profile;
}

int tt_accuracy_pick(const char *list, tt_accuracy_ladder *out, size_t max, size_t *n)
{
    size_t nall;
    const tt_accuracy_ladder *all = tt_accuracy_ladders(&nall);
    *n = 0;
    char buf[256];
    if (snprintf(buf, sizeof buf, "%s", list) >= (int)sizeof buf)
        return tt_error(TT_EINVAL, "a list of %zu characters, at most %zu", strlen(list), sizeof buf - 1);
    for (char *save = NULL, *tok = strtok_r(buf, ", ", &save); tok; tok = strtok_r(NULL, ", ", &save)) {
        size_t i;
        if (*n == max)
            return tt_error(TT_EINVAL, "more than %zu methods", max);
        for (i = 0; i < nall; i++)
            if (strcmp(tt_accuracy_ladder_name(&all[i]), tok) == 0)
                break;
        if (i == nall) {
            char known[256] = "";
            for (size_t k = 0; k < nall; k++) {
                size_t used = strlen(known);
                snprintf(known + used, sizeof known - used, "%s %s", k ? "," : "",
                         tt_accuracy_ladder_name(&all[k]));
            }
            return tt_error(TT_EINVAL, "unknown method '%s'; known:%s", tok, known);
        }
        out[(*n)++] = all[i];
    }
    return *n ? TT_OK : tt_error(TT_EINVAL, "no method named");
}

const char *tt_accuracy_role_name(tt_accuracy_role r)
{
    return r == TT_ACCURACY_REFERENCE ? "reference" : r == TT_ACCURACY_FLOOR ? "floor" : "setting";
}

const char *tt_accuracy_tier_name(tt_tier t)
{
    return tt_tier_name(t);
}
