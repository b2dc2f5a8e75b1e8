/* Force laws for tests, given to tt_contact_alloc_custom. */
#ifndef TT_LAWS_H
#define TT_LAWS_H

/* A smooth law, P = k3 delta^3 in contact (user points to k3): the solution stays smooth
 * through the contact events, so a method must show its full order, event times
 * included. */
static inline double tt_cubic_load(double delta, int in_contact, double *dPdd, void *user)
{
    (void)in_contact;
    double k3 = *(double *)user;
    if (delta <= 0) {
        if (dPdd)
            *dPdd = 0;
        return 0;
    }
    if (dPdd)
        *dPdd = 3 * k3 * delta * delta;
    return k3 * delta * delta * delta;
}

/* Its potential, dU/ddelta = P. */
static inline double tt_cubic_energy(double delta, int in_contact, void *user)
{
    (void)in_contact;
    double k3 = *(double *)user;
    return delta <= 0 ? 0 : 0.25 * k3 * delta * delta * delta * delta;
}

#endif
