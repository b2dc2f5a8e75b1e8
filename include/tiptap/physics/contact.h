/* tiptap: tip-sample contact mechanics (Burnham et al. section 2.2, docs/physics.md).
 *
 * A tt_contact holds one material's force law: the Maugis-Dugdale curve (eq. 7) or one
 * of its limits (Hertz eq. 4, DMT eq. 5, JKR eq. 6), precomputed once into a table on
 * the stable branch with a Hertz tail, joined to the van der Waals branch (eq. 10 with
 * the sign fixed in docs/physics.md) at (P0, Delta0), and the jump-in / pull-off points of
 * the hysteresis loop. With w = 0 it is Hertz in physical units exactly: no table, no
 * van der Waals branch, no hysteresis.
 *
 * Conventions: delta is the penetration d - s in metres (positive into the sample,
 * negative for a gap); the load P is in newtons, positive when repulsive. The contact
 * state (in_contact) is part of the caller's state: it changes only at the events
 * delta >= tt_contact_jumpin() (approaching, out of contact) and
 * delta <= tt_contact_jumpout() (receding, in contact).
 *
 * Ownership: tt_contact_alloc returns an object the caller frees with tt_contact_free;
 * it is read-only after allocation and may be shared between threads.
 */
#ifndef TIPTAP_CONTACT_H
#define TIPTAP_CONTACT_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef enum {
    TT_CONTACT_MAUGIS = 0, /* Maugis-Dugdale, eq. 7, any lambda */
    TT_CONTACT_HERTZ,      /* eq. 4: no adhesion at all (w ignored) */
    TT_CONTACT_DMT,        /* eq. 5, with the van der Waals branch joined at (-2, 0) */
    TT_CONTACT_JKR         /* eq. 6: no force out of contact */
} tt_contact_model;

/* Parse "maugis", "hertz", "dmt", "jkr"; returns -1 if unknown. */
int tt_contact_model_parse(const char *name, tt_contact_model *out);
const char *tt_contact_model_name(tt_contact_model m);

/* The most relaxation arms a sample may have (tt_contact_params.arms). */
#define TT_CONTACT_ARMS_MAX 4

typedef struct {
    tt_contact_model model;
    double K;      /* reduced modulus, Pa (> 0) */
    double R;      /* reduced radius, m (> 0) */
    double w;      /* Dupre work of adhesion, J/m^2 (>= 0; 0 is exactly Hertz) */
    double xi0;    /* equilibrium interatomic distance, m (> 0 when w > 0 unless lambda given) */
    double lambda; /* Maugis parameter; NAN: derived from xi0 (Lennard-Jones, eq. 3) */
    /* the sample's own losses and support (contact_visco.c, docs/physics.md): both 0
     * leave the elastic law exactly as it is */
    double viscosity;      /* Kelvin-Voigt viscosity eta, Pa s (>= 0): the law adds
                            * eta a(delta) ddelta/dt in contact, a the contact radius */
    double film_thickness; /* m (>= 0; 0: bulk): a film bonded to a rigid substrate,
                            * Garcia & Garcia's bottom-effect series (Hertz law only) */
    /* relaxation arms (contact_sls.c, docs/physics.md): a generalised Maxwell sample,
     * K its relaxed (equilibrium) modulus and each arm a Maxwell element in parallel,
     * its modulus in K's units (reduced, Pa, >= 0) and its relaxation time (s, > 0;
     * INFINITY: a spring that never relaxes); one arm is the standard linear solid. The
     * surface's position is the law's state, so it lags behind a tip that leaves.
     * Hertz law only; 0 arms leave the elastic law as it is */
    int arms;
    double arm_modulus[TT_CONTACT_ARMS_MAX];
    double arm_time[TT_CONTACT_ARMS_MAX];
} tt_contact_params;

