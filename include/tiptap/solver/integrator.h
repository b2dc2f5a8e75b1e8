/* tiptap: time integration of the tapping cantilever, one drive cycle at a time.
 *
 * A tt_sim advances the cantilever of tt_cantilever against one material's force law
 * (tt_contact) through whole drive cycles. The contact state is part of the state and
 * flips only at located events (jump-in, pull-off; docs/physics.md), never inside a step.
 * Time is kept as (cycle index, time within the cycle), so the drive phase never
 * drifts however long the run. Each cycle yields the observables of tt_cycle, computed
 * as integrals carried along by the same integrator (so they are as accurate as the
 * motion), and an energy-balance residual that estimates the run's integration error.
 *
 * The settings come from a scene by tt_solver_from_scene (tiptap/config/solver_scene.h).
 *
 * Usage (initialise, iterate, test):
 *   tt_sim_alloc(&sim, &cantilever, &solver);
 *   tt_sim_set_contact(sim, contact, Qi);
 *   tt_sim_set_sample(sim, gap, 0);
 *   tt_sim_reset_free(sim);
 *   while (...) { tt_sim_cycle(sim, &cycle); ... }
 *
 * Ownership: the sim keeps pointers to the tt_contact given to it (not copies); they
 * must outlive their use. A sim is used by one thread at a time.
 */
#ifndef TIPTAP_INTEGRATOR_H
#define TIPTAP_INTEGRATOR_H

#include "tiptap/export.h"
#include "tiptap/physics/cantilever.h"
#include "tiptap/physics/contact.h"

TT_BEGIN_DECLS

typedef enum { TT_METHOD_DOPRI5 = 0, TT_METHOD_RK4 = 1, TT_METHOD_RADAU = 2 } tt_method;

/* Which cycles a scan integrates (docs/dynamics.md, Tiers): every one, those the
 * envelope tier's error control asks for (tiptap/solver/envelope.h), or none: the
 * averaged preview tier follows the slow flow of amplitude and phase instead
 * (tiptap/solver/averaged.h). */
typedef enum { TT_TIER_EVERY = 0, TT_TIER_ENVELOPE = 1, TT_TIER_AVERAGED = 2, TT_TIER_COUNT = 3 } tt_tier;
/* The tiers' names in enum order ("every", "envelope", "averaged"; "?" for no tier): the
 * one table the scene's [solver] tier, the outputs and the console's page read. A tier
 * named (0) or -1 for a name that is none; tt_tier_count for a caller that lists them by
 * index (TT_TIER_COUNT). */
const char *tt_tier_name(tt_tier t);
int tt_tier_parse(const char *name, tt_tier *t);
int tt_tier_count(void);

typedef struct {
    tt_method method;
    double tolerance;     /* dopri5, radau: local error per step relative to the free amplitude */
    int steps_per_cycle;  /* rk4 */
    tt_tier tier;         /* scans only */
} tt_solver;

/* Defaults: dopri5, tolerance 1e-8, rk4 at 512 steps per cycle, every cycle. */
void tt_solver_default(tt_solver *s);
const char *tt_method_name(tt_method m);

/* What one drive cycle did. Energies in J per cycle. */
typedef struct {
    double amplitude;        /* fundamental of the deflection y = d - z, m */
    double phase;            /* its lag behind the drive, rad (pi/2 at free resonance) */
    double mean;             /* mean deflection, m */
    double y_min, y_max;     /* extremes of the deflection at step ends and events, m
                              * (only with tt_sim_track_extremes; else +-INFINITY) */
    double peak_force;       /* greatest tip-sample force (load + interaction damping), N */
    double max_indentation;  /* greatest penetration d - s, m (negative: a gap remained) */
    double contact_fraction; /* fraction of the cycle in contact */
    double e_drive;          /* work done by the drive */
    double e_damp;           /* lost to the cantilever's damping */
    double e_ts;             /* lost in the tip-sample interaction: the three below */
    double e_hyst;           /* ... of it to adhesion hysteresis (the jumps' energy) */
    double e_ci;             /* ... to interaction damping (c_i, the oscillator's) */
    double e_visc;           /* ... to the sample's viscosity (Kelvin-Voigt); NAN where a
                              * tier does not book the mechanisms apart */
    double e_sample;         /* work done on a moving sample (ramps, scans) */
    double residual;         /* e_drive - e_damp - e_ts - e_sample - (E_end - E_start) */
    double residual_rel;     /* |residual| relative to the free oscillation's loss per cycle,
                              * pi c w A0^2: the run's error estimate, also where the drive
                              * work itself is small (capture, transients) */
    double t_contact;        /* time of the cycle's first jump-in from its start, s (NAN: none) */
    double t_release;        /* time of the cycle's last pull-off from its start, s (NAN: none) */
    long steps;              /* accepted steps */
    long rejected;           /* rejected steps (dopri5, radau; radau counts Newton failures) */
    long events;             /* contact changes */
} tt_cycle;

