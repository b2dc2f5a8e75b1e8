/* Time integration of the tapping cantilever with located contact events
 * (see include/tiptap/solver/integrator.h; seed eq. 2 with PHYSICS.md's conventions).
 *
 * The state vector carries the motion (d, v) and, as extra components integrated by
 * the same steps, the per-cycle integrals that give the observables: the Fourier
 * sums of the deflection, the energies, the contact time. Events are found on the
 * step's continuous extension (dense output), then the step is redone up to the event
 * so that the state at the switch is a true integration result. Out of contact and away
 * from the surface, dopri5 gives way to exact-propagator steps (flight_step), which
 * integrate the same quantities by quadrature and hand back before any event. */
#include "tiptap/solver/integrator.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

enum {
    Y_D,      /* tip position */
    Y_V,      /* tip velocity */
    Y_WDRIVE, /* drive work */
    Y_WDAMP,  /* cantilever damping loss */
    Y_WCI,    /* interaction damping loss */
    Y_WS,     /* work on a moving sample */
    Y_IC,     /* integral of y cos(w t) */
    Y_IS,     /* integral of y sin(w t) */
    Y_IY,     /* integral of y */
    Y_TC,     /* time in contact */
    NY
};

/* Free flight: Gauss-Legendre nodes on [0, 1] (the collocation points of the forcing
 * and the quadrature of the per-cycle integrals) and the step ladder. */
enum { FL_N = 6, FL_RUNGS = 12 };
static const double FL_C[FL_N] = {
    0.5 - 0.4662347571015760, 0.5 - 0.3306046932331323, 0.5 - 0.1193095930415985,
    0.5 + 0.1193095930415985, 0.5 + 0.3306046932331323, 0.5 + 0.4662347571015760};
static const double FL_W[FL_N] = {0.0856622461895852, 0.1803807865240693, 0.2339569672863455,
                                  0.2339569672863455, 0.1803807865240693, 0.0856622461895852};

/* The free oscillator's propagator and the drive's rotation at the nodes and the end
 * (index FL_N) of a step of length h. */
typedef struct {
    double h;
    double e[FL_N + 1], cd[FL_N + 1], sd[FL_N + 1]; /* exp(-sig tau), cos, sin(wdm tau) */
    double cw[FL_N + 1], sw[FL_N + 1];              /* cos, sin(w tau) */
    int ok;
} fl_cache;

struct tt_sim {
    tt_cantilever c;
    tt_solver solver;
    const tt_contact *contact;
    double ci;           /* interaction damping coefficient, kg/s */
    double inv_m;        /* 1 / m*: the right-hand side multiplies rather than divides */
    double jumpin, jumpout, margin;
    /* sample: s(tau) = s0 + sdot tau within the current cycle */
    double s0, sdot;
    /* state */
    long cycle;          /* completed cycles */
    double tau;          /* time within the cycle, s */
    double y[NY];
    int contact_state;
    double h;            /* dopri5: next step size */
    int rk4_j;           /* rk4: index of the next grid point in the cycle */
    /* first-same-as-last derivative at (tau, y), valid while fsal_ok */
    double fsal[NY];
    int fsal_ok;
    /* the current step, for dense output */
    double step_tau, step_h;
    double y0[NY], y1[NY], k[7][NY];
    double rcont[5][2];  /* dense output of d and v: dopri5's, or radau's collocation
                          * polynomial in Newton form */
    double acc1;         /* rk4: acceleration at the step end */
    /* radau: the last accepted step's collocation polynomial, extrapolated for the
     * Newton starting values (valid while ext_ok), and the Newton iteration's memory */
    double ext[4][2], ext_tau, ext_h;
    int ext_ok;
    double radau_tol;    /* the tolerance radau's O(h^4) estimate is held to */
    double radau_hmax;   /* radau's longest step, for the quadratures (INFINITY otherwise) */
    double newton_eta;   /* contraction estimate theta / (1 - theta) of the last step */
    int newton_it;       /* Newton iterations of the last step (0: it failed) */
    int last_rejected;
    double rk4_dmax;     /* rk4: deepest penetration among the step's stages and end */
    /* sampling */
    int nsamp;
    tt_sample *samples;
    int next_sample;
    int track_extremes;
    /* per-cycle accumulators outside the state vector */
    double peak_force, max_indent, y_min, y_max, e_jumps, t_contact, t_release;
    long steps, rejected, events;
    int failed;
    /* free flight: exponential steps out of contact (dopri5 only; see flight_step) */
    int fl_ok;           /* this sim may fly: dopri5, underdamped, no extremes tracked */
    int step_flight;     /* the current step is a flight step: dense output from fl_* */
    int fl_rung;         /* ladder rung of the flight's next step */
    int fl_nrung;        /* rungs usable (w0 h >= 0.1; see flight_particular) */
    int fl_skip;         /* dopri5 steps to take before the flight is tried again */
    int fl_wait;         /* handed over near the surface: dopri5 until the tip recedes */
    int fl_rej;          /* the last flight attempt was rejected: do not lengthen the next */
    double fl_h0;        /* the ladder's longest step, min(T, 2 pi / w0) / 8 */
    double fl_sig, fl_wdm, fl_w02; /* decay rate c / 2m, damped frequency, k / m */
    double fl_hr[FL_RUNGS]; /* the rungs' step lengths, fl_h0 2^(-r/4) */
    double fl_Dr, fl_Di; /* steady drive response d_p = Dr cos(w t) - Di sin(w t) */
    double fl_margin;    /* hand over to dopri5 within this penetration of jump-in */
    double fl_vinv[FL_N][FL_N]; /* node values to monomial coefficients in theta */
    fl_cache fl_lad[FL_RUNGS], fl_scr; /* propagators per ladder rung, and a scratch one */
    /* the current flight step: q(theta) = sum b_k theta^k and the homogeneous part's
     * initial offset r0 and its time derivative */
    double fl_b[FL_N], fl_r0, fl_r0d;
    double fl_pen[FL_N + 2], fl_vel[FL_N + 2]; /* penetration and its rate at 0, nodes, 1 */
};

/* ---- dopri5 coefficients (Dormand & Prince 1980; dense output of Hairer's dopri5) ---- */
static const double C2 = 0.2, C3 = 0.3, C4 = 0.8, C5 = 8.0 / 9.0;
static const double A21 = 0.2;
static const double A31 = 3.0 / 40.0, A32 = 9.0 / 40.0;
static const double A41 = 44.0 / 45.0, A42 = -56.0 / 15.0, A43 = 32.0 / 9.0;
static const double A51 = 19372.0 / 6561.0, A52 = -25360.0 / 2187.0, A53 = 64448.0 / 6561.0,
                    A54 = -212.0 / 729.0;
static const double A61 = 9017.0 / 3168.0, A62 = -355.0 / 33.0, A63 = 46732.0 / 5247.0,
                    A64 = 49.0 / 176.0, A65 = -5103.0 / 18656.0;
static const double A71 = 35.0 / 384.0, A73 = 500.0 / 1113.0, A74 = 125.0 / 192.0,
                    A75 = -2187.0 / 6784.0, A76 = 11.0 / 84.0;
static const double E1 = 71.0 / 57600.0, E3 = -71.0 / 16695.0, E4 = 71.0 / 1920.0,
                    E5 = -17253.0 / 339200.0, E6 = 22.0 / 525.0, E7 = -1.0 / 40.0;
static const double D1 = -12715105075.0 / 11282082432.0, D3 = 87487479700.0 / 32700410799.0,
                    D4 = -10690763975.0 / 1880347072.0, D5 = 701980252875.0 / 199316789632.0,
                    D6 = -1453857185.0 / 822651844.0, D7 = 69997945.0 / 29380423.0;

/* ---- Radau IIA, 3 stages, order 5 (Hairer & Wanner, Solving ODEs II, IV.5 and IV.8) ---- */
#define RS6 2.449489742783178098197284
static const double RC[3] = {(4.0 - RS6) / 10.0, (4.0 + RS6) / 10.0, 1.0};
static const double RA[3][3] = {
    {(88.0 - 7.0 * RS6) / 360.0, (296.0 - 169.0 * RS6) / 1800.0, (-2.0 + 3.0 * RS6) / 225.0},
    {(296.0 + 169.0 * RS6) / 1800.0, (88.0 + 7.0 * RS6) / 360.0, (-2.0 - 3.0 * RS6) / 225.0},
    {(16.0 - RS6) / 36.0, (16.0 + RS6) / 36.0, 1.0 / 9.0}};
/* error estimate of RADAU5: gamma0 = 1 / (the real eigenvalue of A^-1), and the weights
 * of the stage increments */
static const double RG0 = 0.2748888295956773677478286;
static const double RE[3] = {-(13.0 + 7.0 * RS6) / 3.0, (-13.0 + 7.0 * RS6) / 3.0, -1.0 / 3.0};
enum { NEWTON_MAX = 7 };

void tt_solver_default(tt_solver *s)
{
    s->method = TT_METHOD_DOPRI5;
    s->tolerance = 1e-8;
    s->steps_per_cycle = 512;
}

const char *tt_method_name(tt_method m)
{
    return m == TT_METHOD_RK4 ? "rk4" : m == TT_METHOD_RADAU ? "radau" : "dopri5";
}

