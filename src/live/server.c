/* The live console's server (include/tiptap/live/server.h): libwebsockets' event loop on
 * this thread, the instrument on the engine's. */
#include "tiptap/live/server.h"

#include <errno.h>
#include <libwebsockets.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "live_private.h"
#include "tiptap/live/engine.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/util/clock.h"

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
    unsigned long seen_controls, seen_frame, seen_rows, seen_scope, seen_status;
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

static void wake(void *user)
{
    server *s = user;
    lws_cancel_service(s->ctx);
}

static void wake_all(server *s)
{
    for (pss *p = s->all; p; p = p->next)
        if (p->ws || p->waiting)
            lws_callback_on_writable(p->wsi);
}

/* Cancellation (Ctrl-C) is polled here too: lws_service may sleep past a signal
 * that arrived just before it polled. */
static void tick(lws_sorted_usec_list_t *sul)
{
    server *s = lws_container_of(sul, server, sul);
    if (!tt_cancel_requested())
        lws_sul_schedule(s->ctx, 0, &s->sul, tick, 200 * LWS_US_PER_MS);
}

static void unlink_pss(server *s, pss *p)
{
    for (pss **q = &s->all; *q; q = &(*q)->next)
        if (*q == p) {
            *q = p->next;
            break;
        }
    if (p->file)
        fclose(p->file);
    free(p->rx);
    p->file = NULL;
    p->rx = NULL;
}

/* The Host, and the Origin where a browser sends one, must be this server's: another web
 * page open in the same browser may not drive the instrument nor read it, and a name that
 * resolves to 127.0.0.1 (DNS rebinding) is not this server's. Every request passes here,
 * a page's as a WebSocket's. */
static int trusted(struct lws *wsi, int port)
{
    char h[256];
    int n = lws_hdr_total_length(wsi, WSI_TOKEN_HOST);
    if (n <= 0 || n >= (int)sizeof h || lws_hdr_copy(wsi, h, sizeof h, WSI_TOKEN_HOST) <= 0 ||
        !tt_live_authority_ok(h, 0, port))
        return 0;
    if ((n = lws_hdr_total_length(wsi, WSI_TOKEN_ORIGIN)) <= 0)
        return 1; /* not a browser, or a browser's plain navigation */
    return n < (int)sizeof h && lws_hdr_copy(wsi, h, sizeof h, WSI_TOKEN_ORIGIN) > 0 &&
           tt_live_authority_ok(h, 1, port);
}

/* One message to a page: the buffer's text as a WebSocket text frame. */
static int send_buf(server *s, struct lws *wsi)
{
    if (s->out.failed)
        return 0; /* too large or out of memory: skipped, never half sent */
    int n = lws_write(wsi, s->out.mem + s->out.pre, s->out.len, LWS_WRITE_TEXT);
    return n < (int)s->out.len ? -1 : 0;
}

/* The next thing a page has not seen, newest first in importance: its reply, the
 * controls, the frame, the status, the scope, then the oldest row it lacks. */
static int ws_writeable(server *s, pss *p)
{
    tt_live_buf_reset(&s->out);
    int more = 1;
    instrument *in = p->inst;
    if (p->have_reply) {
        tt_live_msg_reply(&s->out, p->reply_ok, p->reply, p->dropped);
        p->have_reply = 0;
        p->dropped = 0;
    } else if (!in) {
        return 0; /* no instrument yet: nothing more to send */
    } else if (p->seen_controls != in->controls_version) {
        tt_live_msg_controls(&s->out, in->controls, in->number, s->max_inst);
        p->seen_controls = in->controls_version;
    } else {
        tt_live_engine_lock(in->engine);
        const tt_live_view *v = tt_live_engine_view(in->engine);
        if (p->seen_frame != v->frame_version && v->row_version) {
            tt_live_msg_frame(&s->out, v);
            p->seen_frame = v->frame_version;
            p->seen_rows = v->frame_version;
        } else if (p->seen_status < v->status_version) {
            tt_live_msg_status(&s->out, v, s->clients);
            p->seen_status = v->status_version;
        } else if (p->seen_scope < v->scope_version && v->scope_line >= 0) {
            tt_live_msg_scope(&s->out, v);
            p->seen_scope = v->scope_version;
        } else {
            long best = -1;
            for (long l = 0; v->row_version && l < v->lines; l++)
                if (v->row_version[l] > p->seen_rows &&
                    (best < 0 || v->row_version[l] < v->row_version[best]))
                    best = l;
            if (best >= 0) {
                tt_live_msg_row(&s->out, v, best);
                p->seen_rows = v->row_version[best];
            } else {
                more = 0;
            }
        }
        tt_live_engine_unlock(in->engine);
        if (!more)
            return 0;
    }
    if (send_buf(s, p->wsi))
        return -1;
    lws_callback_on_writable(p->wsi);
    return 0;
}

