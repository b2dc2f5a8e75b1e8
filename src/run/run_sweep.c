/* A sweep's combinations as rows of a table (see include/tiptap/run/sweep.h). */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run_common.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/solver_scene.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/run/sweep.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/util/warning.h"

static const char *const kinds[] = {"steady", "setpoint", "approach", "scan"};

int tt_sweep_kind_parse(const char *name, tt_sweep_kind *kind)
{
    for (int i = 0; i < 4; i++)
        if (strcmp(name, kinds[i]) == 0) {
            *kind = (tt_sweep_kind)i;
            return 0;
        }
    return -1;
}

const char *tt_sweep_kind_name(tt_sweep_kind kind) { return kinds[kind <= TT_SWEEP_SCAN ? kind : 0]; }

enum { Z, AMP, PHASE, MEAN, PEAK, INDENT, FRACTION, DISS, DRIVE, RESIDUAL, REGIME, DIRECTION,
       SETTLED, CYCLES, PERIOD, FOUND, NPOINT, HYST = NPOINT, CI, VISC, NPOINT_VISCOUS };

static const run_column point_columns[NPOINT_VISCOUS] = {
    {"z", "m", 0}, {"amplitude", "m", 0}, {"phase", "deg", 0}, {"mean_deflection", "m", 0},
    {"peak_force", "N", 0}, {"max_indentation", "m", 0}, {"contact_fraction", "", 0},
    {"dissipated", "J", 0}, {"drive_work", "J", 0}, {"energy_residual", "", 0},
    {"regime", "", 1}, {"direction", "", 1}, {"settled", "", 0}, {"cycles", "", 0}, {"period", "", 0},
    {"found", "", 1},
    /* viscous grids only (tt_sweep_viscous): the loss per mechanism */
    {"dissipated_hysteresis", "J", 0}, {"dissipated_damping", "J", 0},
    {"dissipated_viscous", "J", 0},
};
/* bimodal grids (tt_sweep_bimodal): mode 2's lock-in at the point, after the rest */
enum { NPOINT_MODE2 = 2 };
static const run_column point_mode2_columns[NPOINT_MODE2] = {{"amplitude_2", "m", 0}, {"phase_2", "deg", 0}};

enum { FOLDER, LINES, BALANCE, EST_H, EST_P, MATERIAL, PIXELS, HMEAN, HSTD, PMEAN, PSTD, HCONTRAST,
       PCONTRAST, NSCAN, A2MEAN = NSCAN, P2MEAN, P2STD, P2CONTRAST, NSCAN_BIMODAL };

static const run_column scan_columns[NSCAN_BIMODAL] = {
    {"folder", "", 1}, {"lines_done", "", 0}, {"energy_balance", "", 0},
    {"error_estimate_height", "m", 0}, {"error_estimate_phase", "deg", 0}, {"material", "", 1},
    {"pixels", "", 0}, {"height_mean", "m", 0}, {"height_std", "m", 0}, {"phase_mean", "deg", 0},
    {"phase_std", "deg", 0}, {"height_contrast", "m", 0}, {"phase_contrast", "deg", 0},
    /* bimodal grids only (tt_sweep_bimodal): mode 2's lock-in */
    {"amplitude_2_mean", "m", 0}, {"phase_2_mean", "deg", 0}, {"phase_2_std", "deg", 0},
    {"phase_2_contrast", "deg", 0},
};

int tt_run_sweep_columns(const tt_sweep *grid, tt_sweep_kind kind, tt_table **out)
{
    tt_table *t;
    int rc = tt_table_alloc(&t);
    if (!rc)
        rc = tt_table_add(t, "combination", "", 0);
    for (size_t k = 0; k < tt_sweep_keys(grid) && !rc; k++) {
        const char *u = tt_sweep_unit(grid, k);
        rc = tt_table_add(t, tt_sweep_key(grid, k), u, u[0] == '\0');
    }
    if (!rc && kind == TT_SWEEP_SETPOINT)
        rc = tt_table_add(t, "setpoint", "m", 0);
    const run_column *c = kind == TT_SWEEP_SCAN ? scan_columns : point_columns;
    size_t n = kind == TT_SWEEP_SCAN ? (tt_sweep_bimodal(grid) ? NSCAN_BIMODAL : NSCAN)
                                     : tt_sweep_viscous(grid) ? NPOINT_VISCOUS : NPOINT;
    for (size_t i = 0; i < n && !rc; i++)
        rc = tt_table_add(t, c[i].name, c[i].unit, c[i].text);
    for (size_t i = 0; kind != TT_SWEEP_SCAN && tt_sweep_bimodal(grid) && i < NPOINT_MODE2 && !rc; i++)
        rc = tt_table_add(t, point_mode2_columns[i].name, point_mode2_columns[i].unit, 0);
    if (rc) {
        tt_table_free(t);
        t = NULL;
    }
    *out = t;
    return rc;
}

