/* A plot's points held to a budget (trace --plot of 1e8 cycles grew without bound):
 * the count stays within it, and each line's extremes survive. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/io/decimate.h"

static void long_input_held_to_budget(void **st)
{
    (void)st;
    tt_decimate *d;
    const size_t total = 1000000, budget = 1000;
    assert_int_equal(tt_decimate_alloc(&d, 2, (double)total, budget), 0);
    for (size_t i = 0; i < total; i++) {
        /* a sine with one spike, as a contact pulse in a long trace */
        double v[2] = {(double)i, sin(0.01 * (double)i) + (i == 654321 ? 5 : 0)};
        assert_int_equal(tt_decimate_push(d, v), 0);
    }
    assert_int_equal(tt_decimate_finish(d), 0);
    size_t n = tt_decimate_count(d);
    assert_true(n <= budget + 2 && n >= budget / 2);
    const double *t = tt_decimate_line(d, 0), *y = tt_decimate_line(d, 1);
    double hi = -INFINITY, lo = INFINITY;
    for (size_t i = 0; i < n; i++) {
        hi = fmax(hi, y[i]);
        lo = fmin(lo, y[i]);
        if (i)
            assert_true(t[i] >= t[i - 1]);
    }
    assert_close(hi, 5 + sin(0.01 * 654321), 1e-12); /* the spike survives */
    assert_true(lo < -0.9999);                        /* and the envelope */
    tt_decimate_free(d);
}

static void short_input_kept_whole(void **st)
{
    (void)st;
    tt_decimate *d;
    assert_int_equal(tt_decimate_alloc(&d, 2, 500, 1000), 0);
    for (int i = 0; i < 500; i++) {
        double v[2] = {i, 2.0 * i};
        assert_int_equal(tt_decimate_push(d, v), 0);
    }
    assert_int_equal(tt_decimate_finish(d), 0);
    assert_int_equal(tt_decimate_count(d), 500);
    assert_close(tt_decimate_line(d, 1)[321], 642, 0);
    tt_decimate_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(long_input_held_to_budget),
        cmocka_unit_test(short_input_kept_whole),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