static void reply(pss *p, int ok, const char *why)
{
    p->have_reply = 1;
    p->reply_ok = ok;
    tt_live_text(p->reply, sizeof p->reply, why);
    lws_callback_on_writable(p->wsi);
}

/* A checked change to the instrument's engine, which makes its scan now or refuses it. */
static int take(void *user, tt_scene *scene, tt_scan_params *p, int restart)
{
    instrument *in = user;
    return tt_live_engine_submit(in->engine, scene, p, restart);
}

/* An instrument made afresh at the start's settings (its old engine and controls freed):
 * TT_OK, or the error with the slot left empty. */
static int make_instrument(server *s, instrument *in)
{
    in->generation++;
    tt_live_engine_free(in->engine);
    tt_live_controls_free(in->controls);
    in->engine = NULL;
    in->controls = NULL;
    in->used = 0;
    tt_scene *scene = NULL;
    tt_scan_params prm;
    int rc = tt_live_controls_copy(&in->controls, s->controls);
    if (!rc && !(rc = tt_live_controls_scene(in->controls, &scene, &prm)))
        rc = tt_live_engine_alloc(&in->engine, scene, &prm, wake, s);
    if (rc) {
        tt_live_controls_free(in->controls);
        in->controls = NULL;
        return rc;
    }
    tt_live_engine_set_writer(in->engine, s->o->write, s->o->write_user);
    in->controls_version++;
    return TT_OK;
}

/* A page's instrument: the one it asked for where no page holds it (a reload), else one
 * no page has held, else a new one while fewer than max_inst are made, else the one idle
 * longest, reset; none while every one is held (the page is told, and waits). */
static void attach(server *s, pss *p)
{
    instrument *in = NULL, *idle = NULL;
    int keep = 0; /* a reload's instrument, taken as it is */
    if (p->want >= 1 && p->want <= s->max_inst && s->inst[p->want - 1].engine &&
        !s->inst[p->want - 1].page) {
        in = &s->inst[p->want - 1];
        keep = 1;
    }
    for (int i = 0; !in && i < s->max_inst; i++)
        if (s->inst[i].engine && !s->inst[i].page && !s->inst[i].used)
            in = &s->inst[i];
    for (int i = 0; !in && i < s->max_inst; i++)
        if (!s->inst[i].engine)
            in = &s->inst[i];
    for (int i = 0; !in && i < s->max_inst; i++)
        if (!s->inst[i].page && (!idle || s->inst[i].released_at < idle->released_at))
            idle = &s->inst[i];
    if (!in && !idle) {
        char why[300];
        snprintf(why, sizeof why, "console: all %d instruments are in use by other pages (tiptap "
                 "live --instruments N allows more); this page gets one when another closes",
                 s->max_inst);
        reply(p, 0, why);
        return;
    }
    if (!keep && (!in || !in->engine || in->used)) {
        in = in ? in : idle;
        if (make_instrument(s, in)) {
            reply(p, 0, tt_error_message());
            return;
        }
    }
    in->page = p;
    in->used = 1;
    p->inst = in;
    p->seen_controls = p->seen_frame = p->seen_rows = p->seen_scope = p->seen_status = 0;
    s->last = in;
    /* a page looks: the engine runs (it waits, no CPU, while none does) */
    tt_live_engine_watched(in->engine, 1);
    lws_callback_on_writable(p->wsi);
}

/* A page gone: its instrument idles, kept for a reload; the page waiting longest takes it. */
static void detach(server *s, pss *p)
{
    instrument *in = p->inst;
    p->inst = NULL;
    if (!in || s->closing)
        return;
    in->page = NULL;
    in->released_at = tt_clock(TT_CLOCK_WALL);
    tt_live_engine_watched(in->engine, 0);
    /* the page waiting longest: the list is newest first */
    pss *wait = NULL;
    for (pss *q = s->all; q; q = q->next)
        if (q->ws && !q->inst && q != p)
            wait = q;
    if (wait)
        attach(s, wait);
}

