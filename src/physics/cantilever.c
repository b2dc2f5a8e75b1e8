/* Cantilever constants and the free transfer function (Burnham et al. eqs. 1, 2). */
#include "tiptap/physics/cantilever.h"

#include <math.h>
#include <string.h>

#include "tiptap/util/error.h"

/* |H(w)| and lag of y for unit forcing amplitude on y's equation:
 * m y'' + c y' + k y = f cos(w t)  ->  y = f/|k - m w^2 + i c w| cos(w t - lag). */
static void unit_response(const tt_cantilever *c, double w, double *gain, double *lag)
{
    double re = c->k - c->m * w * w, im = c->c * w;
    *gain = 1.0 / hypot(re, im);
    *lag = atan2(im, re);
}

int tt_cantilever_init(tt_cantilever *c, double k, double f0, double Q, double A0, double fd,
                       tt_drive drive)
{
    if (!(k > 0) || !isfinite(k))
        return tt_error(TT_EINVAL, "cantilever spring constant must be positive and finite");
    if (!(f0 > 0) || !isfinite(f0))
        return tt_error(TT_EINVAL, "cantilever resonance frequency must be positive and finite");
    if (!(Q > 0) || !isfinite(Q))
        return tt_error(TT_EINVAL, "cantilever quality factor must be positive and finite");
    if (!(A0 > 0) || !isfinite(A0))
        return tt_error(TT_EINVAL, "cantilever free amplitude must be positive and finite");
    if (!(fd > 0) || !isfinite(fd))
        return tt_error(TT_EINVAL, "drive frequency must be positive and finite");
    memset(c, 0, sizeof *c);
    c->k = k;
    c->f0 = f0;
    c->Q = Q;
    c->A0 = A0;
    c->fd = fd;
    c->drive = drive;
    c->w0 = 2 * M_PI * f0;
    c->wd = 2 * M_PI * fd;
    c->T = 1.0 / fd;
    c->m = k / (c->w0 * c->w0);
    c->c = c->m * c->w0 / Q;
    double gain, lag;
    unit_response(c, c->wd, &gain, &lag);
    c->phi0 = lag;
    /* Base drive: y obeys m y'' + c y' + k y = -m z'' = m w^2 a_d cos(w t). */
    c->a_d = drive == TT_DRIVE_BASE ? A0 / (gain * c->m * c->wd * c->wd) : 0.0;
    c->F0 = drive == TT_DRIVE_FORCE ? A0 / gain : 0.0;
    return TT_OK;
}

void tt_cantilever_response(const tt_cantilever *c, double w, double *amp, double *lag)
{
    double gain;
    unit_response(c, w, &gain, lag);
    double forcing = c->drive == TT_DRIVE_BASE ? c->m * w * w * c->a_d : c->F0;
    *amp = gain * forcing;
}