/* A new row with the combination's number and its varied keys; *first: the column
 * after them. */
static int keys_row(tt_table *t, const tt_sweep *g, size_t i, size_t *first)
{
    int rc = tt_table_row(t);
    if (rc)
        return rc;
    tt_table_set(t, 0, (double)(i + 1));
    for (size_t k = 0; k < tt_sweep_keys(g) && !rc; k++) {
        double v = tt_sweep_value(g, i, k);
        if (tt_table_is_text(t, 1 + k))
            rc = tt_table_set_text(t, 1 + k, tt_sweep_text(g, i, k));
        else
            tt_table_set(t, 1 + k, v);
    }
    *first = 1 + tt_sweep_keys(g);
    return rc;
}

/* Free oscillation, or the attractive (phase lag above 90 degrees) or repulsive regime
 * of tapping (Burnham et al.'s two branches of the approach curve). */
static const char *regime(const tt_cycle *c, double A0)
{
    if (c->contact_fraction == 0 && c->max_indentation < 0 && fabs(c->amplitude - A0) < 1e-3 * A0)
        return "free";
    return c->phase > M_PI / 2 ? "attractive" : "repulsive";
}

/* A point's row from column c on; found: the last column when not how the point was
 * found (NULL). A failed point keeps its z, the rest NaN. Mode 2's columns, when the
 * table has them, are its last two. */
static int put_point(tt_table *t, size_t c, const tt_approach_point *p, double A0, int ok,
                     const char *found)
{
    const tt_cycle *y = &p->cycle;
    int rc;
    tt_table_set(t, c + Z, p->z);
    size_t last = tt_table_columns(t);
    if (ok && last >= 2 && strcmp(tt_table_name(t, last - 1), "phase_2") == 0) {
        tt_table_set(t, last - 2, p->amplitude2);
        tt_table_set(t, last - 1, p->phase2 * 180 / M_PI);
    }
    if (!ok) {
        tt_table_set(t, c + SETTLED, 0);
        tt_table_set(t, c + CYCLES, 0);
        tt_table_set(t, c + PERIOD, 0);
        if ((rc = tt_table_set_text(t, c + REGIME, "failed")) || (rc = tt_table_set_text(t, c + DIRECTION, "approach")))
            return rc;
        return tt_table_set_text(t, c + FOUND, "failed");
    }
    const double v[NPOINT] = {p->z, y->amplitude, y->phase * 180 / M_PI, y->mean, y->peak_force,
                              y->max_indentation, y->contact_fraction, y->e_ts, y->e_drive,
                              y->residual_rel, NAN, NAN, p->settled, (double)p->cycles,
                              (double)p->period, NAN};
    for (size_t k = 0; k < NPOINT; k++)
        if (!isnan(v[k]))
            tt_table_set(t, c + k, v[k]);
    if (tt_table_columns(t) >= c + NPOINT_VISCOUS) {
        tt_table_set(t, c + HYST, y->e_hyst);
        tt_table_set(t, c + CI, y->e_ci);
        tt_table_set(t, c + VISC, y->e_visc);
    }
    if ((rc = tt_table_set_text(t, c + REGIME, regime(y, A0))) ||
        (rc = tt_table_set_text(t, c + DIRECTION, p->retract ? "retract" : "approach")))
        return rc;
    if (!found)
        found = p->period == 0                  ? TT_SWEEP_UNSETTLED
                : p->period > 1                 ? TT_SWEEP_PERIODIC
                : p->shot.how == TT_SHOOT_NEWTON ? "newton"
                                                : "settled";
    return tt_table_set_text(t, c + FOUND, found);
}

/* rc with the combination named in front of the message. */
static int name_combination(const tt_sweep *g, size_t i, int rc)
{
    char label[512], msg[1024];
    tt_sweep_label(g, i, label, sizeof label);
    snprintf(msg, sizeof msg, "%s", tt_error_message());
    return tt_error(rc, "combination %zu (%s): %s", i + 1, label, msg);
}

/* One combination made ready: its scene, setup with the [approach] material under the
 * tip, and [approach]. */