/* A whole message from a page: checked by the controls, taken by the engine, or
 * refused with nothing changed. */
static void ws_message(server *s, pss *p)
{
    double t = tt_clock(TT_CLOCK_WALL);
    p->tokens += (t - p->tokens_at) * RATE;
    if (p->tokens > BURST)
        p->tokens = BURST;
    p->tokens_at = t;
    if (p->tokens < 1) {
        p->dropped++;
        char why[128];
        snprintf(why, sizeof why, "console: more than %d messages a second: %u dropped", RATE,
                 p->dropped);
        reply(p, 0, why);
        return;
    }
    p->tokens -= 1;
    if (p->rx_over) {
        char why[128];
        snprintf(why, sizeof why, "console: a message of more than %d bytes: ignored", RX_MAX);
        reply(p, 0, why);
        return;
    }
    /* the scan's own buttons: one word a message, nothing else in it */
    size_t n = p->rxlen;
    while (n > 0 && (p->rx[n - 1] == '\n' || p->rx[n - 1] == '\r' || p->rx[n - 1] == ' '))
        n--;
    instrument *in = p->inst;
    if (!in) {
        char why[200];
        snprintf(why, sizeof why, "console: this page has no instrument yet (all %d are in use)",
                 s->max_inst);
        reply(p, 0, why);
        return;
    }
    int pause = n == 5 && memcmp(p->rx, "pause", 5) == 0, resume = n == 6 && memcmp(p->rx, "resume", 6) == 0,
        step = n == 4 && memcmp(p->rx, "step", 4) == 0;
    if (pause || resume || step) {
        if (step)
            tt_live_engine_step(in->engine);
        else
            tt_live_engine_pause(in->engine, pause);
        reply(p, 1, "");
        wake_all(s);
        return;
    }
    tt_live_change ch;
    if (tt_live_controls_apply(in->controls, p->rx, p->rxlen, &ch, take, in)) {
        reply(p, 0, ch.why);
        return;
    }
    in->controls_version++;
    s->last = in;
    reply(p, 1, "");
    wake_all(s);
}

static void ws_receive(server *s, pss *p, const void *in, size_t len)
{
    if (!p->rx && !(p->rx = malloc(RX_MAX))) {
        p->rx_over = 1;
    } else if (!p->rx_over && p->rxlen + len <= RX_MAX) {
        memcpy(p->rx + p->rxlen, in, len);
        p->rxlen += len;
    } else {
        p->rx_over = 1;
    }
    if (lws_is_final_fragment(p->wsi) && lws_remaining_packet_payload(p->wsi) == 0) {
        ws_message(s, p);
        p->rxlen = 0;
        p->rx_over = 0;
    }
}

static const tt_live_asset *find_asset(const char *uri)
{
    size_t n;
    const tt_live_asset *a = tt_live_assets(&n);
    if (strcmp(uri, "/") == 0)
        uri = "/index.html";
    for (size_t i = 0; i < n; i++)
        if (strcmp(a[i].path, uri) == 0)
            return &a[i];
    return NULL;
}

/* The names an export may ask for: scene.ini, scan.gwy, CHANNEL_trace.gsf, ... */
static int export_name_ok(const char *name)
{
    size_t n = strlen(name);
    if (n == 0 || n > 100 || strchr(name, '/') || name[0] == '.')
        return 0;
    for (size_t i = 0; i < n; i++)
        if (!((name[i] >= 'a' && name[i] <= 'z') || (name[i] >= '0' && name[i] <= '9') ||
              name[i] == '_' || name[i] == '.'))
            return 0;
    return strcmp(name, "scene.ini") == 0 || strcmp(name, "scan.gwy") == 0 || strcmp(name, "lesson.ini") == 0 ||
           (n > 4 && strcmp(name + n - 4, ".gsf") == 0);
}

static int http_headers(struct lws *wsi, unsigned code, const char *mime, size_t len,
                        const char *disposition, const char *allow)
{
    unsigned char buf[LWS_PRE + 1024], *start = buf + LWS_PRE, *p = start, *end = buf + sizeof buf - 1;
    if (lws_add_http_common_headers(wsi, code, mime, (lws_filepos_t)len, &p, end))
        return -1;
    if (lws_add_http_header_by_name(wsi, (const unsigned char *)"cache-control:",
                                    (const unsigned char *)"no-store", 8, &p, end))
        return -1;
    if (disposition &&
        lws_add_http_header_by_name(wsi, (const unsigned char *)"content-disposition:",
                                    (const unsigned char *)disposition, (int)strlen(disposition),
                                    &p, end))
        return -1;
    if (allow && lws_add_http_header_by_name(wsi, (const unsigned char *)"allow:",
                                             (const unsigned char *)allow, (int)strlen(allow), &p, end))
        return -1;
    return lws_finalize_write_http_header(wsi, start, &p, end) ? -1 : 0;
}

