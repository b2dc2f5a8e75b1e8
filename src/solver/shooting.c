/* Steady oscillations by shooting (see include/tiptap/solver/shooting.h). */
#include "tiptap/solver/shooting.h"

#include <math.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "shooting_linalg.h"

void tt_shoot_default(tt_shoot_params *p)
{
    p->presettle = 16;
    p->max_iter = 20;
    p->attempts = 5;
    p->fd_step = 1e-5;
    p->tol = 1e-9;
}

/* The one-period map in scaled coordinates: positions over the free amplitude L,
 * velocities over w_d L (the state's even and odd components; a further mode's over
 * w_n L, its own frequency), so that all components weigh alike. */
typedef struct {
    tt_sim *sim;
    int n;       /* the state's components (tt_sim_dim) */
    double sc[TT_SIM_DIM_MAX];
    int contact; /* the contact flag every evaluation starts with */
    double floor; /* |F| the integrator's own error leaves (noise_floor) */
    int cancelled; /* a cycle returned TT_EINTR: every later one would too */
    long cycles;
    tt_cycle cy;
} map_ctx;

enum { N = TT_SIM_DIM_MAX };

/* The residual the map's own integration error leaves. With further modes the highest
 * one's components carry the adaptive integrator's error, about its tolerance relative
 * to the free amplitude, and not smoothly in the state: Newton stalls there above any
 * step of 1e-9 (a 3-mode lever in contact at tolerance 3e-8: |F| 7e-8 to 1e-6, 26 of 61
 * approach points settled instead), so a stalled iteration within ten tolerances has
 * converged. One mode's map and rk4's fixed steps are smooth: 0, the step's test alone. */
static double noise_floor(const tt_sim *sim)
{
    const tt_solver *s = tt_sim_solver(sim);
    return tt_sim_cantilever(sim)->modes > 1 && s->method != TT_METHOD_RK4 ? 10 * s->tolerance : 0;
}

static void map_init(map_ctx *m, tt_sim *sim)
{
    const tt_cantilever *c = tt_sim_cantilever(sim);
    double x[N];
    m->sim = sim;
    m->n = tt_sim_dim(sim);
    for (int i = 0; i < m->n; i++)
        m->sc[i] = i % 2 ? c->wd * c->A0 : c->A0;
    for (int i = 1; i < c->modes; i++)
        m->sc[2 * i + 1] = 2 * M_PI * c->mode_f[i] * c->A0;
    m->floor = noise_floor(sim);
    m->cycles = 0;
    m->cancelled = 0;
    tt_sim_get_x(sim, x, &m->contact);
}

static void map_get(const map_ctx *m, double *x, int *contact)
{
    tt_sim_get_x(m->sim, x, contact);
    for (int i = 0; i < m->n; i++)
        x[i] /= m->sc[i];
}

static void map_set(const map_ctx *m, const double *x)
{
    double y[N];
    for (int i = 0; i < m->n; i++)
        y[i] = x[i] * m->sc[i];
    tt_sim_set_x(m->sim, y, m->contact);
}

/* F(x) = P(x) - x. A cycle that fails, or ends with another contact flag than it began
 * with (the map's non-smooth edge), gives F = NAN: no fixed point there. A cancelled
 * cycle does too, and keeps its message for the caller. */
static void residual(map_ctx *m, const double *x, double *F)
{
    double px[N];
    int pc;
    map_set(m, x);
    m->cycles++;
    int rc = tt_sim_cycle(m->sim, &m->cy);
    if (rc != TT_OK) {
        if (rc == TT_EINTR)
            m->cancelled = 1;
        else
            tt_error_clear();
        for (int i = 0; i < m->n; i++)
            F[i] = NAN;
        return;
    }
    map_get(m, px, &pc);
    for (int i = 0; i < m->n; i++)
        F[i] = px[i] - x[i];
    if (pc != m->contact)
        F[0] = NAN;
}

/* |a| over n components (hypot for two, as the one-mode map always took it). */
static double norm(int n, const double *a)
{
    if (n == 2)
        return hypot(a[0], a[1]);
    double s = 0;
    for (int i = 0; i < n; i++)
        s += a[i] * a[i];
    return sqrt(s);
}

static int all_finite(int n, const double *a)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i]))
            return 0;
    return 1;
}

/* Jacobian of F (n x n by rows) by forward differences around x, where F(x) = F0. */
static int jacobian_F(map_ctx *m, const double *x, const double *F0, double h, double *J)
{
    const int n = m->n;
    for (int j = 0; j < n; j++) {
        double xp[N], Fp[N];
        memcpy(xp, x, (size_t)n * sizeof *x);
        xp[j] += h;
        residual(m, xp, Fp);
        if (!all_finite(n, Fp))
            return 0;
        for (int i = 0; i < n; i++)
            J[i * n + j] = (Fp[i] - F0[i]) / h;
    }
    return 1;
}

