/* Seeded noise (see include/tiptap/solver/noise.h): the counter-based generator, the
 * per-cycle table of the cantilever's Langevin force and the z piezo's low-passed
 * position noise. */
#include "tiptap/solver/noise.h"

#include <math.h>
#include <stdlib.h>

#include "noise_private.h"
#include "stepper.h"
#include "tiptap/util/error.h"

uint64_t tt_noise_key(uint64_t seed, unsigned stream, long line)
{
    return tt_noise_mix64(tt_noise_mix64(tt_noise_mix64(seed + 0x9e3779b97f4a7c15ULL) ^ (uint64_t)stream) +
                          (uint64_t)line);
}

double tt_noise_gauss(uint64_t key, uint64_t index)
{
    /* the ziggurat: each index its own counters, so no value is shared between indices */
    return tt_noise_ziggurat(key, index);
}

int tt_noise_ou_init(tt_noise_ou *p, double n, double fc, double dt)
{
    p->sd = p->a = p->b = 0;
    if (!(n >= 0 && n < INFINITY && fc > 0 && dt > 0 && fc * dt <= 0.5 && dt < INFINITY))
        return tt_error(TT_EINVAL,
                        "a noise of density %g m/sqrt(Hz) and bandwidth %g Hz sampled every %g s: "
                        "expected a density of 0 or more and a bandwidth above 0 and at most "
                        "half the sampling rate",
                        n, fc, dt);
    /* the low-pass's noise bandwidth is pi fc / 2 */
    const double w = 2 * M_PI * fc * dt;
    p->sd = n * sqrt(M_PI * fc / 2);
    p->a = exp(-w);
    p->b = p->sd * sqrt(-expm1(-2 * w));
    return TT_OK;
}

double tt_noise_ou_first(const tt_noise_ou *p, uint64_t key)
{
    return p->sd * tt_noise_gauss(key, 0);
}

double tt_noise_ou_next(const tt_noise_ou *p, uint64_t key, uint64_t index, double z)
{
    return p->a * z + p->b * tt_noise_gauss(key, index);
}

int tt_sim_set_thermal(tt_sim *S, double temperature, int points)
{
    free(S->sys.nz_f);
    S->sys.nz_f = NULL;
    S->sys.nz_n = 0;
    if (!(temperature > 0)) {
        tt_step_setup(S);
        return TT_OK;
    }
    if (points < 4)
        return tt_error(TT_EINVAL, "[noise] points: %d is below 4", points);
    if (S->solver.method == TT_METHOD_RK4 && S->solver.steps_per_cycle % points != 0)
        return tt_error(TT_EINVAL,
                        "[noise] points: rk4's steps_per_cycle (%d) must be a multiple of it (%d)",
                        S->solver.steps_per_cycle, points);
    /* a table per mode, whatever the modes now: tt_sim_set_cantilever may add some */
    S->sys.nz_f = calloc((size_t)TT_MODES_MAX * ((size_t)points + 1), sizeof *S->sys.nz_f);
    if (!S->sys.nz_f)
        return tt_error_nomem("the thermal force, [noise] points = %d", points);
    S->sys.nz_n = points;
    S->sys.nz_dt = S->c.T / points;
    /* white noise of two-sided density 2 c kB T drawn every dt: variance 2 c kB T / dt */
    S->sys.nz_sigma = sqrt(2.0 * S->c.c * TT_BOLTZMANN * temperature / S->sys.nz_dt);
    S->sys.nz_temp = temperature;
    S->sys.nz_cycle = 0;
    tt_step_setup(S);
    return TT_OK;
}

void tt_sim_noise_key(tt_sim *S, uint64_t key)
{
    S->sys.nz_key = key;
    S->sys.nz_cycle = 0;
}

void tt_noise_pair(uint64_t key, uint64_t index, double g[2])
{
    g[0] = tt_noise_ziggurat(key, 2 * index);
    g[1] = tt_noise_ziggurat(key, 2 * index + 1);
}

void tt_noise_cycle(tt_sim *S)
{
    /* the cycle's points 0..n; point n is the next cycle's point 0, drawn again there */
    uint64_t base = (uint64_t)S->sys.nz_cycle * (uint64_t)S->sys.nz_n;
    for (int j = 0; j <= S->sys.nz_n; j++)
        S->sys.nz_f[j] = S->sys.nz_sigma * tt_noise_gauss(S->sys.nz_key, base + (uint64_t)j);
    /* each further mode its own Langevin force (density 2 c_i kB T), its own stream */
    for (int i = 1; i < S->sys.modes; i++) {
        double sig = sqrt(2.0 * S->sys.c[i] * TT_BOLTZMANN * S->sys.nz_temp / S->sys.nz_dt);
        uint64_t key = tt_noise_mix64(S->sys.nz_key ^ (0x6a09e667f3bcc909ULL * (uint64_t)i));
        double *f = S->sys.nz_f + i * (S->sys.nz_n + 1);
        for (int j = 0; j <= S->sys.nz_n; j++)
            f[j] = sig * tt_noise_gauss(key, base + (uint64_t)j);
    }
    S->sys.nz_cycle++;
}

double tt_noise_next_knot(const tt_sim *S, double hmin)
{
    long j = (long)(S->tau / S->sys.nz_dt) + 1;
    double t = (double)j * S->c.T / S->sys.nz_n;
    if (t - S->tau < hmin)
        t = (double)(j + 1) * S->c.T / S->sys.nz_n;
    return t;
}