/* A reply whose body is in memory (static: the page's files, or a line of text), sent
 * from the writeable callback; a HEAD request's without its body. */
static int http_send(pss *p, unsigned code, const char *mime, const void *body, size_t len,
                     const char *allow)
{
    p->body = body;
    p->len = len;
    p->pos = 0;
    if (http_headers(p->wsi, code, mime, len, NULL, allow))
        return -1;
    p->headers = 1;
    lws_callback_on_writable(p->wsi);
    return 0;
}

static int http_request(server *s, pss *p, const char *uri)
{
    static const char forbidden[] = "not this server's Host or Origin\n",
                      not_allowed[] = "only GET and HEAD\n";
    char *u;
    int ul, method = lws_http_get_uri_and_method(p->wsi, &u, &ul);
    p->head = method == LWSHUMETH_HEAD;
    if (!trusted(p->wsi, s->port))
        return http_send(p, HTTP_STATUS_FORBIDDEN, "text/plain", forbidden, sizeof forbidden - 1, NULL);
    if (method != LWSHUMETH_GET && method != LWSHUMETH_HEAD)
        return http_send(p, HTTP_STATUS_METHOD_NOT_ALLOWED, "text/plain", not_allowed,
                         sizeof not_allowed - 1, "GET, HEAD");
    if (strncmp(uri, "/export/", 8) == 0) {
        /* /export/N/NAME: instrument N's; /export/NAME: the one last taken or changed */
        const char *name = uri + 8;
        instrument *in = s->last;
        if (name[0] >= '1' && name[0] <= '9') {
            char *end;
            long k = strtol(name, &end, 10);
            in = *end == '/' && k <= s->max_inst ? &s->inst[k - 1] : NULL;
            name = in ? end + 1 : name;
        }
        if (!in || !in->engine || !export_name_ok(name))
            return lws_return_http_status(p->wsi, HTTP_STATUS_NOT_FOUND, "no such export") ? -1 : 0;
        snprintf(p->export_name, sizeof p->export_name, "%s", name);
        p->export_inst = in;
        p->export_gen = in->generation;
        p->export_id = tt_live_engine_export(in->engine);
        p->waiting = 1;
        /* the engine writes it between two lines: give it a slow line's time */
        lws_set_timeout(p->wsi, PENDING_TIMEOUT_HTTP_CONTENT, EXPORT_WAIT_S);
        return 0; /* answered when the engine has written it (http_export) */
    }
    const tt_live_asset *a = find_asset(uri);
    if (!a)
        return lws_return_http_status(p->wsi, HTTP_STATUS_NOT_FOUND, NULL) ? -1 : 0;
    return http_send(p, HTTP_STATUS_OK, a->mime, a->data, a->len, NULL);
}

/* The export asked for, once written: opened (the engine may remove the folder once it
 * writes the next; the open file stays readable) and streamed a chunk at a time, so that
 * a request holds a chunk's memory whatever the file's size. */
static int http_export(server *s, pss *p)
{
    const char *dir, *why;
    int status;
    char path[4400], disp[200], msg[600];
    instrument *in = p->export_inst;
    (void)s;
    if (in->generation != p->export_gen || !in->engine) {
        /* another page took the instrument over: its files are gone with it */
        p->waiting = 0;
        lws_set_timeout(p->wsi, NO_PENDING_TIMEOUT, 0);
        return lws_return_http_status(p->wsi, HTTP_STATUS_NOT_FOUND, "the instrument was reset") ? -1 : 0;
    }
    tt_live_engine_lock(in->engine);
    unsigned long done = tt_live_engine_exported(in->engine, &dir, &status, &why);
    if (done < p->export_id) {
        tt_live_engine_unlock(in->engine);
        return 0;
    }
    int bad = status != TT_OK || !dir;
    tt_live_text(msg, sizeof msg, bad ? why : "");
    snprintf(path, sizeof path, "%s/%s", dir ? dir : "", p->export_name);
    FILE *f = bad ? NULL : fopen(path, "rb");
    tt_live_engine_unlock(in->engine);
    struct stat st;
    if (f && fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode)) {
        p->file = f;
        p->len = (size_t)st.st_size;
    } else {
        if (f)
            fclose(f);
        if (!bad)
            snprintf(msg, sizeof msg, "%s: not written by this scan", p->export_name);
    }
    p->waiting = 0;
    lws_set_timeout(p->wsi, NO_PENDING_TIMEOUT, 0);
    if (!p->file)
        return lws_return_http_status(p->wsi, HTTP_STATUS_NOT_FOUND, msg) ? -1 : 0;
    p->pos = 0;
    snprintf(disp, sizeof disp, "attachment; filename=\"%s\"", p->export_name);
    const char *mime = strstr(p->export_name, ".ini") ? "text/plain" : "application/octet-stream";
    if (http_headers(p->wsi, HTTP_STATUS_OK, mime, p->len, disp, NULL))
        return -1;
    p->headers = 1;
    lws_callback_on_writable(p->wsi);
    return 0;
}

