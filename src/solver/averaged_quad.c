/* The averaged tier's quadrature over a cycle: Gauss-Legendre nodes, and one piece of a
 * cycle on one contact branch into the table's sums (averaged.c, averaged_arms.c). */
#include "averaged_private.h"

/* Gauss-Legendre nodes by Newton's iteration on P_n (Golub-Welsch not needed at n = 24). */
void tt_averaged_gauss_legendre(int n, double *x, double *w)
{
    for (int i = 0; i < n; i++) {
        double z = cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = z;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1);
            double dz = p1 / dp;
            z -= dz;
            if (fabs(dz) < 1e-16)
                break;
        }
        x[i] = z;
        w[i] = 2 / ((1 - z * z) * dp * dp);
    }
}

/* One piece [t0, t1] of the cycle on one contact branch into the sums (cos and sin
 * of h theta by recurrence). */
void tt_averaged_piece(const tt_averaged *a, double u, double B, double t0, double t1, int in,
                       double *sum, double *peak)
{
    if (!(t1 > t0))
        return;
    const double half = 0.5 * (t1 - t0), mid = 0.5 * (t1 + t0), w = a->c.wd;
    for (int q = 0; q < NQ; q++) {
        double th = mid + half * a->gx[q], wt = half * a->gw[q];
        double cs = cos(th), sn = sin(th);
        double delta = u + B * cs, deltad = -B * w * sn;
        tt_contact_forces f = a->force(a->contact, a->ci, delta, deltad, in, NULL);
        double load = f.conservative + f.dissipative;
        if (load > *peak)
            *peak = load;
        tt_averaged_accumulate(a, th, cs, sn, wt, -load, sum);
    }
}