typedef struct {
    int adhesive;          /* 0 when w = 0 or model = hertz: Hertz in physical units */
    double lambda;         /* Maugis parameter used (0 for DMT, INFINITY for JKR) */
    double force_scale;    /* F* = pi w R, N (0 when not adhesive) */
    double depth_scale;    /* d* = (pi^2 w^2 R / K^2)^(1/3), m */
    double radius_scale;   /* a* = (pi w R^2 / K)^(1/3), m */
    double xi0;            /* m, as used (derived from lambda when lambda was given) */
    /* normalised (eq. 3 units) */
    double P0, Delta0;     /* the A -> 0 end of the contact curve (eq. 8, exact) */
    double pulloff_load;   /* least load on the contact curve (load-controlled pull-off) */
    double pulloff_delta;  /* Delta where that least load occurs */
    double jumpout_delta;  /* least Delta on the stable branch: displacement-controlled pull-off */
    double jumpout_load;   /* load there */
    double jumpin_delta;   /* Delta where an approaching tip contacts (= Delta0) */
    double jumpin_load;    /* load on the stable branch just after jump-in */
    int hysteresis;        /* 1 when jumpout_delta < jumpin_delta (lambda above about 0.938) */
    /* physical */
    double hamaker;        /* J, by continuity at (P0, Delta0); 0 when no van der Waals branch */
    double loop_energy;    /* J: energy lost per approach-retract loop of a stiff tip */
} tt_contact_summary;

typedef struct tt_contact tt_contact;

/* The largest interatomic distance xi0, in depth scales d*, that a force law takes
 * (tt_contact_alloc and tt_contact_alloc_normalised refuse more with TT_EINVAL): its van
 * der Waals branch P0 (Delta0 - xi)^2 / (Delta - xi)^2 squares it, which overflows past
 * 1e154. Lennard-Jones surfaces within the Maugis range (lambda 1e-4 to 1e4, eq. 3)
 * have xi0 = 0.656 d* / lambda, 6.6e-5 to 6.6e3 d*. */
#define TT_CONTACT_XI0N_MAX 1e6

/* Build the force law (and its table). Fails with TT_EINVAL and a message naming the
 * parameter on bad input (K <= 0, NaN, ...). */
int tt_contact_alloc(tt_contact **out, const tt_contact_params *p);

/* The normalised curve of a model at a given lambda: the same object with
 * F* = d* = a* = 1 (R = 1, w = 1/pi, K = 1) and xi0 (normalised) = xi0n. */
int tt_contact_alloc_normalised(tt_contact **out, tt_contact_model model, double lambda,
                                double xi0n);

/* A force law given by the caller (teaching, tests): load(delta, in_contact, &dPdd, user)
 * in N and N/m, energy(delta, in_contact, user) in J with dU/ddelta = load, and the
 * event thresholds in m (jumpout <= jumpin). The caller keeps user alive. */
int tt_contact_alloc_custom(tt_contact **out,
                            double (*load)(double delta, int in_contact, double *dPdd, void *user),
                            double (*energy)(double delta, int in_contact, void *user), void *user,
                            double jumpin, double jumpout);

/* The contact law's local geometry where the tip meets the sample (docs/surfaces.md,
 * "The contact law's geometry at the contact point"): the cosine of the surface's slope
 * there (the contact normal's angle a to z) and the effective radius R_eff, 1/R_eff =
 * 1/R + 1/r for a feature of curvature radius r there (r > 0 convex, < 0 concave). */
typedef struct {
    double cos_slope; /* cos a, in (0, 1]; 1 on a flat */
    double R_eff;     /* m (> 0); the tip's radius on a flat */
} tt_contact_geometry;

/* The largest effective radius, in tip radii, a concave feature gives: a hollow as
 * curved as the tip (1/r = -1/R) would make R_eff infinite (a conforming contact no law
 * in the table describes), so R_eff is clamped here. */
#define TT_CONTACT_CONCAVE_MAX 10.0

/* The geometry for a tip of radius R (m) on a surface of slope angle a (cos_slope) whose
 * principal normal curvatures there are k1, k2 (1/m, positive convex): 1/R_eff =
 * sqrt((1/R + k1) (1/R + k2)), Hertz's equivalent radius of an elliptic contact (exact
 * for a sphere, k1 = k2 = 1/r), each factor at least 1 / (TT_CONTACT_CONCAVE_MAX R). */
tt_contact_geometry tt_contact_geometry_of(double R, double cos_slope, double k1, double k2);

