/* The work-precision study of the solvers (see include/tiptap/instrument/accuracy.h). */
#include "tiptap/instrument/accuracy.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scanner.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/solver_scene.h"

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* Half decades: the step between neighbours is small enough that "ten times more
 * accurate" lands near a measured setting. */
static const double dopri5_tolerances[] = {1e-4, 3e-5, 1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8,
                                           1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 3e-11, 1e-11};
static const double rk4_steps[] = {32, 64, 128, 256, 512, 1024, 2048};

/* One row per method: a new method joins the study here. */
static const tt_accuracy_ladder ladders[] = {
    {TT_METHOD_DOPRI5, "tolerance", dopri5_tolerances, COUNT(dopri5_tolerances)},
    {TT_METHOD_RK4, "steps_per_cycle", rk4_steps, COUNT(rk4_steps)},
    {TT_METHOD_RADAU, "tolerance", dopri5_tolerances, COUNT(dopri5_tolerances)},
};

const tt_accuracy_ladder *tt_accuracy_ladders(size_t *count)
{
    *count = COUNT(ladders);
    return ladders;
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
    double *profile;   /* line: heights, trace then retrace */
    double seconds, cpu_seconds, steps_per_cycle, residual_rel;
} run_result;

struct tt_accuracy {
    tt_scene *scene;   /* the study's own copy; [solver] keys change per run */
    tt_accuracy_kind kind;
    tt_accuracy_params p;
    tt_setup *setup;   /* point: cantilever and force law, built once */
    size_t material;
    int has_contact;
    double z;          /* point: rest separation */
    long cycles;
    double A0;
    size_t nprofile;   /* line: values per profile */
    tt_accuracy_row *rows;
    size_t nrows, next;
    int pass;          /* 1: every row computed; 2..repeats: cheap rows timed again */
    run_result ref;
    int ref_done;
};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* CPU time of the process: unlike the wall clock, barely changed by other programs
 * sharing the cores (the runs are single-threaded). */
static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Put a setting into the study's scene: the knob is a [solver] key like any other, so
 * a method needs no code here beyond its ladder row. */
static int apply_setting(tt_scene *s, tt_method m, const char *knob, double value)
{
    char buf[128];
    int rc;
    snprintf(buf, sizeof buf, "solver.method=%s", tt_method_name(m));
    if ((rc = tt_scene_set(s, buf)))
        return rc;
    snprintf(buf, sizeof buf, "solver.%s=%.17g", knob, value);
    return tt_scene_set(s, buf);
}

/* A formatted "section.key=value" through the scene, so that it is validated as a
 * user's --set would be. */
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static int set_key(tt_scene *s, const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    return tt_scene_set(s, buf);
}

static int add_row(tt_accuracy *A, tt_accuracy_role role, tt_method m, const char *knob,
                   double value, int is_default)
{
    tt_accuracy_row *r = realloc(A->rows, (A->nrows + 1) * sizeof *r);
    if (!r)
        return tt_error(TT_ENOMEM, "out of memory");
    A->rows = r;
    r = &A->rows[A->nrows++];
    memset(r, 0, sizeof *r);
    r->role = role;
    r->method = m;
    r->knob = knob;
    r->value = value;
    r->is_default = is_default;
    r->run_time = r->cpu_time = r->steps_per_cycle = r->residual_rel = r->primary = NAN;
    for (int i = 0; i < TT_ACCURACY_MAX_OBS; i++)
        r->err[i] = NAN;
    return TT_OK;
}

/* The scene's own setting: its method and the value of that method's knob. */
static int scene_setting(const tt_scene *s, const tt_accuracy_ladder *lad, size_t nlad,
                         tt_method *m, const char **knob, double *value)
{
    tt_solver sv;
    int rc = tt_solver_from_scene(&sv, s);
    if (rc)
        return rc;
    *m = sv.method;
    *knob = NULL;
    size_t n;
    const tt_accuracy_ladder *all = tt_accuracy_ladders(&n);
    for (size_t i = 0; i < nlad && !*knob; i++)
        if (lad[i].method == sv.method)
            *knob = lad[i].knob;
    for (size_t i = 0; i < n && !*knob; i++)
        if (all[i].method == sv.method)
            *knob = all[i].knob;
    if (!*knob)
        return tt_error(TT_EINVAL, "the accuracy study has no ladder for method %s",
                        tt_method_name(sv.method));
    return tt_scene_get_double(s, "solver", NULL, *knob, value);
}

/* Rows: reference, floor, then the ladders, with the scene's setting marked on its
 * ladder, or put where it falls between two values when it is not one of them. */
