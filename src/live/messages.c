/* The live console's messages to the page, as JSON (docs/live.md, "Protocol"); numbers
 * in the C locale, SI units, NaN as null. */
#include "live_private.h"
#include "bench_private.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "tiptap/solver/integrator.h"

void tt_live_buf_reset(tt_live_buf *b)
{
    b->len = 0;
    b->failed = 0;
}

void tt_live_buf_printf(tt_live_buf *b, const char *fmt, ...)
{
    for (int tries = 0; tries < 2 && !b->failed; tries++) {
        size_t room = b->cap > b->pre + b->len ? b->cap - b->pre - b->len : 0;
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(room ? (char *)b->mem + b->pre + b->len : NULL, room, fmt, ap);
        va_end(ap);
        if (n < 0) {
            b->failed = 1;
            return;
        }
        if ((size_t)n < room) {
            b->len += (size_t)n;
            return;
        }
        size_t want = b->pre + b->len + (size_t)n + 1, cap = b->cap ? b->cap : 4096;
        while (cap < want)
            cap *= 2;
        if (cap > b->max + b->pre + 1) {
            b->failed = 1;
            return;
        }
        unsigned char *m = realloc(b->mem, cap);
        if (!m) {
            b->failed = 1;
            return;
        }
        b->mem = m;
        b->cap = cap;
    }
}

void tt_live_buf_free(tt_live_buf *b)
{
    free(b->mem);
    b->mem = NULL;
    b->cap = b->len = 0;
}

char *tt_live_buf_text(tt_live_buf *b) { return b->mem ? (char *)b->mem + b->pre : NULL; }

size_t tt_live_utf8_char(const char *s, size_t n)
{
    const unsigned char *u = (const unsigned char *)s;
    if (n == 0)
        return 0;
    if (u[0] < 0x80)
        return 1;
    /* RFC 3629: the lead byte gives the length and the second byte's range (no
     * overlong forms, no surrogates, nothing past U+10FFFF) */
    size_t len;
    unsigned char lo = 0x80, hi = 0xBF;
    if (u[0] >= 0xC2 && u[0] <= 0xDF)
        len = 2;
    else if (u[0] >= 0xE0 && u[0] <= 0xEF) {
        len = 3;
        lo = u[0] == 0xE0 ? 0xA0 : 0x80;
        hi = u[0] == 0xED ? 0x9F : 0xBF;
    } else if (u[0] >= 0xF0 && u[0] <= 0xF4) {
        len = 4;
        lo = u[0] == 0xF0 ? 0x90 : 0x80;
        hi = u[0] == 0xF4 ? 0x8F : 0xBF;
    } else
        return 0;
    if (n < len || u[1] < lo || u[1] > hi)
        return 0;
    for (size_t i = 2; i < len; i++)
        if (u[i] < 0x80 || u[i] > 0xBF)
            return 0;
    return len;
}

int tt_live_utf8_valid(const char *s, size_t n)
{
    for (size_t i = 0, k; i < n; i += k)
        if (!(k = tt_live_utf8_char(s + i, n - i)))
            return 0;
    return 1;
}

size_t tt_live_utf8_fit(const char *s, size_t n)
{
    const unsigned char *u = (const unsigned char *)s;
    size_t j = n;
    while (j > 0 && n - j < 3 && (u[j - 1] & 0xC0) == 0x80)
        j--;
    if (j == 0 || u[j - 1] < 0xC0)
        return n;
    size_t want = u[j - 1] >= 0xF0 ? 4 : u[j - 1] >= 0xE0 ? 3 : 2;
    return n - (j - 1) < want ? j - 1 : n;
}

void tt_live_text(char *dst, size_t cap, const char *src)
{
    size_t used = 0, n = src ? tt_live_utf8_fit(src, strlen(src)) : 0;
    for (size_t i = 0; i < n && cap > 0;) {
        size_t k = tt_live_utf8_char(src + i, n - i);
        if (used + (k ? k : 1) >= cap)
            break;
        if (k)
            memcpy(dst + used, src + i, k);
        else
            dst[used] = '?';
        used += k ? k : 1;
        i += k ? k : 1;
    }
    if (cap > 0)
        dst[used] = '\0';
}

