/* Steady oscillations by shooting (see include/tiptap/solver/shooting.h). */
#include "tiptap/solver/shooting.h"

#include <math.h>
#include <string.h>

#include "tiptap/util/error.h"

void tt_shoot_default(tt_shoot_params *p)
{
    p->presettle = 16;
    p->max_iter = 20;
    p->attempts = 5;
    p->fd_step = 1e-5;
    p->tol = 1e-9;
}

/* The one-period map in scaled coordinates: lengths over the free amplitude L,
 * velocities over w_d L, so that both components of the state weigh alike. */
typedef struct {
    tt_sim *sim;
    double L, V;
    int contact; /* the contact flag every evaluation starts with */
    int cancelled; /* a cycle returned TT_EINTR: every later one would too */
    long cycles;
    tt_cycle cy;
} map_ctx;

static void map_init(map_ctx *m, tt_sim *sim)
{
    const tt_cantilever *c = tt_sim_cantilever(sim);
    double d, v;
    m->sim = sim;
    m->L = c->A0;
    m->V = c->wd * c->A0;
    m->cycles = 0;
    m->cancelled = 0;
    tt_sim_get_state(sim, &d, &v, &m->contact);
}

static void map_get(const map_ctx *m, double x[2], int *contact)
{
    double d, v;
    tt_sim_get_state(m->sim, &d, &v, contact);
    x[0] = d / m->L;
    x[1] = v / m->V;
}

static void map_set(const map_ctx *m, const double x[2])
{
    tt_sim_set_state(m->sim, x[0] * m->L, x[1] * m->V, m->contact);
}

/* F(x) = P(x) - x. A cycle that fails, or ends with another contact flag than it began
 * with (the map's non-smooth edge), gives F = NAN: no fixed point there. A cancelled
 * cycle does too, and keeps its message for the caller. */
static void residual(map_ctx *m, const double x[2], double F[2])
{
    double px[2];
    int pc;
    map_set(m, x);
    m->cycles++;
    int rc = tt_sim_cycle(m->sim, &m->cy);
    if (rc != TT_OK) {
        if (rc == TT_EINTR)
            m->cancelled = 1;
        else
            tt_error_clear();
        F[0] = F[1] = NAN;
        return;
    }
    map_get(m, px, &pc);
    F[0] = pc == m->contact ? px[0] - x[0] : NAN;
    F[1] = px[1] - x[1];
}

static double norm2(const double a[2]) { return hypot(a[0], a[1]); }

/* Jacobian of F by forward differences around x, where F(x) = F0 is known. */
static int jacobian_F(map_ctx *m, const double x[2], const double F0[2], double h, double J[2][2])
{
    for (int j = 0; j < 2; j++) {
        double xp[2] = {x[0], x[1]}, Fp[2];
        xp[j] += h;
        residual(m, xp, Fp);
        if (!isfinite(Fp[0]) || !isfinite(Fp[1]))
            return 0;
        J[0][j] = (Fp[0] - F0[0]) / h;
        J[1][j] = (Fp[1] - F0[1]) / h;
    }
    return 1;
}

/* Solve J s = -F (2 x 2, Cramer); 0 if J is singular at working precision. */
static int newton_step(double J[2][2], const double F[2], double s[2])
{
    double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    double scale = fabs(J[0][0] * J[1][1]) + fabs(J[0][1] * J[1][0]);
    if (!(fabs(det) > 1e-14 * scale))
        return 0;
    s[0] = (-F[0] * J[1][1] + F[1] * J[0][1]) / det;
    s[1] = (-F[1] * J[0][0] + F[0] * J[1][0]) / det;
    return 1;
}

/* Broyden's rank-one update of J after the step s changed F by dF. */
static void broyden(double J[2][2], const double s[2], const double dF[2])
{
    double ss = s[0] * s[0] + s[1] * s[1];
    if (!(ss > 0))
        return;
    for (int i = 0; i < 2; i++) {
        double r = dF[i] - (J[i][0] * s[0] + J[i][1] * s[1]);
        J[i][0] += r * s[0] / ss;
        J[i][1] += r * s[1] / ss;
    }
}

/* Backtracking along s from x: the first x + l s (l = 1, 1/2, ... 1/32) whose residual
 * decreases enough. Returns 1 and the new point and residual, or 0. */
static int line_search(map_ctx *m, const double x[2], const double F[2], const double s[2],
                       double xn[2], double Fn[2])
{
    double f0 = norm2(F);
    for (double l = 1; l >= 1.0 / 32; l /= 2) {
        xn[0] = x[0] + l * s[0];
        xn[1] = x[1] + l * s[1];
        residual(m, xn, Fn);
        if (norm2(Fn) <= (1 - 0.25 * l) * f0)
            return 1;
    }
    return 0;
}