/* Solve J s = -F; 0 if J is singular at working precision. */
static int newton_step(int n, const double *J, const double *F, double *s)
{
    double A[N * N], b[N];
    memcpy(A, J, (size_t)n * (size_t)n * sizeof *J);
    for (int i = 0; i < n; i++)
        b[i] = -F[i];
    return tt_shoot_solve(n, A, b, s, 0);
}

/* Broyden's rank-one update of J after the step s changed F by dF. */
static void broyden(int n, double *J, const double *s, const double *dF)
{
    double ss = s[0] * s[0];
    for (int j = 1; j < n; j++)
        ss += s[j] * s[j];
    if (!(ss > 0))
        return;
    for (int i = 0; i < n; i++) {
        double *Ji = J + i * n, js = Ji[0] * s[0];
        for (int j = 1; j < n; j++)
            js += Ji[j] * s[j];
        const double r = dF[i] - js;
        for (int j = 0; j < n; j++)
            Ji[j] += r * s[j] / ss;
    }
}

/* Backtracking along s from x: the first x + l s (l = 1, 1/2, ... 1/32) whose residual
 * decreases enough. Returns 1 and the new point and residual, or 0. */
static int line_search(map_ctx *m, const double *x, const double *F, const double *s,
                       double *xn, double *Fn)
{
    const int n = m->n;
    double f0 = norm(n, F);
    for (double l = 1; l >= 1.0 / 32; l /= 2) {
        for (int i = 0; i < n; i++)
            xn[i] = x[i] + l * s[i];
        residual(m, xn, Fn);
        if (norm(n, Fn) <= (1 - 0.25 * l) * f0)
            return 1;
    }
    return 0;
}

/* Newton from the sim's state; F0 gets the residual there (scaled). TT_EINTR when
 * cancelled, else TT_OK whether it converged or not. */
static int newton(tt_sim *sim, const tt_shoot_params *p, double *F0, int *converged,
                  int *iterations, long *cycles)
{
    map_ctx m;
    map_init(&m, sim);
    const int n = m.n;
    double x[N], F[N], J[N * N], s[N], xn[N], Fn[N];
    int dummy, fresh = 1;
    map_get(&m, x, &dummy);
    *converged = 0;
    *iterations = 0;
    residual(&m, x, F);
    memcpy(F0, F, (size_t)n * sizeof *F);
    int ok = all_finite(n, F) && jacobian_F(&m, x, F, p->fd_step, J);
    for (int it = 0; ok && !m.cancelled && it < p->max_iter; it++) {
        *iterations = it + 1;
        if (!newton_step(n, J, F, s))
            break;
        if (norm(n, s) < p->tol) {
            for (int i = 0; i < n; i++)
                x[i] += s[i];
            *converged = 1;
            break;
        }
        if (!line_search(&m, x, F, s, xn, Fn)) {
            if (norm(n, F) < m.floor) {
                *converged = 1;
                break;
            }
            /* A stale Broyden Jacobian may point the wrong way: one fresh one, then stop. */
            if (fresh || !jacobian_F(&m, x, F, p->fd_step, J))
                break;
            fresh = 1;
            continue;
        }
        double step[N], dF[N];
        for (int i = 0; i < n; i++) {
            step[i] = xn[i] - x[i];
            dF[i] = Fn[i] - F[i];
        }
        broyden(n, J, step, dF);
        fresh = 0;
        memcpy(x, xn, (size_t)n * sizeof *x);
        memcpy(F, Fn, (size_t)n * sizeof *F);
    }
    map_set(&m, x);
    *cycles = m.cycles;
    if (m.cancelled) {
        *converged = 0;
        return TT_EINTR;
    }
    return TT_OK;
}

int tt_shoot_newton(tt_sim *sim, const tt_shoot_params *p, int *converged, int *iterations,
                    long *cycles)
{
    double F0[N];
    return newton(sim, p, F0, converged, iterations, cycles);
}

/* The monodromy matrix dP/dx (scaled, n x n by rows) at the sim's state by central
 * differences. */
static int monodromy(tt_sim *sim, const tt_shoot_params *p, double *J)
{
    map_ctx m;
    map_init(&m, sim);
    const int n = m.n;
    double x[N], h = p->fd_step;
    int dummy;
    map_get(&m, x, &dummy);
    for (int j = 0; j < n; j++) {
        double xp[N], xm[N], Fp[N], Fm[N];
        memcpy(xp, x, (size_t)n * sizeof *x);
        memcpy(xm, x, (size_t)n * sizeof *x);
        xp[j] += h;
        xm[j] -= h;
        residual(&m, xp, Fp);
        residual(&m, xm, Fm);
        /* dP/dx = dF/dx + I */
        for (int i = 0; i < n; i++)
            J[i * n + j] = (Fp[i] - Fm[i]) / (2 * h) + (i == j);
    }
    map_set(&m, x);
    if (m.cancelled)
        return TT_EINTR;
    if (!all_finite(n * n, J))
        return tt_error(TT_ENUM, "Floquet multipliers: the map is not smooth at this orbit");
    return TT_OK;
}

