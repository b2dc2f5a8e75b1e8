/* tiptap: cooperative cancellation.
 *
 * A long run (an approach, a scan) polls tt_cancel_requested() between units of
 * work (points, lines) and stops there with TT_EINTR, keeping what it finished.
 * The command-line program requests cancellation from its SIGINT handler; the call
 * is async-signal-safe. */
#ifndef TIPTAP_CANCEL_H
#define TIPTAP_CANCEL_H

#ifdef __cplusplus
extern "C" {
#endif

void tt_cancel_request(void);
int tt_cancel_requested(void);
void tt_cancel_reset(void);

#ifdef __cplusplus
}
#endif
#endif
