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
#include <time.h>

#include "live_private.h"
#include "tiptap/live/engine.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/util/clock.h"

#include "server_private.h"

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
    } else if (!in || !in->engine) {
        return 0; /* no instrument yet (or the server is closing): nothing more to send */
    } else if (p->seen_controls != in->controls_version) {
        tt_live_msg_controls(&s->out, in->controls, in->number, s->max_inst);
        p->seen_controls = in->controls_version;
    } else if (tt_live_bench_message(in->bench, TT_BENCH_FORCE, &p->seen_bench[TT_BENCH_FORCE], &s->out) ||
               tt_live_bench_message(in->bench, TT_BENCH_TUNE, &p->seen_bench[TT_BENCH_TUNE], &s->out)) {
        /* a bench's run began or ended */
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
    tt_live_bench_free(in->bench);
    tt_live_engine_free(in->engine);
    tt_live_controls_free(in->controls);
    in->bench = NULL;
    in->engine = NULL;
    in->controls = NULL;
    in->used = 0;
    tt_scene *scene = NULL;
    tt_scan_params prm;
    int rc = tt_live_controls_copy(&in->controls, s->controls);
    if (!rc && !(rc = tt_live_controls_scene(in->controls, &scene, &prm)))
        rc = tt_live_engine_alloc(&in->engine, scene, &prm, wake, s);
    if (!rc && (rc = tt_live_bench_alloc(&in->bench, wake, s))) {
        tt_live_engine_free(in->engine);
        in->engine = NULL;
    }
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
    /* a reload sees the benches' last results again */
    for (int k = 0; k < TT_BENCH_KINDS; k++)
        p->seen_bench[k] = 0;
    s->last = in;
    /* a page looks (unless its tab is hidden): the engine runs (it waits, no CPU, while
     * none does) */
    tt_live_engine_watched(in->engine, !p->hidden);
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

/* A bench's run on the instrument's accepted scene (its sample's materials, its noise,
 * the ramp and record in force), on the bench's thread: refused while the lesson hides
 * the bench, while a run is under way, or when its section fails the checks. */
static void bench(server *s, pss *p, int kind)
{
    instrument *in = p->inst;
    const char *what = kind == TT_BENCH_FORCE ? "force" : "tune";
    tt_scene *scene = NULL;
    if (tt_live_controls_panel_hidden(in->controls, what)) {
        char why[600];
        snprintf(why, sizeof why, "console: the lesson %s hides the %s", tt_live_controls_lesson(in->controls)->path,
                 kind == TT_BENCH_FORCE ? "force curve" : "thermal tune");
        reply(p, 0, why);
        return;
    }
    if (tt_live_controls_scene(in->controls, &scene, NULL) || tt_live_bench_run(in->bench, kind, scene)) {
        reply(p, 0, tt_error_message());
        return;
    }
    reply(p, 1, "");
    wake_all(s);
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
    /* the tab hidden or shown again: a hidden page idles its instrument as a closed one
     * does (not answered: nothing to refuse, and no field waits on it) */
    int hide = n == 6 && memcmp(p->rx, "hidden", 6) == 0, show = n == 7 && memcmp(p->rx, "visible", 7) == 0;
    if (hide || show) {
        p->hidden = hide;
        if (p->inst)
            tt_live_engine_watched(p->inst->engine, show);
        wake_all(s);
        return;
    }
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
    int force = n == 5 && memcmp(p->rx, "force", 5) == 0, tune = n == 4 && memcmp(p->rx, "tune", 4) == 0;
    if (force || tune) {
        bench(s, p, force ? TT_BENCH_FORCE : TT_BENCH_TUNE);
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
        return tt_live_http_request(s, p, in);
    case LWS_CALLBACK_HTTP_WRITEABLE:
        return tt_live_http_writeable(s, p);
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
        if (s->clients >= s->max_clients || !tt_live_trusted(wsi, s->port))
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
        tt_live_bench_free(s.inst[i].bench);
        s.inst[i].bench = NULL;
        tt_live_engine_free(s.inst[i].engine);
        tt_live_controls_free(s.inst[i].controls);
        s.inst[i].engine = NULL;
        s.inst[i].controls = NULL;
    }
    s.closing = 1;
    lws_context_destroy(s.ctx);
    free(s.inst);
    tt_live_buf_free(&s.out);
    return TT_OK;
}
