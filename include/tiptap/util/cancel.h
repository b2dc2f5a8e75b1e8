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

TT_END_DECLS
#endif
