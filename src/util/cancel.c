/* Cooperative cancellation flag (see include/tiptap/util/cancel.h). */
#include "tiptap/util/cancel.h"

#include <signal.h>

static volatile sig_atomic_t requested = 0;
static volatile sig_atomic_t by_signal = 0;
/* per thread: a flag of the caller's, read as it may change on another thread */
static _Thread_local const int *watched;

void tt_cancel_request(void) { requested = 1; }
void tt_cancel_request_signal(int sig)
{
    by_signal = sig;
    requested = 1;
}
int tt_cancel_requested(void)
{
    return requested != 0 || (watched && __atomic_load_n(watched, __ATOMIC_RELAXED) != 0);
}

const int *tt_cancel_watch(const int *flag)
{
    const int *old = watched;
    watched = flag;
    return old;
}
int tt_cancel_signal(void) { return by_signal; }
void tt_cancel_reset(void)
{
    requested = 0;
    by_signal = 0;
}