/* The force law of p pressed on a feature of geometry g (NULL or a flat's: the same
 * law tt_contact_alloc builds, byte for byte): the penetration along the normal is
 * delta cos a and the load returned is the normal load's z part, P(delta cos a) cos a,
 * of the law at R_eff (Burnham et al. eq. 4 to 7 with R -> R_eff). Hertz, its
 * Kelvin-Voigt sample and relaxation arms are that exactly as Hertz at R_eff cos^5 a;
 * the film's series at R_eff with each term's cos a power; Maugis-Dugdale, DMT and JKR
 * rebuild their table at R_eff (lambda ~ R^(1/3), xi0 / d* ~ R^(-1/3)) and scale F* by
 * cos a and d* by 1 / cos a. The contact radius stays the normal contact's, except on
 * the Hertz rows (sqrt(R_eff cos^5 a delta)). Fails as tt_contact_alloc does, or with
 * TT_EINVAL for g outside its ranges. */
int tt_contact_alloc_local(tt_contact **out, const tt_contact_params *p,
                           const tt_contact_geometry *g);

/* base, a law built for a flat (tt_contact_alloc, or tt_contact_alloc_local with cos a
 * = 1), on a slope of cosine cos_slope in (0, 1]: the law tt_contact_alloc_local builds
 * for base's parameters at (cos_slope, base's radius), bit for bit, its table copied
 * and scaled rather than rebuilt (a copy of 307 kB against about 2 ms for a
 * Maugis-Dugdale table). */
int tt_contact_alloc_tilted(tt_contact **out, const tt_contact *base, double cos_slope);

void tt_contact_free(tt_contact *c);

const tt_contact_summary *tt_contact_summary_of(const tt_contact *c);

/* O(1): the load (N) at penetration delta (m) on the branch in_contact selects, its
 * derivative dP/ddelta (N/m) if dPdd is not NULL, and the contact radius (m) if a is
 * not NULL (0 out of contact). Each branch is continued smoothly and finitely a little
 * past its switch point, since the stages of a step may overshoot it. */
double tt_contact_load(const tt_contact *c, double delta, int in_contact, double *dPdd,
                       double *a);

/* Contact laws as a type table (after GSL's gsl_odeiv2_step_type and the solver's
 * step types): each law is one row of functions, and a tt_contact evaluates through the
 * row it was built with (tt_contact_law_of): Maugis-Dugdale, DMT and JKR through their
 * tables, Hertz in closed form, and the custom law of tt_contact_alloc_custom. A law
 * takes the penetration delta (m), its rate (m/s) and its own internal state
 * (state_size doubles; every law so far has state_size 0, state NULL) and gives the
 * conservative force (the load P = dU/ddelta, positive when repulsive) and the
 * dissipative force apart, since the energy balance books them apart. The dissipative
 * force is the interaction damping ci * rate in contact and 0 out of contact, where
 * ci = m* w0 / Q_i (kg/s) is the oscillator's, given at each call, plus the sample's
 * viscous force (the Kelvin-Voigt row, when the material has a viscosity or a film),
 * which it also gives alone so that the loss is booked per mechanism. */
typedef struct {
    double conservative; /* N: the load P */
    double dissipative;  /* N: the law's damping force, along the rate (viscous included) */
    double viscous;      /* N: the sample's viscous part of it (0 for the elastic rows) */
} tt_contact_forces;

/* The forces with their derivatives, for Jacobians and stiffness checks. */
typedef struct {
    tt_contact_forces f;
    double stiffness;    /* dP/ddelta, N/m */
    double damping;      /* d(dissipative)/d(rate), kg/s */
    double radius;       /* contact radius, m (0 out of contact, and for a custom law) */
} tt_contact_detail;

typedef struct tt_contact_law {
    const char *name;
    size_t state_size;   /* doubles of internal state the law carries (0: elastic) */
    /* the forces at (delta, rate) on the branch in_contact selects: the time loop's
     * evaluation, nothing more computed */
    tt_contact_forces (*force)(const tt_contact *c, double ci, double delta, double rate,
                               int in_contact, const double *state);
    /* the forces and their derivatives, and the contact radius */
    void (*detail)(const tt_contact *c, double ci, double delta, double rate, int in_contact,
                   const double *state, tt_contact_detail *out);
    /* the potential U (J) of the conservative force (tt_contact_energy); with internal
     * state, the energy the sample stores too */
    double (*energy)(const tt_contact *c, double delta, int in_contact, const double *state);
    /* a law with internal state (NULL otherwise): the state's rate d state/dt into
     * dstate at (delta, rate, state), and the power (W) its own dissipation takes, which
     * the energy balance books as the viscous loss */
    void (*rate)(const tt_contact *c, double delta, double rate, int in_contact,
                 const double *state, double *dstate, double *power);
    /* ... and where its surface is: the depression (m, >= 0) below the undisturbed
     * surface that the state holds it at with the tip away; contact begins and ends
     * when the penetration crosses it */
    double (*surface)(const tt_contact *c, const double *state);
} tt_contact_law;

