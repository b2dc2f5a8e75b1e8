/* The shared root finder (src/util/root.h): the Illinois steps reach a root to the
 * asked tolerance in few evaluations where plain regula falsi stalls, stop at a value
 * within ftol, and hand back a bracket that still holds the root when they run out. */
#include "tt_test.h"
#include "util/root.h"

typedef struct {
    int calls;
} counter;

/* Convex on the bracket: plain regula falsi keeps one end for ever here. */
static double cube_minus_two(double x, void *data)
{
    ((counter *)data)->calls++;
    return x * x * x - 2;
}

/* Seek the cube root of 2 in [0, 4]; calls counts the evaluations. */
static int seek(tt_root_bracket *br, double xtol, double ftol, int maxit, double *x, int *calls)
{
    counter c = {0};
    *br = (tt_root_bracket){0, 4, -2, 62};
    *x = NAN;
    int found = tt_root_illinois(cube_minus_two, &c, br, xtol, ftol, maxit, x);
    *calls = c.calls;
    return found;
}

static void converges_superlinearly(void **st)
{
    (void)st;
    tt_root_bracket br;
    double x;
    int calls, found = seek(&br, 1e-15, 1e-14, 100, &x, &calls);
    assert_int_equal(found, 1);
    assert_close(x, cbrt(2.0), 1e-14);
    /* regula falsi alone takes hundreds here; bisection about 50 */
    assert_true(calls <= 20);
}

static void bracket_keeps_the_root(void **st)
{
    (void)st;
    tt_root_bracket br;
    double x;
    int calls, found = seek(&br, 1e-15, 0, 5, &x, &calls);
    assert_int_equal(found, 0);
    assert_int_equal(calls, 5);
    assert_true(br.a < cbrt(2.0) && cbrt(2.0) < br.b);
    assert_true(br.a > 0 || br.b < 4);                 /* it narrowed */
    assert_true(br.fa < 0 && br.fb > 0);               /* signs kept at the ends */
}

static void stops_at_xtol(void **st)
{
    (void)st;
    tt_root_bracket br;
    double x;
    int calls, found = seek(&br, 1e-6, 0, 100, &x, &calls);
    (void)calls;
    assert_int_equal(found, 0);
    assert_true(br.b - br.a <= 1e-6);
    assert_true(br.a <= cbrt(2.0) && cbrt(2.0) <= br.b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(converges_superlinearly),
        cmocka_unit_test(bracket_keeps_the_root),
        cmocka_unit_test(stops_at_xtol),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