static int plan(tt_accuracy *A)
{
    const tt_accuracy_ladder *lad = A->p.ladders;
    size_t nlad = A->p.nladders;
    if (!lad)
        lad = tt_accuracy_ladders(&nlad);
    tt_method dm;
    const char *dknob;
    double dval;
    int rc;
    if ((rc = scene_setting(A->scene, lad, nlad, &dm, &dknob, &dval)) ||
        (rc = add_row(A, TT_ACCURACY_REFERENCE, TT_METHOD_DOPRI5, "tolerance", A->p.ref_tolerance, 0)) ||
        (rc = add_row(A, TT_ACCURACY_FLOOR, TT_METHOD_DOPRI5, "tolerance", A->p.check_tolerance, 0)))
        return rc;
    int placed = 0;
    for (size_t l = 0; l < nlad; l++) {
        const tt_accuracy_ladder *L = &lad[l];
        const double *v = L->values;
        size_t n = L->nvalues, pos = n + 1; /* n + 1: the default is not added here */
        if (L->method == dm && strcmp(L->knob, dknob) == 0 && !placed) {
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
                if ((rc = add_row(A, TT_ACCURACY_SETTING, dm, dknob, dval, 1)))
                    return rc;
                placed = 1;
            }
            if (i == n)
                break;
            int is_def = !placed && L->method == dm && strcmp(L->knob, dknob) == 0 && v[i] == dval;
            if ((rc = add_row(A, TT_ACCURACY_SETTING, L->method, L->knob, v[i], is_def)))
                return rc;
            placed |= is_def;
        }
    }
    /* a method left out of the ladders still has its own setting judged */
    if (!placed && (rc = add_row(A, TT_ACCURACY_SETTING, dm, dknob, dval, 1)))
        return rc;
    return TT_OK;
}

/* The line segment: the scene's first pixels of its middle line, with its pixel size
 * and its time per pixel, so that a pixel sees what it would see in the full scan. */
static int make_segment(tt_accuracy *A)
{
    tt_raster r;
    int rc;
    if ((rc = tt_raster_from_scene(&r, A->scene)))
        return rc;
    long P = A->p.line_pixels;
    if (P < 2)
        return tt_error(TT_EINVAL, "a scan line needs at least 2 pixels (got %ld)", P);
    double frac = (double)P / (double)r.pixels;
    double rate = r.line_rate / frac;
    if ((rc = set_key(A->scene, "scan.pixels=%ld", P)) || (rc = set_key(A->scene, "scan.lines=1")) ||
        (rc = set_key(A->scene, "scan.profile_line=-1")) ||
        (rc = set_key(A->scene, "scan.channels=height")) ||
        (rc = set_key(A->scene, "scan.line_rate=%.17g Hz", rate)))
        return rc;
    if (r.fast_y)
        rc = set_key(A->scene, "scan.size_y=%.17g m", r.size_y * frac);
    else
        rc = set_key(A->scene, "scan.size=%.17g m", r.size_x * frac);
    if (!rc)
        rc = set_key(A->scene, r.fast_y ? "scan.size=%.17g m" : "scan.size_y=%.17g m",
                     r.fast_y ? r.size_x : r.size_y);
    A->nprofile = (size_t)P * (r.retrace ? 2 : 1);
    return rc;
}

