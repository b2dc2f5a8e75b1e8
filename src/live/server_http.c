/* The live console's plain HTTP (src/live/server_private.h): the checks of Host and
 * Origin, the page's files from the binary, and the exports streamed from their file. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "server_private.h"
#include "tiptap/util/error.h"

/* The Host, and the Origin where a browser sends one, must be this server's: another web
 * page open in the same browser may not drive the instrument nor read it, and a name that
 * resolves to 127.0.0.1 (DNS rebinding) is not this server's. Every request passes here,
 * a page's as a WebSocket's. */
int tt_live_trusted(struct lws *wsi, int port)
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

int tt_live_http_request(server *s, pss *p, const char *uri)
{
    static const char forbidden[] = "not this server's Host or Origin\n",
                      not_allowed[] = "only GET and HEAD\n";
    char *u;
    int ul, method = lws_http_get_uri_and_method(p->wsi, &u, &ul);
    p->head = method == LWSHUMETH_HEAD;
    if (!tt_live_trusted(p->wsi, s->port))
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

int tt_live_http_writeable(server *s, pss *p)
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
