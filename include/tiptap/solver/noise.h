/* tiptap: seeded noise, reproducible on any number of threads.
 *
 * Every random number is a pure function of (key, index): a counter-based generator
 * (a splitmix64 hash of the key and the counter, one of them to most of the ziggurat's
 * normal numbers), so
 * a value never depends on which thread drew what before it. A key is made from the
 * scene's seed, a stream (thermal, detector, z piezo) and a line of the scan; the index
 * counts the cycles (and the points or samples within them) from that line's start.
 *
 * Thermal noise (docs/dynamics.md, "Noise"): the Langevin force of the cantilever's
 * damping c at temperature T, white with two-sided power spectral density 2 c kB T, so
 * that the free cantilever's mean square thermal deflection is kB T / k. It is drawn at
 * `points` equally spaced times per drive cycle and interpolated linearly between them,
 * so the force stays continuous; the adaptive steppers end their steps on those times.
 * Its spectrum is 2 c kB T sinc^4(f dt) for dt = T_drive / points: flat to 0.2 % at the
 * drive frequency with 64 points, to 1 % up to 2.5 times it and to 10 % up to 8 times.
 *
 * Ownership: nothing is allocated here but the sim's own table (freed with the sim).
 */
#ifndef TIPTAP_NOISE_H
#define TIPTAP_NOISE_H

#include <stdint.h>

#include "tiptap/export.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

#define TT_BOLTZMANN 1.380649e-23 /* J/K */

/* The streams of a key: each kind of noise draws from its own. */
enum { TT_NOISE_THERMAL = 1, TT_NOISE_DETECTOR = 2, TT_NOISE_PIEZO = 3, TT_NOISE_ENVELOPE = 4 };

/* The key of (seed, stream, line). */
uint64_t tt_noise_key(uint64_t seed, unsigned stream, long line);
/* A standard normal number, a pure function of (key, index). */
double tt_noise_gauss(uint64_t key, uint64_t index);

/* Two independent standard normal numbers, a pure function of (key, index), by the
 * ziggurat (the envelope tier's draws, a few pairs a cycle, where the cost counts). */
void tt_noise_pair(uint64_t key, uint64_t index, double g[2]);

/* A position noise of one-sided density n (m/sqrt(Hz)) through a first-order low-pass of
 * corner fc, the z piezo's (docs/dynamics.md, "Noise"): an Ornstein-Uhlenbeck process of
 * variance n^2 pi fc / 2 and spectrum n^2 / (1 + (f / fc)^2), sampled exactly every dt,
 * z' = a z + b g with a = exp(-2 pi fc dt), b = sd sqrt(1 - a^2), g a standard normal of
 * (key, index): so a stretch drawn again draws the same. */
typedef struct {
    double sd, a, b;
} tt_noise_ou;

/* The process of density n and corner fc sampled every dt. TT_EINVAL unless n >= 0, fc > 0
 * and fc <= 1 / (2 dt) (the samples' Nyquist frequency), all finite. */
int tt_noise_ou_init(tt_noise_ou *p, double n, double fc, double dt);
/* The first sample: from the stationary distribution (index 0 of key). */
double tt_noise_ou_first(const tt_noise_ou *p, uint64_t key);
/* The sample after z, drawing index (1 and up) of key. */
double tt_noise_ou_next(const tt_noise_ou *p, uint64_t key, uint64_t index, double z);

/* Thermal force noise at temperature (K) on `points` times per cycle (temperature 0:
 * off, the default). TT_EINVAL when points < 4, or for rk4 when its steps_per_cycle
 * is not a multiple of points (its grid must hold the interpolation's corners). The free
 * flight (exact steps of the noiseless oscillator) is off while noise is on. */
int tt_sim_set_thermal(tt_sim *sim, double temperature, int points);
/* The key of the thermal noise from now on; its cycle counter restarts at 0. */
void tt_sim_noise_key(tt_sim *sim, uint64_t key);

TT_END_DECLS
#endif
