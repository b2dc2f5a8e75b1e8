/* tiptap force: a force-distance curve of the undriven cantilever (see
 * include/tiptap/run/force.h). */
#include "tiptap/run/force.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run_common.h"
#include "run_force_private.h"
#include "tiptap/config/config.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/config/setup.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

enum { COL_T, Z, DEFL, SEP, FORCE, LEVER, CONTACT, LEG, NCOL };
static const run_column columns[NCOL] = {
    {"t", "s", 0},          {"z", "m", 0},     {"deflection", "m", 0}, {"separation", "m", 0},
    {"force", "N", 0},      {"lever_force", "N", 0}, {"contact", "", 0}, {"leg", "", 1},
};
static const char *const leg_names[3] = {"approach", "dwell", "retract"};

/* Samples the analysis reads per drive period: the snap's start to an eighth of one. */
#define POINTS_PER_PERIOD 8

/* The online analysis of the samples, in time order. */
typedef struct {
    tt_force_summary s;
    double vth;  /* the tip's speed that marks the snap, m/s */
    int touched; /* the approach has contacted */
    double last_calm_z, last_calm_f, last_calm_gap;
    double last_contact_z, last_contact_f;
} force_scan;

static void analyse(force_scan *a, int leg, double z, double v, double gap, double F, int contact)
{
    tt_force_summary *s = &a->s;
    if (F > s->max_force || isnan(s->max_force))
        s->max_force = F;
    if (contact && (-gap > s->indentation || isnan(s->indentation)))
        s->indentation = -gap;
    if (leg == 0 && !a->touched) {
        if (contact) {
            a->touched = 1;
            s->contact_z = z;
            s->jumpin_z = a->last_calm_z;
            s->jumpin_force = a->last_calm_f;
            s->jumpin_gap = a->last_calm_gap;
        } else if (fabs(v) <= a->vth) {
            a->last_calm_z = z;
            a->last_calm_f = F;
            a->last_calm_gap = gap;
        }
    }
    if (leg == 2) {
        if (-F > s->adhesion || isnan(s->adhesion))
            s->adhesion = -F;
        if (contact) {
            a->last_contact_z = z;
            a->last_contact_f = F;
        } else if (!isnan(a->last_contact_z) && isnan(s->pulloff_z)) {
            s->pulloff_z = z;
            s->pulloff_force = a->last_contact_f;
        }
    }
}

/* -dF/dz of the rows of leg in contact whose lever force is above half the leg's
 * largest, a straight line by least squares; also d(deflection)/dz. NAN with fewer than
 * three such rows. */
static void contact_slope(const tt_table *t, const char *leg, double *slope, double *sdefl)
{
    const double *z = tt_table_numbers(t, Z), *F = tt_table_numbers(t, LEVER), *y = tt_table_numbers(t, DEFL);
    const double *c = tt_table_numbers(t, CONTACT);
    double fmax = 0;
    for (size_t i = 0; i < tt_table_rows(t); i++)
        if (c[i] > 0 && F[i] > fmax && strcmp(tt_table_text(t, LEG, i), leg) == 0)
            fmax = F[i];
    double n = 0, sz = 0, szz = 0, sf = 0, szf = 0, sy = 0, szy = 0;
    for (size_t i = 0; i < tt_table_rows(t); i++) {
        if (strcmp(tt_table_text(t, LEG, i), leg) != 0 || !(c[i] > 0) || !(F[i] >= 0.5 * fmax))
            continue;
        n++, sz += z[i], szz += z[i] * z[i], sf += F[i], szf += z[i] * F[i], sy += y[i], szy += z[i] * y[i];
    }
    double den = n * szz - sz * sz;
    *slope = *sdefl = NAN;
    if (n >= 3 && den > 0 && fmax > 0) {
        *slope = -(n * szf - sz * sf) / den;
        *sdefl = (n * szy - sz * sy) / den;
    }
}

