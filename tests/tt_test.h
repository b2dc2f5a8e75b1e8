/* Shared test scaffolding: cmocka includes and small helpers. */
#ifndef TT_TEST_H
#define TT_TEST_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "tiptap/util/error.h"

/* assert |got - want| <= tol with both numbers in the failure message */
#define assert_close(got, want, tol)                                                            \
    do {                                                                                        \
        double g_ = (got), w_ = (want), t_ = (tol);                                             \
        if (!(fabs(g_ - w_) <= t_))                                                             \
            fail_msg("%s = %.12g, expected %.12g within %.3g (off by %.3g)", #got, g_, w_, t_,  \
                     fabs(g_ - w_));                                                            \
    } while (0)

#define assert_between(got, lo, hi)                                                             \
    do {                                                                                        \
        double g_ = (got), l_ = (lo), h_ = (hi);                                                \
        if (!(g_ >= l_ && g_ <= h_))                                                            \
            fail_msg("%s = %.12g, expected within [%.6g, %.6g]", #got, g_, l_, h_);            \
    } while (0)

/* assert that the library's last error message contains fragment, quoting both if not */
#define assert_message_has(fragment)                                                            \
    do {                                                                                        \
        const char *m_ = tt_error_message(), *f_ = (fragment);                                  \
        if (!strstr(m_, f_))                                                                    \
            fail_msg("'%s' lacks '%s'", m_, f_);                                                \
    } while (0)

/* The main() of a test file: the listed cmocka_unit_test(...) entries, run as one group. */
#define TT_TEST_MAIN(...)                                                                       \
    int main(void)                                                                              \
    {                                                                                           \
        const struct CMUnitTest tests[] = {__VA_ARGS__};                                        \
        return cmocka_run_group_tests(tests, NULL, NULL);                                       \
    }

#endif