typedef struct {
    tt_scene *scene;
    tt_setup *st;
    tt_approach_params p;
} combo;

static void combo_close(combo *c)
{
    tt_setup_free(c->st);
    tt_scene_free(c->scene);
}

static int combo_open(const tt_sweep *g, size_t i, combo *c)
{
    memset(c, 0, sizeof *c);
    int rc;
    if ((rc = tt_sweep_scene(g, i, &c->scene)))
        return rc;
    if ((rc = tt_setup_alloc(&c->st, c->scene)) || (rc = tt_config_approach_setup(c->st, c->scene, &c->p))) {
        combo_close(c);
        return name_combination(g, i, rc);
    }
    return TT_OK;
}

/* The steady oscillation at rest separation z, from a fresh approach of one point. */
static int steady_at(combo *c, double z, tt_approach_point *pt)
{
    tt_approach_params p = c->p;
    p.from = p.to = z;
    p.points = 1;
    p.retract = 0;
    p.mode = TT_APPROACH_STEADY;
    tt_approach *ap = NULL;
    memset(pt, 0, sizeof *pt);
    pt->z = z;
    int rc = tt_approach_alloc(&ap, tt_setup_sim(c->st), &p);
    if (!rc)
        rc = tt_approach_iterate(ap, pt);
    tt_approach_free(ap);
    return rc;
}

/* The rest separation where the steady amplitude equals the setpoint (to 1e-3 of A0,
 * below what an image resolves): secant steps
 * from the guess A(z) = z (the repulsive branch's slope, Burnham et al. fig. 1), kept
 * inside a bracket once one is found (regula falsi, Illinois). *reached: whether it
 * was; when not (an amplitude that never comes down to the setpoint, as at Q = 1, or
 * jumps across it), *pt is the closest point. */
static int setpoint_point(combo *c, double target, tt_approach_point *pt, int *reached)
{
    double A0 = tt_setup_cantilever(c->st)->A0, tol = 1e-3 * A0;
    double zl = NAN, fl = NAN, zh = NAN, fh = NAN, z = target;
    tt_approach_point best = {0};
    double bestf = INFINITY;
    int side = 0;
    for (int it = 0; it < 16; it++) {
        int rc = steady_at(c, z, pt);
        if (rc)
            return rc;
        double f = pt->cycle.amplitude - target;
        if (fabs(f) < fabs(bestf))
            bestf = f, best = *pt;
        if (fabs(f) < tol)
            break;
        if (f < 0)
            zl = z, fl = f;
        else
            zh = z, fh = f;
        if (!isnan(zl) && !isnan(zh)) {
            if (fabs(zh - zl) < 1e-6 * A0)
                break;
            if (side == (f < 0 ? -1 : 1)) {
                if (f < 0)
                    fh /= 2;
                else
                    fl /= 2;
            }
            side = f < 0 ? -1 : 1;
            z = zl - fl * (zh - zl) / (fh - fl);
        } else
            z -= f; /* amplitude rises about one to one with the separation */
    }
    *pt = best;
    *reached = fabs(bestf) < tol;
    return TT_OK;
}

/* A steady or setpoint combination's one row. */
static int one_point(const tt_sweep *g, tt_sweep_kind kind, size_t i, combo *c, tt_table *t)
{
    double A0 = tt_setup_cantilever(c->st)->A0, target = 0;
    tt_approach_point pt;
    tt_feedback_params fp;
    int rc = TT_OK, run, reached = 1;
    if (kind == TT_SWEEP_SETPOINT && !(rc = tt_config_feedback(c->scene, A0, &fp)))
        target = fp.setpoint;
    if (rc)
        return rc;
    run = kind == TT_SWEEP_STEADY ? steady_at(c, c->p.from, &pt) : setpoint_point(c, target, &pt, &reached);
    /* a cancelled point is no failed one: the combination is left for the resume */
    if (run == TT_EINTR)
        return run;
    size_t col;
    if ((rc = keys_row(t, g, i, &col)))
        return rc;
    if (kind == TT_SWEEP_SETPOINT)
        tt_table_set(t, col++, target);
    return put_point(t, col, &pt, A0, run == TT_OK, reached ? NULL : TT_SWEEP_UNREACHABLE);
}

