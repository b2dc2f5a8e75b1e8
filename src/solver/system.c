/* The system the steps integrate: its plan (dimension and kernels), the one-mode
 * elastic system's specialised right-hand side and energy, and the generic n-mode
 * kernels beside them (sim.h, tt_system). */
#include "stepper.h"

void tt_sim_rhs(const tt_sim *S, double tau, const double *Y, int contact, double *Fo)
{
    drive_val dv;
    drive1_at(S, tau, &dv.z, &dv.zd, &dv.F, &dv.cw, &dv.sw);
    /* the thermal force acts as a force on the tip: its work is booked with the drive's */
    if (S->sys.nz_f)
        dv.F += noise_force(S, tau);
    rhs_with(S, tau, &dv, Y, contact, Fo);
}

/* Mechanical energy of the tip system on the current branch: kinetic + spring +
 * tip-sample potential. */
double tt_sim_energy(const tt_sim *S, double tau, const double *Y, int contact)
{
    double z, zd, Fd, cw, sw;
    drive1_at(S, tau, &z, &zd, &Fd, &cw, &sw);
    double d = Y[Y_D], v = Y[Y_V];
    double U = S->sys.contact ? tt_contact_energy(S->sys.contact, d - (S->sys.s0 + S->sys.sdot * tau), contact) : 0;
    return 0.5 * S->c.m * v * v + 0.5 * S->c.k * (d - z) * (d - z) + U;
}

/* The tip: mode 0's position and velocity plus the further modes' deflections. */
static void system_tip(const tt_system *sys, const double *Y, double *d, double *v)
{
    double dt = Y[0], vt = Y[1];
    for (int i = 1; i < sys->modes; i++) {
        dt += Y[2 * i];
        vt += Y[2 * i + 1];
    }
    *d = dt;
    *v = vt;
}

/* The generic right-hand side: each mode driven by the force on the tip, mode 0 against
 * the base; the quadratures (Y_WDRIVE - 2 ... from index n) summed over the modes in
 * mode order, so that one mode gives rhs_with's operations exactly. */
void tt_system_rhs_n(const tt_sim *S, double tau, const double *Y, int contact, double *Fo)
{
    const tt_system *sys = &S->sys;
    drive_val dv;
    drive_at(S, tau, &dv.z, &dv.zd, &dv.F, &dv.cw, &dv.sw);
    double d, v;
    system_tip(sys, Y, &d, &v);
    const double *q = tt_system_law_state(S, Y);
    double delta, deltad;
    tt_contact_forces f = tip_forces(S, tau, d, v, contact, q, &delta, &deltad);
    double P = f.conservative, Fi = f.dissipative;
    double wdrive = 0, wdamp = 0, z2 = drive2_z(S, tau);
    for (int i = 0; i < sys->modes; i++) {
        /* mode 0 moves against the base (z, z'); the deflection modes against rest */
        double zi = i ? 0.0 : dv.z, zdi = i ? 0.0 : dv.zd;
        double qi = Y[2 * i], ui = Y[2 * i + 1];
        double spring = sys->k[i] * (qi - zi), damp = sys->c[i] * (ui - zdi);
        /* the drive's force on the tip, each mode's own Langevin force, and a base
         * drive's inertial force on the further modes (-g_i m_i z'', z'' = -w^2 z) */
        double Fd = dv.F;
        if (sys->nz_f)
            Fd += noise_force_mode(S, tau, i);
        if (i)
            Fd += z2 == 0.0 ? sys->base[i] * dv.z : sys->base[i] * (dv.z - z2) + sys->base2[i] * z2;
        Fo[2 * i] = ui;
        Fo[2 * i + 1] = (-damp - spring - P - Fi + Fd) * sys->inv_m[i];
        double wd = Fd * ui - (spring + damp) * zdi, wl = damp * (ui - zdi);
        wdrive = i ? wdrive + wd : wd;
        wdamp = i ? wdamp + wl : wl;
    }
    double y = d - dv.z;
    double *Q = Fo + sys->n - Y_WDRIVE;
    Q[Y_WDRIVE] = wdrive;
    Q[Y_WDAMP] = wdamp;
    Q[Y_WCI] = (Fi - f.viscous) * deltad;
    Q[Y_WVISC] = f.viscous * deltad;
    if (q) {
        /* the law's states after the modes, and the power their dashpots dissipate */
        double loss;
        sys->law->rate(sys->contact, delta, deltad, contact, q, Fo + 2 * sys->modes, &loss);
        Q[Y_WVISC] += loss;
    }
    Q[Y_WS] = (P + Fi) * S->sys.sdot;
    Q[Y_IC] = y * dv.cw;
    Q[Y_IS] = y * dv.sw;
    Q[Y_IY] = y;
    Q[Y_TC] = contact ? 1.0 : 0.0;
}

