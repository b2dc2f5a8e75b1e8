/* tiptap: the scene's [force] and [tune] sections read and checked for tiptap force and
 * tiptap tune (tiptap/run/force.h, tiptap/run/tune.h; docs/force-and-tune.md).
 *
 * Ownership: the material text in the parameters points into the scene, which must
 * outlive it.
 */
#ifndef TIPTAP_READ_FORCE_TUNE_H
#define TIPTAP_READ_FORCE_TUNE_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/scene.h"

TT_BEGIN_DECLS

typedef struct {
    const char *material; /* NULL: the first */
    double from, to;      /* rest separation at the ramp's start and at its turn, m (from > to) */
    double speed;         /* m/s, asked for */
    double dwell;         /* s at the turn */
    long samples;         /* rows per leg (approach, dwell, retract) */
    long leg_periods;     /* drive periods a leg takes: the speed as run is (from - to) / (this T) */
    long dwell_periods;
} tt_force_params;

typedef struct {
    double duration;        /* record length, s */
    long samples_per_cycle;
    long cycles;            /* drive periods recorded */
    size_t segment;         /* Welch segment, samples (a power of two) */
} tt_tune_params;

/* [force]: from (or to + range) above to; the whole ramp at most 1e9 drive periods.
 * TT_EINVAL with "file: [force] key: what is wrong". */
int tt_config_force(const tt_scene *s, tt_force_params *p);

/* [tune] and what it needs of [noise]: a temperature above 0 K, a record of at most 2e8
 * samples holding at least 8 half-overlapping segments of the bin width asked for (0: the
 * scene's f0 / 16 Q). TT_EINVAL with "file: [section] key: what is wrong". */
int tt_config_tune(const tt_scene *s, tt_tune_params *p);

/* [tune] duration alone, the record's length in seconds, for a caller that shows it before
 * the noise a run needs is on (the console's tune bench). */
int tt_config_tune_duration(const tt_scene *s, double *duration);

TT_END_DECLS
#endif
