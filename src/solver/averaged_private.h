/* The averaged tier's table, private to libtiptap: averaged.c (the table, its look-up and
 * the slow flow), averaged_quad.c (the cycle's quadrature) and averaged_arms.c (the cycle
 * of a law with internal state, a sample's relaxation arms, in its periodic steady
 * state). */
#ifndef TIPTAP_SOLVER_AVERAGED_PRIVATE_H
#define TIPTAP_SOLVER_AVERAGED_PRIVATE_H

#include <math.h>

#include "tiptap/solver/averaged.h"

enum {
    NQ = 24,      /* Gauss-Legendre nodes on each piece of a cycle (contact, flight halves) */
    NB = 65,      /* amplitude nodes, 0 to B_MAX A0 */
    NXH = 128,    /* penetration nodes on each side of jump-in */
    NX = 2 * NXH + 1,
    C_GC = 0, C_GS = 1, C_MEAN = 2, C_PEAK = 3, C_SHIFT = 4, /* columns */
    C_HARM = 5,   /* then the harmonics h >= 2 the lock-in keeps, in pairs */
    NK = 4096,    /* the kernel's nodes over a cycle */
    HK = 64,      /* harmonics in the kernel */
    AVG_NL = TT_CONTACT_ARMS_MAX, /* the most law states the table's cycle follows */
    AVG_NG = 4    /* Gauss-Legendre nodes on each sub-step of a contact with law states */
};

struct tt_averaged {
    tt_cantilever c;
    const tt_contact *contact;
    tt_contact_forces (*force)(const tt_contact *c, double ci, double delta, double rate,
                               int in_contact, const double *state); /* the law's kernel */
    double ci;          /* the law's interaction damping coefficient, kg/s */
    int H, ncol;
    double jin, jout;   /* jump-in and pull-off penetrations, m */
    double db, span;    /* amplitude step; penetration half-span (x - jin = span xi |xi|) */
    double gx[NQ], gw[NQ]; /* Gauss-Legendre nodes and weights on [-1, 1] */
    double kern[NK + 1];   /* the closest approach's shift per unit force at theta */
    double seconds;
    double *t;          /* [NB][NX][ncol] */
    /* a law with internal state (averaged_arms.c; nlaw 0: elastic): its row, the state's
     * rate per radian of the cycle out of contact and in contact (linear in the state,
     * read off the law's rate), which components move at all, the sub-step's nodes */
    const tt_contact_law *law;
    int nlaw;
    double Aout[AVG_NL][AVG_NL], Ain[AVG_NL][AVG_NL];
    int active[AVG_NL];
    double sx[AVG_NG], sw[AVG_NG];
    long unconverged;   /* the build's nodes whose periodic state missed its tolerance */
};

/* Gauss-Legendre nodes and weights on [-1, 1] (averaged_quad.c). */
void tt_averaged_gauss_legendre(int n, double *x, double *w);

/* One piece [t0, t1] of the cycle on one contact branch into the sums, the law's state
 * absent (averaged_quad.c). */
void tt_averaged_piece(const tt_averaged *a, double u, double B, double t0, double t1, int in,
                       double *sum, double *peak);

/* Add the force F (N, on the cantilever) at cycle angle th (cos, sin) of quadrature
 * weight wt to the sums of the columns. */
static inline void tt_averaged_accumulate(const tt_averaged *a, double th, double cs, double sn,
                                          double wt, double F, double *sum)
{
    double kp = (th + M_PI) * (NK / (2 * M_PI));
    int ki = (int)kp;
    ki = ki < 0 ? 0 : ki > NK - 1 ? NK - 1 : ki;
    sum[C_SHIFT] += wt * F * (a->kern[ki] + (kp - ki) * (a->kern[ki + 1] - a->kern[ki]));
    sum[C_MEAN] += wt * F;
    sum[C_GC] += wt * F * cs;
    sum[C_GS] += wt * F * sn;
    double ch = cs, sh = sn;
    for (int h = 2; h <= a->H; h++) {
        double c2 = ch * cs - sh * sn, s2 = sh * cs + ch * sn;
        ch = c2;
        sh = s2;
        sum[C_HARM + 2 * (h - 2)] += wt * F * ch;
        sum[C_HARM + 2 * (h - 2) + 1] += wt * F * sh;
    }
}

/* averaged_arms.c: read the law's state rates (TT_EINVAL when they are not linear in the
 * state, or the force out of contact depends on it), and the sums of one cycle at
 * (B, x) in the periodic steady state of the law's state (q0: its start at the cycle's
 * far point, a guess in and the periodic state out; NULL: from rest). Returns 1 when
 * the periodic state missed its tolerance. The static load at penetration x with the
 * state at rest there (amplitude 0). */
int tt_averaged_arms_setup(tt_averaged *a);
double tt_averaged_arms_static(const tt_averaged *a, double x, int in);
int tt_averaged_arms_cycle(const tt_averaged *a, double B, double x, int stuck, double *sum,
                           double *peak, double *q0);

#endif