/* The generic energy: each mode's kinetic and spring energy in mode order, then the
 * tip-sample potential at the tip. */
double tt_system_energy_n(const tt_sim *S, double tau, const double *Y, int contact)
{
    const tt_system *sys = &S->sys;
    double z, zd, Fd, cw, sw;
    drive_at(S, tau, &z, &zd, &Fd, &cw, &sw);
    double E = 0;
    for (int i = 0; i < sys->modes; i++) {
        double qi = Y[2 * i] - (i ? 0.0 : z), ui = Y[2 * i + 1];
        double e = 0.5 * sys->m[i] * ui * ui + 0.5 * sys->k[i] * qi * qi;
        E = i ? E + e : e;
    }
    double d, v;
    system_tip(sys, Y, &d, &v);
    double delta = d - (S->sys.s0 + S->sys.sdot * tau), U = 0;
    if (sys->nlaw)
        U = sys->law->energy(sys->contact, delta, contact, tt_system_law_state(S, Y));
    else if (sys->contact)
        U = tt_contact_energy(sys->contact, delta, contact);
    return E + U;
}

double tt_system_surface_at(const tt_sim *S, double th)
{
    if (!S->sys.nlaw)
        return 0.0;
    double x[TT_SIM_DIM_MAX];
    S->type->dense_x(S->step, S, th, x);
    return S->sys.law->surface(S->sys.contact, tt_system_law_state(S, x));
}

void tt_system_plan(tt_sim *S, int generic)
{
    tt_system *sys = &S->sys;
    sys->generic = generic;
    sys->modes = S->c.modes > 1 ? S->c.modes : 1;
    sys->law = sys->contact ? tt_contact_law_of(sys->contact) : NULL;
    sys->nlaw = sys->law ? (int)sys->law->state_size : 0;
    sys->n = 2 * sys->modes + sys->nlaw;
    generic |= sys->nlaw > 0 || sys->modes > 1;
    sys->m[0] = S->c.m;
    sys->k[0] = S->c.k;
    sys->c[0] = S->c.c;
    sys->inv_m[0] = 1.0 / S->c.m;
    sys->base[0] = sys->base2[0] = 0.0;
    for (int i = 1; i < sys->modes; i++) {
        sys->m[i] = S->c.mode_m[i];
        sys->k[i] = S->c.mode_k[i];
        sys->c[i] = S->c.mode_c[i];
        sys->inv_m[i] = 1.0 / S->c.mode_m[i];
        /* a base drive only: a force drive has z = 0 */
        sys->base[i] = S->c.mode_base[i] * S->c.mode_m[i] * S->c.wd * S->c.wd;
        sys->base2[i] = S->c.mode_base[i] * S->c.mode_m[i] * S->c.wd2 * S->c.wd2;
    }
    /* the one-mode elastic system's specialised kernels (FFTW's codelets' idea) */
    sys->rhs = generic ? tt_system_rhs_n : tt_sim_rhs;
    sys->energy = generic ? tt_system_energy_n : tt_sim_energy;
}
