/* tiptap: time traces of the tapping cantilever (Burnham et al.'s figures 4b to 8): the tip, base
 * and sample positions and the tip-sample force sampled through each drive cycle,
 * optionally while the sample moves from one rest separation to another and while one
 * scene key (the adhesion energy, the spring constant) ramps linearly over the run.
 *
 * The cantilever starts in its free steady oscillation, runs settle_cycles at the first
 * separation unrecorded, then records cycles rows, each one drive cycle of
 * samples_per_cycle samples.
 *
 * Noise ([noise], as a scan's: tiptap/instrument/scan.h) keyed by (seed, line 0) and
 * counted in cycles from the settling's start: the thermal force on the cantilever,
 * z piezo noise moving the sample (through its bandwidth, exact at each cycle's start,
 * linear between) and the detector's
 * noise added to each sample's measured deflection (tt_trace_sample deflection), not
 * to the tip's position.
 *
 * Usage: tt_trace_alloc(&t, setup, &params); while (!tt_trace_done(t))
 * { tt_trace_iterate(t, &row); ... }; tt_trace_free(t).
 * Ownership: the trace borrows the setup (which must outlive it) and drives its sim;
 * a ramp changes the setup's scene through tt_setup_apply. The samples of a row
 * belong to the trace and are overwritten by the next tt_trace_iterate.
 */
#ifndef TIPTAP_TRACE_H
#define TIPTAP_TRACE_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/setup.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

typedef struct {
    const char *material;    /* material under the tip (NULL: the first) */
    double separation;       /* rest separation at the first recorded cycle, m */
    double separation_end;   /* at the end of the last one (= separation: the sample rests), m */
    long cycles;             /* recorded cycles */
    long settle_cycles;      /* unrecorded cycles at separation first */
    long samples_per_cycle;
    const char *ramp;        /* key ramped over the recorded cycles, "material.NAME.key" or
                              * "cantilever.key" (NULL: none) */
    double ramp_from, ramp_to; /* its values at the first and last recorded cycle, SI */
    tt_scan_noise noise;     /* all zero: none */
} tt_trace_params;

/* One sample within a cycle, SI units along the axis into the sample. */
typedef struct {
    double t;                /* s, absolute */
    double base, tip;        /* base and tip positions, m */
    double deflection;       /* what the detector reads, m: tip - base, plus its noise */
    double sample;           /* sample surface, m */
    double force;            /* tip-sample force, N */
    double contact_radius;   /* m */
    double pressure;         /* Hertzian mean pressure K a / (pi R), Pa (0 out of contact) */
    int contact;
} tt_trace_sample;

typedef struct {
    long cycle;                     /* recorded cycle, from 0 */
    double ramp_value;              /* the ramped key's value during the cycle (0: no ramp) */
    tt_cycle summary;               /* the cycle's observables (peak_force: the true peak,
                                     * at the located contact, whatever the sampling) */
    double peak_pressure;           /* Hertzian pressure at the cycle's greatest indentation,
                                     * Pa (0: no contact) */
    size_t nsamples;
    const tt_trace_sample *samples; /* belong to the trace, valid until the next iterate */
} tt_trace_row;

typedef struct tt_trace tt_trace;

/* Puts the material under the tip and the ramped key at its first value. TT_EINVAL
 * naming "[trace] KEY" for a bad material, ramp or count. */
int tt_trace_alloc(tt_trace **out, tt_setup *st, const tt_trace_params *p);
void tt_trace_free(tt_trace *t);
size_t tt_trace_rows(const tt_trace *t);
int tt_trace_done(const tt_trace *t);
/* Run the next recorded cycle (and the settling cycles before the first). TT_ENUM
 * etc. on solver failure, TT_EINVAL on a ramp value the scene refuses. */
int tt_trace_iterate(tt_trace *t, tt_trace_row *row);

/* Raise the TT_WARN_VALIDITY warning (tt_contact_warn_validity, as a scan does) when the
 * recorded cycles' contact went furthest beyond the force laws' small-contact
 * assumption: the contact radius at a cycle's greatest indentation past 0.5 R, or the
 * indentation past R, with the force law of that cycle (a ramp changes it). Returns
 * whether it warned. Once per run, on the calling thread: the program's companion run
 * (its error estimate) does not call it. */
int tt_trace_warn_contact(const tt_trace *t);

TT_END_DECLS
#endif
