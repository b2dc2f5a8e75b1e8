/* The sim's private state and the equation of motion (Burnham et al. eq. 2) that every
 * stepper integrates: the right-hand side, the drive and the energy. Private to libtiptap.
 *
 * The state vector carries the motion (d, v) and, as extra components integrated by
 * the same steps, the per-cycle integrals that give the observables: the Fourier
 * sums of the deflection, the energies, the contact time. */
#ifndef TIPTAP_SOLVER_SIM_H
#define TIPTAP_SOLVER_SIM_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "tiptap/solver/integrator.h"

enum {
    Y_D,      /* tip position */
    Y_V,      /* tip velocity */
    Y_WDRIVE, /* drive work */
    Y_WDAMP,  /* cantilever damping loss */
    Y_WCI,    /* interaction damping loss */
    Y_WVISC,  /* the sample's viscous loss (the law's viscous force) */
    Y_WS,     /* work on a moving sample */
    Y_IC,     /* integral of y cos(w t) */
    Y_IS,     /* integral of y sin(w t) */
    Y_IY,     /* integral of y */
    Y_TC,     /* time in contact */
    NY
};

/* The state's layout for a system of dimension n: [the modes' (q, q') and the law's
 * states: n][the quadratures Y_WDRIVE..Y_TC: NQ], quadrature q at index n + q - Y_WDRIVE;
 * n = 2 is the enum above. The arrays are sized for the largest system (NYMAX). */
enum { NQ = NY - Y_WDRIVE, NYMAX = TT_SIM_DIM_MAX + NQ };

typedef struct tt_step_type tt_step_type;

/* The system the steps integrate, planned when the sim is made (system.c): its dimension
 * (position and velocity of each mode, the quadratures after them) and its kernels, the
 * right-hand side and the energy, and what they read: the modes, the contact, the sample's
 * motion and the thermal force. The one-mode elastic system (n = 2) has specialised
 * kernels (sim.h's rhs_with and energy); the generic ones loop over the modes and equal
 * them bit for bit at n = 2 (tests/test_system.c). Mode 0 is the tip's position, each
 * further mode i a deflection q_i (m_i q_i'' + c_i q_i' + k_i q_i = the force on the
 * tip) added to it. The law's internal states (a viscoelastic sample's) follow the
 * modes, first-order components integrated by the same steps. */
enum { TT_MODES_MAX = 4 };
typedef struct {
    int n;         /* 2 per mode, then the law's states; the quadratures start at index n */
    int modes;
    int nlaw;      /* the law's internal states, at index 2 modes (0: an elastic law) */
    int generic;   /* the generic kernels asked for (tt_system_plan) */
    double m[TT_MODES_MAX], k[TT_MODES_MAX], c[TT_MODES_MAX];
    double inv_m[TT_MODES_MAX]; /* 1 / m: the right-hand side multiplies rather than divides */
    double base[TT_MODES_MAX];  /* g_i m_i w^2: a base drive's inertial force per z (i >= 1) */
    double base2[TT_MODES_MAX]; /* g_i m_i w2^2: the same for mode 2's drive */
    double th2;                 /* mode 2's drive phase at the cycle's start, rad */
    const tt_contact *contact;
    const tt_contact_law *law; /* its row: the state's rate and the surface (nlaw > 0) */
    /* the law's time-loop kernel, chosen when the contact is set (tt_sim_set_contact):
     * one indirect call, no dispatch among the laws per evaluation */
    tt_contact_forces (*force)(const tt_contact *c, double ci, double delta, double rate,
                               int in_contact, const double *state);
    double ci;           /* the law's interaction damping coefficient c_i = m* w0 / Q_i, kg/s */
    double jumpin, jumpout, margin;
    /* sample: s(tau) = s0 + sdot tau within the current cycle */
    double s0, sdot;
    /* the thermal force (noise.c): the Langevin force at the cycle's nz_n + 1 equally spaced
     * points, linear between them; NULL when off */
    double *nz_f;
    int nz_n;
    double nz_dt, nz_sigma, nz_temp; /* nz_sigma: mode 0's; each mode i its own at nz_f + i (nz_n + 1) */
    uint64_t nz_key;
    long nz_cycle;       /* cycles drawn since the key was set */
    void (*rhs)(const tt_sim *S, double tau, const double *Y, int contact, double *Fo);
    double (*energy)(const tt_sim *S, double tau, const double *Y, int contact);
} tt_system;