int tt_solver_from_scene(tt_solver *s, const tt_scene *scene)
{
    tt_solver_default(s);
    const char *m = tt_scene_get_string(scene, "solver", NULL, "method");
    s->method = TT_METHOD_DOPRI5;
    if (m && strcmp(m, "rk4") == 0)
        s->method = TT_METHOD_RK4;
    else if (m && strcmp(m, "radau") == 0)
        s->method = TT_METHOD_RADAU;
    long n;
    int rc;
    if ((rc = tt_scene_get_double(scene, "solver", NULL, "tolerance", &s->tolerance)) ||
        (rc = tt_scene_get_int(scene, "solver", NULL, "steps_per_cycle", &n)))
        return rc;
    s->steps_per_cycle = (int)n;
    return TT_OK;
}

/* The free flight's constants for the current cantilever. Out of contact seed eq. 2 is
 * m d'' + c d' + k d = k z + c z' + F - P_vdw(d - s): its drive part has the steady
 * solution d_p = Re(D e^(i w t)), D = (k a + F0 + i c w a) / (k - m w^2 + i c w), and
 * x = d - d_p obeys a damped oscillator forced by -P / m alone. */
static void flight_setup(tt_sim *S)
{
    const tt_cantilever *c = &S->c;
    double zeta = 0.5 * c->c / (c->m * c->w0);
    S->fl_ok = S->solver.method == TT_METHOD_DOPRI5 && zeta < 0.8 && !S->track_extremes;
    S->fl_sig = 0.5 * c->c / c->m;
    S->fl_w02 = c->k / c->m;
    S->fl_wdm = sqrt(fmax(S->fl_w02 - S->fl_sig * S->fl_sig, 0.0));
    double a = c->drive == TT_DRIVE_BASE ? c->a_d : 0.0, F0 = c->drive == TT_DRIVE_BASE ? 0.0 : c->F0;
    double nr = c->k * a + F0, ni = c->c * c->wd * a;
    double dr = c->k - c->m * c->wd * c->wd, di = c->c * c->wd, den = dr * dr + di * di;
    S->fl_Dr = (nr * dr + ni * di) / den;
    S->fl_Di = (ni * dr - nr * di) / den;
    /* at most one turning point of the drive or the free motion per step (T/8), which the
     * hand-over check relies on */
    S->fl_h0 = fmin(c->T, 2 * M_PI / c->w0) / 8;
    S->fl_nrung = 0;
    for (int r = 0; r < FL_RUNGS; r++) {
        S->fl_lad[r].ok = 0;
        S->fl_hr[r] = S->fl_h0 * pow(2.0, -0.25 * r);
        if (c->w0 * S->fl_hr[r] >= 0.1)
            S->fl_nrung = r + 1;
    }
    if (S->fl_nrung < 4)
        S->fl_ok = 0;
    S->fl_rung = 0;
    S->fl_skip = 0;
    S->fl_wait = 0;
    S->fl_scr.ok = 0;
    /* the node-value to monomial map: the inverse of the Vandermonde matrix V[j][k] =
     * c_j^k, by Gauss-Jordan (well conditioned at degree 5 on [0, 1]) */
    double V[FL_N][2 * FL_N];
    for (int j = 0; j < FL_N; j++)
        for (int k = 0; k < FL_N; k++) {
            V[j][k] = pow(FL_C[j], k);
            V[j][FL_N + k] = j == k;
        }
    for (int col = 0; col < FL_N; col++) {
        int p = col;
        for (int r = col + 1; r < FL_N; r++)
            if (fabs(V[r][col]) > fabs(V[p][col]))
                p = r;
        for (int k = 0; k < 2 * FL_N; k++) {
            double t = V[col][k];
            V[col][k] = V[p][k];
            V[p][k] = t;
        }
        double piv = V[col][col];
        for (int k = 0; k < 2 * FL_N; k++)
            V[col][k] /= piv;
        for (int r = 0; r < FL_N; r++)
            if (r != col) {
                double f = V[r][col];
                for (int k = 0; k < 2 * FL_N; k++)
                    V[r][k] -= f * V[col][k];
            }
    }
    for (int k = 0; k < FL_N; k++)
        for (int j = 0; j < FL_N; j++)
            S->fl_vinv[k][j] = V[k][FL_N + j];
}

int tt_sim_alloc(tt_sim **out, const tt_cantilever *c, const tt_solver *solver)
{
    *out = NULL;
    if (solver->method == TT_METHOD_RK4 && solver->steps_per_cycle < 8)
        return tt_error(TT_EINVAL, "rk4 needs at least 8 steps per cycle");
    if (solver->method != TT_METHOD_RK4 && !(solver->tolerance > 0 && solver->tolerance < 1))
        return tt_error(TT_EINVAL, "solver tolerance must lie between 0 and 1");
    tt_sim *S = calloc(1, sizeof *S);
    if (!S)
        return tt_error(TT_ENOMEM, "out of memory");
    S->c = *c;
    S->inv_m = 1.0 / c->m;
    S->solver = *solver;
    S->h = c->T / 64;
    /* Radau's estimate is of an order-3 solution while the order-5 one is kept, so as in
     * Hairer's RADAU5 it is held to 0.1 tol^(2/3): about dopri5's accuracy at equal tol. */
    S->radau_tol = 0.1 * pow(solver->tolerance, 2.0 / 3.0);
    /* The per-cycle integrals are quadratures over the steps, off by about 1e-5 (w h)^6
     * of the amplitude (measured), which the motion's estimate does not see. */
    S->radau_hmax = solver->method == TT_METHOD_RADAU ? pow(1e5 * solver->tolerance, 1.0 / 6.0) / c->wd
                                                      : INFINITY;
    flight_setup(S);
    tt_sim_set_contact(S, NULL, NAN);
    tt_sim_reset_free(S);
    *out = S;
    return TT_OK;
}

void tt_sim_free(tt_sim *sim) { free(sim); }

/* The state was changed from outside the steps: the derivative at it and the last
 * step's polynomial no longer describe it. */
static void invalidate(tt_sim *S)
{
    S->fsal_ok = 0;
    S->ext_ok = 0;
    /* nor does the last contraction rate: without it one Newton step could pass for
     * converged on a new branch */
    S->newton_eta = 1.0;
}

void tt_sim_set_contact(tt_sim *S, const tt_contact *contact, double Qi)
{
    S->contact = contact;
    S->ci = (isfinite(Qi) && Qi > 0) ? S->c.m * S->c.w0 / Qi : 0.0;
    if (contact) {
        S->jumpin = tt_contact_jumpin(contact);
        S->jumpout = tt_contact_jumpout(contact);
    } else {
        S->jumpin = INFINITY;
        S->jumpout = -INFINITY;
        S->contact_state = 0;
    }
    /* A re-stepped event lands a hair (the local error) on either side of its
     * threshold, and a grazing tip may end a step just past one without a sign change;
     * only past this margin is a switch forced (tiny next to any force-law length). */
    S->margin = 1e-6 * S->c.A0;
    /* within this of jump-in the flight hands over to dopri5, so that contact events are
     * always located on dopri5 steps exactly as without it */
    S->fl_margin = 0.05 * S->c.A0;
    invalidate(S);
}

void tt_sim_set_sample(tt_sim *S, double s, double sdot)
{
    S->s0 = s;
    S->sdot = sdot;
    invalidate(S);
}

void tt_sim_set_sampling(tt_sim *S, int n, tt_sample *buf)
{
    S->nsamp = buf ? n : 0;
    S->samples = buf;
}

void tt_sim_track_extremes(tt_sim *S, int on)
{
    S->track_extremes = on;
    /* the extremes are taken at step ends, which the flight's long steps would coarsen */
    flight_setup(S);
}

void tt_sim_set_cantilever(tt_sim *S, const tt_cantilever *c)
{
    /* Same drive period required: the cycle bookkeeping assumes it. */
    S->c = *c;
    S->inv_m = 1.0 / c->m;
    flight_setup(S);
    tt_sim_set_contact(S, S->contact, S->ci > 0 ? S->c.m * S->c.w0 / S->ci : NAN);
}

const tt_cantilever *tt_sim_cantilever(const tt_sim *S) { return &S->c; }

double tt_sim_time(const tt_sim *S) { return (double)S->cycle * S->c.T; }
long tt_sim_cycles(const tt_sim *S) { return S->cycle; }

void tt_sim_get_state(const tt_sim *S, double *d, double *v, int *contact)
{
    *d = S->y[Y_D];
    *v = S->y[Y_V];
    *contact = S->contact_state;
}

void tt_sim_set_state(tt_sim *S, double d, double v, int contact)
{
    S->y[Y_D] = d;
    S->y[Y_V] = v;
    S->contact_state = S->contact ? contact : 0;
    invalidate(S);
}

