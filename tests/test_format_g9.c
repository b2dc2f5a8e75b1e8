/* tt_format_g9 writes what printf's "%.9g" writes, byte for byte: on 2 million doubles of
 * random bits (every magnitude and sign), on the scope's kinds of values (times,
 * heights of picometres to micrometres, phases), on decimal ties and near-ties of the
 * ninth digit, at the fixed/exponent boundaries (1e-4, 1e9) and where rounding carries
 * into a new digit, and on zero, signed zero, infinities and NaN. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "tt_test.h"
#include "tiptap/util/str.h"

static long checked, differ;

static void same(double x)
{
    char a[64], b[64];
    int n = tt_format_g9(a, x);
    snprintf(b, sizeof b, "%.9g", x);
    checked++;
    if (strcmp(a, b) != 0 || n != (int)strlen(b)) {
        if (differ++ < 10)
            print_message("%a: own %s, printf %s\n", x, a, b);
    }
}

static uint64_t state = 0x9e3779b97f4a7c15u;
static uint64_t next(void)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
}

static void random_bits(void **st)
{
    (void)st;
    for (int i = 0; i < 2000000; i++) {
        uint64_t u = next();
        double x;
        memcpy(&x, &u, sizeof x);
        same(x);
    }
    assert_int_equal(differ, 0);
}

static void scope_values(void **st)
{
    (void)st;
    for (int i = 0; i < 1000000; i++) {
        double r = (double)(next() >> 11) / 9007199254740992.0; /* [0, 1) */
        int k = (int)(next() % 24);
        same(r * pow(10, -k));            /* heights, errors: 1e-24 to 1 */
        same(-r * 4 + 1e-3 * (double)k);  /* times and offsets */
        same((r - 0.5) * 360);            /* phases */
    }
    assert_int_equal(differ, 0);
}

static void ties_and_boundaries(void **st)
{
    (void)st;
    static const double edge[] = {0.0, -0.0, 1, -1, 0.5, 0.1, 1e-4, 9.9999999995e-5, 9.99999999e-5,
                                  1e9, 999999999.5, 999999999.4, 999999998.5, 1234567895,
                                  1234567885, 12345678950, 9.999999995, 9.9999999949, 99.5,
                                  1e-5, 123456789, 100000000, 1e16, 1e21, 1e22, 1e-280, 1e280,
                                  DBL_MAX, DBL_MIN, DBL_TRUE_MIN, INFINITY, -INFINITY, NAN};
    for (size_t i = 0; i < sizeof edge / sizeof edge[0]; i++) {
        same(edge[i]);
        same(-edge[i]);
        same(nextafter(edge[i], INFINITY));
        same(nextafter(edge[i], -INFINITY));
    }
    /* exact ties of the ninth digit: integers of ten digits ending in 5, halves */
    for (long v = 1000000005; v < 1000000005 + 2000000; v += 10) {
        same((double)v);
        same((double)v / 1024);
    }
    assert_int_equal(differ, 0);
    print_message("%ld values, all as printf\n", checked);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_bits),
        cmocka_unit_test(scope_values),
        cmocka_unit_test(ties_and_boundaries),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
