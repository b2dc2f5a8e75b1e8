/* tiptap: lock-in demodulator.
 *
 * The deflection is sampled N times per drive period (N a power of two is fastest),
 * at t = k T / N from a period boundary. Each block of whole periods is transformed
 * with FFTW (one plan made at alloc), giving the in-phase and quadrature parts of the
 * fundamental and of the harmonics up to nharm; these then pass a low-pass filter of
 * the given order (cascaded first-order sections, each with the time constant tau),
 * as in an instrument's lock-in. Amplitude is the peak amplitude; phase is the lag of
 * the harmonic behind cos(h w t), in radians.
 *
 * Ownership: tt_lockin_alloc returns a handle the caller frees with tt_lockin_free.
 * A handle is not shared between threads (each scan line has its own).
 */
#ifndef TIPTAP_LOCKIN_H
#define TIPTAP_LOCKIN_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct {
    double drive_frequency;  /* Hz */
    int samples_per_period;  /* N >= 8 */
    int periods_per_block;   /* periods per transform (>= 1) */
    int harmonics;           /* harmonics kept, >= 1 (1: the fundamental only) */
    double time_constant;    /* s; 0: no filter (each block's raw result) */
    int filter_order;        /* 1 to 8 */
    double ratio2;           /* a second reference at ratio2 times drive_frequency (0: none) */
} tt_lockin_params;

typedef struct tt_lockin tt_lockin;

int tt_lockin_alloc(tt_lockin **out, const tt_lockin_params *p);
void tt_lockin_free(tt_lockin *l);

/* Start the filter from these values (for example the free oscillation), so that a
 * scan does not begin with a filter transient from zero. */
void tt_lockin_reset(tt_lockin *l, double amplitude, double phase);

/* Copy the filter's state (and the last block's results) of src into dst, a lock-in of
 * the same parameters: a snapshot to return to (the envelope tier's rollback). */
void tt_lockin_copy(tt_lockin *dst, const tt_lockin *src);

/* Feed one block: samples_per_period * periods_per_block samples. */
int tt_lockin_push(tt_lockin *l, const double *samples);

/* A period's components: what a block's transform is linear in, for a caller that has
 * them without the samples (the envelope tier's model cycles). Per period of N
 * samples y: the mean, then per harmonic h = 1..harmonics the in-phase and quadrature
 * parts (2 / N) sum y cos(h w t), (2 / N) sum y sin(h w t); a block's results are their
 * means over its periods, as the transform of its samples gives them (up to rounding). */
int tt_lockin_components(const tt_lockin *l); /* 1 + 2 harmonics */
/* The components' matrix, components x samples_per_period by rows (the lock-in's). */
const double *tt_lockin_component_matrix(const tt_lockin *l);
/* One period's samples to its components (c: tt_lockin_components values). */
void tt_lockin_transform(const tt_lockin *l, const double *samples, double *c);
/* Feed one block as its periods' components, periods_per_block x components: the same
 * filter step as tt_lockin_push of its samples. */
int tt_lockin_push_components(tt_lockin *l, const double *c);

/* The second reference (bimodal imaging: mode 2's drive, ratio2 times the drive
 * frequency, in general no whole number of its periods in a block). It demodulates as an
 * analogue lock-in does, sample by sample: the samples times 2 cos and 2 sin of the
 * reference's phase, each product through the same cascade of first-order sections
 * stepped at the sample interval, so that the first drive's deflection, mixed to
 * |ratio2 - h| times the drive frequency, is attenuated by the filter's roll-off
 * (docs/physics.md, "Bimodal imaging"); with time_constant 0 it is the plain mean of the
 * block's products. Feed each period with the reference's phase at its first sample,
 * in turns, before the block's tt_lockin_push (or _push_components), which closes the
 * block's raw result. */
void tt_lockin_second_period(tt_lockin *l, const double *samples, double turns);
void tt_lockin_reset_second(tt_lockin *l, double amplitude, double phase);
double tt_lockin_second_amplitude(const tt_lockin *l);
double tt_lockin_second_phase(const tt_lockin *l);
double tt_lockin_second_raw_amplitude(const tt_lockin *l);
double tt_lockin_second_raw_phase(const tt_lockin *l);

/* Filtered outputs for harmonic h (1 = fundamental, up to harmonics). */
double tt_lockin_amplitude(const tt_lockin *l, int h);
double tt_lockin_phase(const tt_lockin *l, int h);
/* Unfiltered result of the last block. */
double tt_lockin_raw_amplitude(const tt_lockin *l, int h);
double tt_lockin_raw_phase(const tt_lockin *l, int h);
/* Mean (DC) of the last block, unfiltered. */
double tt_lockin_mean(const tt_lockin *l);

TT_END_DECLS
#endif