static int put_meta(tt_table *t, const tt_force_summary *s)
{
    const struct {
        const char *key;
        double v;
    } m[] = {{"speed", s->speed},           {"cycles", (double)s->cycles},
             {"k", s->k},                   {"jumpin_z", s->jumpin_z},
             {"jumpin_force", s->jumpin_force}, {"jumpin_gap", s->jumpin_gap},
             {"contact_z", s->contact_z},   {"pulloff_z", s->pulloff_z},
             {"pulloff_force", s->pulloff_force}, {"adhesion", s->adhesion},
             {"max_force", s->max_force},   {"slope", s->slope},
             {"slope_deflection", s->slope_deflection}, {"slope_retract", s->slope_retract},
             {"indentation", s->indentation}};
    int rc = TT_OK;
    for (size_t i = 0; i < sizeof m / sizeof m[0] && rc == TT_OK; i++)
        rc = run_meta_number(t, m[i].key, m[i].v);
    return rc;
}

tt_table *force_table(void)
{
    return run_table(columns, NCOL);
}

int force_lever_alloc(const tt_scene *s, force_lever *L)
{
    tt_scan_noise noise;
    memset(L, 0, sizeof *L);
    int rc;
    if ((rc = tt_scene_locate(s, tt_config_force(s, &L->p))) || (rc = run_setup(s, &L->copy, &L->st)) ||
        (rc = tt_config_noise(L->copy, tt_setup_solver(L->st), tt_setup_cantilever(L->st)->fd, &noise)))
        return rc;
    tt_sim *sim = tt_setup_sim(L->st);
    /* the lever undriven: no base motion, no drive force; the drive period only sets
     * the length of the solver's cycles */
    L->c = *tt_setup_cantilever(L->st);
    L->c.a_d = 0;
    L->c.F0 = 0;
    L->temperature = noise.temperature;
    L->seed = noise.seed;
    tt_sim_set_cantilever(sim, &L->c);
    if ((rc = tt_sim_set_thermal(sim, noise.temperature, noise.points)))
        return rc;
    if (!(L->buf = calloc(POINTS_PER_PERIOD, sizeof *L->buf)))
        return tt_error_nomem("the force curve's samples");
    tt_sim_set_sampling(sim, POINTS_PER_PERIOD, L->buf);
    return TT_OK;
}

void force_lever_free(force_lever *L)
{
    if (L->st) {
        tt_sim_set_sampling(tt_setup_sim(L->st), 0, NULL);
        tt_sim_set_thermal(tt_setup_sim(L->st), 0, 0);
    }
    free(L->buf);
    tt_setup_free(L->st);
    tt_scene_free(L->copy);
    memset(L, 0, sizeof *L);
}

/* One sample: into the analysis, and a row of t when it is one of the leg's rows. */
static int take_sample(force_scan *a, tt_table *t, const force_lever *L, const tt_sample *x, int leg,
                       int row)
{
    tt_sim *sim = tt_setup_sim(L->st);
    const double z = x->s, y = x->d - x->z, F = tt_sim_force(sim, x, NULL);
    analyse(a, leg, z, x->v, z - y, F, x->contact);
    if (!row)
        return TT_OK;
    int rc = tt_table_row(t);
    if (rc)
        return rc;
    const double v[LEG] = {x->t, z, y, z - y, F, -L->c.k * y, x->contact};
    for (int col = 0; col < LEG; col++)
        tt_table_set(t, (size_t)col, v[col]);
    return tt_table_set_text(t, LEG, leg_names[leg]);
}

/* The analysis at a curve's start: nothing found yet, the ramp's speed u. */
static force_scan scan_start(const force_lever *L, double u)
{
    force_scan a = {.s = {.speed = u, .k = L->c.k, .jumpin_z = NAN, .jumpin_force = NAN, .jumpin_gap = NAN,
                          .contact_z = NAN, .pulloff_z = NAN, .pulloff_force = NAN, .adhesion = NAN,
                          .max_force = NAN, .slope = NAN, .slope_deflection = NAN, .slope_retract = NAN,
                          .indentation = NAN},
                    .last_calm_z = NAN, .last_calm_f = NAN, .last_calm_gap = NAN,
                    .last_contact_z = NAN, .last_contact_f = NAN};
    /* the snap's start: the tip faster than ten times the ramp, or five times the thermal
     * rms speed sqrt(kB T / m) when the lever is warm */
    a.vth = fmax(10 * u, 5 * sqrt(TT_BOLTZMANN * L->temperature / L->c.m));
    return a;
}