/* The evolve loop's own state: the system (cantilever, contact, sample, thermal force),
 * the state vector and the cycle's bookkeeping. The step types keep their own state
 * behind `step` (stepper.h); they write only the current step's record below. */
struct tt_sim {
    tt_cantilever c;
    tt_solver solver;
    tt_system sys;            /* dimension and kernels (system.c) */
    const tt_step_type *type; /* the method's steps (stepper.h) */
    void *step;               /* the step type's own state (type->alloc) */
    /* state */
    long cycle;          /* completed cycles */
    double tau;          /* time within the cycle, s */
    double y[NYMAX];
    int contact_state;
    /* first-same-as-last derivative at (tau, y), valid while fsal_ok */
    double fsal[NYMAX];
    int fsal_ok;
    /* the current step, written by the step type: its start and length, the state and
     * the derivative at both ends (dydt_out unset after a long step) */
    double step_tau, step_h;
    double y0[NYMAX], y1[NYMAX], dydt_in[NYMAX], dydt_out[NYMAX];
    int step_long;       /* a long exact step (flight): no derivative at its end, and its
                          * ends too far apart to stand for the turning points between */
    /* sampling */
    int nsamp;
    tt_sample *samples;
    int next_sample;
    double *mode_samples; /* each mode's deflection at each sample (tt_sim_set_mode_sampling) */
    /* probes: the state at further times within each cycle (tt_sim_set_probes) */
    int nprobe, next_probe;
    const double *probe_tau;
    tt_sample *probes;
    int track_extremes;
    int skip_peaks;      /* peak force and indentation not asked for (tt_sim_track_peaks) */
    /* per-cycle accumulators outside the state vector */
    double peak_force, max_indent, y_min, y_max, e_jumps, t_contact, t_release;
    double switched_at; /* tau of the cycle's last contact switch (-1: none yet) ... */
    int switches_there; /* ... and how many were made at that instant */
    int switches_near;  /* ... and within 1e-12 T of one another (events.c) */
    long steps, rejected, events;
    long work; /* steps and rejected steps over the sim's life (tt_sim_work) */
};

/* The length of the state in use: the system's n components and the quadratures. */
static inline int sim_ny(const tt_sim *S)
{
    return S->sys.n + NQ;
}

/* The quadratures of a state Y of the sim's system: q[Y_WDRIVE] .. q[Y_TC]. */
static inline const double *sim_quad(const tt_sim *S, const double *Y)
{
    return Y + S->sys.n - Y_WDRIVE;
}

/* Copy a state of the sim's length: a fixed-size copy for the one-mode elastic system
 * (inlined moves), the used length otherwise. */
static inline void sim_copy(const tt_sim *S, double *dst, const double *src)
{
    if (S->sys.n == 2)
        memcpy(dst, src, NY * sizeof *dst);
    else
        memcpy(dst, src, (size_t)sim_ny(S) * sizeof *dst);
}

/* The law's internal states within a state Y of the system (NULL: an elastic law). */
static inline const double *tt_system_law_state(const tt_sim *S, const double *Y)
{
    return S->sys.nlaw ? Y + 2 * S->sys.modes : NULL;
}

/* The run's time at tau within the current cycle, s. */
static inline double sim_time(const tt_sim *S, double tau)
{
    return (double)S->cycle * S->c.T + tau;
}

/* Draw the thermal force's points of the cycle about to start (noise.c). */
void tt_noise_cycle(tt_sim *S);
/* The next of the force's points after tau, at least hmin past it (noise.c). */
double tt_noise_next_knot(const tt_sim *S, double hmin);

