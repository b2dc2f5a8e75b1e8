/* The Dormand-Prince 5(4) step type with its dense output and step-size factor; out of
 * contact it lets the free flight (flight.c) take the steps it can. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "control.h"
#include "flight.h"
#include "tiptap/util/error.h"

/* dopri5's own state: its step-size control, the free flight it hands steps to, the
 * stages and the dense output's coefficients of d and v. */
typedef struct {
    tt_step_control ctl;
    tt_flight *fl;
    double k[6][NYMAX]; /* stages 1 to 5 (stage 0 and the end are the record's dydt_in, dydt_out) */
    double rcont[5][TT_SIM_DIM_MAX]; /* the dense output of the system's n components */
} dopri5_state;

/* Dormand & Prince 1980; dense output of Hairer's dopri5. */
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

/* dopri5's step-size factor 0.9 err^(-1/5), clamped to [0.2, 5], without pow (a tenth
 * of the run time, on the critical path of every step): with err = m 2^e, m in [1, 2),
 * a table gives 0.9 2^(-e/5) and a degree-5 polynomial (Chebyshev nodes, Estrin form)
 * m^(-1/5) to 3.3e-6, far finer than a step-size factor needs. Inside the clamps err
 * lies in [(0.9/5)^5, (0.9/0.2)^5], so e runs from -13 to 10. */