int tt_shoot_multipliers(tt_sim *sim, const tt_shoot_params *p, double *mu_re, double *mu_im)
{
    const int n = tt_sim_dim(sim);
    double J[N * N];
    for (int i = 0; i < n; i++)
        mu_re[i] = mu_im[i] = NAN;
    int rc = monodromy(sim, p, J);
    if (rc == TT_OK)
        tt_shoot_eigen(n, J, mu_re, mu_im, 0);
    return rc;
}

/* Whether a cycle touched the sample: the attractive and repulsive branches of a
 * bistable scene differ in this (Garcia and San Paulo 1999). */
static int touched(const tt_cycle *c) { return c->contact_fraction > 0 || c->events > 0; }

/* The last cycle-start states of the real motion (scaled), oldest first, with the
 * state the motion reached last. */
#define TRAIL 16
typedef struct {
    double x[TRAIL + 2][N];
    int n;
} trail;

/* Run n cycles of the real motion, keeping its last states in tr; *pattern: 1 or 0 if
 * the last four cycles all touched or all did not, -1 if they disagree (the motion is
 * still changing branch). */
static int run_cycles(tt_sim *sim, long n, tt_cycle *out, int *pattern, trail *tr, long *cycles)
{
    map_ctx m;
    int last[4] = {-1, -2, -3, -4}, dummy;
    map_init(&m, sim);
    tr->n = 0;
    for (long i = 0; i < n; i++) {
        if (n - i <= TRAIL && 2 * i >= n) /* the first cycles may still be far out */
            map_get(&m, tr->x[tr->n++], &dummy);
        int rc = tt_sim_cycle(sim, out);
        (*cycles)++;
        if (rc)
            return rc;
        last[i % 4] = touched(out);
    }
    *pattern = (last[0] == last[1] && last[1] == last[2] && last[2] == last[3]) ? last[0] : -1;
    return TT_OK;
}

/* e^T M e (M n x n by rows; the one-mode form as it always summed). */
static double quadratic(int n, const double *M, const double *e)
{
    if (n == 2)
        return M[0] * e[0] * e[0] + 2 * M[1] * e[0] * e[1] + M[3] * e[1] * e[1];
    double V = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            V += M[i * n + j] * e[i] * e[j];
    return V;
}

/* Whether the real motion runs into the orbit xs: V, the orbit's Lyapunov function,
 * falls along its last cycles (allowing the nonlinear motion a rise of 5 % in a cycle)
 * and is still at its least at the end. A stable orbit near a jump between branches has
 * a small basin; a motion that passes by it (and settles on the other branch) shows V
 * rising again, and then settling decides. */
static int in_basin(int n, const trail *tr, const double *xs, const double *J, double mu_abs)
{
    double M[N * N], first = 0, prev = 0, least = INFINITY, e[N], r[N];
    if (!tt_shoot_lyapunov(n, J, M, 0))
        return 0;
    for (int k = 0; k < tr->n; k++) {
        for (int i = 0; i < n; i++)
            e[i] = tr->x[k][i] - xs[i];
        double V = quadratic(n, M, e);
        if (k > 0 && V > 1.05 * prev && V > 1e-16)
            return 0;
        if (k == 0)
            first = V;
        prev = V;
        least = fmin(least, V);
    }
    /* and it must still be closing in at the end, not passing by, and be near: a motion
     * far out (a tenth of the free amplitude) may still swing over to another branch */
    const double *x = tr->x[tr->n - 1], *x0 = tr->x[tr->n - 2];
    double off[N];
    for (int i = 0; i < n; i++)
        e[i] = x0[i] - xs[i];
    for (int i = 0; i < n; i++) { /* what the linearisation misses of the last cycle */
        double je = J[i * n] * e[0];
        for (int j = 1; j < n; j++)
            je += J[i * n + j] * e[j];
        r[i] = x[i] - xs[i] - je;
        off[i] = x[i] - xs[i];
    }
    int linear = norm(n, r) < 0.01 * (1 - mu_abs) * norm(n, e);
    if (!linear && norm(n, off) > 0.1)
        return 0;
    return prev < 1e-16 || (prev < first && prev <= 1.01 * least);
}

/* Newton's orbit from the sim's state, checked; 1 if it is the point (out is its last
 * cycle, the sim at its end), 0 if refused (res->why says why; the sim is anywhere) or
 * cancelled (*rc = TT_EINTR). */