/* An approach combination's rows, one per point, up to a failed one. */
static int curve(const tt_sweep *g, size_t i, combo *c, tt_table *t)
{
    double A0 = tt_setup_cantilever(c->st)->A0;
    tt_approach *ap = NULL;
    int rc = tt_approach_alloc(&ap, tt_setup_sim(c->st), &c->p);
    while (!rc && !tt_approach_done(ap)) {
        tt_approach_point pt;
        size_t col;
        if (tt_cancel_requested()) {
            rc = TT_EINTR;
            break;
        }
        int run = tt_approach_iterate(ap, &pt);
        if (run == TT_EINTR) {
            rc = run;
            break;
        }
        /* a ramp's row is one cycle of the moving sample, found by no search */
        const char *found = c->p.mode == TT_APPROACH_RAMP ? TT_SWEEP_RAMP : NULL;
        if ((rc = keys_row(t, g, i, &col)) || (rc = put_point(t, col, &pt, A0, run == TT_OK, found)))
            break;
        if (run)
            break; /* the branch cannot go on from a failed point */
    }
    tt_approach_free(ap);
    return rc;
}

int tt_run_sweep_points(const tt_sweep *grid, tt_sweep_kind kind, size_t i, tt_table *t)
{
    combo c;
    int rc = combo_open(grid, i, &c);
    if (rc)
        return rc;
    rc = kind == TT_SWEEP_APPROACH ? curve(grid, i, &c, t) : one_point(grid, kind, i, &c, t);
    combo_close(&c);
    return rc;
}

/* Mean and standard deviation of an image over the pixels of material m (m < 0: all). */
static void image_stats(const double *img, const int *mat, size_t n, int m, double *mean, double *sd,
                        size_t *count)
{
    double s = 0, s2 = 0;
    size_t k = 0;
    for (size_t j = 0; j < n; j++)
        if ((m < 0 || mat[j] == m) && isfinite(img[j]))
            s += img[j], k++;
    *mean = k ? s / (double)k : NAN;
    for (size_t j = 0; j < n; j++)
        if ((m < 0 || mat[j] == m) && isfinite(img[j]))
            s2 += (img[j] - *mean) * (img[j] - *mean);
    *sd = k > 1 ? sqrt(s2 / (double)(k - 1)) : NAN;
    *count = k;
}

/* The scan's summary rows: every material (the one the tip touches at each pixel's
 * centre), and its height and phase contrast against the first material. */
int tt_run_sweep_scan_rows(const tt_sweep *grid, size_t i, const tt_scene *scene,
                           const tt_scan *scan, const tt_scan_error *est, tt_table *t)
{
    long xr = tt_scan_xres(scan), yr = tt_scan_yres(scan);
    size_t n = (size_t)(xr * yr);
    const double *h = tt_scan_image(scan, 0, 0), *ph = tt_scan_image(scan, 2, 0);
    const double *a2 = tt_scan_image(scan, TT_CH_AMPLITUDE2_INDEX, 0);
    const double *ph2 = tt_scan_image(scan, TT_CH_PHASE2_INDEX, 0);
    const size_t ncol = tt_sweep_bimodal(grid) ? NSCAN_BIMODAL : NSCAN;
    tt_material *mats = NULL;
    size_t nm = 0;
    tt_surface *surf = NULL;
    int *mat = calloc(n, sizeof *mat);
    char folder[32];
    snprintf(folder, sizeof folder, "%04zu", i + 1);
    int rc = mat ? TT_OK : tt_error(TT_ENOMEM, "out of memory");
    if (!rc && !(rc = tt_config_materials(scene, &mats, &nm)))
        rc = tt_config_surface_alloc(&surf, scene, tt_scan_size_x(scan), tt_scan_size_y(scan));
    const tt_dilation *dil = tt_scan_dilation(scan);
    for (long y = 0; y < yr && !rc; y++)
        for (long x = 0; x < xr; x++) {
            double px = ((double)x + 0.5) * tt_scan_size_x(scan) / (double)xr;
            double py = ((double)y + 0.5) * tt_scan_size_y(scan) / (double)yr;
            if (dil) /* where the tip touches, as the scan read it */
                tt_dilation_contact(dil, px, py, &px, &py);
            mat[y * xr + x] = tt_surface_material(surf, px, py);
        }
    double h0 = NAN, p0 = NAN, q0 = NAN;
    for (int m = -1; m < (int)nm && !rc; m++) {
        double hm, hs, pm = NAN, ps = NAN, am = NAN, as, qm = NAN, qs = NAN;
        size_t cnt, c, c2;
        image_stats(h, mat, n, m, &hm, &hs, &cnt);
        if (ph)
            image_stats(ph, mat, n, m, &pm, &ps, &cnt);
        if (a2)
            image_stats(a2, mat, n, m, &am, &as, &c2);
        if (ph2)
            image_stats(ph2, mat, n, m, &qm, &qs, &c2);
        if (m >= 0 && cnt == 0)
            continue;
        if (m >= 0 && isnan(h0))
            h0 = hm, p0 = pm, q0 = qm;
        if ((rc = keys_row(t, grid, i, &c)) || (rc = tt_table_set_text(t, c + FOLDER, folder)) ||
            (rc = tt_table_set_text(t, c + MATERIAL, m < 0 ? "all" : mats[m].name)))
            break;
        const double v[NSCAN_BIMODAL] = {NAN, (double)tt_scan_lines_done(scan), tt_scan_error_estimate(scan),
                                 est ? est->height_max : NAN, est ? est->phase_max : NAN, NAN,
                                 (double)cnt, hm, hs, pm, ps, m < 0 ? NAN : hm - h0, m < 0 ? NAN : pm - p0,
                                 am, qm, qs, m < 0 ? NAN : qm - q0};
        for (size_t k = 0; k < ncol; k++)
            if (k != FOLDER && k != MATERIAL)
                tt_table_set(t, c + k, v[k]);
    }
    tt_surface_free(surf);
    free(mats);
    free(mat);
    return rc;
}

