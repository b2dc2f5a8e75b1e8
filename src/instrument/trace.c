/* Time traces: settle, then record cycles while the sample moves and a key ramps (see
 * include/tiptap/instrument/trace.h). */
#include "tiptap/instrument/trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/physics/material.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/error.h"

struct tt_trace {
    tt_setup *st;
    tt_trace_params p;
    size_t mat;              /* the material under the tip */
    long row;
    double sdot;             /* sample speed, m/s, fixed at the first recorded cycle */
    tt_sample *raw;          /* the sim's samples of the current cycle */
    tt_trace_sample *out;    /* the same with force and pressure */
    long cycles;             /* cycles run, settling included: the noise's count */
    double sd;               /* detector noise per sample, m rms */
    tt_noise_ou zn;          /* the z piezo's noise through its bandwidth (sd 0: off) */
    double za;               /* its value at cycle zk's start */
    long zk;
    uint64_t kd, kz;         /* the detector's and the z piezo's keys */
    /* the recorded cycles' contact furthest past the small-contact bound (the largest
     * of a / (0.5 R) and delta / R): indentation, radius, tip radius, m (indent NAN: none) */
    double indent, radius, tip_radius, worst;
};

/* Set the ramped key to one end's value; a refusal names that end ("[trace] ramp_to:
 * ..."). tt_setup_apply sets it as a --set would: that origin is dropped, since the
 * user wrote the value into [trace]. */
static int apply_end(tt_setup *st, const tt_trace_params *p, const char *key, double value)
{
    if (tt_setup_apply(st, p->ramp, value) == TT_OK)
        return TT_OK;
    const char *m = tt_error_message();
    if (strncmp(m, "--set: ", 7) == 0)
        m += 7;
    char why[1024];
    snprintf(why, sizeof why, "%s", m);
    return tt_error(TT_EINVAL, "[trace] %s: %s", key, why);
}

int tt_trace_alloc(tt_trace **out, tt_setup *st, const tt_trace_params *p)
{
    *out = NULL;
    if (p->cycles < 1)
        return tt_error(TT_EINVAL, "[trace] cycles: must be at least 1");
    if (p->settle_cycles < 0)
        return tt_error(TT_EINVAL, "[trace] settle_cycles: must not be negative");
    if (p->samples_per_cycle < 1 || p->samples_per_cycle > 1000000)
        return tt_error(TT_EINVAL, "[trace] samples_per_cycle: must be 1 to 1e6");
    size_t mat;
    int rc;
    if ((rc = tt_setup_find_material(st, p->material, "trace", "material", &mat)) ||
        (rc = tt_setup_use_material(st, mat)))
        return rc;
    /* Both ends before the first cycle, so that a ramp_to the scene cannot take is
     * refused before anything runs, not at the last cycle; the run starts at ramp_from. */
    if (p->ramp && ((rc = apply_end(st, p, "ramp_to", p->ramp_to)) ||
                    (rc = apply_end(st, p, "ramp_from", p->ramp_from))))
        return rc;
    tt_trace *t = calloc(1, sizeof *t);
    size_t n = (size_t)p->samples_per_cycle;
    if (!t || !(t->raw = calloc(n, sizeof *t->raw)) || !(t->out = calloc(n, sizeof *t->out))) {
        tt_trace_free(t);
        return tt_error_nomem("[trace] samples_per_cycle = %ld samples", p->samples_per_cycle);
    }
    t->st = st;
    t->p = *p;
    t->mat = mat;
    /* white noise of one-sided density n sampled at rate fs has variance n^2 fs / 2 */
    const double T = tt_setup_cantilever(st)->T;
    t->sd = p->noise.detector * sqrt(0.5 * (double)p->samples_per_cycle / T);
    if (p->noise.z_piezo > 0 && (rc = tt_noise_ou_init(&t->zn, p->noise.z_piezo, p->noise.z_bandwidth, T))) {
        tt_trace_free(t);
        return rc;
    }
    t->kd = tt_noise_key(p->noise.seed, TT_NOISE_DETECTOR, 0);
    t->kz = tt_noise_key(p->noise.seed, TT_NOISE_PIEZO, 0);
    t->za = tt_noise_ou_first(&t->zn, t->kz); /* from its stationary distribution */
    tt_sim *sim = tt_setup_sim(st);
    if ((rc = tt_sim_set_thermal(sim, p->noise.temperature, p->noise.points))) {
        tt_trace_free(t);
        return rc;
    }
    tt_sim_noise_key(sim, tt_noise_key(p->noise.seed, TT_NOISE_THERMAL, 0));
    *out = t;
    return TT_OK;
}

void tt_trace_free(tt_trace *t)
{
    if (!t)
        return;
    /* the sim outlives the trace: it must not write into freed samples */
    if (t->st) {
        tt_sim_set_sampling(tt_setup_sim(t->st), 0, NULL);
        tt_sim_set_thermal(tt_setup_sim(t->st), 0, 0);
    }
    free(t->raw);
    free(t->out);
    free(t);
}

size_t tt_trace_rows(const tt_trace *t) { return (size_t)t->p.cycles; }
int tt_trace_done(const tt_trace *t) { return t->row >= t->p.cycles; }

/* The sample for the next cycle: at s, moving at sdot, plus the z piezo's noise through
 * its bandwidth (exact at each cycle's start, linear between; as a scan draws it,
 * src/instrument/scan_cycle.c). Set again for the same cycle, it is the same. */