static int http_writeable(server *s, pss *p)
{
    if (p->waiting)
        return http_export(s, p);
    if (!p->headers)
        return 0;
    unsigned char buf[LWS_PRE + CHUNK];
    size_t n = p->head ? 0 : p->len - p->pos < CHUNK ? p->len - p->pos : CHUNK;
    if (n && p->file && fread(buf + LWS_PRE, 1, n, p->file) != n)
        return -1; /* the file shrank: the reply cannot be completed */
    if (n && !p->file)
        memcpy(buf + LWS_PRE, p->body + p->pos, n);
    p->pos += n;
    int final = p->head || p->pos >= p->len;
    if (!p->head && lws_write(p->wsi, buf + LWS_PRE, n, final ? LWS_WRITE_HTTP_FINAL : LWS_WRITE_HTTP) < (int)n)
        return -1;
    if (final) {
        if (p->file)
            fclose(p->file);
        p->file = NULL;
        p->headers = 0;
        return lws_http_transaction_completed(p->wsi) ? -1 : 0;
    }
    lws_callback_on_writable(p->wsi);
    return 0;
}

static int callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in,
                    size_t len)
{
    server *s = lws_context_user(lws_get_context(wsi));
    pss *p = user;
    switch (reason) {
    case LWS_CALLBACK_EVENT_WAIT_CANCELLED:
        wake_all(s);
        return 0;
    case LWS_CALLBACK_HTTP:
        if (!p->wsi) {
            p->wsi = wsi;
            p->next = s->all;
            s->all = p;
        }
        return http_request(s, p, in);
    case LWS_CALLBACK_HTTP_WRITEABLE:
        return http_writeable(s, p);
    case LWS_CALLBACK_CLOSED_HTTP:
    case LWS_CALLBACK_HTTP_DROP_PROTOCOL:
        if (p && p->wsi && !p->ws)
            unlink_pss(s, p);
        if (p)
            p->wsi = NULL;
        return 0;
    case LWS_CALLBACK_FILTER_PROTOCOL_CONNECTION:
        /* refused here, it never counts as a page (ESTABLISHED counts, CLOSED of a page
         * uncounts) */
        if (s->clients >= s->max_clients || !trusted(wsi, s->port))
            return 1;
        return 0;
    case LWS_CALLBACK_ESTABLISHED: {
        if (p->wsi) /* an HTTP connection upgraded: it was listed as one */
            unlink_pss(s, p);
        memset(p, 0, sizeof *p);
        p->wsi = wsi;
        p->ws = 1;
        p->tokens = BURST;
        p->tokens_at = tt_clock(TT_CLOCK_WALL);
        p->next = s->all;
        s->all = p;
        s->clients++;
        /* the path /N: the instrument this page had before a reload */
        char u[32];
        if (lws_hdr_copy(wsi, u, sizeof u, WSI_TOKEN_GET_URI) > 1 && u[0] == '/' && u[1] >= '1' &&
            u[1] <= '9' && strlen(u) <= 4)
            p->want = atoi(u + 1);
        attach(s, p);
        lws_callback_on_writable(wsi);
        return 0;
    }
    case LWS_CALLBACK_SERVER_WRITEABLE:
        return ws_writeable(s, p);
    case LWS_CALLBACK_RECEIVE:
        ws_receive(s, p, in, len);
        return 0;
    case LWS_CALLBACK_CLOSED:
        unlink_pss(s, p);
        if (p->ws) {
            s->clients--;
            detach(s, p);
        }
        p->ws = 0;
        return 0;
    default:
        return 0;
    }
}