/* Mode i's own Langevin force at tau (linear between the cycle's points, so continuous). */
static inline double noise_force_mode(const tt_sim *S, double tau, int i)
{
    const double *nz = S->sys.nz_f;
    double u = tau / S->sys.nz_dt;
    int j = (int)u;
    if (j >= S->sys.nz_n)
        j = S->sys.nz_n - 1;
    if (j < 0)
        j = 0;
    double f = u - j;
    nz += i * (S->sys.nz_n + 1);
    return nz[j] + f * (nz[j + 1] - nz[j]);
}

/* The thermal force at tau on mode 0 (the one-mode system's). */
static inline double noise_force(const tt_sim *S, double tau)
{
    return noise_force_mode(S, tau, 0);
}


/* sin and cos of a drive phase in [0, 2 pi] and a little beyond, to within 2 ulp:
 * quadrant reduction with a two-part pi/2 and Taylor polynomials on [-pi/4, pi/4].
 * The library's sincos is a third of the run time otherwise, and the phase here is
 * always small, so its general argument reduction is not needed. */
static inline void phase_sincos(double x, double *sn, double *cs)
{
    static const double pio2_hi = 1.57079632679489655800e+00, pio2_lo = 6.12323399573676603587e-17;
    /* round to the nearest quadrant inline: nearbyint is a library call without SSE4.1 */
    double u = x * (2.0 / M_PI) + 0.5;
    long qi = (long)u;
    if (u < (double)qi)
        qi--; /* truncation rounds a negative u up */
    double q = (double)qi;
    double r = (x - q * pio2_hi) - q * pio2_lo;
    double r2 = r * r;
    double s = r * (1 + r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 * (1.0 / 362880 +
               r2 * (-1.0 / 39916800 + r2 * (1.0 / 6227020800 + r2 * (-1.0 / 1307674368000))))))));
    double c = 1 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 +
               r2 * (-1.0 / 3628800 + r2 * (1.0 / 479001600 + r2 * (-1.0 / 87178291200 +
               r2 * (1.0 / 20922789888000))))))));
    switch (qi & 3) {
    case 0: *sn = s; *cs = c; break;
    case 1: *sn = c; *cs = -s; break;
    case 2: *sn = -s; *cs = -c; break;
    default: *sn = -c; *cs = s; break;
    }
}

/* Base position and velocity, drive force, of the first drive alone: the one-mode
 * kernels' (mode 2's drive needs modes >= 2, which the generic kernels serve). */
static inline void drive1_at(const tt_sim *S, double tau, double *z, double *zd, double *F,
                             double *cw, double *sw)
{
    const tt_cantilever *c = &S->c;
    double sn, cs;
    phase_sincos(c->wd * tau, &sn, &cs);
    *cw = cs;
    *sw = sn;
    if (c->drive == TT_DRIVE_BASE) {
        *z = c->a_d * cs;
        *zd = -c->a_d * c->wd * sn;
        *F = 0;
    } else {
        *z = 0;
        *zd = 0;
        *F = c->F0 * cs;
    }
}

/* Base position and velocity, drive force: both drives. */
static inline void drive_at(const tt_sim *S, double tau, double *z, double *zd, double *F,
                            double *cw, double *sw)
{
    const tt_cantilever *c = &S->c;
    double sn, cs;
    drive1_at(S, tau, z, zd, F, cw, sw);
    if (c->A2 > 0) {
        /* mode 2's drive, on the clock of whole periods of the first (sim.c) */
        phase_sincos(c->wd2 * tau + S->sys.th2, &sn, &cs);
        *z += c->a_d2 * cs;
        *zd -= c->a_d2 * c->wd2 * sn;
        *F += c->F02 * cs;
    }
}

/* Mode 2's base drive alone at tau (0 without it): the further modes' inertial force
 * is g_n m_n w^2 z per frequency. */
static inline double drive2_z(const tt_sim *S, double tau)
{
    const tt_cantilever *c = &S->c;
    if (!(c->A2 > 0) || c->drive != TT_DRIVE_BASE)
        return 0.0;
    double sn, cs;
    phase_sincos(c->wd2 * tau + S->sys.th2, &sn, &cs);
    return c->a_d2 * cs;
}