/* The row c evaluates through (Hertz when w = 0, whatever the model). */
const tt_contact_law *tt_contact_law_of(const tt_contact *c);

/* The row's force and detail, through tt_contact_law_of(c). */
tt_contact_forces tt_contact_force(const tt_contact *c, double ci, double delta, double rate,
                                   int in_contact, const double *state);
void tt_contact_evaluate(const tt_contact *c, double ci, double delta, double rate, int in_contact,
                         const double *state, tt_contact_detail *out);

/* Potential energy (J) with dU/ddelta = P on the branch in_contact selects: U = 0 far
 * from the sample on the out-of-contact branch, and the contact branch continuous with
 * it at jump-in, so that U_contact(jumpout) - U_out(jumpout) is the loop energy. */
double tt_contact_energy(const tt_contact *c, double delta, int in_contact);

/* Hertz, DMT, JKR and Maugis-Dugdale all take the sphere for a paraboloid and the
 * contact for small against it, a << R, in linear elasticity (Johnson, Contact
 * Mechanics, 1985, sections 4.2 and 5.6). Against Sneddon's exact sphere (Int. J. Eng.
 * Sci. 3 (1965) 47) the paraboloid's load at a given indentation is 0.9 % high at
 * a = 0.3 R, 2.8 % at 0.5 R and 8 % at 0.75 R (at a given radius: 3.7 %, 11 %, 27 %
 * low), and the mean strain, about 0.2 a / R (Tabor), passes 10 % at 0.5 R, beyond the
 * linear range of polymers; past an indentation of R the sphere is buried to its
 * equator. The bound is 0.5 R, not 0.3 R, where the error is a percent
 * (docs/reliability.md, Tip shapes, lists the bundled examples beyond it). Returns 1
 * when a contact radius a (m) or an indentation delta (m) on a tip of radius R is
 * beyond these. */
#define TT_CONTACT_MAX_RADIUS_RATIO 0.5
int tt_contact_beyond_validity(double a, double delta, double R);

/* When a contact of radius a (m) at indentation delta (m) on a tip of radius R (m) is
 * beyond these (tt_contact_beyond_validity), raise the TT_WARN_VALIDITY warning
 * (tiptap/util/warning.h) that names the material, the figures and what keeps within
 * them (remedy: "a larger [tip] radius, ..."); returns whether it warned. Scans,
 * traces and approaches warn through it alike. */
int tt_contact_warn_validity(const char *material, double a, double delta, double R,
                             const char *remedy);

/* The event thresholds, m: an out-of-contact tip contacts when delta rises to
 * jumpin; an in-contact tip leaves when delta falls to jumpout (<= jumpin). */
double tt_contact_jumpin(const tt_contact *c);
double tt_contact_jumpout(const tt_contact *c);

/* Direct evaluation of eq. 7 at parameter m > 1 (normalised): A, Delta, P. For tests
 * and for the full curve in plots; never called in a time loop. */
void tt_contact_maugis_point(double lambda, double m, double *A, double *Delta, double *P);

/* The largest error of the tabulated load against direct evaluation of the curve
 * (eq. 7 for Maugis) at n points spread over the stable branch, relative to max(1, |P|)
 * in normalised units: the run's own check of its table (0 for closed forms). */
double tt_contact_table_error(const tt_contact *c, size_t n);

/* Sample the whole normalised contact curve (stable and unstable parts) of c at n
 * points ordered by A from near 0 to A_max: A, Delta, P, and stable (1 where
 * dDelta/dA > 0, the displacement-controlled stable branch). */
int tt_contact_curve(const tt_contact *c, size_t n, double A_max, double *A, double *Delta,
                     double *P, int *stable);

TT_END_DECLS
#endif
