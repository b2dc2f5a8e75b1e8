/* The system's right-hand side with the drive and the thermal force at tau: the steps'
 * kernel (sim.h). */
#include "sim.h"

void tt_sim_rhs(const tt_sim *S, double tau, const double *Y, int contact, double *Fo)
{
    drive_val dv;
    drive_at(S, tau, &dv.z, &dv.zd, &dv.F, &dv.cw, &dv.sw);
    /* the thermal force acts as a force on the tip: its work is booked with the drive's */
    if (S->nz_f)
        dv.F += noise_force(S, tau);
    rhs_with(S, tau, &dv, Y, contact, Fo);
}