/* The drive at one time: radau's Newton iteration reuses it at its stage times. */
typedef struct {
    double z, zd, F, cw, sw;
} drive_val;

/* The tip-sample force on the contact branch at the tip's (d, v) at tau with the law's
 * state q (NULL: none), the penetration and its rate in *delta, *deltad. */
static inline tt_contact_forces tip_forces(const tt_sim *S, double tau, double d, double v,
                                           int contact, const double *q, double *delta,
                                           double *deltad)
{
    double s = S->sys.s0 + S->sys.sdot * tau;
    *delta = d - s;
    *deltad = v - S->sys.sdot;
    tt_contact_forces f = {0.0, 0.0, 0.0};
    if (S->sys.contact)
        f = S->sys.force(S->sys.contact, S->sys.ci, *delta, *deltad, contact, q);
    return f;
}

/* The right-hand side: Burnham et al. eq. 2 plus the per-cycle integrals. The contact
 * state is fixed for the whole step (docs/physics.md: never flip it inside the
 * right-hand side; events flip it). */
static inline void rhs_with(const tt_sim *S, double tau, const drive_val *dv, const double *Y,
                            int contact, double *Fo)
{
    const tt_cantilever *c = &S->c;
    double z = dv->z, zd = dv->zd, Fd = dv->F, cw = dv->cw, sw = dv->sw;
    double d = Y[Y_D], v = Y[Y_V];
    double delta, deltad;
    tt_contact_forces f = tip_forces(S, tau, d, v, contact, NULL, &delta, &deltad);
    double P = f.conservative, Fi = f.dissipative;
    double spring = c->k * (d - z), damp = c->c * (v - zd);
    double y = d - z;
    Fo[Y_D] = v;
    Fo[Y_V] = (-damp - spring - P - Fi + Fd) * S->sys.inv_m[0];
    Fo[Y_WDRIVE] = Fd * v - (spring + damp) * zd;
    Fo[Y_WDAMP] = damp * (v - zd);
    Fo[Y_WCI] = (Fi - f.viscous) * deltad;
    Fo[Y_WVISC] = f.viscous * deltad;
    Fo[Y_WS] = (P + Fi) * S->sys.sdot;
    Fo[Y_IC] = y * cw;
    Fo[Y_IS] = y * sw;
    Fo[Y_IY] = y;
    Fo[Y_TC] = contact ? 1.0 : 0.0;
}

/* The right-hand side with the drive evaluated at tau (system.c): the system's kernel,
 * specialised (tt_sim_rhs) or generic (tt_system_rhs_n), chosen when it is planned. */
void tt_sim_rhs(const tt_sim *S, double tau, const double *Y, int contact, double *Fo);
void tt_system_rhs_n(const tt_sim *S, double tau, const double *Y, int contact, double *Fo);
/* The energy (system.c), specialised (tt_sim_energy) or generic. */
double tt_sim_energy(const tt_sim *S, double tau, const double *Y, int contact);
double tt_system_energy_n(const tt_sim *S, double tau, const double *Y, int contact);
/* Plan the system of the sim's cantilever (one mode) and its contact law's states: the
 * specialised kernels for an elastic law, or the generic ones when generic is set (for
 * the test of their equality) or the law has internal states. */
void tt_system_plan(tt_sim *S, int generic);
/* The depression of the sample's surface below s by the law's state (m, 0 for an
 * elastic law) at fraction th of the current step, on its dense output (system.c): the
 * surface the events locate contact against. */
double tt_system_surface_at(const tt_sim *S, double th);

/* The derivative at the current state, for a step's first stage: kept from the last
 * step's end (first same as last) unless the state changed since. */
static inline void ensure_fsal(tt_sim *S)
{
    if (!S->fsal_ok) {
        S->sys.rhs(S, S->tau, S->y, S->contact_state, S->fsal);
        S->fsal_ok = 1;
    }
}

#endif
