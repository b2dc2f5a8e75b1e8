/* tiptap: the clocks run times are read on, in seconds.
 *
 * Wall time for what a user waits; CPU time of the calling thread or of the whole
 * process for what a run costs, which other programs sharing the cores barely change.
 */
#ifndef TIPTAP_CLOCK_H
#define TIPTAP_CLOCK_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef enum {
    TT_CLOCK_WALL = 0,    /* monotonic wall time */
    TT_CLOCK_THREAD = 1,  /* the calling thread's CPU time */
    TT_CLOCK_PROCESS = 2  /* the process's CPU time, all threads */
} tt_clock_kind;

/* The clock's reading, s, from an arbitrary origin: take differences. */
double tt_clock(tt_clock_kind kind);

TT_END_DECLS
#endif
