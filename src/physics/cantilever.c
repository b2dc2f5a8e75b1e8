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

/* The clamped-free beam's modes 1..3 (cos b cosh b = -1; the slope and the base coupling
 * of the tip-normalised mode shapes integrated numerically; docs/physics.md). */
static const double beam_root[TT_CANTILEVER_MODES_MAX] = {1.8751040687119612, 4.6940911329741746,
                                                          7.8547574382376126};
static const double beam_slope[TT_CANTILEVER_MODES_MAX] = {1.3765054846725348, 4.7807784102116340,
                                                           7.8486660464895032};
static const double beam_gamma[TT_CANTILEVER_MODES_MAX] = {1.5659835120792515, -0.86787179022143854,
                                                           0.50885059373221142};

static int mode_known(int n) { return n >= 1 && n <= TT_CANTILEVER_MODES_MAX; }

double tt_beam_root(int n) { return mode_known(n) ? beam_root[n - 1] : NAN; }
double tt_beam_slope(int n) { return mode_known(n) ? beam_slope[n - 1] : NAN; }
double tt_beam_base_coupling(int n) { return mode_known(n) ? beam_gamma[n - 1] / beam_gamma[0] : NAN; }

static double given(const double *a, int i, double dflt)
{
    return a && !isnan(a[i - 1]) ? a[i - 1] : dflt;
}

int tt_cantilever_set_modes(tt_cantilever *c, int modes, const double *f, const double *k,
                            const double *Q)
{
    if (!mode_known(modes))
        return tt_error(TT_EINVAL, "cantilever modes: %d, expected 1 to %d", modes,
                        TT_CANTILEVER_MODES_MAX);
    c->modes = modes;
    c->mode_k[0] = c->k;
    c->mode_f[0] = c->f0;
    c->mode_Q[0] = c->Q;
    c->mode_m[0] = c->m;
    c->mode_c[0] = c->c;
    c->mode_base[0] = 1.0;
    for (int i = 1; i < modes; i++) {
        double r = beam_root[i] / beam_root[0];
        double fi = given(f, i, c->f0 * r * r);
        double ki = given(k, i, c->k * (fi / c->f0) * (fi / c->f0));
        double Qi = given(Q, i, c->Q * fi / c->f0);
        if (!(fi > c->mode_f[i - 1]) || !isfinite(fi))
            return tt_error(TT_EINVAL, "mode %d's frequency %g Hz: expected above mode %d's (%g Hz)",
                            i + 1, fi, i, c->mode_f[i - 1]);
        if (!(ki > 0) || !isfinite(ki) || !(Qi > 0) || !isfinite(Qi))
            return tt_error(TT_EINVAL, "mode %d's stiffness %g N/m and Q %g: expected both positive",
                            i + 1, ki, Qi);
        double w = 2 * M_PI * fi;
        c->mode_f[i] = fi;
        c->mode_k[i] = ki;
        c->mode_Q[i] = Qi;
        c->mode_m[i] = ki / (w * w);
        c->mode_c[i] = c->mode_m[i] * w / Qi;
        c->mode_base[i] = tt_beam_base_coupling(i + 1);
    }
    return TT_OK;
}

void tt_cantilever_response_modes(const tt_cantilever *c, double w, double *re, double *im)
{
    /* mode n: m_n q'' + c_n q' + k_n q = f_n, f_n = g_n m_n w^2 (base, g_1 = 1: the point
     * mass's deflection from the base) or 1 (a force on the tip) */
    int modes = c->modes > 1 ? c->modes : 1;
    double sr = 0, si = 0;
    for (int i = 0; i < modes; i++) {
        double m = i ? c->mode_m[i] : c->m, k = i ? c->mode_k[i] : c->k;
        double cc = i ? c->mode_c[i] : c->c, g = i ? c->mode_base[i] : 1.0;
        double f = c->drive == TT_DRIVE_BASE ? g * m * w * w : 1.0;
        double dr = k - m * w * w, di = cc * w, den = dr * dr + di * di;
        sr += f * dr / den;
        si -= f * di / den;
    }
    *re = sr;
    *im = si;
}

int tt_cantilever_set_drive2(tt_cantilever *c, double A2, double fd2)
{
    if (c->modes < 2)
        return tt_error(TT_EINVAL, "mode 2's drive needs modes = 2 or more (modes is %d)",
                        c->modes > 1 ? c->modes : 1);
    if (isnan(fd2))
        fd2 = c->mode_f[1];
    if (!(A2 > 0) || !isfinite(A2))
        return tt_error(TT_EINVAL, "mode 2's free amplitude %g m: expected positive", A2);
    if (!(fd2 > 0) || !isfinite(fd2) || fd2 == c->fd)
        return tt_error(TT_EINVAL, "mode 2's drive frequency %g Hz: expected positive and apart "
                                   "from the first drive's %g Hz", fd2, c->fd);
    double re, im, w = 2 * M_PI * fd2;
    tt_cantilever_response_modes(c, w, &re, &im);
    /* the reference is the drive's force on mode 2: the base's sign follows g_2's */
    double sign = c->drive == TT_DRIVE_BASE && c->mode_base[1] < 0 ? -1.0 : 1.0;
    double gain = hypot(re, im), lag = -atan2(sign * im, sign * re);
    c->A2 = A2;
    c->fd2 = fd2;
    c->wd2 = w;
    c->ratio2 = fd2 / c->fd;
    c->a_d2 = c->drive == TT_DRIVE_BASE ? sign * A2 / gain : 0.0;
    c->F02 = c->drive == TT_DRIVE_FORCE ? A2 / gain : 0.0;
    c->phi2 = lag < -M_PI / 2 ? lag + 2 * M_PI : lag;
    return TT_OK;
}

double tt_cantilever_drive2_turns(const tt_cantilever *c, long n)
{
    double t = c->ratio2 * (double)n;
    return t - floor(t);
}
