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

#endif