int tt_live_authority_ok(const char *t, int is_origin, int port)
{
    static const char *const hosts[] = {"127.0.0.1", "localhost", "[::1]"};
    if (is_origin) {
        if (strncmp(t, "http://", 7) != 0)
            return 0;
        t += 7;
    }
    for (size_t i = 0; i < sizeof hosts / sizeof hosts[0]; i++) {
        size_t n = strlen(hosts[i]);
        if (strncasecmp(t, hosts[i], n) != 0)
            continue;
        const char *r = t + n;
        if (*r == '\0')
            return port == 80; /* no port: the scheme's own */
        if (*r++ != ':')
            continue;
        long v = 0;
        size_t d = 0;
        for (; r[d] >= '0' && r[d] <= '9' && d < 6; d++)
            v = 10 * v + (r[d] - '0');
        return d > 0 && d < 6 && r[d] == '\0' && v == port;
    }
    return 0;
}

/* A JSON string: quotes, backslashes and control characters escaped, and any byte that is
 * not part of a UTF-8 character sent as U+FFFD (the one gate every text sent passes). */
static void str(tt_live_buf *b, const char *s)
{
    size_t n = s ? strlen(s) : 0;
    tt_live_buf_printf(b, "\"");
    for (size_t i = 0, k; i < n; i += k ? k : 1) {
        unsigned char c = (unsigned char)s[i];
        k = tt_live_utf8_char(s + i, n - i);
        if (!k)
            tt_live_buf_printf(b, "\\ufffd");
        else if (c == '"' || c == '\\')
            tt_live_buf_printf(b, "\\%c", c);
        else if (c < 0x20)
            tt_live_buf_printf(b, "\\u%04x", c);
        else
            tt_live_buf_printf(b, "%.*s", (int)k, s + i);
    }
    tt_live_buf_printf(b, "\"");
}

static void num(tt_live_buf *b, double x)
{
    if (isfinite(x))
        tt_live_buf_printf(b, "%.7g", x);
    else
        tt_live_buf_printf(b, "null");
}

static void array(tt_live_buf *b, const double *x, size_t n)
{
    tt_live_buf_printf(b, "[");
    for (size_t i = 0; i < n; i++) {
        if (i)
            tt_live_buf_printf(b, ",");
        num(b, x ? x[i] : NAN);
    }
    tt_live_buf_printf(b, "]");
}

void tt_live_json_str(tt_live_buf *b, const char *s) { str(b, s); }
void tt_live_json_num(tt_live_buf *b, double x) { num(b, x); }
void tt_live_json_array(tt_live_buf *b, const double *x, size_t n) { array(b, x, n); }

/* What each tier means on the console, for its menu (the names are the solver's table,
 * tt_tier_name). */
static const char *tier_hint(tt_tier t)
{
    switch (t) {
    case TT_TIER_EVERY: return "integrates every cycle: the reference, far slower than real time";
    case TT_TIER_ENVELOPE: return "integrates cycles only where the loop moves";
    /* noise too since docs/dynamics.md's "Noise on the averaged tier" (the teaching
     * scene's tier: examples/feedback-tuning/common.ini) */
    case TT_TIER_AVERAGED: return "the slow flow of amplitude and phase, noise included, cycles "
                                  "integrated only where it fails: fastest";
    default: return "";
    }
}

static void tiers(tt_live_buf *b)
{
    tt_live_buf_printf(b, ",\"tiers\":[");
    for (int i = 0; i < tt_tier_count(); i++) {
        tt_live_buf_printf(b, "%s{\"name\":", i ? "," : "");
        str(b, tt_tier_name((tt_tier)i));
        tt_live_buf_printf(b, ",\"hint\":");
        str(b, tier_hint((tt_tier)i));
        tt_live_buf_printf(b, "}");
    }
    tt_live_buf_printf(b, "]");
}