/* A state sample at a fixed time within a cycle (see tt_sim_set_sampling). */
typedef struct {
    double t;       /* s, absolute */
    double z;       /* base position, m */
    double d, v;    /* tip position (m) and velocity (m/s) */
    double s;       /* sample surface position, m */
    int contact;
    /* a sample with internal states (relaxation arms): its surface's depression below
     * s, m (at the tip in contact, where the arms let it be out; 0 for an elastic
     * law), and the tip-sample force there, N (NAN for an elastic law, which
     * tt_sim_force computes from d - s alone) */
    double u, f;
    /* and the law's states there (not written for an
     * elastic law): the envelope tier's thermal noise measures their flow */
    double q[TT_CONTACT_ARMS_MAX];
} tt_sample;

typedef struct tt_sim tt_sim;

int tt_sim_alloc(tt_sim **out, const tt_cantilever *c, const tt_solver *solver);
void tt_sim_free(tt_sim *sim);

/* The force law under the tip (NULL: no sample interaction) and the interaction
 * quality factor Q_i (NAN or <= 0: no interaction damping); c_i = m* w0 / Q_i. */
void tt_sim_set_contact(tt_sim *sim, const tt_contact *contact, double Qi);

/* Sample surface position s (m, along the axis into the sample) at the start of the
 * next cycle, moving at sdot (m/s) through it. With the base at rest at 0, s is the
 * rest separation (gap) of the scene. */
void tt_sim_set_sample(tt_sim *sim, double s, double sdot);

/* Record n samples per cycle at t = k T / n (k = 0 .. n-1) into buf (NULL: none). */
void tt_sim_set_sampling(tt_sim *sim, int n, tt_sample *buf);
/* The buffer the samples go to (NULL: none). */
const tt_sample *tt_sim_samples(const tt_sim *sim);
/* With the samples, each mode's own deflection at each (mode 0's d - z, the further
 * modes' q_n) into buf[k * modes + i] for sample k, mode i: what an optical lever weighs
 * mode by mode (the thermal tune). buf holds n * modes doubles (NULL: none). */
void tt_sim_set_mode_sampling(tt_sim *sim, double *buf);

/* Record the state at n more times within each cycle, tau[0] < ... < tau[n-1] in
 * [0, T) from the cycle's start, into buf (buf or tau NULL: none): the envelope tier's
 * probes of the tip's closest approach (tiptap/solver/graze.h); their base position z
 * is not computed (NAN). The sim keeps both
 * pointers; they must outlive their use. */
void tt_sim_set_probes(tt_sim *sim, int n, const double *tau, tt_sample *buf);
/* The buffer the probes go to (NULL: none). */
const tt_sample *tt_sim_probes(const tt_sim *sim);

/* Change the cantilever's constants (a ramp of its stiffness), keeping the state and
 * the interaction damping coefficient. The drive frequency must stay the same. */
void tt_sim_set_cantilever(tt_sim *sim, const tt_cantilever *c);
const tt_cantilever *tt_sim_cantilever(const tt_sim *sim);
/* The method and tolerance it integrates with. */
const tt_solver *tt_sim_solver(const tt_sim *sim);

/* Track the deflection's extremes in each cycle (costs a little; off by default). */
void tt_sim_track_extremes(tt_sim *sim, int on);

/* Track the peak force and the greatest indentation of each cycle (on by default). Off,
 * they read NAN: a scan that records neither skips the force evaluations they take. */
void tt_sim_track_peaks(tt_sim *sim, int on);

/* Put the cantilever in its free steady oscillation at a cycle start, out of contact. */
void tt_sim_reset_free(tt_sim *sim);

/* Advance one drive cycle. TT_ENUM with a message if the solution fails (NaN, step
 * size underflow, rk4 steps too coarse for the contact stiffness, radau's Newton
 * iteration failing at an event); TT_EINTR when cancellation is requested
 * (util/cancel.h: polled at the cycle's start and every 1024 steps), the cycle then
 * unfinished and the sim at a step within it. */
int tt_sim_cycle(tt_sim *sim, tt_cycle *out);

/* Run cycles until amplitude and phase settle: the remaining change, extrapolated
 * from the geometric decay of successive changes, is below tol (relative to the free
 * amplitude, and in rad); at most max_cycles. *settled tells whether it did. The last
 * cycle is returned in out. TT_EINTR when cancelled, as tt_sim_cycle. */
int tt_sim_settle(tt_sim *sim, long max_cycles, double tol, tt_cycle *out, int *settled,
                  long *cycles);

/* The longest orbit tt_sim_settle_orbit looks for, in cycles, and the window of last
 * cycles its means are taken over when it finds none. Over a soft, sticky sample the
 * jump-ins lock into long patterns (periods 4, 10, 11, 15, 20, 27 and 41 on the polymer
 * blend's matrix between 2 and 10 nm: docs/dynamics.md, Settling). */
