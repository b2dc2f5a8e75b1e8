/* tiptap: the configuration layer: a scene read into the typed parameters of the
 * modules that run it.
 *
 * Each function reads every key of its sections once, converts units, and checks every
 * rule on a single key and between keys; errors are one line, "file: [section] key:
 * what is wrong". The modules themselves never see the scene. tt_config_scan reads and
 * checks every material of the scene, used by a pixel or not, so that a scan is
 * refused before anything runs or any file is written.
 *
 * Ownership: tt_config_materials and tt_config_scan allocate the material list
 * (tt_config_scan: p->materials); the caller frees it with free() (tt_config_scan_free
 * for a scan's parameters). Everything else is plain values.
 */
#ifndef TIPTAP_CONFIG_H
#define TIPTAP_CONFIG_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/scene.h"
#include "tiptap/config/setup.h"
#include "tiptap/instrument/accuracy.h"
#include "tiptap/config/solver_scene.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scanner.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/instrument/trace.h"
#include "tiptap/physics/cantilever.h"
#include "tiptap/physics/material.h"

TT_BEGIN_DECLS

/* [cantilever], its derived constants filled (tt_cantilever_init). */
int tt_config_cantilever(const tt_scene *s, tt_cantilever *c);

/* [tip]. */
int tt_config_tip(const tt_scene *s, tt_tip *tip);

/* Every [material NAME] in order of appearance, each paired with the [tip]; a scene
 * without any has one, "sample", with the schema's defaults. *out is allocated. */
int tt_config_materials(const tt_scene *s, tt_material **out, size_t *n);

/* The material that [section] material names (the first when it names none), as an
 * index into the list of tt_config_materials. */
int tt_config_material_index(const tt_scene *s, const char *section, const tt_material *m,
                             size_t n, size_t *index);

/* [scan] raster. */
int tt_config_raster(const tt_scene *s, tt_raster *r);

/* [surface], its map resolved against the materials' names and colours. */
int tt_config_surface(const tt_scene *s, const tt_material *m, size_t n, tt_surface_params *p);

/* [lockin] (harmonics: as many as the lock-in offers). */
int tt_config_lockin(const tt_scene *s, tt_lockin_params *p);

/* [feedback], the setpoint in metres (a percentage is of the cantilever's free
 * amplitude A0, m). */
int tt_config_feedback(const tt_scene *s, double A0, tt_feedback_params *p);

/* [tip] shape and half_angle, with the [tip] radius (tiptap scan). */
int tt_config_tip_shape(const tt_scene *s, tt_tip_shape *t);

/* [noise] (seed, temperature, points, detector, z_piezo, z_piezo_bandwidth) for a run on
 * this solver setting at drive frequency fd (Hz): rk4's steps_per_cycle must be a
 * multiple of points when the temperature is on, and the z piezo's bandwidth at most
 * fd / 2 when its noise is (tiptap scan and tiptap trace). */
int tt_config_noise(const tt_scene *s, const tt_solver *solver, double fd, tt_scan_noise *n);

/* [instrument]: tilt, drift, the z piezo's dynamics and creep (all zero by default). */
int tt_config_instrument(const tt_scene *s, tt_instrument_params *p);

/* Everything a scan reads: [cantilever], [solver], [tip], every [material], [scan],
 * [surface], [lockin], [feedback], [instrument]. */
int tt_config_scan(const tt_scene *s, tt_scan_params *p);
void tt_config_scan_free(tt_scan_params *p);

/* [approach]. */
int tt_config_approach(const tt_scene *s, tt_approach_params *p);

/* [approach] on a setup made from the same scene: its parameters read into *p and the
 * material it names put under the tip (tt_config_approach_setup), then the approach
 * made, the module's errors naming the scene file (tt_scene_locate). The approach
 * borrows the setup's simulation: free it before the setup. */
int tt_config_approach_setup(tt_setup *st, const tt_scene *s, tt_approach_params *p);
int tt_config_approach_alloc(tt_approach **out, tt_setup *st, const tt_scene *s,
                             tt_approach_params *p);

