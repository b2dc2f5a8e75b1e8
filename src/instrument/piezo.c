/* The z piezo's dynamics and creep (see include/tiptap/instrument/piezo.h). */
#include "tiptap/instrument/piezo.h"

#include <math.h>
#include <string.h>

/* Weights of the first creep elements (time constants t0 10^(k/2), k = -1, 0, ...),
 * fitted by least squares to log10(1 + t / t0); the later ones carry half a decade each
 * and the last 0.731, standing for the elements beyond it. */
static const double creep_head[] = {0.0225, 0.1825, 0.3654, 0.4518, 0.4848, 0.4948, 0.4985, 0.4994};

int tt_piezo_ideal(const tt_piezo_params *p) { return !(p->resonance > 0) && !(p->creep != 0); }

void tt_piezo_init(tt_piezo *pz, const tt_piezo_params *p, double z0, double span)
{
    memset(pz, 0, sizeof *pz);
    pz->p = *p;
    pz->z = pz->rest = pz->cmd = z0;
    if (p->creep == 0 || !(p->creep_time > 0))
        return;
    /* elements until one is ten times slower than the span */
    int n = 0;
    double tau = p->creep_time / sqrt(10.0);
    do {
        pz->tau[n] = tau;
        pz->w[n] = n < (int)(sizeof creep_head / sizeof *creep_head) ? creep_head[n] : 0.5;
        n++;
        tau *= sqrt(10.0);
    } while (n < TT_PIEZO_CREEP_MAX && pz->tau[n - 1] < 10 * span);
    pz->w[n - 1] = 0.731;
    pz->ncreep = n;
}

double tt_piezo_creep(const tt_piezo *pz)
{
    double c = 0;
    for (int k = 0; k < pz->ncreep; k++)
        c += pz->w[k] * pz->e[k];
    return pz->p.creep * c;
}

/* Each element follows the move since rest, tau e' = u - e, exactly for a command
 * linear over the step. */
static void creep_advance(tt_piezo *pz, double ua, double ub, double dt)
{
    double slope = (ub - ua) / dt;
    for (int k = 0; k < pz->ncreep; k++) {
        double a = exp(-dt / pz->tau[k]);
        pz->e[k] = ub + (pz->e[k] - ua) * a + slope * pz->tau[k] * expm1(-dt / pz->tau[k]);
    }
}

/* The second-order response to an input linear from ia to ib over dt (classic RK4 in
 * steps of at most 1/20 of 1 / w_p: error below 1e-8 of the input's change). */
static void dynamics_advance(tt_piezo *pz, double ia, double ib, double dt)
{
    double w = 2 * M_PI * pz->p.resonance, zeta = pz->p.damping;
    int n = (int)ceil(w * dt / 0.05);
    double h = dt / n, z = pz->z, v = pz->v;
    for (int i = 0; i < n; i++) {
        double u0 = ia + (ib - ia) * i / n, um = ia + (ib - ia) * (i + 0.5) / n;
        double u1 = ia + (ib - ia) * (i + 1.0) / n;
#define ACC(zz, vv, uu) (w * w * ((uu) - (zz)) - 2 * zeta * w * (vv))
        double k1z = v, k1v = ACC(z, v, u0);
        double k2z = v + 0.5 * h * k1v, k2v = ACC(z + 0.5 * h * k1z, v + 0.5 * h * k1v, um);
        double k3z = v + 0.5 * h * k2v, k3v = ACC(z + 0.5 * h * k2z, v + 0.5 * h * k2v, um);
        double k4z = v + h * k3v, k4v = ACC(z + h * k3z, v + h * k3v, u1);
#undef ACC
        z += h / 6 * (k1z + 2 * k2z + 2 * k3z + k4z);
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    pz->z = z;
    pz->v = v;
}

double tt_piezo_advance(tt_piezo *pz, double z_to, double dt)
{
    double ia = pz->cmd + tt_piezo_creep(pz);
    if (pz->ncreep)
        creep_advance(pz, pz->cmd - pz->rest, z_to - pz->rest, dt);
    pz->cmd = z_to;
    double ib = z_to + tt_piezo_creep(pz);
    if (pz->p.resonance > 0)
        dynamics_advance(pz, ia, ib, dt);
    else
        pz->z = ib;
    return pz->z;
}
