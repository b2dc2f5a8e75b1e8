/* tiptap: the live console's server (tiptap live; docs/live.md).
 *
 * One HTTP and WebSocket server (libwebsockets) on 127.0.0.1: it serves the console's
 * page from the binary (web/, embedded at build time; nothing from elsewhere), the
 * current image and scene as files (/export/scan.gwy, /export/CHANNEL_trace.gsf,
 * /export/scene.ini: what tiptap scan writes for that scene), and a WebSocket
 * (protocol "tiptap-live") that sends the instrument's state (docs/live.md, "Protocol")
 * and takes the console's messages (controls.h).
 *
 * It stays bounded whatever the clients do: no queue per client (each holds the version
 * it has seen of the frame, rows, scope and status, and is sent the newest of each as
 * its socket allows, so a slow one skips scopes and is sent each row once, at its
 * latest), at most 16 KiB a message from a client and 20 messages a second (a burst of
 * 40; the rest dropped with one reply saying how many), at most max_clients WebSockets
 * (counted from the accepted handshake to the close), at most 64 connections at once,
 * exports streamed from their file 16 KiB at a time. Every request, plain or WebSocket,
 * is refused (403) unless its Host, and its Origin where it has one, are this server's:
 * 127.0.0.1, localhost or [::1] with the port, or without it on port 80 (no other web
 * page may drive or read the instrument, nor a rebound name); only GET and HEAD are
 * served (others 405). Every text sent is UTF-8.
 *
 * Each page (WebSocket) drives an instrument of its own, at most max_instruments of them
 * (docs/live.md, "One instrument per page"): a copy of the controls and an engine, kept
 * idle after its page closes (for its exports and a reload at /N) until a new page needs
 * the slot; its exports are /export/N/NAME.
 *
 * Ownership: tt_live_serve borrows the controls (the start's settings, copied for each
 * instrument); it makes and frees the instruments, and runs until cancellation is
 * requested (util/cancel.h), then closes every connection.
 */
#ifndef TIPTAP_LIVE_SERVER_H
#define TIPTAP_LIVE_SERVER_H

#include "tiptap/config/scene.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/live/controls.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int port;        /* 0: one the system picks */
    int max_clients; /* WebSockets at once (0: 16) */
    /* instruments at once (0: 4): each page has its own (controls, engine, exports), and
     * a page beyond them is told so and waits for one */
    int max_instruments;
    /* writes the current scan's files into dir as tiptap scan does (the exports) */
    int (*write)(void *user, const tt_scan *scan, const tt_scene *scene, const char *dir);
    void *write_user;
    /* called once listening, with the port */
    void (*ready)(void *user, int port);
    void *ready_user;
} tt_live_options;

/* TT_OK when stopped by cancellation; TT_EIO when it cannot listen, TT_EINVAL when the
 * first scene cannot be scanned. */
int tt_live_serve(tt_live_controls *c, const tt_live_options *o);

#ifdef __cplusplus
}
#endif
#endif
