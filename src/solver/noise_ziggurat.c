/* Standard normal numbers by the ziggurat (Marsaglia and Tsang, J. Stat. Softw. 5 (2000);
 * in Doornik's form, 2005, whose layer and value come from separate bits): most draws
 * cost one hash, a table lookup and a comparison, where Box-Muller or the polar method
 * take a logarithm. The envelope tier draws a few of them every model cycle. Each
 * number is a pure function of (key, index): its tries take counters of their own. */
#include <math.h>

#include "noise_private.h"

enum {
    LAYERS = 128, /* the ziggurat's boxes */
    PER = 16      /* counters per index; the last two are Box-Muller's */
};

/* The boxes' right edges x[i] (x[0]: the base's width, V / f(R)) and the ratios
 * x[i + 1] / x[i] below which a point lies inside the next box up; for 128 boxes of area
 * V each, the base's edge R. */
static const double R = 3.442619855899, V = 9.91256303526217e-3;
static double X[LAYERS + 1], Q[LAYERS];

/* Made as the library loads, before any thread can draw. */
__attribute__((constructor)) static void tables(void)
{
    double f = exp(-0.5 * R * R);
    X[0] = V / f;
    X[1] = R;
    X[LAYERS] = 0;
    for (int i = 2; i < LAYERS; i++) {
        X[i] = sqrt(-2 * log(V / X[i - 1] + f));
        f = exp(-0.5 * X[i] * X[i]);
    }
    for (int i = 0; i < LAYERS; i++)
        Q[i] = X[i + 1] / X[i];
}

/* Box-Muller on two counters of the index's own: the fallback after many rejections. */
static double box_muller(uint64_t key, uint64_t c)
{
    const double u1 = tt_noise_unit(tt_noise_bits(key, c)), u2 = tt_noise_unit(tt_noise_bits(key, c + 1));
    return sqrt(-2.0 * log(u1)) * cos(2.0 * M_PI * u2);
}

double tt_noise_ziggurat(uint64_t key, uint64_t index)
{
    const uint64_t c0 = index * PER, end = c0 + PER - 2;
    for (uint64_t c = c0; c < end;) {
        const uint64_t h = tt_noise_bits(key, c++);
        const double u = 2 * tt_noise_unit(h) - 1; /* bits 11 to 63 */
        const int i = (int)(h & (LAYERS - 1));     /* bits 0 to 6 */
        if (fabs(u) < Q[i])
            return u * X[i];
        if (i == 0) { /* the base's tail beyond R (Marsaglia's exponential method) */
            while (c + 1 < end) {
                const double x = log(tt_noise_unit(tt_noise_bits(key, c))) / R;
                const double y = log(tt_noise_unit(tt_noise_bits(key, c + 1)));
                c += 2;
                if (-2 * y >= x * x)
                    return u < 0 ? x - R : R - x;
            }
            break;
        }
        /* the wedge between box i and the curve */
        if (c >= end)
            break;
        const double x = u * X[i];
        const double f0 = exp(-0.5 * (X[i] * X[i] - x * x));
        const double f1 = exp(-0.5 * (X[i + 1] * X[i + 1] - x * x));
        if (f1 + tt_noise_unit(tt_noise_bits(key, c++)) * (f0 - f1) < 1.0)
            return x;
    }
    return box_muller(key, end);
}