/* One leg (0 approach, 1 dwell, 2 retract) of n periods at the sample's speed sdot from
 * s0; every stride-th sample a row, and the leg's last. */
static int run_leg(force_lever *L, force_scan *a, tt_table *t, int leg, long n, double s0, double sdot,
                   long stride, tt_progress_fn progress, void *user, long *done, long total)
{
    tt_sim *sim = tt_setup_sim(L->st);
    const double T = L->c.T;
    int rc = TT_OK;
    for (long i = 0; i < n && rc == TT_OK; i++) {
        tt_cycle cy;
        if (tt_cancel_requested())
            return tt_error(TT_EINTR, "interrupted: %ld of %ld drive periods finished", *done, total);
        tt_sim_set_sample(sim, s0 + sdot * (double)i * T, sdot);
        if ((rc = tt_sim_cycle(sim, &cy)))
            break;
        for (int k = 0; k < POINTS_PER_PERIOD && rc == TT_OK; k++) {
            long idx = i * POINTS_PER_PERIOD + k;
            int last = i == n - 1 && k == POINTS_PER_PERIOD - 1;
            rc = take_sample(a, t, L, &L->buf[k], leg, idx % stride == 0 || last);
        }
        a->s.cycles++;
        ++*done;
        if (progress && (*done % 256 == 0 || *done == total))
            progress(user, *done, total);
    }
    return rc;
}

int force_curve(force_lever *L, size_t mat, uint64_t key, tt_table *t, tt_force_summary *sum,
                tt_progress_fn progress, void *user, long *done, long total)
{
    int rc = tt_setup_use_material(L->st, mat);
    if (rc)
        return rc;
    tt_sim *sim = tt_setup_sim(L->st);
    const tt_force_params *p = &L->p;
    tt_sim_noise_key(sim, key);
    tt_sim_reset_free(sim);
    tt_sim_set_state(sim, 0, 0, 0);
    const long nleg = p->leg_periods, ndwell = p->dwell_periods;
    const double u = (p->from - p->to) / ((double)nleg * L->c.T), n = POINTS_PER_PERIOD;
    force_scan a = scan_start(L, u);
    const long legs[3] = {nleg, ndwell, nleg};
    /* rows: every stride-th sample of a leg, and its last */
    const long stride_leg = (long)fmax(1, floor((double)nleg * n / (double)p->samples));
    const long stride_dwell = (long)fmax(1, floor((double)ndwell * n / (double)p->samples));
    for (int leg = 0; leg < 3 && rc == TT_OK; leg++)
        rc = run_leg(L, &a, t, leg, legs[leg], leg == 0 ? p->from : p->to, leg == 0 ? -u : leg == 2 ? u : 0,
                     leg == 1 ? stride_dwell : stride_leg, progress, user, done, total);
    if (rc == TT_OK) {
        double dummy;
        contact_slope(t, "approach", &a.s.slope, &a.s.slope_deflection);
        contact_slope(t, "retract", &a.s.slope_retract, &dummy);
    }
    *sum = a.s;
    return rc;
}

int tt_run_force(const tt_scene *s, tt_table **out, tt_force_summary *sum, tt_progress_fn progress,
                 void *user)
{
    force_lever L;
    tt_force_summary r;
    size_t mat;
    long done = 0;
    *out = NULL;
    int rc;
    if ((rc = force_lever_alloc(s, &L)) ||
        (rc = tt_scene_locate(L.copy, tt_setup_find_material(L.st, L.p.material, "force", "material", &mat))))
        goto done;
    if (!(*out = force_table())) {
        rc = TT_ENOMEM;
        goto done;
    }
    const long total = 2 * L.p.leg_periods + L.p.dwell_periods;
    rc = force_curve(&L, mat, tt_noise_key(L.seed, TT_NOISE_THERMAL, 0), *out, &r, progress, user, &done,
                     total);
    if (rc == TT_OK)
        rc = put_meta(*out, &r);
    if (sum)
        *sum = r;
done:
    force_lever_free(&L);
    return rc;
}
