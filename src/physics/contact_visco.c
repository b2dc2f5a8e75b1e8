/* The Kelvin-Voigt sample and the film bonded to a rigid substrate (docs/physics.md,
 * Viscoelastic samples; see include/tiptap/physics/contact.h).
 *
 * One row of the law table serves both: the elastic law of the material (Hertz, or
 * a tabulated Maugis-Dugdale, DMT or JKR curve) plus the viscous force eta a ddelta/dt
 * in contact, a the contact radius (dForce 1.0's and pyDAMPF's form). A film of
 * thickness h on a rigid substrate replaces the Hertz load by Garcia & Garcia's
 * bottom-effect series P = K sqrt(R) delta^(3/2) sum_k c_k chi^k, chi = sqrt(R delta) / h,
 * and scales the viscous force alike: the Kelvin-Voigt solid is the elastic one with
 * K -> K + (2 eta / 3) d/dt (the correspondence principle), so its viscous force is
 * (2 eta / 3K) dP/ddelta ddelta/dt, which is eta a ddelta/dt in bulk Hertz. */
#include <math.h>

#include "contact_private.h"

/* Garcia & Garcia, Biophys. J. 114 (2018) 2923: the paraboloid on a bonded film (checked
 * against an implementation citing the paper: docs/physics.md). */
static const double garcia[5] = {1.0, 1.133, 1.497, 1.469, 0.755};

/* The film's load, dP/ddelta and potential at delta > 0 (x = sqrt(delta)). */
static inline double film_load(const struct tt_contact *c, double delta, double *dPdd)
{
    if (delta <= 0) {
        *dPdd = 0;
        return 0;
    }
    double x = sqrt(delta), P = 0, dP = 0;
    for (int k = 4; k >= 0; k--) {
        P = P * x + c->film_k[k];
        dP = dP * x + c->film_k[k] * (3 + k) * 0.5;
    }
    *dPdd = dP * x;
    return P * x * delta;
}

static double film_energy(const struct tt_contact *c, double delta)
{
    if (delta <= 0)
        return 0;
    double x = sqrt(delta), U = 0;
    for (int k = 4; k >= 0; k--)
        U = U * x + c->film_k[k] * 2.0 / (5 + k);
    return U * x * delta * delta;
}

/* The conservative load, its stiffness, the contact radius and the viscous force's
 * coefficient (kg/s) at delta. */
static inline double kv_load(const struct tt_contact *c, double delta, int in_contact,
                             double *dPdd, double *a, double *cv)
{
    double P;
    if (c->film_h > 0) {
        P = film_load(c, delta, dPdd);
        *a = delta > 0 ? sqrt(c->p.R * delta) : 0.0;
        *cv = c->film_rate * *dPdd;
    } else {
        P = c->elastic_load(c, delta, in_contact, dPdd, a);
        *cv = c->eta * *a;
    }
    return P;
}

static tt_contact_forces kv_force(const tt_contact *c, double ci, double delta, double rate,
                                  int in_contact, const double *q)
{
    (void)q;
    double dP, a, cv;
    tt_contact_forces f;
    f.conservative = kv_load(c, delta, in_contact, &dP, &a, &cv);
    f.viscous = cv * rate;
    f.dissipative = (in_contact ? ci * rate : 0.0) + f.viscous;
    return f;
}

static void kv_detail(const tt_contact *c, double ci, double delta, double rate, int in_contact,
                      const double *q, tt_contact_detail *out)
{
    (void)q;
    double cv;
    out->stiffness = 0;
    out->f.conservative = kv_load(c, delta, in_contact, &out->stiffness, &out->radius, &cv);
    out->f.viscous = cv * rate;
    out->f.dissipative = (in_contact ? ci * rate : 0.0) + out->f.viscous;
    out->damping = (in_contact ? ci : 0.0) + cv;
}

static double kv_energy(const tt_contact *c, double delta, int in_contact, const double *q)
{
    return c->film_h > 0 ? film_energy(c, delta) : c->elastic->energy(c, delta, in_contact, q);
}

const tt_contact_law tt_contact_kelvin_voigt = {"kelvin-voigt", 0, kv_force, kv_detail, kv_energy, NULL, NULL};

void tt_contact_visco_setup(struct tt_contact *c, const tt_contact_params *p)
{
    if (!(p->viscosity > 0) && !(p->film_thickness > 0))
        return; /* elastic: the law's own row, untouched */
    c->elastic = c->law;
    c->elastic_load = c->hertz ? tt_contact_hertz_load : tt_contact_table_load;
    c->eta = p->viscosity;
    c->film_h = p->film_thickness;
    if (c->film_h > 0) {
        double r = sqrt(p->R) / c->film_h, f = p->K * sqrt(p->R);
        for (int k = 0; k < 5; k++, f *= r)
            c->film_k[k] = garcia[k] * f;
        c->film_rate = 2.0 * c->eta / (3.0 * p->K);
    }
    c->law = &tt_contact_kelvin_voigt;
}