int tt_run_sweep_check(const tt_sweep *grid, tt_sweep_kind kind, size_t i)
{
    if (kind == TT_SWEEP_SCAN) {
        tt_scene *scene = NULL;
        tt_scan_params p;
        int rc = tt_sweep_scene(grid, i, &scene);
        if (!rc && !(rc = tt_config_scan(scene, &p)))
            tt_config_scan_free(&p);
        if (rc && scene)
            rc = name_combination(grid, i, rc);
        tt_scene_free(scene);
        return rc;
    }
    /* the configuration layer only, which checks every key and rule, without building
     * force tables (a third of a steady point's cost) */
    tt_scene *scene = NULL;
    tt_cantilever cant;
    tt_solver solver;
    tt_material *mats = NULL;
    tt_approach_params ap;
    tt_feedback_params fp;
    size_t nm = 0, mat = 0;
    int rc = tt_sweep_scene(grid, i, &scene);
    if (rc)
        return rc;
    if ((rc = tt_config_cantilever(scene, &cant)) ||
        (rc = tt_solver_from_scene(&solver, scene)) ||
        (rc = tt_config_materials(scene, &mats, &nm)) ||
        (rc = tt_config_material_index(scene, "approach", mats, nm, &mat)) ||
        (rc = tt_config_approach(scene, &ap)) ||
        (kind == TT_SWEEP_SETPOINT && (rc = tt_config_feedback(scene, cant.A0, &fp))))
        rc = name_combination(grid, i, rc);
    free(mats);
    tt_scene_free(scene);
    return rc;
}

/* Combination i of a scan sweep: its scan run on threads threads, its summary rows. */
static int scan_combination(const tt_sweep *g, size_t i, int threads, tt_table *t)
{
    tt_scene *scene = NULL;
    tt_scan *scan = NULL;
    int rc;
    if (!(rc = tt_sweep_scene(g, i, &scene)) && !(rc = tt_config_scan_alloc(&scan, scene)) &&
        !(rc = tt_scan_run(scan, threads, NULL, NULL))) {
        tt_scan_error est; /* the scan's own error estimate, as tiptap scan reports it */
        int erc = tt_scan_estimate_error(scan, &est);
        rc = erc == TT_EINTR ? erc : tt_run_sweep_scan_rows(g, i, scene, scan, erc ? NULL : &est, t);
    }
    tt_scan_free(scan);
    tt_scene_free(scene);
    return rc;
}

/* Each combination into its own table (parts[i]), points on threads threads. */
static int compute_all(const tt_sweep *g, tt_sweep_kind kind, int threads, tt_table **parts,
                       int *finished, tt_progress_fn progress, void *user)
{
    long n = (long)tt_sweep_count(g), done = 0;
    int err = TT_OK, stop = 0;
    char saved[1024] = "";
#pragma omp parallel for schedule(dynamic, 1) num_threads(kind == TT_SWEEP_SCAN ? 1 : threads)
    for (long i = 0; i < n; i++) {
        int halt;
#pragma omp atomic read
        halt = stop;
        if (halt || tt_cancel_requested())
            continue;
        int rc = tt_run_sweep_columns(g, kind, &parts[i]);
        if (!rc)
            rc = kind == TT_SWEEP_SCAN ? scan_combination(g, (size_t)i, threads, parts[i])
                                       : tt_run_sweep_points(g, kind, (size_t)i, parts[i]);
#pragma omp critical(tt_run_sweep_done)
        {
            if (rc && !err) {
                err = rc;
                snprintf(saved, sizeof saved, "%s", tt_error_message());
#pragma omp atomic write
                stop = 1;
            }
            if (!rc) {
                finished[i] = 1;
                if (progress)
                    progress(user, ++done, n);
            }
        }
    }
    if (tt_cancel_requested() && (!err || err == TT_EINTR))
        return tt_error(TT_EINTR, "interrupted: %ld of %ld combinations finished", done, n);
    return err ? tt_error(err, "%s", saved) : TT_OK;
}