/* What the accuracy study judges: the cantilever and [solver], the [approach]
 * material and point, and the scan when the scene has [scan]. Free with
 * tt_config_accuracy_free. */
int tt_config_accuracy(const tt_scene *s, tt_accuracy_subject *subject);
void tt_config_accuracy_free(tt_accuracy_subject *subject);

/* Runs made straight from a scene: read, check, and make the object; the errors of
 * the module name the scene file too (tt_scene_locate). */
int tt_config_scan_alloc(tt_scan **out, const tt_scene *s);
int tt_config_surface_alloc(tt_surface **out, const tt_scene *s, double size_x, double size_y);
/* Note the files the scene was read from and those it names ([surface] png, map_png;
 * those that exist) as inputs of the run (tt_input_note: remembered whether tracking is
 * on or not), so that an output of the same name is refused before anything runs. */
void tt_config_note_inputs(const tt_scene *s);
int tt_config_accuracy_alloc(tt_accuracy **out, const tt_scene *s, const tt_accuracy_params *p);

/* rk4 at [solver] steps_per_cycle against the stiffest contact the run can reach: the
 * contact stiffness at the depth where the contact's potential equals the energy of the
 * free oscillation (1/2 k A^2, A the free amplitude plus how far s_min, the lowest rest
 * separation of the run, lies inside the sample), and the interaction damping's rate.
 * Refused ("[solver] steps_per_cycle: ...") before the run starts, instead of by the
 * solver at the first step too coarse, after the run's first lines. section: the run's
 * section whose `material` key picks the material ("trace", "approach": run by
 * tt_config_trace and tt_config_approach); NULL checks every material (tiptap scan runs
 * it after tt_config_scan, which the accuracy study also reads, and that study tries
 * coarse settings on purpose). TT_OK for the other methods. The depth is what the energy
 * allows, an upper bound in steady tapping; the solver's own check stays, for the
 * stages of a step that overshoot deeper. */
int tt_config_check_rk4(const tt_scene *s, const char *section, double s_min);

/* What a run will cost, told before it starts: the drive cycles it simulates, the wall
 * time on one thread (an order of magnitude from the solver and f0 / fd: an adaptive
 * step resolves the resonance, so a drive far below it costs f0 / fd times more a
 * cycle), and the memory it holds. */
typedef struct {
    double cycles;        /* drive cycles to simulate */
    double cycle_seconds; /* wall time of one, one thread */
    double seconds;       /* of the whole run, one thread */
    double seconds_low;   /* the least (the envelope tier, where the model follows most
                           * cycles); seconds otherwise */
    int envelope;         /* 1: a scan on the envelope tier (seconds_low to seconds) */
    double integrated_low, integrated_high; /* its fractions of the cycles integrated */
    int upper_bound;      /* 1: cycles and seconds are the most it can take (settling) */
    double bytes;         /* memory held for the run (scan: images and previews) */
    double thread_bytes;  /* and per thread */
    double scope_bytes;   /* a scan: one line's scope record (instrument/scan_scope.h), which
                           * tiptap scan keeps of its profile line and tiptap live of each */
} tt_estimate;

double tt_config_cycle_seconds(const tt_cantilever *c, const tt_solver *s);
void tt_config_scan_estimate(const tt_scan_params *p, tt_estimate *e);
void tt_config_trace_estimate(const tt_cantilever *c, const tt_solver *s, const tt_trace_params *p,
                              tt_estimate *e);
void tt_config_approach_estimate(const tt_cantilever *c, const tt_solver *s,
                                 const tt_approach_params *p, tt_estimate *e);

/* The materials of a scan that its surface map never puts under the tip (uniform: all
 * but the first; two-material maps: all but the two named; PNG maps: those without a
 * map_value). Fills idx with up to max indices; returns how many there are. */
size_t tt_config_scan_unused(const tt_scan_params *p, size_t *idx, size_t max);

TT_END_DECLS
#endif
