/* The clocks run times are read on (tiptap/util/clock.h). */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "tiptap/util/clock.h"

double tt_clock(tt_clock_kind kind)
{
    static const clockid_t id[] = {CLOCK_MONOTONIC, CLOCK_THREAD_CPUTIME_ID,
                                   CLOCK_PROCESS_CPUTIME_ID};
    struct timespec ts;
    clock_gettime(id[kind], &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
