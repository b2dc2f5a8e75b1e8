/* The live console's server inside (src/live/server.c, server_http.c): its limits, an
 * instrument (a page's own controls and engine), a connection's state, the server's; and
 * the plain HTTP side (the page's files and the exports). Nothing outside src/live/
 * includes it.
 *
 * Ownership: the server owns its instruments and the connections' states are
 * libwebsockets' (per connection), listed in server.all while open.
 */
#ifndef TIPTAP_LIVE_SERVER_PRIVATE_H
#define TIPTAP_LIVE_SERVER_PRIVATE_H

#include <libwebsockets.h>
#include <stdio.h>

#include "bench_private.h"
#include "live_private.h"
#include "tiptap/live/engine.h"
#include "tiptap/live/server.h"

enum {
    RX_MAX = 16384,         /* bytes of one message from a page */
    RATE = 20, BURST = 40,  /* messages a second from one page, and its burst */
    OUT_MAX = 64 << 20,     /* the largest message sent (a row of 16384 pixels is ~1 MB) */
    EXPORT_WAIT_S = 300,    /* how long an export may wait for the line under way */
    CONN_MAX = 64,          /* connections at once, pages and requests (a browser opens 6
                             * a host; more wait in the kernel's backlog) */
    CHUNK = 16384           /* bytes of a file sent at a time: all a request holds */
};

typedef struct pss pss;

/* An instrument: a page's own controls and engine (its scan, images and exports). It
 * outlives its page, idle (the engine waits: no CPU), so that a reload finds it again and
 * its exports stay; a new page takes it over, reset to the start, only when no slot is
 * free (the one idle longest). */
typedef struct {
    int number;                 /* 1 ..: in the page's messages and export paths */
    tt_live_controls *controls; /* NULL with engine: not made yet, or its reset failed */
    tt_live_engine *engine;
    tt_live_bench *bench;       /* its force curve and thermal tune (with engine) */
    unsigned long controls_version;
    pss *page;                  /* the page that holds it (NULL: none) */
    int used;                   /* a page has held it since it was made */
    double released_at;         /* when its last page left, wall s */
    unsigned long generation;   /* bumped when it is remade: a waiting export notices */
} instrument;

struct pss {
    struct lws *wsi;
    pss *next;
    int ws;
    /* HTTP: a body from memory (the page) or streamed from a file (an export) */
    const unsigned char *body;
    FILE *file;
    size_t len, pos;
    int headers, waiting, head;
    instrument *export_inst;
    unsigned long export_id, export_gen;
    char export_name[128];
    /* WebSocket: its instrument (NULL: all are held by other pages, it waits for one), the
     * one it asked for (its path /N: a reload's; 0 none), and what it has seen */
    instrument *inst;
    int want;
    int hidden; /* the page said its tab is hidden (the Page Visibility API): it does not look */
    unsigned long seen_controls, seen_frame, seen_rows, seen_scope, seen_status;
    unsigned long seen_bench[TT_BENCH_KINDS];
    int have_reply, reply_ok;
    unsigned dropped;
    char reply[600];
    char *rx;
    size_t rxlen;
    int rx_over;
    double tokens, tokens_at;
};

typedef struct {
    struct lws_context *ctx;
    tt_live_controls *controls; /* the start: each instrument's controls are a copy */
    const tt_live_options *o;
    instrument *inst;           /* max_inst of them */
    instrument *last;           /* the one last taken or changed: /export/NAME's */
    int clients, max_clients, max_inst, port;
    int closing; /* the instruments are freed: the closing pages leave nothing to do */
    pss *all;
    tt_live_buf out;
    lws_sorted_usec_list_t sul;
} server;

/* A request's Host, and its Origin where it has one, are this server's on port. */
int tt_live_trusted(struct lws *wsi, int port);
/* A plain request for uri (the page's files, /export/...): answered, or waiting for its
 * export; and its writeable callback. 0, or -1 to close the connection. */
int tt_live_http_request(server *s, pss *p, const char *uri);
int tt_live_http_writeable(server *s, pss *p);

#endif