static void set_sample(tt_trace *t, double s, double sdot)
{
    if (t->zn.sd > 0) {
        for (; t->zk < t->cycles; t->zk++)
            t->za = tt_noise_ou_next(&t->zn, t->kz, (uint64_t)t->zk + 1, t->za);
        const double a = t->za, b = tt_noise_ou_next(&t->zn, t->kz, (uint64_t)t->cycles + 1, a);
        s += a;
        sdot += (b - a) / tt_setup_cantilever(t->st)->T;
    }
    tt_sim_set_sample(tt_setup_sim(t->st), s, sdot);
}

/* From the free steady state, settle_cycles at the first separation, unrecorded. */
static int settle(tt_trace *t)
{
    tt_sim *sim = tt_setup_sim(t->st);
    tt_cycle cy;
    int rc = TT_OK;
    tt_sim_reset_free(sim);
    set_sample(t, t->p.separation, 0);
    for (long i = 0; i < t->p.settle_cycles && rc == TT_OK; i++, t->cycles++) {
        if (i > 0 && t->zn.sd > 0) /* a sample at rest is set once: the stepper keeps its state */
            set_sample(t, t->p.separation, 0);
        rc = tt_sim_cycle(sim, &cy);
    }
    if (rc)
        return rc;
    tt_sim_set_sampling(sim, (int)t->p.samples_per_cycle, t->raw);
    t->sdot = (t->p.separation_end - t->p.separation) / ((double)t->p.cycles * tt_setup_cantilever(t->st)->T);
    return TT_OK;
}

/* The ramped key's value at recorded cycle i: linear from ramp_from to ramp_to. */
static double ramp_value(const tt_trace_params *p, long i)
{
    if (p->cycles <= 1)
        return p->ramp_from;
    return p->ramp_from + (p->ramp_to - p->ramp_from) * (double)i / (double)(p->cycles - 1);
}

/* The Hertzian mean pressure over a contact circle of radius a, K a / (pi R) (the load
 * K a^3 / R over pi a^2). */
static double hertz_pressure(const tt_contact_params *cp, double a)
{
    return cp->K * a / (M_PI * cp->R);
}

/* Force and pressure of the cycle's samples; K and R are read after each cycle since a
 * ramp may change them. */
static void fill_samples(tt_trace *t)
{
    const tt_contact_params *cp = &tt_setup_material(t->st, t->mat)->contact;
    for (long k = 0; k < t->p.samples_per_cycle; k++) {
        const tt_sample *s = &t->raw[k];
        tt_trace_sample *o = &t->out[k];
        double a = 0;
        o->force = tt_sim_force(tt_setup_sim(t->st), s, &a);
        o->t = s->t;
        o->base = s->z;
        o->tip = s->d;
        o->deflection = s->d - s->z;
        if (t->sd > 0)
            o->deflection += t->sd * tt_noise_gauss(t->kd, (uint64_t)t->row * (uint64_t)t->p.samples_per_cycle +
                                                               (uint64_t)k);
        /* the surface where it is: a sample with relaxation arms lags behind the tip */
        o->sample = s->u != 0 ? s->s + s->u : s->s;
        o->contact_radius = a;
        o->pressure = s->contact ? hertz_pressure(cp, a) : 0;
        o->contact = s->contact;
    }
}

/* The Hertzian pressure at the cycle's greatest indentation, located by the
 * integrator, where the contact circle is widest: the peak that samples at fixed times
 * miss when the contact is short against the cycle. */
static double peak_pressure(tt_trace *t, const tt_cycle *c)
{
    if (!(c->contact_fraction > 0) || !(c->max_indentation > -INFINITY))
        return 0;
    const tt_contact_params *cp = &tt_setup_material(t->st, t->mat)->contact;
    tt_sample s = {.d = c->max_indentation, .contact = 1};
    double a = 0;
    tt_sim_force(tt_setup_sim(t->st), &s, &a);
    /* kept for tt_trace_warn_contact, with the law of this cycle (a ramp changes it) */
    double q = fmax(a / (TT_CONTACT_MAX_RADIUS_RATIO * cp->R), c->max_indentation / cp->R);
    if (c->max_indentation > 0 && !(q <= t->worst)) {
        t->worst = q;
        t->indent = c->max_indentation;
        t->radius = a;
        t->tip_radius = cp->R;
    }
    return hertz_pressure(cp, a);
}

int tt_trace_warn_contact(const tt_trace *t)
{
    if (!(t->indent > 0))
        return 0;
    return tt_contact_warn_validity(tt_setup_material(t->st, t->mat)->name, t->radius, t->indent,
                                    t->tip_radius, "a larger [tip] radius, a larger [trace] "
                                    "separation or a smaller [cantilever] free_amplitude");
}

int tt_trace_iterate(tt_trace *t, tt_trace_row *row)
{
    if (tt_trace_done(t))
        return tt_error(TT_EINVAL, "trace already finished");
    int rc;
    if (t->row == 0 && (rc = settle(t)))
        return rc;
    long i = t->row;
    row->cycle = i;
    row->ramp_value = 0;
    row->nsamples = 0;
    row->samples = NULL;
    if (t->p.ramp) {
        row->ramp_value = ramp_value(&t->p, i);
        if ((rc = tt_setup_apply(t->st, t->p.ramp, row->ramp_value)))
            return rc;
    }
    /* the sample moves at sdot through the recorded cycles (Burnham et al.'s figure 4b) */
    set_sample(t, t->p.separation + t->sdot * (double)i * tt_setup_cantilever(t->st)->T, t->sdot);
    rc = tt_sim_cycle(tt_setup_sim(t->st), &row->summary);
    t->cycles++;
    if (rc)
        return rc;
    fill_samples(t);
    row->peak_pressure = peak_pressure(t, &row->summary);
    row->nsamples = (size_t)t->p.samples_per_cycle;
    row->samples = t->out;
    t->row++;
    return TT_OK;
}