#define TT_SETTLE_MAX_PERIOD 64
#define TT_SETTLE_WINDOW 64

/* How tt_sim_settle_orbit ended. */
typedef struct {
    int settled;       /* amplitude and phase settled: steady (period 1) or repeating */
    int period;        /* the orbit's period in cycles: 1 a steady oscillation, 2 to
                        * TT_SETTLE_MAX_PERIOD a period-n orbit (jump-ins in some cycles
                        * and not in others, period doubling); 0 none found within
                        * max_cycles (chaos, or a transient slower than max_cycles) */
    int window;        /* cycles the observables are the mean of: the period, or the last
                        * TT_SETTLE_WINDOW cycles (fewer if fewer ran) when none */
    long cycles;       /* cycles run */
    double amp_min, amp_max; /* the amplitude's range over those cycles, m */
    double amp_change; /* its mean change per cycle, m: over one period of an orbit (so its
                        * phases do not pass for a drift), else over the window */
    double max_indentation; /* the greatest of their max_indentation, m */
} tt_settle_result;

/* As tt_sim_settle, and an orbit that repeats every n cycles (2 <= n <=
 * TT_SETTLE_MAX_PERIOD: amplitude and phase drift over n cycles by less than tol,
 * extrapolated, and spread over them by more than tol and ten times that drift, through
 * n + 2 cycles in a row) is settled too. out: the last cycle of a steady oscillation
 * (exactly what tt_sim_settle returns, which stops at the same cycle); the mean of the
 * orbit's n cycles (tt_cycle_mean); or, when neither was found within max_cycles, the
 * mean of the last TT_SETTLE_WINDOW cycles. TT_EINTR when cancelled, as tt_sim_cycle. */
int tt_sim_settle_orbit(tt_sim *sim, long max_cycles, double tol, tt_cycle *out,
                        tt_settle_result *res);

/* What settling watches instead of each cycle's amplitude and phase: after each cycle
 * fn gives n values (1 to TT_SETTLE_OBSERVED, each in the units of tol: relative to the
 * free amplitude, or rad), or an error that ends the settling. A bimodal approach watches
 * its lock-ins' outputs, in which mode 2's incommensurate drive is filtered out. */
#define TT_SETTLE_OBSERVED 4
typedef int (*tt_settle_observe_fn)(void *user, const tt_cycle *c, double *values);
typedef struct {
    tt_settle_observe_fn fn;
    void *user;
    int n;
    long min_cycles; /* none settles sooner: a filter's memory of where it started */
} tt_settle_observer;

/* As tt_sim_settle_orbit with the observer's values as the sequences that must settle
 * (or repeat); out is the mean of the last TT_SETTLE_WINDOW cycles (fewer if fewer ran)
 * whatever the period, and res->window their count. TT_EINVAL for n out of range. */
int tt_sim_settle_observed(tt_sim *sim, long max_cycles, double tol, const tt_settle_observer *obs,
                           tt_cycle *out, tt_settle_result *res);

/* The observables of cycles c[0..n) taken together, as over one period of an orbit:
 * amplitude and phase of their mean fundamental (what a lock-in reads over the n
 * cycles), the means of the mean deflection, peak force, indentation, contact fraction,
 * energies and residual (the energy balance holds for the means), the deflection's
 * extremes over all n, the largest residual_rel, the first cycle's contact time and
 * the last release (NAN: none) among them, and the steps per cycle rounded. n = 1 gives
 * c[0] unchanged. */
void tt_cycle_mean(const tt_cycle *c, int n, tt_cycle *out);

/* Absolute time at the current cycle start, s; cycles completed. */
double tt_sim_time(const tt_sim *sim);
long tt_sim_cycles(const tt_sim *sim);
/* The steps, accepted and rejected, of every cycle the sim integrated since it was
 * made: a measure of what its runs cost that does not depend on the machine (the
 * error estimate's budget, tt_scan_estimate_error). */
long tt_sim_work(const tt_sim *sim);
void tt_sim_get_state(const tt_sim *sim, double *d, double *v, int *contact);
void tt_sim_set_state(tt_sim *sim, double d, double v, int contact);
/* The state of the cycle map in any dimension: the system's n components (position and
 * velocity of each mode, then the sample's internal states; tt_sim_dim gives n, at most
 * TT_SIM_DIM_MAX) and the contact branch. x holds n doubles, owned by the caller.
 * tt_sim_get_state/set_state are its first two components (mode 0). */
enum { TT_SIM_DIM_MAX = 16 };
int tt_sim_dim(const tt_sim *sim);
void tt_sim_get_x(const tt_sim *sim, double *x, int *contact);
void tt_sim_set_x(tt_sim *sim, const double *x, int contact);
/* Tip-sample force (N) for a recorded sample, on the sim's current material. */
double tt_sim_force(const tt_sim *sim, const tt_sample *smp, double *a);

TT_END_DECLS
#endif
