/* tiptap: the point-mass cantilever and its drive (Burnham et al. eqs. 1, 2; docs/physics.md).
 *
 * Tip position d, base z, sample surface s on one axis pointing into the sample.
 *   m* d'' + c (d' - z') + k (d - z) = -P(d - s) - c_i (d' - s') [in contact] + F(t)
 * with m* = k / w0^2 and c = m* w0 / Q (the standard quality factor; Burnham et al.'s
 * 2/sqrt(2 + 4 Q^2) differs by under 0.1 % for Q >= 10).
 * Base drive (Burnham et al.'s): z = a_d cos(w t), F = 0. Force drive: z = 0,
 * F = F0 cos(w t). The drive strength is derived from the free amplitude A0 of the
 * deflection y = d - z at the drive frequency, so both drives give the same free
 * oscillation y = A0 cos(w t - phi0), phi0 = the lag, 90 degrees at resonance.
 *
 * Plain struct, no ownership.
 */
#ifndef TIPTAP_CANTILEVER_H
#define TIPTAP_CANTILEVER_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef enum { TT_DRIVE_BASE = 0, TT_DRIVE_FORCE = 1 } tt_drive;

typedef struct {
    /* given */
    double k;        /* spring constant, N/m */
    double f0;       /* resonance frequency, Hz */
    double Q;        /* quality factor */
    double A0;       /* free deflection amplitude at the drive frequency, m */
    double fd;       /* drive frequency, Hz */
    tt_drive drive;
    /* derived by tt_cantilever_init */
    double w0, wd;   /* rad/s */
    double m;        /* effective mass, kg */
    double c;        /* damping coefficient, kg/s */
    double a_d;      /* base drive amplitude, m (base drive) */
    double F0;       /* force drive amplitude, N (force drive) */
    double phi0;     /* free phase lag of y behind the drive, rad */
    double T;        /* drive period, s */
} tt_cantilever;

/* Fill the derived constants; TT_EINVAL with a message on non-physical input. */
int tt_cantilever_init(tt_cantilever *c, double k, double f0, double Q, double A0, double fd,
                       tt_drive drive);

/* Steady free response of the deflection at angular frequency w to the configured
 * drive strength: amplitude (m) and lag (rad), from the transfer function. */
void tt_cantilever_response(const tt_cantilever *c, double w, double *amp, double *lag);

TT_END_DECLS
#endif
