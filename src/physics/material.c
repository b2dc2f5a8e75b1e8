/* A tip and a sample material as contact parameters (see include/tiptap/physics/material.h). */
#include "tiptap/physics/material.h"

#include <math.h>

double tt_material_reduced_modulus(const tt_tip *tip, double E, double nu)
{
    double Et = tip->youngs_modulus, nut = tip->poisson_ratio;
    return 1.0 / (0.75 * ((1 - nut * nut) / Et + (1 - nu * nu) / E));
}

int tt_material_viscous(const tt_material *m)
{
    return m->contact.viscosity > 0 || m->contact.film_thickness > 0 || m->contact.arms > 0;
}

double tt_material_lambda(const tt_contact_params *p)
{
    return 2.06 / p->xi0 * cbrt(p->w * p->w * p->R / (M_PI * p->K * p->K));
}
