/* A double as printf's "%.9g" writes it in the C locale (see tt_format_g9 in
 * include/tiptap/util/str.h): the nine significant digits from one scaling by an exact
 * power of ten with its rounding error (fma), checked to be away from a rounding tie,
 * else printf itself. Why: the noisy blend's scope.csv holds 168,750 numbers, and
 * printf's exact decimal conversion of them was 3 % of the run's CPU samples. */
#include "tiptap/util/str.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* 10^k for 0 <= k <= 22, exact in a double */
static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* ax * 10^k as an integer part *fl and a fraction (within 1e-16 of the exact one,
 * possibly just under 0 or over 1): the product's rounding error from fma, or the
 * quotient's remainder, both exact. */
static double scaled(double ax, int k, double *fl)
{
    if (k >= 0) {
        const double p = pow10_exact[k], hi = ax * p, lo = fma(ax, p, -hi);
        *fl = floor(hi);
        return (hi - *fl) + lo;
    }
    const double p = pow10_exact[-k], q = ax / p, r = fma(-q, p, ax);
    *fl = floor(q);
    return (q - *fl) + r / p;
}

/* |x| as nine digits: D in [1e8, 1e9] and x's decimal exponent *e (log10's guess,
 * corrected), rounded to nearest; 0 when the scaled value lies within 1e-9 of a tie
 * (printf's exact ties go to even) or out of the exact powers' range. */
static long nine_digits(double ax, int *e)
{
    double fl, fr;
    for (int pass = 0; pass < 2; pass++) {
        const int k = 8 - *e;
        if (k > 22 || k < -22)
            return 0;
        fr = scaled(ax, k, &fl);
        if (fl >= 1e9)
            (*e)++; /* log10 put the exponent one off */
        else if (fl < 1e8)
            (*e)--;
        else
            break;
        if (pass == 1)
            return 0;
    }
    if (fabs(fr - 0.5) < 1e-9)
        return 0;
    long d = (long)fl + (fr > 0.5);
    if (d >= 1000000000L) { /* 999999999.5 and over: 1.00000000e(e+1) */
        d /= 10;
        (*e)++;
    }
    return d;
}

/* printf itself, its decimal point the C locale's whatever the process's (a caller
 * embedding the library may have set one with a comma) */
static int by_printf(char *buf, double x)
{
    int n = snprintf(buf, 32, "%.9g", x);
    for (char *p = buf; *p; p++)
        if (*p == ',')
            *p = '.';
    return n;
}

int tt_format_g9(char *buf, double x)
{
    const double ax = fabs(x);
    if (!(ax >= 1e-280 && ax <= 1e280)) /* zero, subnormal, huge, inf, nan */
        return by_printf(buf, x);
    int e = (int)floor(log10(ax));
    const long d = nine_digits(ax, &e);
    if (!d)
        return by_printf(buf, x);
    char dig[10];
    int nd = 9;
    for (long v = d, i = 8; i >= 0; i--, v /= 10)
        dig[i] = (char)('0' + v % 10);
    while (nd > 1 && dig[nd - 1] == '0') /* %g drops trailing zeros */
        nd--;
    char *p = buf;
    if (x < 0)
        *p++ = '-';
    if (e >= -4 && e < 9) { /* fixed: e + 1 digits before the point */
        if (e < 0) {
            *p++ = '0';
            *p++ = '.';
            for (int i = 0; i < -e - 1; i++)
                *p++ = '0';
            memcpy(p, dig, (size_t)nd);
            p += nd;
        } else {
            memcpy(p, dig, (size_t)(e + 1));
            p += e + 1;
            if (nd > e + 1) {
                *p++ = '.';
                memcpy(p, dig + e + 1, (size_t)(nd - e - 1));
                p += nd - e - 1;
            }
        }
    } else { /* d.dddddddde+XX */
        *p++ = dig[0];
        if (nd > 1) {
            *p++ = '.';
            memcpy(p, dig + 1, (size_t)(nd - 1));
            p += nd - 1;
        }
        *p++ = 'e';
        *p++ = e < 0 ? '-' : '+';
        const int ae = e < 0 ? -e : e;
        if (ae >= 100)
            *p++ = (char)('0' + ae / 100);
        *p++ = (char)('0' + ae / 10 % 10);
        *p++ = (char)('0' + ae % 10);
    }
    *p = '\0';
    return (int)(p - buf);
}