void tt_live_msg_controls(tt_live_buf *b, const tt_live_controls *c, int number, int count)
{
    size_t n;
    const tt_live_control *t = tt_live_control_table(&n);
    char v[256];
    tt_live_buf_printf(b, "{\"type\":\"controls\",\"instrument\":%d,\"instruments\":%d,\"controls\":[",
                       number, count);
    for (size_t i = 0; i < n; i++) {
        tt_live_buf_printf(b, "%s{\"name\":", i ? "," : "");
        str(b, t[i].name);
        tt_live_buf_printf(b, ",\"label\":");
        str(b, t[i].label);
        tt_live_buf_printf(b, ",\"unit\":");
        str(b, t[i].unit);
        const tt_live_lesson *l = tt_live_controls_lesson(c);
        tt_live_buf_printf(b, ",\"restarts\":%s,\"hidden\":%s,\"locked\":%s,\"value\":",
                           t[i].restarts ? "true" : "false", l && l->hide >> i & 1 ? "true" : "false",
                           l && l->lock >> i & 1 ? "true" : "false");
        str(b, tt_live_controls_value(c, i, v, sizeof v));
        tt_live_buf_printf(b, ",\"panel\":");
        if (t[i].panel)
            str(b, t[i].panel);
        else
            tt_live_buf_printf(b, "null");
        tt_live_buf_printf(b, "}");
    }
    tt_live_buf_printf(b, "],\"samples\":[");
    for (size_t i = 0; i < tt_live_controls_samples(c); i++) {
        tt_live_buf_printf(b, "%s", i ? "," : "");
        str(b, tt_live_controls_sample(c, i));
    }
    int si = tt_live_controls_sample_index(c);
    tt_live_buf_printf(b, "],\"sample\":");
    str(b, si >= 0 ? tt_live_controls_sample(c, (size_t)si) : "");
    tiers(b);
    tt_live_buf_printf(b, ",\"benches\":{\"force\":%s,\"tune\":%s}",
                       tt_live_controls_panel_hidden(c, "force") ? "false" : "true",
                       tt_live_controls_panel_hidden(c, "tune") ? "false" : "true");
    const tt_live_lesson *l = tt_live_controls_lesson(c);
    tt_live_buf_printf(b, ",\"lesson\":");
    if (l) {
        tt_live_buf_printf(b, "{\"title\":");
        str(b, l->title);
        tt_live_buf_printf(b, ",\"instructions\":");
        str(b, l->instructions);
        tt_live_buf_printf(b, ",\"file\":");
        str(b, l->path);
        tt_live_buf_printf(b, "}");
    } else {
        tt_live_buf_printf(b, "null");
    }
    tt_live_buf_printf(b, "}");
}

void tt_live_msg_frame(tt_live_buf *b, const tt_live_view *v)
{
    tt_live_buf_printf(b, "{\"type\":\"frame\",\"frame\":%ld,\"pixels\":%ld,\"lines\":%ld,"
                          "\"size_fast\":",
                       v->frame, v->pixels, v->lines);
    num(b, v->size_fast);
    tt_live_buf_printf(b, ",\"size_slow\":");
    num(b, v->size_slow);
    tt_live_buf_printf(b, ",\"fast_y\":%s,\"retrace\":%s,\"channels\":[", v->fast_y ? "true" : "false",
                       v->retrace ? "true" : "false");
    for (int c = 0, k = 0; c < TT_LIVE_NCH; c++) {
        if (!v->channel_name[c])
            continue;
        tt_live_buf_printf(b, "%s{\"name\":", k++ ? "," : "");
        str(b, v->channel_name[c]);
        tt_live_buf_printf(b, ",\"unit\":");
        str(b, v->channel_unit[c]);
        tt_live_buf_printf(b, ",\"file\":");
        str(b, v->channel_file[c]);
        tt_live_buf_printf(b, "}");
    }
    tt_live_buf_printf(b, "]}");
}

