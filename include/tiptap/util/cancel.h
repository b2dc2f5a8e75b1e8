/* tiptap: cooperative cancellation.
 *
 * A long run (an approach, a scan) polls tt_cancel_requested() between units of
 * work (points, lines) and stops there with TT_EINTR, keeping what it finished. The
 * drive cycle itself polls it at its start and every 1024 steps (tt_sim_cycle), so that
 * everything built on cycles (settling, shooting, the envelope tier, the accuracy
 * study) returns TT_EINTR within milliseconds, abandoning the unit under way.
 * The command-line program requests cancellation from its SIGINT and SIGTERM handler
 * with tt_cancel_request_signal, so that it can exit 128 + the signal's number (130 for
 * Ctrl-C, 143 for SIGTERM); the requests are async-signal-safe. */
#ifndef TIPTAP_CANCEL_H
#define TIPTAP_CANCEL_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

void tt_cancel_request(void);
void tt_cancel_request_signal(int sig);
int tt_cancel_requested(void);
/* The signal that requested cancellation, 0 when none did. */
int tt_cancel_signal(void);
void tt_cancel_reset(void);
/* A cancellation of the calling thread's own: while *flag is non-zero (stored with
 * __atomic_store_n, by any thread), tt_cancel_requested() answers 1 on this thread, so
 * that its run stops at the next poll with TT_EINTR as on Ctrl-C, and the others run on
 * (the live console abandons a line so). NULL: none. Returns the flag it replaces. */
const int *tt_cancel_watch(const int *flag);

TT_END_DECLS
#endif