/* Newton from the sim's state; F0 gets the residual there (scaled). TT_EINTR when
 * cancelled, else TT_OK whether it converged or not. */
static int newton(tt_sim *sim, const tt_shoot_params *p, double F0[2], int *converged,
                   int *iterations, long *cycles)
{
    map_ctx m;
    map_init(&m, sim);
    double x[2], F[2], J[2][2], s[2], xn[2], Fn[2];
    int dummy, fresh = 1;
    map_get(&m, x, &dummy);
    *converged = 0;
    *iterations = 0;
    residual(&m, x, F);
    F0[0] = F[0];
    F0[1] = F[1];
    int ok = isfinite(F[0]) && isfinite(F[1]) && jacobian_F(&m, x, F, p->fd_step, J);
    for (int it = 0; ok && !m.cancelled && it < p->max_iter; it++) {
        *iterations = it + 1;
        if (!newton_step(J, F, s))
            break;
        if (norm2(s) < p->tol) {
            x[0] += s[0];
            x[1] += s[1];
            *converged = 1;
            break;
        }
        if (!line_search(&m, x, F, s, xn, Fn)) {
            /* A stale Broyden Jacobian may point the wrong way: one fresh one, then stop. */
            if (fresh || !jacobian_F(&m, x, F, p->fd_step, J))
                break;
            fresh = 1;
            continue;
        }
        double step[2] = {xn[0] - x[0], xn[1] - x[1]}, dF[2] = {Fn[0] - F[0], Fn[1] - F[1]};
        broyden(J, step, dF);
        fresh = 0;
        memcpy(x, xn, sizeof x);
        memcpy(F, Fn, sizeof F);
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
    double F0[2];
    return newton(sim, p, F0, converged, iterations, cycles);
}

/* The monodromy matrix dP/dx (scaled) at the sim's state by central differences. */
static int monodromy(tt_sim *sim, const tt_shoot_params *p, double J[2][2])
{
    map_ctx m;
    map_init(&m, sim);
    double x[2], h = p->fd_step;
    int dummy;
    map_get(&m, x, &dummy);
    for (int j = 0; j < 2; j++) {
        double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]}, Fp[2], Fm[2];
        xp[j] += h;
        xm[j] -= h;
        residual(&m, xp, Fp);
        residual(&m, xm, Fm);
        /* dP/dx = dF/dx + I */
        J[0][j] = (Fp[0] - Fm[0]) / (2 * h) + (j == 0);
        J[1][j] = (Fp[1] - Fm[1]) / (2 * h) + (j == 1);
    }
    map_set(&m, x);
    if (m.cancelled)
        return TT_EINTR;
    if (!(isfinite(J[0][0]) && isfinite(J[0][1]) && isfinite(J[1][0]) && isfinite(J[1][1])))
        return tt_error(TT_ENUM, "Floquet multipliers: the map is not smooth at this orbit");
    return TT_OK;
}

static void eigenvalues(double J[2][2], double mu_re[2], double mu_im[2])
{
    double tr = J[0][0] + J[1][1], det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    double disc = 0.25 * tr * tr - det;
    if (disc >= 0) {
        double r = sqrt(disc);
        mu_re[0] = 0.5 * tr + r;
        mu_re[1] = 0.5 * tr - r;
        mu_im[0] = mu_im[1] = 0;
    } else {
        mu_re[0] = mu_re[1] = 0.5 * tr;
        mu_im[0] = sqrt(-disc);
        mu_im[1] = -mu_im[0];
    }
}

int tt_shoot_multipliers(tt_sim *sim, const tt_shoot_params *p, double mu_re[2], double mu_im[2])
{
    double J[2][2];
    mu_re[0] = mu_re[1] = mu_im[0] = mu_im[1] = NAN;
    int rc = monodromy(sim, p, J);
    if (rc == TT_OK)
        eigenvalues(J, mu_re, mu_im);
    return rc;
}

/* Whether a cycle touched the sample: the attractive and repulsive branches of a
 * bistable scene differ in this (Garcia and San Paulo 1999). */
static int touched(const tt_cycle *c) { return c->contact_fraction > 0 || c->events > 0; }

/* The last cycle-start states of the real motion (scaled), oldest first, with the
 * state the motion reached last. */
