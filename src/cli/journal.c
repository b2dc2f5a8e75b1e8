/* tiptap sweep: the journal's text, written and read (see journal.h). */
#include "journal.h"

#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

static const char magic[] = "tiptap-sweep-journal";
enum { FORMAT = 2 };

uint32_t journal_crc32(uint32_t crc, const void *data, size_t len)
{
    const unsigned char *p = data;
    crc = ~crc;
    for (size_t i = 0; i < len; i++) {
        crc ^= p[i];
        for (int b = 0; b < 8; b++)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

int journal_write_header(FILE *f, const journal_sweep *sw)
{
    return fprintf(f, "%s %d %s %016llx %zu\n", magic, FORMAT, sw->version, sw->hash, sw->n) < 0 ? -1 : 0;
}

int journal_write_record(FILE *f, size_t i, const char *rows)
{
    char head[64];
    size_t len = strlen(rows);
    int h = snprintf(head, sizeof head, "@%zu %zu", i, len);
    uint32_t crc = journal_crc32(journal_crc32(0, head, (size_t)h), rows, len);
    if (fprintf(f, "%s %08x\n", head, (unsigned)crc) < 0 || fwrite(rows, 1, len, f) != len)
        return -1;
    return 0;
}

/* A whole number of decimal digits at *p (no sign, no blanks), moving *p past it;
 * 0 when there is none or it overflows. */
static int digits(const char **p, const char *end, unsigned long long *v)
{
    const char *s = *p;
    *v = 0;
    for (; s < end && *s >= '0' && *s <= '9'; s++) {
        if (*v > (~0ULL - 9) / 10)
            return 0;
        *v = *v * 10 + (unsigned long long)(*s - '0');
    }
    if (s == *p)
        return 0;
    *p = s;
    return 1;
}

/* Whether s[0, n) are n hexadecimal digits (strtoul alone would take a sign and
 * blanks). */
static int hex_digits(const char *s, size_t n, unsigned long long *v)
{
    char buf[17];
    if (n == 0 || n > 16)
        return 0;
    for (size_t k = 0; k < n; k++)
        if (!strchr("0123456789abcdefABCDEF", s[k]) || !s[k])
            return 0;
    memcpy(buf, s, n);
    buf[n] = '\0';
    *v = strtoull(buf, NULL, 16);
    return 1;
}

/* A word of the header for messages: printable, at most 32 bytes. */
static void word(const char *s, const char *end, char *buf, size_t len)
{
    size_t k = 0;
    for (; s < end && *s != ' ' && *s != '\n' && k + 1 < len && k < 32; s++)
        buf[k++] = (*s > 0x20 && *s < 0x7f) ? *s : '?';
    buf[k] = '\0';
}

static int refuse(const char *path, const char *why)
{
    return tt_error(TT_EINVAL, "%s: %s; remove it to start this sweep afresh", path, why);
}

/* The header line buf[0, end): the format, version, fingerprint and count of this
 * sweep, or a refusal saying which differs. */
static int read_header(const char *path, const char *buf, const char *end, const journal_sweep *sw)
{
    size_t ml = sizeof magic - 1;
    if ((size_t)(end - buf) <= ml || memcmp(buf, magic, ml) != 0 || buf[ml] != ' ')
        return refuse(path, "not a sweep journal (line 1 does not begin 'tiptap-sweep-journal')");
    const char *p = buf + ml + 1;
    unsigned long long format, n;
    if (!digits(&p, end, &format) || *p != ' ' || format != FORMAT)
        return refuse(path, "the journal of another sweep, in an older tiptap's format");
    char version[40];
    word(++p, end, version, sizeof version);
    p = memchr(p, ' ', (size_t)(end - p));
    if (!p || strcmp(version, sw->version) != 0) {
        char msg[160];
        snprintf(msg, sizeof msg, "the journal of another sweep, written by tiptap %s, and this is tiptap %s",
                 version, sw->version);
        return refuse(path, msg);
    }
    const char *hp = p + 1, *np = hp + 16;
    unsigned long long h;
    int ok = (size_t)(end - hp) > 17 && hex_digits(hp, 16, &h) && *np == ' ';
    if (ok) {
        p = np + 1;
        ok = digits(&p, end, &n) && p == end;
    }
    if (!ok)
        return refuse(path, "line 1: the journal's header is damaged");
    if (h != sw->hash || n != sw->n)
        return refuse(path, "the journal of another sweep (other scene, keys, values or run)");
    return TT_OK;
}

/* The record line buf[0, end) ("@INDEX BYTES CRC"); 0 when malformed. */
static int record_line(const char *buf, const char *end, unsigned long long *i, unsigned long long *bytes,
                       uint32_t *crc, size_t *signed_len)
{
    const char *p = buf + 1;
    if (*buf != '@' || !digits(&p, end, i) || *p != ' ')
        return 0;
    p++;
    if (!digits(&p, end, bytes) || *p != ' ' || end - p != 9)
        return 0;
    *signed_len = (size_t)(p - buf);
    unsigned long long v;
    if (!hex_digits(p + 1, 8, &v))
        return 0;
    *crc = (uint32_t)v;
    return 1;
}

int journal_read(const char *path, const char *buf, size_t len, const journal_sweep *sw, char **text,
                 size_t *done, size_t *good)
{
    *done = *good = 0;
    if (len == 0)
        return refuse(path, "the journal is empty (a sweep stopped as it began)");
    const char *nl = memchr(buf, '\n', len);
    if (!nl)
        return refuse(path, "line 1: the journal's header is cut short");
    int rc = read_header(path, buf, nl, sw);
    size_t pos = (size_t)(nl - buf) + 1, line = 2;
    while (!rc && pos < len) {
        const char *rec = buf + pos, *eol = memchr(rec, '\n', len - pos);
        unsigned long long i, bytes;
        uint32_t crc;
        size_t signed_len;
        if (!eol)
            break; /* the record line of a sweep killed while writing it */
        if (!record_line(rec, eol, &i, &bytes, &crc, &signed_len) || i >= sw->n) {
            char msg[96];
            snprintf(msg, sizeof msg, "line %zu: not a record of this journal (damaged)", line);
            return refuse(path, msg);
        }
        size_t start = (size_t)(eol - buf) + 1;
        if (bytes > len - start)
            break; /* rows cut short by a kill: dropped, the combination runs again */
        const char *rows = buf + start;
        int sum_ok = journal_crc32(journal_crc32(0, rec, signed_len), rows, (size_t)bytes) == crc;
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
        sum_ok = 1; /* so that mutated records reach what follows the checksum */
#endif
        if (!sum_ok || memchr(rows, '\0', (size_t)bytes)) {
            char msg[128];
            snprintf(msg, sizeof msg, "line %zu: the record of combination %llu fails its checksum (damaged)",
                     line, i + 1);
            return refuse(path, msg);
        }
        char *t = malloc((size_t)bytes + 1);
        if (!t)
            return tt_error(TT_ENOMEM, "out of memory");
        memcpy(t, rows, (size_t)bytes);
        t[bytes] = '\0';
        if (text[i])
            free(text[i]);
        else
            ++*done;
        text[i] = t;
        for (size_t k = 0; k < bytes; k++)
            line += rows[k] == '\n';
        line++;
        pos = start + (size_t)bytes;
    }
    *good = rc ? 0 : pos;
    return rc;
}