/* The combinations (numbers from 1) whose rows say found=what: how many rows, and the
 * first WARN_LIST combinations as "1, 5, 7" (", ..." after them when more). */
#define WARN_LIST 10
static size_t found_rows(const tt_table *t, long found, const char *what, char *list, size_t len)
{
    size_t rows = 0, listed = 0, used = 0;
    double last = NAN;
    list[0] = '\0';
    for (size_t r = 0; r < tt_table_rows(t); r++) {
        if (strcmp(tt_table_text(t, (size_t)found, r), what) != 0)
            continue;
        rows++;
        double comb = tt_table_numbers(t, 0)[r];
        if (comb == last)
            continue;
        last = comb;
        if (listed++ < WARN_LIST && used < len)
            used += (size_t)snprintf(list + used, len - used, "%s%.0f", listed > 1 ? ", " : "", comb);
        else if (listed == WARN_LIST + 1 && used < len)
            used += (size_t)snprintf(list + used, len - used, ", ...");
    }
    return rows;
}

void tt_run_sweep_warn(const tt_table *t)
{
    long found = tt_table_find(t, "found");
    if (found < 0 || !tt_table_is_text(t, (size_t)found))
        return; /* a scan sweep's table */
    char list[256];
    size_t n = tt_table_rows(t), k;
    if ((k = found_rows(t, found, TT_SWEEP_PERIODIC, list, sizeof list)))
        tt_warn(TT_WARN_SETTLE,
                "%zu of %zu points are periodic orbits of more than one cycle, not steady "
                "oscillations (found=%s; combinations %s): their rows are the means over the period, "
                "which the period column gives in cycles", k, n, TT_SWEEP_PERIODIC, list);
    if ((k = found_rows(t, found, TT_SWEEP_UNSETTLED, list, sizeof list)))
        tt_warn(TT_WARN_SETTLE,
                "%zu of %zu points found no period up to %d cycles within [approach] "
                "max_cycles (found=%s; combinations %s): their rows are the means over their last "
                "%d cycles; chaos, or raise [approach] max_cycles", k, n, TT_SETTLE_MAX_PERIOD,
                TT_SWEEP_UNSETTLED, list, TT_SETTLE_WINDOW);
}

int tt_run_sweep(const tt_sweep *grid, tt_sweep_kind kind, int threads, tt_table **out,
                 tt_progress_fn progress, void *user)
{
    size_t n = tt_sweep_count(grid);
    *out = NULL;
    int rc = TT_OK;
    for (size_t i = 0; i < n && !rc; i++)
        rc = tt_run_sweep_check(grid, kind, i);
    if (rc)
        return rc;
    if (threads <= 0)
        threads = omp_get_max_threads();
    tt_table **parts = calloc(n, sizeof *parts), *all = NULL;
    int *finished = calloc(n, sizeof *finished);
    if (!parts || !finished)
        rc = tt_error_nomem("the tables of %zu combinations", n);
    if (!rc)
        rc = compute_all(grid, kind, threads, parts, finished, progress, user);
    /* the combinations in order, up to the first unfinished one */
    int mrc = parts ? tt_run_sweep_columns(grid, kind, &all) : TT_ENOMEM;
    for (size_t i = 0; i < n && !mrc && finished[i]; i++)
        mrc = run_table_append(all, parts[i]);
    for (size_t i = 0; parts && i < n; i++)
        tt_table_free(parts[i]);
    free(parts);
    free(finished);
    if (mrc) {
        tt_table_free(all);
        return rc ? rc : mrc;
    }
    if (kind == TT_SWEEP_SETPOINT)
        tt_run_warn_unreached(all);
    if (kind != TT_SWEEP_SCAN)
        tt_run_sweep_warn(all);
    *out = all;
    return rc;
}