static const struct lws_protocols protocols[] = {
    {"tiptap-live", callback, sizeof(pss), 4096, 0, NULL, 0},
    {NULL, NULL, 0, 0, 0, NULL, 0}};

/* libwebsockets' own words, kept for the one line that tells a failure (a port in use
 * is its "ERROR on binding fd 5 to port 8421 (-1 98)") rather than printed. */
static char lws_last[256];
static void log_line(int level, const char *line)
{
    (void)level;
    if (!lws_last[0]) {
        snprintf(lws_last, sizeof lws_last, "%s", line);
        lws_last[strcspn(lws_last, "\r\n")] = '\0';
    }
}

/* A port another program holds, told in one line before libwebsockets tries it (which
 * would log its own lines, and keeps a few bytes when its context fails). */
static int port_free(int port)
{
    if (port == 0)
        return TT_OK;
    int fd = socket(AF_INET, SOCK_STREAM, 0), one = 1, rc = TT_OK;
    struct sockaddr_in a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((unsigned short)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd >= 0)
        setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (fd >= 0 && bind(fd, (struct sockaddr *)&a, sizeof a) != 0)
        rc = tt_error(TT_EIO, "cannot listen on 127.0.0.1:%d: %s%s", port, strerror(errno),
                      errno == EADDRINUSE ? " (another program's; --port picks another)" : "");
    if (fd >= 0)
        close(fd);
    return rc;
}

int tt_live_serve(tt_live_controls *c, const tt_live_options *o)
{
    server s;
    memset(&s, 0, sizeof s);
    s.controls = c;
    s.o = o;
    s.max_clients = o->max_clients > 0 ? o->max_clients : 16;
    s.max_inst = o->max_instruments > 0 ? o->max_instruments : 4;
    s.out.pre = LWS_PRE;
    s.out.max = OUT_MAX;
    lws_set_log_level(LLL_ERR, log_line);
    struct lws_context_creation_info info;
    memset(&info, 0, sizeof info);
    info.port = o->port;
    info.iface = "127.0.0.1";
    info.protocols = protocols;
    info.user = &s;
    info.gid = -1;
    info.uid = -1;
    info.options = LWS_SERVER_OPTION_DISABLE_IPV6;
    info.timeout_secs = 30;
    info.timeout_secs_ah_idle = EXPORT_WAIT_S; /* an export's request waits for a line */
    /* the connections at once: lws accepts no more while its descriptors are taken (a
     * few are its own: the listening socket, the cancel pipe) */
    info.fd_limit_per_thread = CONN_MAX + 8;
    int rc = port_free(o->port);
    if (rc)
        return rc;
    lws_last[0] = '\0';
    s.ctx = lws_create_context(&info);
    if (!s.ctx)
        return tt_error(TT_EIO, "cannot listen on 127.0.0.1:%d (a port in use? --port picks "
                                "another): %s", o->port,
                        lws_last[0] ? lws_last : "libwebsockets failed to start");
    s.port = lws_get_vhost_listen_port(lws_get_vhost_by_name(s.ctx, "default"));
    /* the first instrument now: a scene that cannot be scanned fails before any page */
    if (!(s.inst = calloc((size_t)s.max_inst, sizeof *s.inst)))
        rc = tt_error_nomem("the console's instruments");
    for (int i = 0; !rc && i < s.max_inst; i++)
        s.inst[i].number = i + 1;
    if (!rc)
        rc = make_instrument(&s, &s.inst[0]);
    if (rc) {
        free(s.inst);
        lws_context_destroy(s.ctx);
        return rc;
    }
    s.last = &s.inst[0];
    if (o->ready)
        o->ready(o->ready_user, s.port);
    lws_sul_schedule(s.ctx, 0, &s.sul, tick, 200 * LWS_US_PER_MS);
    while (!tt_cancel_requested())
        if (lws_service(s.ctx, 0) < 0)
            break;
    /* the engines first: their lines stop at the cancellation; then the connections */
    for (int i = 0; i < s.max_inst; i++) {
        tt_live_engine_free(s.inst[i].engine);
        tt_live_controls_free(s.inst[i].controls);
    }
    s.closing = 1;
    lws_context_destroy(s.ctx);
    free(s.inst);
    tt_live_buf_free(&s.out);
    return TT_OK;
}
