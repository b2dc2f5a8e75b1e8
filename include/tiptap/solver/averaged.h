/* tiptap: the averaged preview tier's model (docs/dynamics.md, Tiers, Averaged).
 *
 * Krylov-Bogoliubov averaging of the equation of motion: the deflection is taken as
 * y = m0 + X cos(w t) + Y sin(w t) with (X, Y) slowly varying, so that
 *   2 m w X' = kappa Y - c w X - Fy,     2 m w Y' = f - kappa X - c w Y + Fx,
 * kappa = k - m w^2, f the drive's force amplitude on y, and (Fx, Fy) twice the means
 * over a cycle of the tip-sample force times cos(w t) and sin(w t); the mean deflection
 * is quasi-static, k m0 = the force's mean. The tip moves as d = m0 + B cos(w t - psi)
 * (the base's motion added to y's), so the force's harmonics depend on the tip's
 * amplitude B and its closest penetration x = m0 + B - s only, rotated by psi: they
 * are tabulated once per material over (B, x) (tt_averaged_alloc) with the hysteresis
 * of the contact by branch: out of contact at the cycle's far point (the tip touches
 * when x reaches jump-in and leaves when its penetration falls to pull-off), or stuck
 * (in contact all cycle: the oscillation has collapsed onto the sample, which the
 * averaged model cannot follow faithfully; tt_averaged_step says so).
 *
 * Ownership: tt_averaged_alloc returns a table the caller frees with tt_averaged_free;
 * it keeps a pointer to the force law (which must outlive it), is read-only after
 * allocation and may be shared between threads.
 */
#ifndef TIPTAP_AVERAGED_H
#define TIPTAP_AVERAGED_H

#include "tiptap/export.h"
#include "tiptap/physics/cantilever.h"
#include "tiptap/physics/contact.h"

TT_BEGIN_DECLS

enum { TT_AVG_HMAX = 8 }; /* harmonics the table can hold */

typedef struct tt_averaged tt_averaged;

/* The table of one material: its force law, interaction quality factor Qi (NAN or
 * <= 0: no interaction damping) and the harmonics the lock-in keeps (1 to TT_AVG_HMAX). */
int tt_averaged_alloc(tt_averaged **out, const tt_cantilever *c, const tt_contact *contact,
                      double Qi, int harmonics);
void tt_averaged_free(tt_averaged *a);

/* The force's cycle means at tip amplitude B (m) and closest penetration x (m): twice
 * the means of F cos(h theta) and F sin(h theta) (theta = w t - psi, the tip's own
 * phase; F the force on the cantilever, - load - interaction damping), the mean, the
 * peak of load + damping (N), the shift of the closest approach by the higher
 * harmonics of the motion they drive (m), and the partial derivatives of the first three in B and
 * x. direct: by quadrature, not from the table. outside: (B, x) beyond the table
 * (amplitude above 1.5 A0, or penetration more than A0 past jump-in), where the
 * values come from quadrature as well, at about 100 times the cost. */
typedef struct {
    double gc[TT_AVG_HMAX], gs[TT_AVG_HMAX];
    double mean, peak;
    double shift; /* the closest approach's shift by the harmonics h >= 2, m */
    double d_b[3], d_x[3]; /* d/dB and d/dx of gc[0], gs[0], mean */
    int outside;
} tt_averaged_force;

void tt_averaged_force_at(const tt_averaged *a, double B, double x, int stuck, int direct,
                          tt_averaged_force *f);

/* The table's largest error against direct quadrature at the middles of its cells where
 * the tip touches (x from jump-in to 5 nm past, B from a quarter to the whole free
 * amplitude), relative to k A0: the run's own check of its table. */
double tt_averaged_table_error(const tt_averaged *a);

/* The slow state: the deflection's first harmonic (X, Y) and mean m0, m; stuck: the
 * contact branch (1: in contact all cycle). */
typedef struct {
    double X, Y, m0;
    int stuck;
} tt_averaged_state;

/* The free steady oscillation. */
void tt_averaged_state_free(const tt_cantilever *c, tt_averaged_state *st);

/* One step of duration h (s) with the sample at rest separation s (m): the state
 * advanced (linearly implicit, second order in h on the slow flow's linearisation, A-
 * stable) and the step's outputs: per period the lock-in's components (the mean, then
 * per harmonic the in-phase and quadrature parts, averaged over the step: comp holds
 * 1 + 2 harmonics values), the peak force (N), the greatest penetration (m), the
 * tip-sample loss per cycle (J), and collapsed: where the averaged model is wrong:
 * the tip stuck (no tapping branch), the amplitude below a quarter of the free
 * amplitude, an impact (a step that would move X or Y by a tenth of A0, taken again
 * as L-stable halves) or forces beyond the averaging's premise (their mean over a
 * tenth of k A0, their harmonics' shift of the closest approach over a tenth of B),
 * the state then kept bounded; change: the step's largest change of X or Y over the free amplitude (the
 * caller's measure of whether h was short enough). */
typedef struct {
    double comp[1 + 2 * TT_AVG_HMAX];
    double peak, indent, ets, change;
    int collapsed, outside;
} tt_averaged_out;

void tt_averaged_step(const tt_averaged *a, tt_averaged_state *st, double s, double h,
                      tt_averaged_out *o);

/* The same step with the thermal force's impulse over it, kick = (X, Y) in m: the
 * white noise on the slow flow, sqrt(h) times tt_averaged_thermal_density times two
 * independent standard normals, added to the implicit solve's right-hand side, so that
 * the linearised flow's stationary covariance is kept exactly at any h; change
 * counts the flow's move alone (docs/dynamics.md, "Noise on the averaged tier"). */
void tt_averaged_step_noisy(const tt_averaged *a, tt_averaged_state *st, double s, double h,
                            const double kick[2], tt_averaged_out *o);

/* The square root of the two-sided intensity of the thermal force's white noise on each
 * of X' and Y' (m / sqrt(s)) at temperature (K): sqrt(kB T c) / (m w), w the drive's
 * angular frequency; 0 at temperature 0. */
double tt_averaged_thermal_density(const tt_cantilever *c, double temperature);

/* The seconds the tables of a scan took to build (a clock, for the report). */
double tt_averaged_build_seconds(const tt_averaged *a);

/* The table's nodes whose periodic law state (a sample's relaxation arms,
 * docs/dynamics.md) missed its tolerance in the build: 0 when every node met it. */
long tt_averaged_build_misses(const tt_averaged *a);

TT_END_DECLS
#endif