static double dopri5_factor(const void *state, double err)
{
    (void)state;
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

/* Hairer's dense output coefficients of the n components for the step just computed. */
static inline void dopri5_dense_fill(dopri5_state *st, const tt_sim *S, const double *y0, double h,
                                     const int n)
{
    double (*k)[NYMAX] = st->k;
    const double *k0 = S->dydt_in, *k6 = S->dydt_out;
    for (int i = 0; i < n; i++) {
        double ydiff = S->y1[i] - y0[i];
        double bspl = h * k0[i] - ydiff;
        st->rcont[0][i] = y0[i];
        st->rcont[1][i] = ydiff;
        st->rcont[2][i] = bspl;
        st->rcont[3][i] = ydiff - h * k6[i] - bspl;
        st->rcont[4][i] = h * (D1 * k0[i] + D3 * k[2][i] + D4 * k[3][i] + D5 * k[4][i] +
                              D6 * k[5][i] + D7 * k6[i]);
    }
}

/* One Dormand-Prince 5(4) step of a system of n components (a constant where inlined
 * for n = 2, so that the one-mode elastic system's loops unroll). Returns the scaled
 * error norm (<= 1 accepts). */
static inline __attribute__((always_inline)) double dopri5_step_n(void *state, tt_sim *S,
                                                                  double h, const int n)
{
    dopri5_state *st = state;
    double (*k)[NYMAX] = st->k, yt[NYMAX];
    double *k0 = S->dydt_in, *k6 = S->dydt_out;
    const double *y0 = S->y;
    double t = S->tau;
    int cs = S->contact_state;
    const int ny = n + NQ;
    const size_t sz = (size_t)ny * sizeof *yt;
    ensure_fsal(S);
    memcpy(k0, S->fsal, sz);
    /* The stages read only the system's n components (the motion and the law's states):
     * the integrals do not feed back, so only the step's end carries them. */
    memcpy(yt, y0, sz);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + h * A21 * k0[i];
    S->sys.rhs(S, t + C2 * h, yt, cs, k[1]);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + h * (A31 * k0[i] + A32 * k[1][i]);
    S->sys.rhs(S, t + C3 * h, yt, cs, k[2]);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + h * (A41 * k0[i] + A42 * k[1][i] + A43 * k[2][i]);
    S->sys.rhs(S, t + C4 * h, yt, cs, k[3]);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + h * (A51 * k0[i] + A52 * k[1][i] + A53 * k[2][i] + A54 * k[3][i]);
    S->sys.rhs(S, t + C5 * h, yt, cs, k[4]);
    for (int i = 0; i < n; i++)
        yt[i] = y0[i] + h * (A61 * k0[i] + A62 * k[1][i] + A63 * k[2][i] + A64 * k[3][i] +
                             A65 * k[4][i]);
    S->sys.rhs(S, t + h, yt, cs, k[5]);
    for (int i = 0; i < ny; i++)
        S->y1[i] = y0[i] + h * (A71 * k0[i] + A73 * k[2][i] + A74 * k[3][i] + A75 * k[4][i] +
                                A76 * k[5][i]);
    S->sys.rhs(S, t + h, S->y1, cs, k6);
    /* Error on the system's components, relative to the free amplitude (and its
     * velocity for each mode's velocity; a law's states are lengths, held to the
     * amplitude's scale as positions are). */
    const double scd = S->solver.tolerance * S->c.A0, scv = scd * S->c.wd;
    const int nm = 2 * S->sys.modes;
    double err = 0;
    for (int i = 0; i < n; i++) {
        double e = h * (E1 * k0[i] + E3 * k[2][i] + E4 * k[3][i] + E5 * k[4][i] + E6 * k[5][i] +
                        E7 * k6[i]);
        double r = fabs(e) / (i < nm && (i & 1) ? scv : scd);
        if (r > err)
            err = r;
    }
    if (!isfinite(err))
        err = INFINITY;
    dopri5_dense_fill(st, S, y0, h, n);
    memcpy(S->y0, y0, sz);
    S->step_tau = t;
    S->step_h = h;
    S->step_long = 0;
    return err;
}

/* The step: unrolled for the one-mode elastic system, over n otherwise. */
static double dopri5_step(void *state, tt_sim *S, double h)
{
    if (S->sys.n == 2)
        return dopri5_step_n(state, S, h, 2);
    return dopri5_step_n(state, S, h, S->sys.n);
}

static void dopri5_dense(const void *state, const tt_sim *S, double th, double *d, double *v)
{
    const dopri5_state *st = state;
    if (S->step_long) {
        tt_flight_dense(st->fl, S, th, d, v);
        return;
    }
    double th1 = 1 - th;
    double out[2];
    for (int i = 0; i < 2; i++)
        out[i] = st->rcont[0][i] +
                 th * (st->rcont[1][i] +
                       th1 * (st->rcont[2][i] + th * (st->rcont[3][i] + th1 * st->rcont[4][i])));
    *d = out[0];
    *v = out[1];
}

/* The system's n components at fraction th (a flight step's own, exact). */
static void dopri5_dense_x(const void *state, const tt_sim *S, double th, double *x)
{
    const dopri5_state *st = state;
    if (S->step_long) {
        tt_flight_dense_x(st->fl, S, th, x);
        return;
    }
    double th1 = 1 - th;
    for (int i = 0; i < S->sys.n; i++)
        x[i] = st->rcont[0][i] +
               th * (st->rcont[1][i] +
                     th1 * (st->rcont[2][i] + th * (st->rcont[3][i] + th1 * st->rcont[4][i])));
}

/* Out of contact and away from the surface, the free flight's exponential steps; they
 * hand over to dopri5 near jump-in and when they would be short. */
static int dopri5_advance(void *state, tt_sim *S, double T, int *outcome)
{
    dopri5_state *st = state;
    int flown = tt_flight_advance(st->fl, S, T);
    if (flown != TT_STEP_PASS) {
        *outcome = flown;
        return TT_OK;
    }
    return tt_control_advance(&st->ctl, st, S, T, dopri5_step, dopri5_factor, outcome);
}

static int dopri5_redo(void *state, tt_sim *S, double h)
{
    (void)dopri5_step(state, S, h);
    return TT_OK;
}

/* The step of length 0 at (tau, y): its polynomial is the constant y. */
static void dopri5_point(void *state, const tt_sim *S)
{
    tt_poly_point(((dopri5_state *)state)->rcont, S->y, S->sys.n);
}

static void dopri5_reset(void *state, const tt_sim *S)
{
    dopri5_state *st = state;
    tt_control_reset(&st->ctl, S->c.T);
    tt_step_flight.reset(st->fl, S);
}

static void dopri5_setup(void *state, const tt_sim *S)
{
    tt_step_flight.setup(((dopri5_state *)state)->fl, S);
}

static void dopri5_free(void *state)
{
    dopri5_state *st = state;
    if (st)
        tt_step_flight.free(st->fl);
    free(st);
}

static void *dopri5_alloc(const tt_sim *S)
{
    dopri5_state *st = calloc(1, sizeof *st);
    if (!st)
        return NULL;
    st->fl = tt_step_flight.alloc(S);
    if (!st->fl) {
        free(st);
        return NULL;
    }
    tt_control_reset(&st->ctl, S->c.T);
    st->ctl.hmax = INFINITY;
    return st;
}

const tt_step_type tt_step_dopri5 = {
    .name = "dopri5",
    .alloc = dopri5_alloc,
    .free = dopri5_free,
    .reset = dopri5_reset,
    .setup = dopri5_setup,
    .advance = dopri5_advance,
    .redo = dopri5_redo,
    .dense = dopri5_dense,
    .dense_x = dopri5_dense_x,
    .point = dopri5_point,
};
