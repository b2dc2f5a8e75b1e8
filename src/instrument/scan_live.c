/* Changes between the lines of a live scan: the feedback, the noise, the line rate and
 * the free amplitude (see include/tiptap/instrument/scan.h). Each is checked before
 * anything changes, and takes effect from the next line. */
#include <math.h>
#include <stdlib.h>

#include "scan_engine.h"
#include "tiptap/util/error.h"

void tt_scan_get_feedback(const tt_scan *S, tt_feedback_params *p)
{
    *p = (tt_feedback_params){S->setpoint, S->kp, S->ki, S->z_range};
}

int tt_scan_set_feedback(tt_scan *S, const tt_feedback_params *p)
{
    if (!(p->setpoint > 0 && p->setpoint < S->A0))
        return tt_error(TT_EINVAL, "[feedback] setpoint: %g nm must lie between 0 and the free "
                                   "amplitude (%g nm)", p->setpoint * 1e9, S->A0 * 1e9);
    if (!(p->kp >= 0 && p->kp <= 1e6))
        return tt_error(TT_EINVAL, "[feedback] proportional_gain: %g must lie between 0 and 1e6", p->kp);
    if (!(p->ki >= 0 && isfinite(p->ki)))
        return tt_error(TT_EINVAL, "[feedback] integral_gain: %g Hz must be 0 or more", p->ki);
    if (!(p->z_range > 0 && isfinite(p->z_range)))
        return tt_error(TT_EINVAL, "[feedback] z_range: %g m must be above 0", p->z_range);
    S->setpoint = p->setpoint;
    S->kp = p->kp;
    S->ki = p->ki;
    S->z_range = p->z_range;
    /* a continuous line carries the loop on: retuned in place, its z kept */
    if (S->step && S->step->engaged)
        tt_feedback_retune(&S->step->fb, p);
    return TT_OK;
}

void tt_scan_get_noise(const tt_scan *S, tt_scan_noise *n) { *n = S->noise; }

int tt_scan_set_noise(tt_scan *S, const tt_scan_noise *n)
{
    if (!(n->temperature >= 0 && isfinite(n->temperature)))
        return tt_error(TT_EINVAL, "[noise] temperature: %g K must be 0 or more", n->temperature);
    if (n->temperature > 0 && n->points < 4)
        return tt_error(TT_EINVAL, "[noise] points: %d is below 4", n->points);
    if (n->temperature > 0 && S->solver.method == TT_METHOD_RK4 &&
        S->solver.steps_per_cycle % n->points != 0)
        return tt_error(TT_EINVAL, "[noise] points: rk4's steps_per_cycle (%d) must be a multiple of it (%d)",
                        S->solver.steps_per_cycle, n->points);
    if (!(n->detector >= 0 && isfinite(n->detector)))
        return tt_error(TT_EINVAL, "[noise] detector: %g m/sqrt(Hz) must be 0 or more", n->detector);
    if (!(n->z_piezo >= 0 && isfinite(n->z_piezo)))
        return tt_error(TT_EINVAL, "[noise] z_piezo: %g m/sqrt(Hz) must be 0 or more", n->z_piezo);
    tt_noise_ou zn;
    int rc = tt_scan_piezo_noise(n, &S->cantilever, &zn);
    if (rc)
        return rc;
    S->noise = *n;
    /* as tt_scan_alloc sets them: white noise of one-sided density n sampled at rate fs
     * has variance n^2 fs / 2; the z piezo's through its bandwidth */
    S->sd = n->detector * sqrt(0.5 * S->lockin.samples_per_period / S->cantilever.T);
    S->zn = zn;
    return S->step ? tt_scan_worker_retune(S, S->step) : TT_OK;
}

double tt_scan_line_rate(const tt_scan *S) { return S->raster.line_rate; }

int tt_scan_set_line_rate(tt_scan *S, double rate)
{
    const tt_instrument_params *in = &S->inst;
    if (in->drift_x != 0 || in->drift_y != 0 || in->drift_z != 0)
        return tt_error(TT_EINVAL, "[scan] line_rate: fixed with drift on (the drift's clock and "
                                   "the surface's extent follow it): a new scan");
    if (!(rate > 0 && isfinite(rate)))
        return tt_error(TT_EINVAL, "[scan] line_rate: %g Hz must be above 0", rate);
    tt_raster r = S->raster;
    r.line_rate = rate;
    const long P = S->lockin.periods_per_block;
    const double cycles = S->cantilever.fd / (2 * rate);
    /* each pixel a lock-in block at least, as the scene's check asks (src/config) */
    if (!(cycles <= 1e9) || tt_raster_cycles_per_direction(&r, S->cantilever.T) / r.pixels < P)
        return tt_error(TT_EINVAL, "[scan] line_rate: %g Hz gives %.3g drive cycles each way "
                                   "along a line of %ld pixels: from %ld (a lock-in block a "
                                   "pixel) to 1e9", rate, cycles, r.pixels, P * r.pixels);
    S->raster = r;
    return TT_OK;
}

double tt_scan_free_amplitude(const tt_scan *S) { return S->A0; }

int tt_scan_set_free_amplitude(tt_scan *S, double A0)
{
    if (!(A0 > S->setpoint && isfinite(A0)))
        return tt_error(TT_EINVAL, "[cantilever] free_amplitude: %g nm must exceed the setpoint "
                                   "(%g nm; set that first)", A0 * 1e9, S->setpoint * 1e9);
    const tt_cantilever *c = &S->cantilever;
    tt_cantilever nc;
    int rc = tt_cantilever_init(&nc, c->k, c->f0, c->Q, A0, c->fd, c->drive);
    /* the further modes as they were (the drive is mode 1's) */
    if (!rc && c->modes > 1)
        rc = tt_cantilever_set_modes(&nc, c->modes, c->mode_f + 1, c->mode_k + 1, c->mode_Q + 1);
    if (!rc && c->A2 > 0) /* and mode 2's drive */
        rc = tt_cantilever_set_drive2(&nc, c->A2, c->fd2);
    if (rc)
        return rc;
    S->cantilever = nc;
    S->A0 = A0;
    /* everything made for the old drive goes: the stepping workspace (its sim, the
     * envelope model scaled by A0) and the averaged tier's tables, made again when
     * next needed */
    if (S->step) {
        tt_scan_worker_free(S->step);
        free(S->step);
        S->step = NULL;
    }
    for (size_t i = 0; i < S->nmaterials && S->avg; i++)
        tt_averaged_free(S->avg[i]);
    free(S->avg);
    S->avg = NULL;
    return TT_OK;
}
