/* tiptap: parameter grids over scene keys, for `tiptap sweep`.
 *
 * A grid is built from one or more "KEY=VALUES" specifications, each varying one scene
 * key (section.key, or section.NAME.key for named sections) over
 *   a list      "10 nm,20 nm,30 nm"   (any key: numbers with units, names, choices),
 *   a range     "10nm:30nm:5"         (FROM:TO:N, N values evenly spaced, ends included),
 *   a log range "log:1nm:100nm:3"     (N values evenly spaced in the logarithm).
 * The key "scene" instead reads each of a list of scene files over the base (before
 * the varied keys are set), for what no single key says: "scene=soft.ini,stiff.ini".
 * Several keys make the full grid; the combinations are numbered like nested loops,
 * the first key varying slowest. Combination i's scene is the base scene with its
 * values set, exactly as --set would set them, so every value is checked by the scene.
 *
 * Ownership: tt_sweep_alloc copies nothing of the base scene but borrows it (it must
 * outlive the sweep); tt_sweep_scene returns a new scene the caller frees. Strings the
 * accessors return belong to the sweep.
 */
#ifndef TIPTAP_CONFIG_SWEEP_H
#define TIPTAP_CONFIG_SWEEP_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/scene.h"

TT_BEGIN_DECLS

typedef struct tt_sweep tt_sweep;

/* The most combinations a grid may have: each is checked before the first runs, and a
 * sweep keeps every finished one's rows in memory until it writes its table. */
#define TT_SWEEP_MAX_COMBINATIONS 10000000

/* Refuse a grid of more than TT_SWEEP_MAX_COMBINATIONS combinations from its n
 * specifications alone, before any value is parsed or stored, so that neither time nor
 * memory grows with the count (which may be far beyond 2^64): TT_EINVAL with one line
 * naming the specifications and the count. Other faults of a specification are left
 * to tt_sweep_vary. */
int tt_sweep_check_size(const char *const *specs, size_t n);

int tt_sweep_alloc(tt_sweep **out, const tt_scene *base);
void tt_sweep_free(tt_sweep *sw);

/* Add a varied key from "KEY=VALUES"; TT_EINVAL with one line naming the key on a bad
 * key, value, unit or range, and on a grid that would grow beyond
 * TT_SWEEP_MAX_COMBINATIONS (checked before the values are stored). */
int tt_sweep_vary(tt_sweep *sw, const char *spec);

/* Number of varied keys and of combinations (1 when nothing varies). */
size_t tt_sweep_keys(const tt_sweep *sw);
size_t tt_sweep_count(const tt_sweep *sw);

/* Key k as written ("cantilever.free_amplitude"), and the SI unit of its values ("m";
 * "1" for fractions and plain numbers; "" for keys whose values are text). */
const char *tt_sweep_key(const tt_sweep *sw, size_t k);
const char *tt_sweep_unit(const tt_sweep *sw, size_t k);

/* Combination i's value of key k: the text set in the scene, its SI value (NAN for
 * text), and its position in the key's list. */
const char *tt_sweep_text(const tt_sweep *sw, size_t i, size_t k);
double tt_sweep_value(const tt_sweep *sw, size_t i, size_t k);
size_t tt_sweep_level(const tt_sweep *sw, size_t i, size_t k);
size_t tt_sweep_levels(const tt_sweep *sw, size_t k);

/* 1 when the grid's scenes may be viscous: a material of the base scene has a viscosity
 * or a film (tt_material_viscous), or a varied key is a material's viscosity or
 * film_thickness; the sweep's rows then carry the loss per mechanism. */
int tt_sweep_viscous(const tt_sweep *sw);

/* 1 when the grid's scenes drive mode 2 (bimodal AM-AM): the base scene sets
 * [cantilever] mode2_free_amplitude, or a varied key is it; a scan sweep's rows then
 * carry mode 2's amplitude and phase. */
int tt_sweep_bimodal(const tt_sweep *sw);

/* "cantilever.free_amplitude=10 nm, approach.material=disk" for messages. */
void tt_sweep_label(const tt_sweep *sw, size_t i, char *buf, size_t len);

/* Combination i's scene: a copy of the base with its values set. On a refused value
 * the error names the combination and the key. */
int tt_sweep_scene(const tt_sweep *sw, size_t i, tt_scene **out);

/* A 64-bit fingerprint of the grid (keys and value texts) mixed into h, so that a
 * journal of finished combinations is only resumed by the same sweep. */
unsigned long long tt_sweep_hash(const tt_sweep *sw, unsigned long long h);

TT_END_DECLS
#endif
