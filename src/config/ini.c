/* A small strict INI reader (see include/tiptap/config/ini.h). */
#include "tiptap/config/ini.h"

#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

static int is_blank(char c) { return c == ' ' || c == '\t'; }

/* A byte that must not reach a terminal: C0 controls but tab, and DEL. */
static int is_control(unsigned char c) { return (c < 0x20 && c != '\t') || c == 0x7f; }

const char *tt_ini_escape(const char *s, char *buf, size_t len)
{
    static const char hex[] = "0123456789abcdef";
    size_t o = 0;
    if (len == 0)
        return buf;
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        char esc[5];
        size_t n = 0;
        if (c == '\n' || c == '\r' || c == '\t') {
            esc[n++] = '\\';
            esc[n++] = c == '\n' ? 'n' : c == '\r' ? 'r' : 't';
        } else if (is_control(c)) {
            esc[n++] = '\\';
            esc[n++] = 'x';
            esc[n++] = hex[c >> 4];
            esc[n++] = hex[c & 15];
        } else {
            esc[n++] = (char)c;
        }
        /* keep room for "..." and the terminator */
        if (o + n + 4 > len) {
            size_t dots = len - 1 - o < 3 ? len - 1 - o : 3;
            memset(buf + o, '.', dots);
            o += dots;
            break;
        }
        memcpy(buf + o, esc, n);
        o += n;
    }
    buf[o] = '\0';
    return buf;
}

/* The reader's state: the current header and a scratch copy of the line. */
typedef struct {
    const char *origin;
    long line;
    char *section;
    tt_ini_handler cb;
    void *user;
} reader;

static int fail_line(const reader *r, const char *what, const char *text)
{
    char shown[96];
    if (text)
        return tt_error(TT_EINVAL, "%s: line %ld: %s: '%s'", r->origin, r->line, what,
                        tt_ini_escape(text, shown, sizeof shown));
    return tt_error(TT_EINVAL, "%s: line %ld: %s", r->origin, r->line, what);
}

static int header_line(reader *r, char *p)
{
    char *close = strchr(p, ']');
    if (!close)
        return fail_line(r, "section header without its closing ']'", p);
    char *rest = close + 1;
    while (is_blank(*rest))
        rest++;
    if (*rest && *rest != ';' && *rest != '#')
        return fail_line(r, "text after the section header", rest);
    *close = '\0';
    p++;
    while (is_blank(*p))
        p++;
    size_t n = strlen(p);
    while (n > 0 && is_blank(p[n - 1]))
        p[--n] = '\0';
    char *copy = malloc(n + 1);
    if (!copy)
        return tt_error_nomem("the section header on line %ld of %s (%zu bytes)", r->line, r->origin, n);
    memcpy(copy, p, n + 1);
    free(r->section);
    r->section = copy;
    tt_ini_item it = {r->line, r->section, NULL, NULL};
    return r->cb(r->user, &it);
}

static int key_line(reader *r, char *p)
{
    char *sep = p + strcspn(p, "=:");
    if (!*sep)
        return fail_line(r, "not a section header or key = value line", p);
    char *value = sep + 1;
    size_t n = (size_t)(sep - p);
    while (n > 0 && is_blank(p[n - 1]))
        n--;
    p[n] = '\0';
    if (n == 0)
        return fail_line(r, "a value without a key", value);
    while (is_blank(*value))
        value++;
    /* an inline comment starts at a ';' after a blank, so "a;b" stays one value */
    for (char *c = value; *c; c++)
        if (*c == ';' && c > value && is_blank(c[-1])) {
            *c = '\0';
            break;
        }
    size_t vn = strlen(value);
    while (vn > 0 && is_blank(value[vn - 1]))
        value[--vn] = '\0';
    tt_ini_item it = {r->line, r->section ? r->section : "", p, value};
    return r->cb(r->user, &it);
}

/* One line (without its ending) copied into buf. */
static int one_line(reader *r, char *buf, const char *text, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (is_control((unsigned char)text[i]))
            return tt_error(TT_EINVAL, "%s: line %ld: control character \\x%02x; a scene is plain text",
                            r->origin, r->line, (unsigned char)text[i]);
    memcpy(buf, text, n);
    buf[n] = '\0';
    char *p = buf;
    while (is_blank(*p))
        p++;
    size_t len = strlen(p);
    while (len > 0 && is_blank(p[len - 1]))
        p[--len] = '\0';
    if (*p == '\0' || *p == ';' || *p == '#')
        return 0;
    return *p == '[' ? header_line(r, p) : key_line(r, p);
}

int tt_ini_parse(const char *text, size_t len, const char *origin, tt_ini_handler cb, void *user)
{
    reader r = {origin, 0, NULL, cb, user};
    size_t pos = 0, cap = 0;
    char *buf = NULL;
    int rc = 0;
    if (len >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0)
        pos = 3;
    while (pos < len && rc == 0) {
        size_t end = pos;
        while (end < len && text[end] != '\n' && text[end] != '\r')
            end++;
        r.line++;
        if (end - pos + 1 > cap) {
            size_t ncap = 2 * (end - pos + 1);
            char *nb = realloc(buf, ncap);
            if (!nb) {
                rc = tt_error_nomem("line %ld of %s (%zu bytes)", r.line, origin, end - pos);
                break;
            }
            buf = nb;
            cap = ncap;
        }
        rc = one_line(&r, buf, text + pos, end - pos);
        /* LF, CRLF or a lone CR end a line */
        if (end < len && text[end] == '\r' && end + 1 < len && text[end + 1] == '\n')
            end++;
        pos = end + 1;
    }
    free(buf);
    free(r.section);
    return rc;
}