int tt_accuracy_alloc(tt_accuracy **out, const tt_scene *scene, const tt_accuracy_params *p)
{
    *out = NULL;
    tt_accuracy *A = calloc(1, sizeof *A);
    if (!A)
        return tt_error(TT_ENOMEM, "out of memory");
    A->p = *p;
    int rc = TT_OK;
    A->scene = tt_scene_copy(scene);
    if (!A->scene) {
        rc = tt_error(TT_ENOMEM, "out of memory");
        goto fail;
    }
    if (!(A->p.repeats >= 1))
        A->p.repeats = 1;
    if (!(A->p.ref_tolerance > 0 && A->p.check_tolerance > A->p.ref_tolerance)) {
        rc = tt_error(TT_EINVAL, "the check reference's tolerance must be looser than the reference's");
        goto fail;
    }
    A->kind = p->kind;
    if (A->kind == TT_ACCURACY_AUTO)
        A->kind = (!isfinite(p->point) && tt_scene_has_section(scene, "scan", NULL)) ? TT_ACCURACY_LINE
                                                                                    : TT_ACCURACY_POINT;
    tt_cantilever c;
    if ((rc = tt_cantilever_from_scene(&c, A->scene)))
        goto fail;
    A->A0 = c.A0;
    if (A->kind == TT_ACCURACY_LINE) {
        if ((rc = make_segment(A)))
            goto fail;
    } else {
        A->cycles = p->cycles > 0 ? p->cycles : (long)ceil(c.Q * log(1e8) / M_PI);
        if (A->cycles < 10)
            A->cycles = 10;
        A->z = p->point;
        if (!isfinite(A->z)) {
            long npts = 0;
            if (tt_scene_has_section(scene, "approach", NULL) &&
                (rc = tt_scene_get_int(A->scene, "approach", NULL, "points", &npts)))
                goto fail;
            if (npts == 1) {
                if ((rc = tt_scene_get_double(A->scene, "approach", NULL, "from", &A->z)))
                    goto fail;
            } else {
                A->z = 0.8 * c.A0;
            }
        }
        if ((rc = tt_setup_alloc(&A->setup, A->scene)))
            goto fail;
        A->has_contact = A->setup->nmaterials > 0;
        if (A->has_contact &&
            ((rc = tt_setup_find_material(A->setup,
                                          tt_scene_get_string(A->scene, "approach", NULL, "material"),
                                          "approach", "material", &A->material)) ||
             (rc = tt_setup_use_material(A->setup, A->material))))
            goto fail;
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
    tt_setup_free(A->setup);
    tt_scene_free(A->scene);
    free(A->ref.profile);
    free(A->rows);
    free(A);
}

/* Point: the free steady state at the separation, then the same cycles for every
 * setting; only the integration is timed. */
static int run_point(tt_accuracy *A, run_result *res)
{
    tt_solver sv;
    tt_sim *sim = NULL;
    int rc;
    if ((rc = tt_solver_from_scene(&sv, A->scene)) ||
        (rc = tt_sim_alloc(&sim, &A->setup->cantilever, &sv)))
        return rc;
    if (A->has_contact)
        tt_sim_set_contact(sim, A->setup->contacts[A->material], A->setup->Qi[A->material]);
    tt_sim_set_sample(sim, A->z, 0);
    tt_sim_reset_free(sim);
    long steps = 0;
    double worst = 0, amp = NAN;
    tt_cycle cy;
    memset(&cy, 0, sizeof cy);
    double t0 = now(), c0 = cpu_now();
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
    res->seconds = now() - t0;
    res->cpu_seconds = cpu_now() - c0;
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
    int rc = tt_scan_alloc(&scan, A->scene);
    if (rc)
        return rc;
    double t0 = now(), c0 = cpu_now();
    rc = tt_scan_run(scan, 1, NULL, NULL);
    res->seconds = now() - t0;
    res->cpu_seconds = cpu_now() - c0;
    if (!rc) {
        free(res->profile);
        res->profile = malloc(A->nprofile * sizeof *res->profile);
        if (!res->profile)
            rc = tt_error(TT_ENOMEM, "out of memory");
    }
    if (!rc) {
        size_t P = A->nprofile / (tt_scan_has_retrace(scan) ? 2 : 1);
        for (int r = 0; r < (tt_scan_has_retrace(scan) ? 2 : 1); r++) {
            const double *img = tt_scan_image(scan, 0, r);
            memcpy(res->profile + (size_t)r * P, img, P * sizeof *img);
        }
        res->steps_per_cycle = NAN;
        res->residual_rel = tt_scan_error_estimate(scan);
    }
    tt_scan_free(scan);
    return rc;
}

static int run_setting(tt_accuracy *A, const tt_accuracy_row *row, run_result *res)
{
    int rc = apply_setting(A->scene, row->method, row->knob, row->value);
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
        double mx = 0, ss = 0;
        for (size_t i = 0; i < A->nprofile; i++) {
            double d = fabs(res->profile[i] - A->ref.profile[i]);
            if (!(d <= mx))
                mx = d; /* NaN wins: a failed pixel is no accuracy */
            ss += d * d;
        }
        row->err[0] = mx;
        row->err[1] = sqrt(ss / (double)A->nprofile);
        row->primary = mx / A->A0;
        return;
    }
    const tt_cycle *c = &res->last, *r = &A->ref.last;
    const tt_cantilever *cl = &A->setup->cantilever;
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

/* The loosest setting of method m from which on every tighter one meets the target:
 * a lucky cancellation of errors at one loose setting is no setting to recommend. */
static const tt_accuracy_row *reliable(const tt_accuracy *A, tt_method m, double target)
{
    const tt_accuracy_row *pick = NULL;
    for (size_t i = 0; i < computed(A); i++) {
        const tt_accuracy_row *r = &A->rows[i];
        if (r->role != TT_ACCURACY_SETTING || r->method != m)
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

const tt_accuracy_row *tt_accuracy_cheapest(const tt_accuracy *A, int method, double target)
{
    const tt_accuracy_row *best = NULL;
    for (size_t i = 0; i < computed(A); i++) {
        const tt_accuracy_row *r = &A->rows[i];
        if (r->role != TT_ACCURACY_SETTING || (method >= 0 && (int)r->method != method))
            continue;
        const tt_accuracy_row *c = reliable(A, r->method, target);
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
    *n = A->nprofile;
    return A->ref.profile;
}
