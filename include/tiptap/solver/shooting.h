/* tiptap: steady oscillations by shooting: the periodic orbit found directly as the
 * fixed point of the one-period (stroboscopic) map P, instead of by running cycles
 * until the transient has died away.
 *
 * P takes the sim's state (its n components, tt_sim_dim: position d and velocity v for
 * one mode, and the contact flag) at a cycle start to its state one drive period later;
 * it is evaluated with tt_sim_cycle. A steady oscillation is a state x with P(x) = x.
 * Newton's method on P(x) - x, with P's n x n Jacobian from finite differences (then
 * Broyden's updates) and a backtracking line search, finds it in a few cycles where
 * settling takes several times Q / pi. The eigenvalues of the monodromy matrix at the
 * fixed point are the orbit's Floquet multipliers (closed form for n = 2, GSL's
 * nonsymmetric eigensolver beyond): it is stable (an oscillation the instrument can
 * show) when all lie inside the unit circle.
 *
 * The map is not smooth where the contact flag flips (jump-in, pull-off): the
 * difference step (1e-5 of the free amplitude, 0.2 pm on the standard scene) is small
 * against the contact's length scales and large against the integrator's tolerance,
 * and perturbed states keep the base state's contact flag.
 *
 * Where two stable orbits coexist (attractive and repulsive branches), Newton may find
 * one the real motion would not reach: the point must be the one settling would give.
 * So Newton starts from the real motion after a few cycles of it, and its orbit is
 * taken only if it is stable, touches the sample as those cycles did, and the motion
 * is running into it: the orbit's quadratic Lyapunov function (from its monodromy
 * matrix) falls along the last cycles and is still falling, and the motion is within
 * a tenth of the free amplitude of it (or the map is linear there). Otherwise more
 * cycles and another try; at last the point is settled (tt_sim_settle_orbit).
 *
 * Usage: tt_shoot_default(&p); tt_shoot_steady(sim, &p, max_cycles, tol, &cycle, &res);
 * Ownership: the functions drive the sim given to them and leave it at the end of the
 * orbit's last cycle; they keep nothing.
 */
#ifndef TIPTAP_SHOOTING_H
#define TIPTAP_SHOOTING_H

#include "tiptap/export.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

typedef struct {
    long presettle;     /* cycles run first to get into the orbit's basin (at least) */
    int max_iter;       /* Newton iterations per attempt */
    int attempts;       /* attempts, each after twice the cycles of settling before */
    double fd_step;     /* difference step, relative to the free amplitude */
    double tol;         /* converged when the Newton step is below tol (relative to the
                         * free amplitude; velocity over w_d times it) */
} tt_shoot_params;

/* Defaults: 16 cycles first, 20 iterations, 5 attempts, step 1e-5, tol 1e-9. */
void tt_shoot_default(tt_shoot_params *p);

typedef enum {
    TT_SHOOT_NEWTON = 0,  /* the point is Newton's fixed point */
    TT_SHOOT_SETTLED = 1  /* Newton failed or found no stable orbit: the point was settled */
} tt_shoot_how;

typedef struct {
    tt_shoot_how how;
    int converged;          /* Newton converged (also when the orbit was then refused) */
    int iterations;         /* Newton iterations of the last attempt */
    long cycles;            /* all cycles run, settling, differences and the last one */
    int n;                  /* the state's components (tt_sim_dim) */
    double x[TT_SIM_DIM_MAX]; /* the fixed point (cycle-start state, n of it) */
    double d, v;            /* its first mode's position and velocity, m, m/s */
    int contact;
    double mu_re[TT_SIM_DIM_MAX], mu_im[TT_SIM_DIM_MAX]; /* Floquet multipliers at the
                                                          * fixed point, n (NAN: none) */
    double mu_abs;          /* the largest |mu|: below 1 for a stable orbit */
    const char *why;        /* why Newton's orbit was refused ("" if it was not) */
    tt_settle_result settle; /* how the point settled instead (TT_SHOOT_SETTLED; else zero) */
} tt_shoot_result;

/* Floquet multipliers of the map at the sim's current cycle-start state (n of them, a
 * complex pair adjacent, into arrays of tt_sim_dim(sim)), from central differences (2 n
 * cycles); the sim is left where it was. TT_EINTR when cancelled (util/cancel.h). */
int tt_shoot_multipliers(tt_sim *sim, const tt_shoot_params *p, double *mu_re, double *mu_im);

/* Newton on P(x) = x from the sim's current state, at most p->max_iter iterations.
 * The sim is left set to the fixed point (*converged = 1) or to Newton's last iterate,
 * at a cycle start; *cycles counts the map's evaluations. TT_EINTR when cancelled
 * (util/cancel.h): a cycle cut short counts as no fixed point, so Newton stops. */
int tt_shoot_newton(tt_sim *sim, const tt_shoot_params *p, int *converged, int *iterations,
                    long *cycles);

/* A steady point from the sim's current state: run p->presettle cycles, Newton, check
 * the orbit (see above), retry after twice the cycles, up to p->attempts times and at
 * most half the cycles settling is expected to take (Q / pi ln(1 / tol) / 2), and fall
 * back to tt_sim_settle_orbit (max_cycles, tol). out is the orbit's last cycle, run from
 * the fixed point, or what settling gave (a period-n orbit's mean; res->settle);
 * *settled whether the point is steady (Newton's, or settled within max_cycles, also
 * to a period-n orbit). TT_EINTR when cancelled (util/cancel.h), the point unfinished. */
int tt_shoot_steady(tt_sim *sim, const tt_shoot_params *p, long max_cycles, double tol,
                    tt_cycle *out, int *settled, tt_shoot_result *res);

TT_END_DECLS
#endif