void tt_sim_reset_free(tt_sim *S)
{
    /* y = A0 cos(w t - phi0) at t = 0, and d = z + y. */
    const tt_cantilever *c = &S->c;
    double z = c->drive == TT_DRIVE_BASE ? c->a_d : 0.0;
    double y = c->A0 * cos(-c->phi0);
    double ydot = -c->A0 * c->wd * sin(-c->phi0);
    memset(S->y, 0, sizeof S->y);
    S->y[Y_D] = z + y;
    S->y[Y_V] = ydot; /* z' = 0 at t = 0 */
    S->contact_state = 0;
    S->tau = 0;
    /* the step controllers' memory too: a run from the free state must not depend on
     * what the sim did before (scan lines give the same images on any thread) */
    S->h = c->T / 64;
    S->last_rejected = 0;
    S->fl_rung = 0;
    S->fl_skip = 0;
    S->fl_wait = 0;
    S->fl_rej = 0;
    invalidate(S);
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

/* Base position and velocity, drive force. */
static inline void drive_at(const tt_sim *S, double tau, double *z, double *zd, double *F,
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

/* The drive at one time: radau's Newton iteration reuses it at its stage times. */
typedef struct {
    double z, zd, F, cw, sw;
} drive_val;

/* The right-hand side: seed eq. 2 plus the per-cycle integrals. The contact state is
 * fixed for the whole step (PHYSICS.md: never flip it inside the right-hand side). */
static void rhs_with(const tt_sim *S, double tau, const drive_val *dv, const double *Y, int contact,
                     double *Fo)
{
    const tt_cantilever *c = &S->c;
    double z = dv->z, zd = dv->zd, Fd = dv->F, cw = dv->cw, sw = dv->sw;
    double d = Y[Y_D], v = Y[Y_V];
    double s = S->s0 + S->sdot * tau;
    double delta = d - s, deltad = v - S->sdot;
    double P = S->contact ? tt_contact_load(S->contact, delta, contact, NULL, NULL) : 0.0;
    double Fi = contact ? S->ci * deltad : 0.0;
    double spring = c->k * (d - z), damp = c->c * (v - zd);
    double y = d - z;
    Fo[Y_D] = v;
    Fo[Y_V] = (-damp - spring - P - Fi + Fd) * S->inv_m;
    Fo[Y_WDRIVE] = Fd * v - (spring + damp) * zd;
    Fo[Y_WDAMP] = damp * (v - zd);
    Fo[Y_WCI] = Fi * deltad;
    Fo[Y_WS] = (P + Fi) * S->sdot;
    Fo[Y_IC] = y * cw;
    Fo[Y_IS] = y * sw;
    Fo[Y_IY] = y;
    Fo[Y_TC] = contact ? 1.0 : 0.0;
}

static void rhs(const tt_sim *S, double tau, const double *Y, int contact, double *Fo)
{
    drive_val dv;
    drive_at(S, tau, &dv.z, &dv.zd, &dv.F, &dv.cw, &dv.sw);
    rhs_with(S, tau, &dv, Y, contact, Fo);
}

/* The acceleration alone: all that radau's Newton iteration needs. */
static double accel(const tt_sim *S, double tau, const drive_val *dv, double d, double v,
                    int contact)
{
    const tt_cantilever *c = &S->c;
    double s = S->s0 + S->sdot * tau;
    double P = S->contact ? tt_contact_load(S->contact, d - s, contact, NULL, NULL) : 0.0;
    double Fi = contact ? S->ci * (v - S->sdot) : 0.0;
    return (-c->c * (v - dv->zd) - c->k * (d - dv->z) - P - Fi + dv->F) * S->inv_m;
}

/* Mechanical energy of the tip system on the current branch: kinetic + spring +
 * tip-sample potential. */
static double energy(const tt_sim *S, double tau, const double *Y, int contact)
{
    double z, zd, Fd, cw, sw;
    drive_at(S, tau, &z, &zd, &Fd, &cw, &sw);
    double d = Y[Y_D], v = Y[Y_V];
    double U = S->contact ? tt_contact_energy(S->contact, d - (S->s0 + S->sdot * tau), contact) : 0;
    return 0.5 * S->c.m * v * v + 0.5 * S->c.k * (d - z) * (d - z) + U;
}

/* dopri5's step-size factor 0.9 err^(-1/5), clamped to [0.2, 5], without pow (a tenth
 * of the run time, on the critical path of every step): with err = m 2^e, m in [1, 2),
 * a table gives 0.9 2^(-e/5) and a degree-5 polynomial (Chebyshev nodes, Estrin form)
 * m^(-1/5) to 3.3e-6, far finer than a step-size factor needs. Inside the clamps err
 * lies in [(0.9/5)^5, (0.9/0.2)^5], so e runs from -13 to 10. */
static inline double step_factor5(double err)
{
    static const double p2[24] = {
        5.456579639437433,  4.750228478782419,  4.135314077989326,  3.6,
        3.133982027866047,  2.7282898197187166, 2.3751142393912095, 2.0676570389946627,
        1.8,                1.5669910139330234, 1.3641449098593583, 1.1875571196956047,
        1.0338285194973316, 0.9,                0.7834955069665117, 0.6820724549296792,
        0.5937785598478024, 0.5169142597486657, 0.45,               0.39174775348325586,
        0.3410362274648396, 0.2968892799239012, 0.25845712987433284, 0.225};
    if (!(err > 1.8896e-4))
        return 5.0; /* includes err = 0 */
    if (!(err < 1845.28))
        return 0.2; /* includes err = INFINITY (dopri5_step returns no NaN) */
    uint64_t b;
    memcpy(&b, &err, sizeof b);
    int e = (int)((b >> 52) & 0x7ff) - 1023;
    b = (b & 0x000FFFFFFFFFFFFFULL) | 0x3FF0000000000000ULL;
    double m;
    memcpy(&m, &b, sizeof m);
    double t = m - 1.5, t2 = t * t;
    double y = (0.9221102377412318 - 0.12294910057924131 * t) +
               t2 * ((0.04901242797985909 - 0.02394432399428421 * t) +
                     t2 * (0.014550106265462144 - 0.008203782016855054 * t));
    double fac = p2[e + 13] * y;
    return fac > 5 ? 5 : fac < 0.2 ? 0.2 : fac;
}

/* ---- one step of each method from (tau, y) with size h into S->y1, filling dense data ---- */

static void ensure_fsal(tt_sim *S)
{
    if (!S->fsal_ok) {
        rhs(S, S->tau, S->y, S->contact_state, S->fsal);
        S->fsal_ok = 1;
    }
}

/* Dormand-Prince 5(4). Returns the scaled error norm (<= 1 accepts). */
static double dopri5_step(tt_sim *S, double h)
{
    double (*k)[NY] = S->k, yt[NY];
    const double *y0 = S->y;
    double t = S->tau;
    int cs = S->contact_state;
    ensure_fsal(S);
    memcpy(k[0], S->fsal, sizeof k[0]);
    /* The stages read only the motion (d, v): the integrals do not feed back, so only
     * the step's end carries them. */
    memcpy(yt, y0, sizeof yt);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + h * A21 * k[0][i];
    rhs(S, t + C2 * h, yt, cs, k[1]);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + h * (A31 * k[0][i] + A32 * k[1][i]);
    rhs(S, t + C3 * h, yt, cs, k[2]);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + h * (A41 * k[0][i] + A42 * k[1][i] + A43 * k[2][i]);
    rhs(S, t + C4 * h, yt, cs, k[3]);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + h * (A51 * k[0][i] + A52 * k[1][i] + A53 * k[2][i] + A54 * k[3][i]);
    rhs(S, t + C5 * h, yt, cs, k[4]);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + h * (A61 * k[0][i] + A62 * k[1][i] + A63 * k[2][i] + A64 * k[3][i] +
                             A65 * k[4][i]);
    rhs(S, t + h, yt, cs, k[5]);
    for (int i = 0; i < NY; i++)
        S->y1[i] = y0[i] + h * (A71 * k[0][i] + A73 * k[2][i] + A74 * k[3][i] + A75 * k[4][i] +
                                A76 * k[5][i]);
    rhs(S, t + h, S->y1, cs, k[6]);
    /* Error on the motion only, relative to the free amplitude (and its velocity). */
    double sc[2] = {S->solver.tolerance * S->c.A0, S->solver.tolerance * S->c.A0 * S->c.wd};
    double err = 0;
    for (int i = 0; i < 2; i++) {
        double e = h * (E1 * k[0][i] + E3 * k[2][i] + E4 * k[3][i] + E5 * k[4][i] + E6 * k[5][i] +
                        E7 * k[6][i]);
        double r = fabs(e) / sc[i];
        if (r > err)
            err = r;
    }
    if (!isfinite(err))
        err = INFINITY;
    for (int i = 0; i < 2; i++) {
        double ydiff = S->y1[i] - y0[i];
        double bspl = h * k[0][i] - ydiff;
        S->rcont[0][i] = y0[i];
        S->rcont[1][i] = ydiff;
        S->rcont[2][i] = bspl;
        S->rcont[3][i] = ydiff - h * k[6][i] - bspl;
        S->rcont[4][i] = h * (D1 * k[0][i] + D3 * k[2][i] + D4 * k[3][i] + D5 * k[4][i] +
                              D6 * k[5][i] + D7 * k[6][i]);
    }
    memcpy(S->y0, y0, sizeof S->y0);
    S->step_tau = t;
    S->step_h = h;
    S->step_flight = 0;
    return err;
}

/* Classic RK4 (fixed steps). */
static void rk4_step(tt_sim *S, double h)
{
    double (*k)[NY] = S->k, yt[NY];
    const double *y0 = S->y;
    double t = S->tau;
    int cs = S->contact_state;
    ensure_fsal(S);
    memcpy(k[0], S->fsal, sizeof k[0]);
    memcpy(yt, y0, sizeof yt); /* the stages read only (d, v) */
    double smid = S->s0 + S->sdot * (t + 0.5 * h), send = S->s0 + S->sdot * (t + h);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + 0.5 * h * k[0][i];
    double dmax = yt[Y_D] - smid;
    rhs(S, t + 0.5 * h, yt, cs, k[1]);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + 0.5 * h * k[1][i];
    dmax = fmax(dmax, yt[Y_D] - smid);
    rhs(S, t + 0.5 * h, yt, cs, k[2]);
    for (int i = 0; i < 2; i++)
        yt[i] = y0[i] + h * k[2][i];
    dmax = fmax(dmax, yt[Y_D] - send);
    rhs(S, t + h, yt, cs, k[3]);
    for (int i = 0; i < NY; i++)
        S->y1[i] = y0[i] + h / 6.0 * (k[0][i] + 2 * k[1][i] + 2 * k[2][i] + k[3][i]);
    /* A step that enters a stiff contact (from its soft onset, where the stiffness at the
     * start says nothing) shows it in its stages: they overshoot deep into it. */
    S->rk4_dmax = fmax(dmax, S->y1[Y_D] - send);
    /* The derivative at the end serves the cubic Hermite dense output and, unless the
     * state changes there, the next step's first stage. */
    rhs(S, t + h, S->y1, cs, k[6]);
    memcpy(S->y0, y0, sizeof S->y0);
    S->step_tau = t;
    S->step_h = h;
    S->step_flight = 0;
}

/* A radau collocation polynomial of d and v in Newton form on the nodes 0, c1, c2, 1. */
static inline void radau_poly(const double (*p)[2], double th, double *d, double *v)
{
    double out[2];
    for (int i = 0; i < 2; i++)
        out[i] = p[0][i] + th * (p[1][i] + (th - RC[0]) * (p[2][i] + (th - RC[1]) * p[3][i]));
    *d = out[0];
    *v = out[1];
}

/* LU factorisation of a 3x3 matrix with partial pivoting, in place; 0 if singular. */
static int lu3(double M[3][3], int piv[3])
{
    for (int c = 0; c < 3; c++) {
        int p = c;
        for (int r = c + 1; r < 3; r++)
            if (fabs(M[r][c]) > fabs(M[p][c]))
                p = r;
        piv[c] = p;
        if (!(fabs(M[p][c]) > 0) || !isfinite(M[p][c]))
            return 0;
        if (p != c)
            for (int j = 0; j < 3; j++) {
                double tmp = M[c][j];
                M[c][j] = M[p][j];
                M[p][j] = tmp;
            }
        for (int r = c + 1; r < 3; r++) {
            M[r][c] /= M[c][c];
            for (int j = c + 1; j < 3; j++)
                M[r][j] -= M[r][c] * M[c][j];
        }
    }
    return 1;
}

/* Solve with lu3's factors: all row swaps first (the multipliers were swapped with
 * their rows), then the two triangular solves. */
static void lu3_solve(double M[3][3], const int piv[3], double b[3])
{
    for (int c = 0; c < 3; c++)
        if (piv[c] != c) {
            double tmp = b[c];
            b[c] = b[piv[c]];
            b[piv[c]] = tmp;
        }
    for (int c = 0; c < 3; c++)
        for (int r = c + 1; r < 3; r++)
            b[r] -= M[r][c] * b[c];
    for (int r = 2; r >= 0; r--) {
        for (int j = r + 1; j < 3; j++)
            b[r] -= M[r][j] * b[j];
        b[r] /= M[r][r];
    }
}

/* Radau IIA, 3 stages, order 5, is L-stable, so a stiff or heavily damped contact
 * limits its step only through accuracy. Simplified Newton on the motion (d, v) with
 * the step start's Jacobian; the quadrature components do not feed back, so they follow
 * from the converged stages with the weights b (the last row of A). Returns the scaled
 * error (RADAU5's embedded estimate; <= 1 accepts), or INFINITY with newton_it = 0. */
static double radau_step(tt_sim *S, double h)
{
    double (*k)[NY] = S->k;
    const double *y0 = S->y;
    const double t = S->tau, d0 = y0[Y_D], v0 = y0[Y_V];
    const int cs = S->contact_state;
    const double tol = S->radau_tol;
    const double scd = tol * S->c.A0, scv = scd * S->c.wd;
    const int first = !S->ext_ok;
    ensure_fsal(S);
    memcpy(k[0], S->fsal, sizeof k[0]);
    memcpy(S->y0, y0, sizeof S->y0);
    S->step_tau = t;
    S->step_h = h;
    S->step_flight = 0;

    /* Jacobian of (d' = v, v' = f) at the step start: df/dd = -(k + dP/ddelta) / m,
     * df/dv = -(c + c_i) / m. */
    double dPdd = 0;
    if (S->contact)
        (void)tt_contact_load(S->contact, d0 - (S->s0 + S->sdot * t), cs, &dPdd, NULL);
    const double Jd = -(S->c.k + dPdd) * S->inv_m;
    const double Jv = -(S->c.c + (cs ? S->ci : 0.0)) * S->inv_m;
    /* Position increments follow linearly from the velocity ones (d' = v), so Newton
     * needs only M = I - h Jv A - h^2 Jd A^2 for the three velocity increments. */
    double M[3][3];
    int piv[3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double a2 = RA[i][0] * RA[0][j] + RA[i][1] * RA[1][j] + RA[i][2] * RA[2][j];
            M[i][j] = (i == j) - h * Jv * RA[i][j] - h * h * Jd * a2;
        }
    int ok = lu3(M, piv);

    drive_val dv[3];
    for (int i = 0; i < 3; i++)
        drive_at(S, t + RC[i] * h, &dv[i].z, &dv[i].zd, &dv[i].F, &dv[i].cw, &dv[i].sw);

    /* starting values: the last accepted step's polynomial, extrapolated */
    double zv[3] = {0, 0, 0}, zd[3];
    if (S->ext_ok)
        for (int i = 0; i < 3; i++) {
            double de, ve;
            radau_poly((const double (*)[2])S->ext, (t + RC[i] * h - S->ext_tau) / S->ext_h, &de, &ve);
            zv[i] = ve - v0;
        }

    /* Simplified Newton; stop when the estimated remaining error, eta |dz|, is a small
     * fraction of the tolerance (Hairer's fnewt). */
    const double fnewt = fmax(10 * DBL_EPSILON / tol, fmin(0.03, sqrt(tol)));
    double eta = pow(fmax(S->newton_eta, DBL_EPSILON), 0.8), prev = 1;
    int conv = 0, it;
    for (it = 1; ok && it <= NEWTON_MAX; it++) {
        double a[3], g[3];
        for (int i = 0; i < 3; i++)
            zd[i] = h * (RA[i][0] * (v0 + zv[0]) + RA[i][1] * (v0 + zv[1]) + RA[i][2] * (v0 + zv[2]));
        for (int j = 0; j < 3; j++)
            a[j] = accel(S, t + RC[j] * h, &dv[j], d0 + zd[j], v0 + zv[j], cs);
        for (int i = 0; i < 3; i++)
            g[i] = h * (RA[i][0] * a[0] + RA[i][1] * a[1] + RA[i][2] * a[2]) - zv[i];
        lu3_solve(M, piv, g);
        double nrm = 0;
        for (int i = 0; i < 3; i++) {
            double dd = h * (RA[i][0] * g[0] + RA[i][1] * g[1] + RA[i][2] * g[2]);
            nrm = fmax(nrm, fmax(fabs(g[i]) / scv, fabs(dd) / scd));
        }
        if (!isfinite(nrm))
            break;
        if (it > 1) {
            double theta = nrm / prev;
            if (theta >= 0.99)
                break; /* diverging */
            eta = theta / (1 - theta);
            if (eta * nrm * pow(theta, NEWTON_MAX - it) > fnewt)
                break; /* would not converge in the iterations left */
        }
        prev = fmax(nrm, DBL_EPSILON);
        for (int i = 0; i < 3; i++)
            zv[i] += g[i];
        if (eta * nrm <= fnewt) {
            conv = 1;
            break;
        }
    }
    S->newton_it = conv ? it : 0;
    if (conv)
        S->newton_eta = eta;

    /* the converged stages: full right-hand side (quadrature integrands included) */
    double Yst[NY];
    memcpy(Yst, y0, sizeof Yst);
    for (int i = 0; i < 3; i++)
        zd[i] = h * (RA[i][0] * (v0 + zv[0]) + RA[i][1] * (v0 + zv[1]) + RA[i][2] * (v0 + zv[2]));
    for (int j = 0; j < 3; j++) {
        Yst[Y_D] = d0 + zd[j];
        Yst[Y_V] = v0 + zv[j];
        rhs_with(S, t + RC[j] * h, &dv[j], Yst, cs, k[1 + j]);
    }
    /* stiffly accurate: the end is the last stage (not y0 + h b.f, which would amplify
     * the Newton error of the stiff part by h |J|) */
    S->y1[Y_D] = d0 + zd[2];
    S->y1[Y_V] = v0 + zv[2];
    for (int q = Y_WDRIVE; q < NY; q++)
        S->y1[q] = y0[q] + h * (RA[2][0] * k[1][q] + RA[2][1] * k[2][q] + RA[2][2] * k[3][q]);
    memcpy(k[6], k[3], sizeof k[6]);

    /* dense output: the collocation polynomial through y0 and the three stages */
    for (int i = 0; i < 2; i++) {
        double z1 = i ? zv[0] : zd[0], z2 = i ? zv[1] : zd[1], z3 = i ? zv[2] : zd[2];
        double f01 = z1 / RC[0], f12 = (z2 - z1) / (RC[1] - RC[0]), f23 = (z3 - z2) / (1 - RC[1]);
        double f012 = (f12 - f01) / RC[1], f123 = (f23 - f12) / (1 - RC[0]);
        S->rcont[0][i] = y0[i];
        S->rcont[1][i] = f01;
        S->rcont[2][i] = f012;
        S->rcont[3][i] = f123 - f012;
        S->rcont[4][i] = 0;
    }
    if (!conv)
        return INFINITY;

    /* error estimate: (I - h g0 J)^-1 (g0 h f0 + g0 sum e_i Z_i), on d and v */
    const double hg = h * RG0, det = (1 - hg * Jv) - hg * hg * Jd;
    double rd = hg * k[0][Y_D] + RG0 * (RE[0] * zd[0] + RE[1] * zd[1] + RE[2] * zd[2]);
    double rv = hg * k[0][Y_V] + RG0 * (RE[0] * zv[0] + RE[1] * zv[1] + RE[2] * zv[2]);
    double ed = ((1 - hg * Jv) * rd + hg * rv) / det, ev = (hg * Jd * rd + rv) / det;
    double err = fmax(fabs(ed) / scd, fabs(ev) / scv);
    if (err >= 1 && (first || S->last_rejected)) {
        /* Hairer's second estimate, with f at y0 + err: keeps stiff components from
         * inflating the first estimate after a discontinuity */
        drive_val d0v;
        drive_at(S, t, &d0v.z, &d0v.zd, &d0v.F, &d0v.cw, &d0v.sw);
        double a1 = accel(S, t, &d0v, d0 + ed, v0 + ev, cs);
        rd = hg * (v0 + ev) + RG0 * (RE[0] * zd[0] + RE[1] * zd[1] + RE[2] * zd[2]);
        rv = hg * a1 + RG0 * (RE[0] * zv[0] + RE[1] * zv[1] + RE[2] * zv[2]);
        ed = ((1 - hg * Jv) * rd + hg * rv) / det;
        ev = (hg * Jd * rd + rv) / det;
        err = fmax(fabs(ed) / scd, fabs(ev) / scv);
    }
    return isfinite(err) ? err : INFINITY;
}

/* ---- free flight: an exponential step out of contact ---- */

static void fl_fill(const tt_sim *S, fl_cache *F, double h)
{
    for (int j = 0; j <= FL_N; j++) {
        double tau = (j < FL_N ? FL_C[j] : 1.0) * h;
        F->e[j] = exp(-S->fl_sig * tau);
        F->cd[j] = cos(S->fl_wdm * tau);
        F->sd[j] = sin(S->fl_wdm * tau);
        F->cw[j] = cos(S->c.wd * tau);
        F->sw[j] = sin(S->c.wd * tau);
    }
    F->h = h;
    F->ok = 1;
}

/* The flight's force term -P(d - s) / m on the out-of-contact branch. */
static inline double fl_force(const tt_sim *S, double delta)
{
    return S->contact ? -tt_contact_load(S->contact, delta, 0, NULL, NULL) * S->inv_m : 0.0;
}

/* The polynomial particular solution of x_thth + 2 sig h x_th + w0^2 h^2 x = h^2 p(theta)
 * for p = sum a_k theta^k, by back substitution from the top degree; it loses about
 * (w0 h)^-10 of rounding relative to the forcing's displacement, which the ladder's
 * floor w0 h >= 0.1 keeps far below any tolerance. */
static void flight_particular(const tt_sim *S, double h, const double *a, double *b)
{
    double h2 = h * h, s2 = 2 * S->fl_sig * h, iw = 1.0 / (S->fl_w02 * h2);
    double b1 = 0, b2 = 0;
    for (int k = FL_N - 1; k >= 0; k--) {
        double bk = (h2 * a[k] - (k + 1) * s2 * b1 - (k + 2) * (k + 1) * b2) * iw;
        b[k] = bk;
        b2 = b1;
        b1 = bk;
    }
}

/* x and x' at a node j of the cache F from the current step's q and r0. */
static inline void fl_node(const tt_sim *S, const fl_cache *F, int j, double th, double h, double *x,
                           double *xd)
{
    const double *b = S->fl_b;
    double q = b[FL_N - 1], qd = 0;
    for (int k = FL_N - 2; k >= 0; k--) {
        qd = qd * th + q;
        q = q * th + b[k];
    }
    double A = S->fl_r0, B = (S->fl_r0d + S->fl_sig * A) / S->fl_wdm;
    double e = F->e[j], cs = F->cd[j], sn = F->sd[j];
    *x = q + e * (A * cs + B * sn);
    *xd = qd / h + e * (S->fl_r0d * cs - (S->fl_sig * B + S->fl_wdm * A) * sn);
}

/* One exponential step of length h from (tau, y) out of contact, into y1 with the
 * per-cycle integrals, filling the dense data. d = d_p + x with x advanced exactly for
 * the linear part (the damped oscillator's propagator) and the van der Waals force
 * interpolated at six Gauss-Legendre nodes by a degree-5 polynomial (collocation,
 * solved by Picard iteration, which contracts by about (dP/ddelta / k) (w0 h)^2, tiny
 * out of contact). The error estimate is the interpolation's miss at the step end,
 * mapped to the velocity it moves over the step (h |dN|), relative to the tolerance of
 * dopri5's estimate. Returns it (<= 1 accepts), or -1 if the iteration did not
 * converge. */
static double flight_step(tt_sim *S, double h, const fl_cache *F)
{
    const tt_cantilever *c = &S->c;
    const double t0 = S->tau, w = c->wd, *y0 = S->y;
    const double Dr = S->fl_Dr, Di = S->fl_Di;
    const double sc = 1.0 / (S->solver.tolerance * c->A0 * w);
    double s0w, c0w;
    phase_sincos(w * t0, &s0w, &c0w);
    double cw[FL_N + 1], sw[FL_N + 1], dp[FL_N + 1], dpd[FL_N + 1], sj[FL_N + 1];
    for (int j = 0; j <= FL_N; j++) {
        cw[j] = c0w * F->cw[j] - s0w * F->sw[j];
        sw[j] = s0w * F->cw[j] + c0w * F->sw[j];
        dp[j] = Dr * cw[j] - Di * sw[j];
        dpd[j] = -w * (Dr * sw[j] + Di * cw[j]);
        sj[j] = S->s0 + S->sdot * (t0 + (j < FL_N ? FL_C[j] : 1.0) * h);
    }
    const double x0 = y0[Y_D] - (Dr * c0w - Di * s0w), x0d = y0[Y_V] + w * (Dr * s0w + Di * c0w);
    double N[FL_N], a[FL_N], xj[FL_N], xdj[FL_N];
    double N0 = fl_force(S, y0[Y_D] - (S->s0 + S->sdot * t0));
    for (int j = 0; j < FL_N; j++)
        N[j] = N0;
    /* Picard iteration. After the first round the next change of the forcing is bounded
     * by its slope |dP/ddelta| / m at the node nearest the surface (the largest, the
     * force rising towards it) times the change of x, which spares the second round of
     * force evaluations when that is small enough. */
    int conv = 0;
    double L = -1, xprev[FL_N];
    for (int it = 0; it < 5 && !conv; it++) {
        for (int k = 0; k < FL_N; k++) {
            double acc = 0;
            for (int j = 0; j < FL_N; j++)
                acc += S->fl_vinv[k][j] * N[j];
            a[k] = acc;
        }
        flight_particular(S, h, a, S->fl_b);
        S->fl_r0 = x0 - S->fl_b[0];
        S->fl_r0d = x0d - S->fl_b[1] / h;
        double dx = 0;
        for (int j = 0; j < FL_N; j++) {
            fl_node(S, F, j, FL_C[j], h, &xj[j], &xdj[j]);
            if (it > 0)
                dx = fmax(dx, fabs(xj[j] - xprev[j]));
            xprev[j] = xj[j];
        }
        /* the last change moves the velocity by about h chg: converged when that is a
         * hundredth of the tolerance */
        if (it > 0 && L >= 0 && h * (2 * L * dx) * sc < 0.01)
        {
            conv = 1;
            break;
        }
        double chg = 0;
        int jn = 0;
        for (int j = 0; j < FL_N; j++) {
            double pen = dp[j] + xj[j] - sj[j];
            double Nn = fl_force(S, pen);
            chg = fmax(chg, fabs(Nn - N[j]));
            N[j] = Nn;
            if (pen > dp[jn] + xj[jn] - sj[jn])
                jn = j;
        }
        conv = h * chg * sc < 0.01;
        if (!conv && it == 0 && S->contact) {
            double dPdd = 0;
            (void)tt_contact_load(S->contact, dp[jn] + xj[jn] - sj[jn], 0, &dPdd, NULL);
            L = fabs(dPdd) * S->inv_m;
        }
    }
    if (!conv)
        return -1;
    double xe, xed;
    fl_node(S, F, FL_N, 1.0, h, &xe, &xed);
    double *y1 = S->y1;
    y1[Y_D] = dp[FL_N] + xe;
    y1[Y_V] = dpd[FL_N] + xed;
    double pe = 0;
    for (int k = 0; k < FL_N; k++)
        pe += a[k];
    double err = h * fabs(fl_force(S, y1[Y_D] - sj[FL_N]) - pe) * sc;
    /* the per-cycle integrals by the nodes' Gauss-Legendre rule: exact to about
     * 1e-13 of a step's share for integrands up to twice the drive frequency at h = T/8 */
    double q[NY] = {0};
    for (int j = 0; j < FL_N; j++) {
        double d = dp[j] + xj[j], v = dpd[j] + xdj[j];
        double z, zd, Fd;
        if (c->drive == TT_DRIVE_BASE) {
            z = c->a_d * cw[j];
            zd = -c->a_d * w * sw[j];
            Fd = 0;
        } else {
            z = zd = 0;
            Fd = c->F0 * cw[j];
        }
        double y = d - z, spring = c->k * y, damp = c->c * (v - zd), W = FL_W[j];
        q[Y_WDRIVE] += W * (Fd * v - (spring + damp) * zd);
        q[Y_WDAMP] += W * damp * (v - zd);
        q[Y_WS] += W * (-N[j] * c->m) * S->sdot;
        q[Y_IC] += W * y * cw[j];
        q[Y_IS] += W * y * sw[j];
        q[Y_IY] += W * y;
    }
    for (int i = Y_WDRIVE; i < NY; i++)
        y1[i] = y0[i] + h * q[i];
    S->fl_pen[0] = y0[Y_D] - (S->s0 + S->sdot * t0);
    S->fl_vel[0] = y0[Y_V] - S->sdot;
    for (int j = 0; j < FL_N; j++) {
        S->fl_pen[j + 1] = dp[j] + xj[j] - sj[j];
        S->fl_vel[j + 1] = dpd[j] + xdj[j] - S->sdot;
    }
    S->fl_pen[FL_N + 1] = y1[Y_D] - sj[FL_N];
    S->fl_vel[FL_N + 1] = y1[Y_V] - S->sdot;
    memcpy(S->y0, y0, sizeof S->y0);
    S->step_tau = t0;
    S->step_h = h;
    S->step_flight = 1;
    return isfinite(err) ? err : INFINITY;
}

/* Dense output of a flight step: the exact propagator at any fraction th. */
static void dense_flight(const tt_sim *S, double th, double *d, double *v)
{
    if (th == 0 || th == 1) {
        const double *y = th == 0 ? S->y0 : S->y1;
        *d = y[Y_D];
        *v = y[Y_V];
        return;
    }
    fl_cache F;
    double h = S->step_h, tau = th * h;
    F.e[0] = exp(-S->fl_sig * tau);
    /* the damped rotation's angle is below 2 pi (steps of at most 1/8 of a free period),
     * where the drive's own sine and cosine serve, at a third of the library's cost */
    phase_sincos(S->fl_wdm * tau, &F.sd[0], &F.cd[0]);
    double x, xd, sn, cs;
    fl_node(S, &F, 0, th, h, &x, &xd);
    phase_sincos(S->c.wd * (S->step_tau + tau), &sn, &cs);
    *d = S->fl_Dr * cs - S->fl_Di * sn + x;
    *v = -S->c.wd * (S->fl_Dr * sn + S->fl_Di * cs) + xd;
}

/* Dense output of d and v at fraction th of the current step. */
static void dense(const tt_sim *S, double th, double *d, double *v)
{
    double h = S->step_h;
    if (S->step_flight) {
        dense_flight(S, th, d, v);
        return;
    }
    if (S->solver.method == TT_METHOD_RADAU) {
        radau_poly(S->rcont, th, d, v);
        return;
    }
    if (S->solver.method == TT_METHOD_DOPRI5) {
        double th1 = 1 - th;
        double out[2];
        for (int i = 0; i < 2; i++)
            out[i] = S->rcont[0][i] +
                     th * (S->rcont[1][i] +
                           th1 * (S->rcont[2][i] + th * (S->rcont[3][i] + th1 * S->rcont[4][i])));
        *d = out[0];
        *v = out[1];
        return;
    }
    /* Cubic Hermite: d from (d, v) at both ends, v from (v, a) at both ends. */
    double t2 = th * th, t3 = t2 * th;
    double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + th, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
    *d = h00 * S->y0[Y_D] + h10 * h * S->y0[Y_V] + h01 * S->y1[Y_D] + h11 * h * S->y1[Y_V];
    *v = h00 * S->y0[Y_V] + h10 * h * S->k[0][Y_V] + h01 * S->y1[Y_V] + h11 * h * S->k[6][Y_V];
}

/* Event functions on the dense output: penetration past a threshold, and the relative
 * velocity (for turning points). */
static double g_delta(const tt_sim *S, double th, double thr)
{
    double d, v;
    dense(S, th, &d, &v);
    return d - (S->s0 + S->sdot * (S->step_tau + th * S->step_h)) - thr;
}

static double g_vel(const tt_sim *S, double th)
{
    double d, v;
    dense(S, th, &d, &v);
    return v - S->sdot;
}

/* Illinois root finder on [a, b] with fa, fb of opposite signs; which = 0 for
 * penetration minus thr, 1 for the relative velocity. Returns the end of the final
 * bracket on b's side, so that the switch happens just past the root. */
static double bracket_root(const tt_sim *S, int which, double thr, double a, double b, double fa,
                           double fb)
{
    int side = 0;
    for (int it = 0; it < 100 && b - a > 1e-14; it++) {
        double m = (a * fb - b * fa) / (fb - fa);
        if (!(m > a && m < b))
            m = 0.5 * (a + b);
        double fm = which ? g_vel(S, m) : g_delta(S, m, thr);
        if (fm == 0)
            return m;
        if ((fm > 0) == (fb > 0)) {
            b = m;
            fb = fm;
            if (side == 1)
                fa *= 0.5;
            side = 1;
        } else {
            a = m;
            fa = fm;
            if (side == -1)
                fb *= 0.5;
            side = -1;
        }
    }
    return b;
}

/* Where in the current step (fraction, 1 = none) the contact state must flip:
 * out of contact when the penetration rises to jumpin, in contact when it falls to
 * jumpout. A turning point inside the step is checked too, so that a brief touch
 * between step ends is not missed. */
static double find_event(const tt_sim *S)
{
    if (!S->contact)
        return 2;
    int in = S->contact_state;
    double thr = in ? S->jumpout : S->jumpin;
    if (!isfinite(thr))
        return 2;
    /* sign convention: event when sgn * g crosses from > 0 to <= 0 */
    double sgn = in ? 1.0 : -1.0;
    double g0 = sgn * g_delta(S, 0, thr);
    if (g0 <= -S->margin)
        return 0; /* already past by more than the margin: switch now */
    double g1 = sgn * g_delta(S, 1, thr);
    if (g0 > 0 && g1 <= 0)
        return bracket_root(S, 0, thr, 0, 1, g_delta(S, 0, thr), g_delta(S, 1, thr));
    /* A turning point of the penetration inside the step: out of contact a maximum,
     * in contact a minimum. */
    double v0 = g_vel(S, 0), v1 = g_vel(S, 1);
    if (g0 > 0 && ((!in && v0 > 0 && v1 < 0) || (in && v0 < 0 && v1 > 0))) {
        double tm = bracket_root(S, 1, 0, 0, 1, v0, v1);
        double gm = sgn * g_delta(S, tm, thr);
        if (gm <= 0)
            return bracket_root(S, 0, thr, 0, tm, g_delta(S, 0, thr), g_delta(S, tm, thr));
    }
    if (g1 <= -S->margin)
        return 1; /* ended past the threshold by more than the margin: switch at the end */
    return 2;
}

/* Whether the current flight step comes within fl_margin of jump-in: at its start, nodes
 * or end, or at a maximum of the penetration between them (located on the exact dense
 * output), so that a brief approach between the step's points is not missed. */
static int flight_near(const tt_sim *S)
{
    if (!S->contact || !isfinite(S->jumpin))
        return 0;
    double thr = S->jumpin - S->fl_margin;
    for (int j = 0; j < FL_N + 2; j++)
        if (S->fl_pen[j] >= thr)
            return 1;
    for (int j = 0; j < FL_N + 1; j++)
        if (S->fl_vel[j] > 0 && S->fl_vel[j + 1] < 0) {
            double a = j == 0 ? 0.0 : FL_C[j - 1], b = j == FL_N ? 1.0 : FL_C[j];
            double tm = bracket_root(S, 1, 0, a, b, S->fl_vel[j], S->fl_vel[j + 1]);
            if (g_delta(S, tm, thr) >= 0)
                return 1;
        }
    return 0;
}

/* Tip-sample force on the current branch at a state. */
static double ts_force(const tt_sim *S, double tau, double d, double v, int contact, double *delta)
{
    double dl = d - (S->s0 + S->sdot * tau);
    *delta = dl;
    if (!S->contact)
        return 0;
    double P = tt_contact_load(S->contact, dl, contact, NULL, NULL);
    return P + (contact ? S->ci * (v - S->sdot) : 0.0);
}

/* Bookkeeping for the part [0, th] of the current step: samples, extremes, peak force. */
static void observe(tt_sim *S, double th)
{
    double h = S->step_h, t0 = S->step_tau;
    const tt_cantilever *c = &S->c;
    /* samples at k T / n inside (t0, t0 + th h]; k = 0 is taken at the cycle start */
    while (S->next_sample < S->nsamp) {
        double ts = c->T * S->next_sample / S->nsamp;
        if (ts > t0 + th * h * (1 + 1e-12))
            break;
        double f = h > 0 ? (ts - t0) / h : 0;
        if (f < 0)
            f = 0;
        tt_sample *smp = &S->samples[S->next_sample++];
        double z, zd, Fd, cw, sw;
        drive_at(S, ts, &z, &zd, &Fd, &cw, &sw);
        dense(S, f, &smp->d, &smp->v);
        smp->t = tt_sim_time(S) + ts;
        smp->z = z;
        smp->s = S->s0 + S->sdot * ts;
        smp->contact = S->contact_state;
    }
    /* deflection extremes (on request: they cost a drive evaluation) and force at the
     * (sub)step end */
    double d, v, delta;
    dense(S, th, &d, &v);
    if (S->track_extremes) {
        double z, zd, Fd, cw, sw;
        drive_at(S, t0 + th * h, &z, &zd, &Fd, &cw, &sw);
        double y = d - z;
        if (y < S->y_min)
            S->y_min = y;
        if (y > S->y_max)
            S->y_max = y;
    }
    double F = ts_force(S, t0 + th * h, d, v, S->contact_state, &delta);
    if (F > S->peak_force)
        S->peak_force = F;
    if (delta > S->max_indent)
        S->max_indent = delta;
    /* a maximum of the penetration inside: locate it for the indentation */
    double v0 = g_vel(S, 0), v1 = g_vel(S, th);
    if (v0 > 0 && v1 < 0) {
        double tm = bracket_root(S, 1, 0, 0, th, v0, v1);
        dense(S, tm, &d, &v);
        F = ts_force(S, t0 + tm * h, d, v, S->contact_state, &delta);
        if (F > S->peak_force)
            S->peak_force = F;
        if (delta > S->max_indent)
            S->max_indent = delta;
    }
    /* A flight step's ends are too far apart to stand for the far turning point, where an
     * attraction is weakest and the force greatest: locate a minimum of the penetration. */
    if (S->step_flight && v0 < 0 && v1 > 0) {
        double tm = bracket_root(S, 1, 0, 0, th, v0, v1);
        dense(S, tm, &d, &v);
        F = ts_force(S, t0 + tm * h, d, v, S->contact_state, &delta);
        if (F > S->peak_force)
            S->peak_force = F;
    }
    /* In contact the force (load plus interaction damping) may peak anywhere in the
     * step: sample it at quarter steps and refine an interior maximum by a parabola. */
    if (S->contact_state && th > 0) {
        double f[5], tq[5];
        int best = 0;
        for (int q = 0; q < 5; q++) {
            tq[q] = th * q / 4.0;
            dense(S, tq[q], &d, &v);
            f[q] = ts_force(S, t0 + tq[q] * h, d, v, 1, &delta);
            if (f[q] > f[best])
                best = q;
        }
        double fmax = f[best];
        if (best > 0 && best < 4) {
            double den = f[best - 1] - 2 * f[best] + f[best + 1];
            if (den < 0) {
                double off = 0.5 * (f[best - 1] - f[best + 1]) / den; /* in quarter steps */
                if (fabs(off) <= 1) {
                    dense(S, tq[best] + off * th / 4.0, &d, &v);
                    double fr = ts_force(S, t0 + (tq[best] + off * th / 4.0) * h, d, v, 1, &delta);
                    if (fr > fmax)
                        fmax = fr;
                }
            }
        }
        if (fmax > S->peak_force)
            S->peak_force = fmax;
    }
}

/* Take the current step (already computed into y1) in full. */
static void accept_full(tt_sim *S)
{
    observe(S, 1);
    memcpy(S->y, S->y1, sizeof S->y);
    memcpy(S->fsal, S->k[6], sizeof S->fsal);
    S->fsal_ok = !S->step_flight; /* a flight step computes no derivative at its end */
    if (S->solver.method == TT_METHOD_RADAU) {
        memcpy(S->ext, S->rcont, sizeof S->ext);
        S->ext_tau = S->step_tau;
        S->ext_h = S->step_h;
        S->ext_ok = 1;
    }
    S->tau = S->step_tau + S->step_h;
    S->steps++;
}

/* Redo the current step up to fraction th, take it, and flip the contact state. */
static int accept_to_event(tt_sim *S, double th)
{
    double h = S->step_h;
    observe(S, th);
    if (th > 0) {
        if (S->solver.method == TT_METHOD_DOPRI5) {
            (void)dopri5_step(S, th * h);
        } else if (S->solver.method == TT_METHOD_RADAU) {
            /* the step's own polynomial gives the redo's Newton iteration its start */
            memcpy(S->ext, S->rcont, sizeof S->ext);
            S->ext_tau = S->step_tau;
            S->ext_h = S->step_h;
            S->ext_ok = 1;
            (void)radau_step(S, th * h);
            if (!S->newton_it)
                return tt_error(TT_ENUM,
                                "radau: Newton iteration failed at a contact event at t = %.9g s "
                                "(cycle %ld); tighten [solver] tolerance",
                                tt_sim_time(S) + S->step_tau, S->cycle);
        } else {
            rk4_step(S, th * h);
        }
        memcpy(S->y, S->y1, sizeof S->y);
        S->tau = S->step_tau + S->step_h;
        S->steps++;
    }
    /* Energy jumps by U_old - U_new at the switch: the hysteresis loss (PHYSICS.md). */
    double U_old = energy(S, S->tau, S->y, S->contact_state);
    S->contact_state = !S->contact_state;
    double U_new = energy(S, S->tau, S->y, S->contact_state);
    S->e_jumps += U_old - U_new;
    if (S->contact_state && !isfinite(S->t_contact))
        S->t_contact = S->tau;
    if (!S->contact_state)
        S->t_release = S->tau;
    invalidate(S);
    S->events++;
    S->step_h = h; /* keep the step length the controller chose */
    return TT_OK;
}

static int check_finite(tt_sim *S)
{
    if (!isfinite(S->y[Y_D]) || !isfinite(S->y[Y_V]))
        return tt_error(TT_ENUM,
                        "the solution became NaN or infinite at t = %.9g s (cycle %ld); "
                        "tighten [solver] tolerance or raise steps_per_cycle",
                        tt_sim_time(S) + S->tau, S->cycle);
    return TT_OK;
}

/* rk4 is stable for oscillation only while h * sqrt(k_contact / m) < 2.8; past that it
 * returns wrong numbers, so refuse with the cause. The stiffness is the current branch's
 * at penetration delta: out of contact too, since a branch may already push back there
 * (Hertz without adhesion has one force law for both states). */
static int rk4_check_stiffness(tt_sim *S, double h, double delta)
{
    if (!S->contact)
        return TT_OK;
    double dPdd = 0;
    (void)tt_contact_load(S->contact, delta, S->contact_state, &dPdd, NULL);
    double keff = S->c.k + (dPdd > 0 ? dPdd : 0);
    double ci = S->contact_state ? S->ci : 0.0; /* interaction damping acts in contact only */
    double wc = sqrt(keff / S->c.m), wi = ci / S->c.m; /* the damping's rate, 1/s */
    if (h * wc > 2.5 || h * wi > 2.5)
        return tt_error(TT_ENUM,
                        "rk4 step too large for the contact: contact stiffness %.3g N/m (%.0f times "
                        "the cantilever's)%s needs at least %.0f steps per cycle; raise [solver] "
                        "steps_per_cycle or use method = dopri5 (or radau, implicit, for a contact "
                        "this stiff)",
                        keff, keff / S->c.k, wi > wc ? " and its damping" : "",
                        ceil(S->c.T * fmax(wc, wi) / 2.5));
    return TT_OK;
}

int tt_sim_cycle(tt_sim *S, tt_cycle *out)
{
    const tt_cantilever *c = &S->c;
    const double T = c->T;
    memset(out, 0, sizeof *out);
    for (int i = Y_WDRIVE; i < NY; i++)
        S->y[i] = 0;
    S->tau = 0;
    S->peak_force = -INFINITY;
    S->max_indent = -INFINITY;
    S->y_min = INFINITY;
    S->y_max = -INFINITY;
    S->e_jumps = 0;
    S->t_contact = S->t_release = NAN;
    S->steps = S->rejected = S->events = 0;
    S->next_sample = 0;
    S->rk4_j = 1;
    S->step_flight = 0;
    double E_start = energy(S, 0, S->y, S->contact_state);

    /* the sample at k = 0 is the cycle-start state */
    if (S->nsamp > 0) {
        S->step_tau = 0;
        S->step_h = 0;
        memcpy(S->y0, S->y, sizeof S->y0);
        memcpy(S->y1, S->y, sizeof S->y1);
        ensure_fsal(S);
        memcpy(S->k[0], S->fsal, sizeof S->k[0]);
        memcpy(S->k[6], S->fsal, sizeof S->k[6]);
        for (int i = 0; i < 2; i++) {
            S->rcont[0][i] = S->y[i];
            S->rcont[1][i] = S->rcont[2][i] = S->rcont[3][i] = S->rcont[4][i] = 0;
        }
        observe(S, 0);
    }

    const double hgrid = T / S->solver.steps_per_cycle;
    const double hmin = T * 1e-13;
    long guard = 0;
    while (S->tau < T) {
        if (++guard > 50000000L)
            return tt_error(TT_ENUM, "no progress within cycle %ld", S->cycle);
        double h;
        if (S->solver.method == TT_METHOD_RK4) {
            /* grid times j T / N, computed from the index, never accumulated */
            double tnext = S->rk4_j >= S->solver.steps_per_cycle ? T : S->rk4_j * hgrid;
            h = tnext - S->tau;
            if (h <= hmin) {
                S->rk4_j++;
                if (tnext >= T) {
                    S->tau = T;
                    break;
                }
                continue;
            }
            int rc = rk4_check_stiffness(S, h, S->y[Y_D] - (S->s0 + S->sdot * S->tau));
            if (rc)
                return rc;
            rk4_step(S, h);
            /* ... and at the deepest stage, before an unstable step is taken */
            if ((rc = rk4_check_stiffness(S, h, S->rk4_dmax)))
                return rc;
        } else {
            /* Out of contact and away from the surface, the free flight's exponential
             * steps; they hand over to dopri5 near jump-in and when they would be short. */
            if (S->fl_wait && S->y[Y_V] - S->sdot < 0)
                S->fl_wait = 0;
            if (S->fl_ok && !S->contact_state && S->fl_skip == 0 && !S->fl_wait &&
                S->y[Y_D] - (S->s0 + S->sdot * S->tau) < S->jumpin - S->fl_margin) {
                int r = S->fl_rung;
                double hf = S->fl_hr[r];
                const fl_cache *F;
                int lastf = 0;
                if (S->tau + hf >= T - hmin) {
                    hf = T - S->tau;
                    lastf = 1;
                }
                if (lastf) {
                    if (!(S->fl_scr.ok && S->fl_scr.h == hf))
                        fl_fill(S, &S->fl_scr, hf);
                    F = &S->fl_scr;
                } else {
                    if (!S->fl_lad[r].ok)
                        fl_fill(S, &S->fl_lad[r], hf);
                    F = &S->fl_lad[r];
                }
                if (S->c.w0 * hf >= 0.1) {
                    double err = flight_step(S, hf, F);
                    if (err < 0 || flight_near(S))
                        S->fl_wait = 1; /* the approach: no more tries until it recedes */
                    else {
                        /* the estimate is O(h^7): one rung (2^(1/4)) per factor 5 */
                        int nr = r;
                        if (err > 1)
                            nr = r + 1 + (int)(log(err) * (4.0 / 7.0 / M_LN2));
                        else if (!lastf && !S->fl_rej && err < 0.2)
                            /* grow by 0.9 err^(-1/7), at most two rungs (a factor 1.41):
                             * an approaching tip's error grows fast from step to step */
                            nr = r - (err < 0.04 ? 2 : 1);
                        S->fl_rej = err > 1;
                        if (nr < 0)
                            nr = 0;
                        if (err > 1) {
                            S->rejected++;
                            if (nr >= S->fl_nrung) {
                                S->fl_rung = S->fl_nrung - 1;
                                S->fl_skip = 4; /* too short to pay: dopri5 for a while */
                            } else {
                                S->fl_rung = nr;
                            }
                            continue;
                        }
                        if (!lastf)
                            S->fl_rung = nr;
                        accept_full(S);
                        int rc = check_finite(S);
                        if (rc)
                            return rc;
                        if (S->tau > T)
                            S->tau = T;
                        continue;
                    }
                }
            }
            if (S->fl_skip > 0)
                S->fl_skip--;
            h = S->h;
            if (h > T / 8)
                h = T / 8; /* keeps turning points of a cycle within reach of the checks */
            if (h > S->radau_hmax)
                h = S->radau_hmax;
            int last = 0;
            if (S->tau + h >= T - hmin) {
                h = T - S->tau;
                last = 1;
            }
            double err, fac;
            if (S->solver.method == TT_METHOD_RADAU) {
                err = radau_step(S, h);
                if (!S->newton_it) {
                    fac = 0.5; /* Newton failed: the step was too long for the Jacobian */
                } else {
                    /* Hairer's safety factor, smaller after a slow Newton iteration; the
                     * estimate is O(h^4) */
                    double safe = fmin(0.9, 0.9 * (1 + 2 * NEWTON_MAX) /
                                                (S->newton_it + 2 * NEWTON_MAX));
                    fac = err > 0 ? safe * pow(err, -0.25) : 5.0;
                }
            } else {
                err = dopri5_step(S, h);
                fac = step_factor5(err);
            }
            if (fac > 5)
                fac = 5;
            if (fac < 0.2)
                fac = 0.2;
            S->last_rejected = err > 1;
            if (err > 1) {
                S->rejected++;
                S->h = h * fac;
                if (S->h < hmin)
                    return tt_error(TT_ENUM,
                                    "step size underflow at t = %.9g s (cycle %ld): the force law is "
                                    "too abrupt for tolerance %g",
                                    tt_sim_time(S) + S->tau, S->cycle, S->solver.tolerance);
                continue;
            }
            if (!last || fac < 1)
                S->h = h * fac;
        }
        double th = find_event(S);
        if (th <= 1) {
            int rc = accept_to_event(S, th);
            if (rc)
                return rc;
        } else {
            accept_full(S);
            if (S->solver.method == TT_METHOD_RK4)
                S->rk4_j++;
        }
        int rc = check_finite(S);
        if (rc)
            return rc;
        if (S->tau > T)
            S->tau = T;
    }

    double E_end = energy(S, T, S->y, S->contact_state);
    double X = 2.0 / T * S->y[Y_IC], Yq = 2.0 / T * S->y[Y_IS];
    out->amplitude = hypot(X, Yq);
    double ph = atan2(Yq, X);
    if (ph < -M_PI / 2)
        ph += 2 * M_PI; /* lags run from about 0 to past 180 degrees */
    out->phase = ph;
    out->mean = S->y[Y_IY] / T;
    out->y_min = S->y_min;
    out->y_max = S->y_max;
    out->peak_force = S->peak_force;
    out->max_indentation = S->max_indent;
    out->contact_fraction = S->y[Y_TC] / T;
    out->e_drive = S->y[Y_WDRIVE];
    out->e_damp = S->y[Y_WDAMP];
    out->e_ts = S->y[Y_WCI] + S->e_jumps;
    out->e_sample = S->y[Y_WS];
    out->residual = out->e_drive - out->e_damp - out->e_ts - out->e_sample - (E_end - E_start);
    out->residual_rel = fabs(out->residual) / (M_PI * c->c * c->wd * c->A0 * c->A0);
    out->t_contact = S->t_contact;
    out->t_release = S->t_release;
    out->steps = S->steps;
    out->rejected = S->rejected;
    out->events = S->events;

    /* the next cycle starts at tau = 0 with the sample carried on */
    S->cycle++;
    S->s0 += S->sdot * T;
    S->tau = 0;
    S->ext_tau -= T; /* radau's last polynomial, in the new cycle's time */
    return TT_OK;
}

double tt_sim_force(const tt_sim *S, const tt_sample *smp, double *a)
{
    if (!S->contact) {
        if (a)
            *a = 0;
        return 0;
    }
    double delta = smp->d - smp->s;
    double P = tt_contact_load(S->contact, delta, smp->contact, NULL, a);
    return P + (smp->contact ? S->ci * (smp->v - S->sdot) : 0.0);
}

/* What is left of a settling sequence, from its last two signed changes d and prevd
 * (NAN: none yet), r = d / prevd. Changes of one sign that shrink are a geometric tail
 * summing to d / (1 - r), and ones that do not shrink a drift of Q cycles. Changes that
 * alternate in sign are an oscillation about the limit, which every value lies within
 * |d| of while it does not grow; its growth is extrapolated over Q cycles, so that a
 * steady alternation (|r| = 1 up to rounding) passes and a growing one does not. */
static double remaining(double d, double prevd, double Q)
{
    if (!isfinite(prevd))
        return fabs(d);
    double r = prevd != 0 ? d / prevd : (d == 0 ? 0 : INFINITY);
    if (r < 0)
        return fabs(d) * pow(fmax(1.0, -r), Q);
    if (r < 1)
        return fabs(d) / (1 - r);
    return fabs(d) * Q;
}

/* The longest cycle-to-cycle pattern the settling test sees through. */
#define SETTLE_PERIOD 4

/* What is left to settle of a sequence x (x[0] the newest of n values), the least over
 * periods p of: its drift over p cycles, extrapolated by remaining() with a memory of
 * Q / p periods, plus the spread of its last p values, which a steady pattern of period
 * p keeps for ever. p = 1 is the plain geometric extrapolation; longer periods let a
 * jitter far below the tolerance (the adaptive step pattern can sustain one, with
 * period 2 or 3) count as steady, while a real period-doubled orbit, whose spread is
 * large, does not. */
static double settle_estimate(const double *x, int n, double Q)
{
    double best = n >= 2 ? remaining(x[0] - x[1], n >= 3 ? x[1] - x[2] : NAN, Q) : INFINITY;
    for (int p = 2; p <= SETTLE_PERIOD && 2 * p < n; p++) {
        double spread = 0;
        for (int j = 1; j < p; j++)
            spread = fmax(spread, fabs(x[0] - x[j]));
        double est = remaining(x[0] - x[p], x[p] - x[2 * p], Q / p) + spread;
        if (est < best)
            best = est;
    }
    return best;
}

int tt_sim_settle(tt_sim *S, long max_cycles, double tol, tt_cycle *out, int *settled,
                  long *cycles)
{
    /* Amplitude and phase approach their steady values geometrically (rate about
     * exp(-pi/Q) per cycle near resonance); the change still to come is estimated
     * from the ratio of successive changes, so a slow approach is not taken for
     * convergence. Far off resonance the free mode's transient alternates from cycle
     * to cycle instead, and the adaptive step pattern may keep a tiny pattern of a few
     * cycles going for ever; see settle_estimate. */
    enum { H = 2 * SETTLE_PERIOD + 1 };
    double hA[H] = {0}, hP[H] = {0}; /* only the first nh are read */
    int nh = 0, ok_in_row = 0;
    *settled = 0;
    long n;
    for (n = 0; n < max_cycles; n++) {
        int rc = tt_sim_cycle(S, out);
        if (rc) {
            if (cycles)
                *cycles = n + 1;
            return rc;
        }
        memmove(hA + 1, hA, (H - 1) * sizeof hA[0]);
        memmove(hP + 1, hP, (H - 1) * sizeof hP[0]);
        hA[0] = out->amplitude / S->c.A0;
        hP[0] = out->phase;
        if (nh < H)
            nh++;
        if (nh >= 2) {
            if (settle_estimate(hA, nh, S->c.Q) < tol && settle_estimate(hP, nh, S->c.Q) < tol)
                ok_in_row++;
            else
                ok_in_row = 0;
            if (ok_in_row >= 3) {
                *settled = 1;
                n++;
                break;
            }
        }
    }
    if (cycles)
        *cycles = n;
    return TT_OK;
}
