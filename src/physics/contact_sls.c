/* The generalised Maxwell sample (standard linear solid with one arm) under a
 * paraboloid tip, with its surface's position as internal state (docs/physics.md,
 * Viscoelastic samples; after López-Guerra & Solares, Beilstein J. Nanotechnol. 5
 * (2014) 2149, in the Lee-Radok form for the paraboloid).
 *
 * A spring of the relaxed modulus K parallel to N Maxwell arms (modulus K_i, time
 * tau_i), each acting on chi(delta) = delta sqrt(delta / R), the Hertz load's
 * P = K R chi in length units. Arm i's state q_i (m) is where its dashpot stands:
 *   P = R (K_g chi - sum K_i q_i),  K_g = K + sum K_i,  tau_i dq_i/dt = chi_s - q_i,
 * chi_s = chi(delta) in contact and, with the tip away, the free surface's
 * chi_f = sum K_i q_i / K_g (where P = 0), at the depression u = (R chi_f^2)^(1/3).
 * The sample stores W = 0.4 K_g sqrt(R) delta^(5/2) - sum K_i R (q_i delta - 0.6 R^(1/3)
 * q_i^(5/3)) (dW/ddelta = P), taken at delta_s = delta in contact and u out of it, and
 * its dashpots take sum K_i R (delta_s - (R q_i^2)^(1/3)) (chi_s - q_i) / tau_i >= 0. */
#include <math.h>

#include "contact_private.h"

/* Hertz's chi(delta) = delta sqrt(delta / R), 0 for a gap. */
static inline double sls_chi(const struct tt_contact *c, double delta)
{
    return delta > 0 ? delta * sqrt(delta / c->p.R) : 0.0;
}

/* The free surface's chi_f = sum K_i q_i / K_g (0 without a state: relaxed). */
static inline double sls_chi_free(const struct tt_contact *c, const double *q)
{
    double s = 0;
    if (q)
        for (int i = 0; i < c->arms; i++)
            s += c->arm_K[i] * q[i];
    return s / c->K_glassy;
}

/* The indentation whose chi is x: (R x^2)^(1/3). */
static inline double sls_depth(const struct tt_contact *c, double x)
{
    return cbrt(c->p.R * x * x);
}

/* The load in contact, P = R (K_g chi - sum K_i q_i) (the instantaneous, glassy law
 * without a state); 0 out of contact, where the tip is above the surface. */
static inline double sls_load(const struct tt_contact *c, double delta, int in_contact,
                              const double *q)
{
    if (!in_contact)
        return 0.0;
    return c->p.R * c->K_glassy * (sls_chi(c, delta) - sls_chi_free(c, q));
}

static tt_contact_forces sls_force(const tt_contact *c, double ci, double delta, double rate,
                                   int in_contact, const double *q)
{
    tt_contact_forces f;
    f.conservative = sls_load(c, delta, in_contact, q);
    f.dissipative = in_contact ? ci * rate : 0.0;
    f.viscous = 0.0; /* the arms' loss is the state's, booked through the rate hook */
    return f;
}

static void sls_detail(const tt_contact *c, double ci, double delta, double rate, int in_contact,
                       const double *q, tt_contact_detail *out)
{
    out->f = sls_force(c, ci, delta, rate, in_contact, q);
    out->stiffness = in_contact && delta > 0 ? 1.5 * c->K_glassy * sqrt(c->p.R * delta) : 0.0;
    out->damping = in_contact ? ci : 0.0;
    out->radius = in_contact && delta > 0 ? sqrt(c->p.R * delta) : 0.0;
}

static double sls_surface(const tt_contact *c, const double *q)
{
    return sls_depth(c, fmax(sls_chi_free(c, q), 0.0));
}

/* Where the sample's surface is: at the tip in contact, where the arms hold it out. */
static inline double sls_delta_s(const struct tt_contact *c, double delta, int in_contact,
                                 const double *q)
{
    return in_contact ? delta : sls_surface(c, q);
}

static double sls_energy(const tt_contact *c, double delta, int in_contact, const double *q)
{
    double ds = sls_delta_s(c, delta, in_contact, q), R = c->p.R;
    double W = ds > 0 ? 0.4 * c->K_glassy * sqrt(R) * ds * ds * sqrt(ds) : 0.0;
    if (q)
        for (int i = 0; i < c->arms; i++)
            W -= c->arm_K[i] * R * (q[i] * ds - 0.6 * cbrt(R) * q[i] * cbrt(q[i] * q[i]));
    return W;
}

static void sls_rate(const tt_contact *c, double delta, double rate, int in_contact,
                     const double *q, double *dq, double *power)
{
    (void)rate;
    double chi = in_contact ? sls_chi(c, delta) : sls_chi_free(c, q);
    double ds = in_contact ? delta : sls_depth(c, fmax(chi, 0.0));
    double D = 0;
    for (int i = 0; i < c->arms; i++) {
        dq[i] = (chi - q[i]) * c->arm_rate[i];
        D += c->arm_K[i] * c->p.R * (ds - sls_depth(c, q[i])) * dq[i];
    }
    *power = D;
}

#define SLS_ROW(name, n) {name, n, sls_force, sls_detail, sls_energy, sls_rate, sls_surface}
static const tt_contact_law sls_rows[TT_CONTACT_ARMS_MAX] = {
    SLS_ROW("standard-linear-solid", 1), SLS_ROW("maxwell-2", 2), SLS_ROW("maxwell-3", 3),
    SLS_ROW("maxwell-4", 4)};

void tt_contact_sls_setup(struct tt_contact *c, const tt_contact_params *p)
{
    if (p->arms <= 0)
        return; /* elastic: the law's own row, untouched */
    c->arms = p->arms;
    c->K_glassy = p->K;
    for (int i = 0; i < p->arms; i++) {
        c->arm_K[i] = p->arm_modulus[i];
        c->arm_rate[i] = isfinite(p->arm_time[i]) ? 1.0 / p->arm_time[i] : 0.0;
        c->K_glassy += p->arm_modulus[i];
    }
    c->law = &sls_rows[p->arms - 1];
}
