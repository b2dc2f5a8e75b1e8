/* Cooperative cancellation flag (see include/tiptap/util/cancel.h). */
#include "tiptap/util/cancel.h"

#include <signal.h>

static volatile sig_atomic_t requested = 0;

void tt_cancel_request(void) { requested = 1; }
int tt_cancel_requested(void) { return requested != 0; }
void tt_cancel_reset(void) { requested = 0; }
