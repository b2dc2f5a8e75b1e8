/* A double as printf's "%.9g" writes it in the C locale (see tt_format_g9 in
 * include/tiptap/util/str.h): the nine significant digits from one scaling in long
 * double, checked to be away from a rounding tie, else printf itself. Why: scope.csv
 * holds 126,000 of them on the noisy blend, and printf's exact decimal conversion took
 * most of that file's writing. */
#include "tiptap/util/str.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* 10^k, exact in long double's 64-bit mantissa up to 10^27 */
static long double pow10l_exact(int k)
{
    long double p = 1;
    for (int i = 0; i < k; i++)
        p *= 10;
    return p;
}

/* |x| * 10^k as nine digits: D in [1e8, 1e9) and x's decimal exponent *e after
 * rounding (half to even), 0 when the scaled value lies too near a tie to tell. */
static long nine_digits(double ax, int *e)
{
    int k = 8 - *e;
    if (k > 27 || k < -27)
        return 0;
    long double m = k >= 0 ? (long double)ax * pow10l_exact(k) : (long double)ax / pow10l_exact(-k);
    if (m >= 1e9L || m < 1e8L) { /* log10 put the exponent one off */
        *e += m >= 1e9L ? 1 : -1;
        k = 8 - *e;
        if (k > 27 || k < -27)
            return 0;
        m = k >= 0 ? (long double)ax * pow10l_exact(k) : (long double)ax / pow10l_exact(-k);
    }
    /* one rounding of the 64-bit mantissa: m is within 6e-11 of the exact product */
    const long double fl = floorl(m), fr = m - fl;
    if (fabsl(fr - 0.5L) < 1e-9L)
        return 0;
    long d = (long)fl + (fr > 0.5L);
    if (d >= 1000000000L) { /* 999999999.5 and over: 1.00000000e(e+1) */
        d /= 10;
        (*e)++;
    }
    return d < 100000000L ? 0 : d;
}

int tt_format_g9(char *buf, double x)
{
    const double ax = fabs(x);
    if (!(ax >= 1e-280 && ax <= 1e280)) /* zero, subnormal, huge, inf, nan */
        return snprintf(buf, 32, "%.9g", x);
    int e = (int)floor(log10(ax));
    const long d = nine_digits(ax, &e);
    if (!d)
        return snprintf(buf, 32, "%.9g", x);
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