#define TRAIL 16
typedef struct {
    double x[TRAIL + 2][2];
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

/* M of the discrete Lyapunov equation J^T M J - M = -I: V(e) = e^T M e falls by |e|^2
 * each cycle of the linearised motion near a stable orbit (3 x 3 system for a, b, c of
 * the symmetric M = [a b; b c], by Cramer's rule). 0 if singular. */
static int lyapunov(double J[2][2], double M[2][2])
{
    double A[3][3], det3;
    for (int u = 0; u < 3; u++) {
        double B[2][2] = {{u == 0, u == 1}, {u == 1, u == 2}}, G[2][2];
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                G[i][j] = -B[i][j];
                for (int k = 0; k < 2; k++)
                    for (int l = 0; l < 2; l++)
                        G[i][j] += J[k][i] * B[k][l] * J[l][j];
            }
        A[0][u] = G[0][0];
        A[1][u] = G[0][1];
        A[2][u] = G[1][1];
    }
    double rhs[3] = {-1, 0, -1}, sol[3];
#define DET3(m) ((m)[0][0] * ((m)[1][1] * (m)[2][2] - (m)[1][2] * (m)[2][1]) - \
                 (m)[0][1] * ((m)[1][0] * (m)[2][2] - (m)[1][2] * (m)[2][0]) + \
                 (m)[0][2] * ((m)[1][0] * (m)[2][1] - (m)[1][1] * (m)[2][0]))
    det3 = DET3(A);
    if (!(fabs(det3) > 0))
        return 0;
    for (int u = 0; u < 3; u++) {
        double C[3][3];
        memcpy(C, A, sizeof C);
        for (int i = 0; i < 3; i++)
            C[i][u] = rhs[i];
        sol[u] = DET3(C) / det3;
    }
#undef DET3
    M[0][0] = sol[0];
    M[0][1] = M[1][0] = sol[1];
    M[1][1] = sol[2];
    return 1;
}

/* Whether the real motion runs into the orbit xs: V, the orbit's Lyapunov function,
 * falls along its last cycles (allowing the nonlinear motion a rise of 5 % in a cycle)
 * and is still at its least at the end. A stable orbit near a jump between branches has
 * a small basin; a motion that passes by it (and settles on the other branch) shows V
 * rising again, and then settling decides. */
static int in_basin(const trail *tr, const double xs[2], double J[2][2], double mu_abs)
{
    double M[2][2], first = 0, prev = 0, least = INFINITY;
    if (!lyapunov(J, M))
        return 0;
    for (int k = 0; k < tr->n; k++) {
        double e0 = tr->x[k][0] - xs[0], e1 = tr->x[k][1] - xs[1];
        double V = M[0][0] * e0 * e0 + 2 * M[0][1] * e0 * e1 + M[1][1] * e1 * e1;
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
    double e[2] = {x0[0] - xs[0], x0[1] - xs[1]}, r[2];
    for (int i = 0; i < 2; i++) /* what the linearisation misses of the last cycle */
        r[i] = x[i] - xs[i] - (J[i][0] * e[0] + J[i][1] * e[1]);
    int linear = hypot(r[0], r[1]) < 0.01 * (1 - mu_abs) * hypot(e[0], e[1]);
    if (!linear && hypot(x[0] - xs[0], x[1] - xs[1]) > 0.1)
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
    double F0[2], J[2][2], xs[2];
    long n = 0;
    int dummy;
    map_init(&m, sim);
    double *x0 = tr->x[tr->n++];
    map_get(&m, x0, &dummy);
    *rc = newton(sim, p, F0, &res->converged, &res->iterations, &n);
    /* the motion's next state, P(x0), from Newton's first residual */
    tr->x[tr->n][0] = x0[0] + F0[0];
    tr->x[tr->n][1] = x0[1] + F0[1];
    tr->n++;
    res->cycles += n;
    if (*rc)
        return 0;
    if (!res->converged) {
        res->why = "Newton did not converge";
        return 0;
    }
    tt_sim_get_state(sim, &res->d, &res->v, &res->contact);
    int mrc = monodromy(sim, p, J);
    res->cycles += 4;
    if (mrc == TT_EINTR) {
        *rc = mrc;
        return 0;
    }
    if (mrc != TT_OK) {
        tt_error_clear();
        res->why = "the map is not smooth at the orbit";
        return 0;
    }
    eigenvalues(J, res->mu_re, res->mu_im);
    res->mu_abs = fmax(hypot(res->mu_re[0], res->mu_im[0]), hypot(res->mu_re[1], res->mu_im[1]));
    if (!(res->mu_abs < 1)) {
        res->why = "the orbit is unstable";
        return 0;
    }
    map_get(&m, xs, &dummy);
    if (!in_basin(tr, xs, J, res->mu_abs)) {
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
    res->mu_re[0] = res->mu_re[1] = res->mu_im[0] = res->mu_im[1] = res->mu_abs = NAN;
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
        double d, v;
        int c;
        tt_sim_get_state(sim, &d, &v, &c);
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
        tt_sim_set_state(sim, d, v, c);
    }
    res->how = TT_SHOOT_SETTLED;
    rc = tt_sim_settle_orbit(sim, max_cycles > run ? max_cycles - run : 1, tol, out, &res->settle);
    *settled = res->settle.settled;
    res->cycles += run + res->settle.cycles;
    tt_sim_get_state(sim, &res->d, &res->v, &res->contact);
    return rc;
}