void tt_live_msg_status(tt_live_buf *b, const tt_live_view *v, int clients)
{
    tt_live_buf_printf(b, "{\"type\":\"status\",\"frame\":%ld,\"line\":%ld,\"lines_done\":%ld,"
                          "\"passes\":%ld,\"first_line_as_set\":%ld,\"tier\":\"%s\",\"clients\":%d,"
                          "\"oscillating\":%s,\"reproducible\":%s,\"realtime\":",
                       v->frame, v->line, v->lines_done, v->passes, v->first_line_as_set,
                       tt_tier_name((tt_tier)v->tier), clients, v->oscillating ? "true" : "false",
                       v->reproducible ? "true" : "false");
    num(b, v->realtime);
    tt_live_buf_printf(b, ",\"realtime_cpu\":");
    num(b, v->realtime_cpu);
    tt_live_buf_printf(b, ",\"line_s\":");
    num(b, v->line_seconds);
    tt_live_buf_printf(b, ",\"preview_ms\":");
    num(b, v->preview_ms);
    tt_live_buf_printf(b, ",\"accurate_ms\":");
    num(b, v->accurate_ms);
    tt_live_buf_printf(b, ",\"ring_hz\":");
    num(b, v->ring_hz);
    tt_live_buf_printf(b, ",\"ring_m\":");
    num(b, v->ring_nm);
    tt_live_buf_printf(b, ",\"ring_damping\":");
    num(b, v->ring_damping);
    tt_live_buf_printf(b, ",\"suggest_ki\":");
    num(b, v->suggest_ki);
    tt_live_buf_printf(b, ",\"lagging\":%s,\"running\":%s,\"paused\":%s,\"idle\":%s,\"judged\":%ld,"
                          "\"judged_line\":",
                       v->lagging ? "true" : "false", v->running ? "true" : "false", v->paused ? "true" : "false",
                       v->idle ? "true" : "false", v->judged);
    if (v->judged_line >= 0)
        tt_live_buf_printf(b, "%ld", v->judged_line);
    else
        tt_live_buf_printf(b, "null");
    tt_live_buf_printf(b, ",\"warnings\":[");
    for (int i = 0; i < v->nwarnings; i++) {
        tt_live_buf_printf(b, "%s{\"category\":", i ? "," : "");
        str(b, v->warning_category[i]);
        tt_live_buf_printf(b, ",\"frame\":%ld,\"text\":", v->warning_frame[i]);
        str(b, v->warning[i]);
        tt_live_buf_printf(b, "}");
    }
    tt_live_buf_printf(b, "]");
    tt_live_buf_printf(b, ",\"error_rms\":");
    num(b, v->error_rms);
    tt_live_buf_printf(b, ",\"setpoint\":");
    num(b, v->setpoint);
    tt_live_buf_printf(b, ",\"height_range\":");
    num(b, v->height_range);
    tt_live_buf_printf(b, ",\"track_rms\":");
    num(b, v->track_rms);
    tt_live_buf_printf(b, ",\"surface_range\":");
    num(b, v->surface_range);
    tt_live_buf_printf(b, ",\"note\":");
    str(b, v->note);
    tt_live_buf_printf(b, "}");
}

void tt_live_msg_row(tt_live_buf *b, const tt_live_view *v, long line)
{
    tt_live_buf_printf(b, "{\"type\":\"row\",\"frame\":%ld,\"line\":%ld,\"tier\":\"%s\",\"preview\":%s,"
                          "\"data\":[",
                       v->frame, line, tt_tier_name((tt_tier)(v->row_tier[line] & ~TT_LIVE_PREVIEW)),
                       v->row_tier[line] & TT_LIVE_PREVIEW ? "true" : "false");
    for (int c = 0, k = 0; c < TT_LIVE_NCH; c++)
        for (int r = 0; r < 2; r++) {
            if (!v->rows[c][r])
                continue;
            tt_live_buf_printf(b, "%s", k++ ? "," : "");
            array(b, v->rows[c][r] + line * v->pixels, (size_t)v->pixels);
        }
    tt_live_buf_printf(b, "]}");
}

void tt_live_msg_scope(tt_live_buf *b, const tt_live_view *v)
{
    static const char *const names[TT_LIVE_NS] = {"position", "z", "error", "amplitude", "phase",
                                                  "surface"};
    tt_live_buf_printf(b, "{\"type\":\"scope\",\"frame\":%ld,\"line\":%ld,\"tier\":\"%s\",\"rate\":",
                       v->frame, v->scope_line, tt_tier_name((tt_tier)v->scope_tier));
    num(b, v->scope_rate);
    tt_live_buf_printf(b, ",\"kp\":");
    num(b, v->scope_kp);
    tt_live_buf_printf(b, ",\"ki\":");
    num(b, v->scope_ki);
    for (int r = 0; r < 2; r++) {
        tt_live_buf_printf(b, ",\"%s\":{\"t0\":", r ? "retrace" : "trace");
        num(b, v->scope_t0[r]);
        tt_live_buf_printf(b, ",\"t1\":");
        num(b, v->scope_t1[r]);
        for (int k = 0; k < TT_LIVE_NS; k++) {
            tt_live_buf_printf(b, ",\"%s\":", names[k]);
            array(b, v->scope_n[r] ? v->scope[r][k] : NULL, v->scope_n[r]);
        }
        tt_live_buf_printf(b, "}");
    }
    tt_live_buf_printf(b, "}");
}

void tt_live_msg_reply(tt_live_buf *b, int ok, const char *why, unsigned dropped)
{
    tt_live_buf_printf(b, "{\"type\":\"reply\",\"ok\":%s,\"dropped\":%u,\"error\":", ok ? "true" : "false",
                       dropped);
    str(b, why ? why : "");
    tt_live_buf_printf(b, "}");
}