static int try_orbit(tt_sim *sim, const tt_shoot_params *p, int pattern, trail *tr,
                     tt_cycle *out, tt_shoot_result *res, int *rc)
{
    map_ctx m;
    double F0[N], J[N * N], xs[N];
    long cyc = 0;
    int dummy;
    map_init(&m, sim);
    const int n = m.n;
    double *x0 = tr->x[tr->n++];
    map_get(&m, x0, &dummy);
    *rc = newton(sim, p, F0, &res->converged, &res->iterations, &cyc);
    /* the motion's next state, P(x0), from Newton's first residual */
    for (int i = 0; i < n; i++)
        tr->x[tr->n][i] = x0[i] + F0[i];
    tr->n++;
    res->cycles += cyc;
    if (*rc)
        return 0;
    if (!res->converged) {
        res->why = "Newton did not converge";
        return 0;
    }
    tt_sim_get_x(sim, res->x, &res->contact);
    res->d = res->x[0];
    res->v = n > 1 ? res->x[1] : 0;
    int mrc = monodromy(sim, p, J);
    res->cycles += 2 * n;
    if (mrc == TT_EINTR) {
        *rc = mrc;
        return 0;
    }
    if (mrc != TT_OK) {
        tt_error_clear();
        res->why = "the map is not smooth at the orbit";
        return 0;
    }
    tt_shoot_eigen(n, J, res->mu_re, res->mu_im, 0);
    res->mu_abs = hypot(res->mu_re[0], res->mu_im[0]);
    for (int i = 1; i < n; i++)
        res->mu_abs = fmax(res->mu_abs, hypot(res->mu_re[i], res->mu_im[i]));
    if (!(res->mu_abs < 1)) {
        res->why = "the orbit is unstable";
        return 0;
    }
    map_get(&m, xs, &dummy);
    if (!in_basin(n, tr, xs, J, res->mu_abs)) {
        res->why = "the motion is not in the orbit's basin yet";
        return 0;
    }
    int crc = tt_sim_cycle(sim, out);
    res->cycles++;
    if (crc == TT_EINTR) {
        *rc = crc;
        return 0;
    }
    if (crc != TT_OK) {
        tt_error_clear();
        res->why = "the orbit's cycle failed";
        return 0;
    }
    if (touched(out) != pattern) {
        res->why = pattern ? "the orbit does not touch, the settling cycles did"
                           : "the orbit touches, the settling cycles did not";
        return 0;
    }
    res->why = "";
    return 1;
}

int tt_shoot_steady(tt_sim *sim, const tt_shoot_params *p, long max_cycles, double tol,
                    tt_cycle *out, int *settled, tt_shoot_result *res)
{
    memset(res, 0, sizeof *res);
    *settled = 0;
    res->n = tt_sim_dim(sim);
    for (int i = 0; i < TT_SIM_DIM_MAX; i++)
        res->mu_re[i] = res->mu_im[i] = NAN;
    res->mu_abs = NAN;
    res->why = "";
    long run = 0, k = p->presettle > 0 ? p->presettle : 1;
    /* Attempts stop at half the cycles settling is expected to need (the transient
     * decays as exp(-pi n / Q)): at low Q settling itself is cheap. */
    double Q = tt_sim_cantilever(sim)->Q;
    double budget = fmin((double)max_cycles, 0.5 * Q / M_PI * log(1 / fmin(tol, 0.1)));
    int rc;
    for (int attempt = 0; attempt < p->attempts && run + k <= fmax(budget, k); attempt++, k *= 2) {
        int pattern;
        trail tr;
        if ((rc = run_cycles(sim, k, out, &pattern, &tr, &run))) {
            res->cycles = run;
            return rc;
        }
        if (pattern < 0)
            continue;
        /* Newton starts from the real motion and returns to it when refused, so that a
         * fall-back settles the same trajectory as settling alone would. */
        double x[N];
        int c;
        tt_sim_get_x(sim, x, &c);
        if (try_orbit(sim, p, pattern, &tr, out, res, &rc)) {
            res->how = TT_SHOOT_NEWTON;
            res->cycles += run;
            *settled = 1;
            return TT_OK;
        }
        if (rc) {
            res->cycles += run;
            return rc;
        }
        tt_sim_set_x(sim, x, c);
    }
    res->how = TT_SHOOT_SETTLED;
    rc = tt_sim_settle_orbit(sim, max_cycles > run ? max_cycles - run : 1, tol, out, &res->settle);
    *settled = res->settle.settled;
    res->cycles += run + res->settle.cycles;
    tt_sim_get_x(sim, res->x, &res->contact);
    res->d = res->x[0];
    res->v = res->n > 1 ? res->x[1] : 0;
    return rc;
}
