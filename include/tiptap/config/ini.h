/* tiptap: a small strict INI reader.
 *
 * Scene files are INI text: "[section]" or "[section name]" headers, "key = value" (or
 * "key: value") lines, blank lines, and comments: a line whose first non-blank character
 * is ';' or '#', and the rest of a value after " ;" (a semicolon after a blank).
 * Lines end in LF, CRLF or a lone CR and may be of any length; a leading UTF-8 byte order
 * mark is skipped. Unlike the INI libraries it replaces, the reader never cuts a line or
 * a name, never reads an indented line as the continuation of the previous value, reports
 * every header (so that a section without keys exists), and refuses what it cannot read
 * with the line number: a header without its ']', a line that is neither header nor key,
 * a control character (shown escaped, never echoed to the terminal).
 *
 * Ownership: the reader borrows the text; the strings it hands to the callback live only
 * during the call.
 */
#ifndef TIPTAP_INI_H
#define TIPTAP_INI_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* One header or key line, as handed to the callback. */
typedef struct {
    long line;           /* 1-based line number */
    const char *section; /* header text between the brackets, trimmed ("material glass");
                            "" before the first header */
    const char *key;     /* NULL for a header line */
    const char *value;   /* NULL for a header line; trimmed, comment removed */
} tt_ini_item;

/* Called for each header and key line in order; a non-zero return stops the reader,
 * which then returns that value. */
typedef int (*tt_ini_handler)(void *user, const tt_ini_item *item);

/* Read len bytes of INI text. Returns 0, the callback's non-zero return, or TT_EINVAL /
 * TT_ENOMEM with the message "origin: line N: what is wrong" (tt_error). */
int tt_ini_parse(const char *text, size_t len, const char *origin, tt_ini_handler cb,
                 void *user);

/* Write s into buf (len bytes, always terminated) with control characters shown as
 * escapes ("\n", "\x1b"), cut with "..." when long:
 * for quoting user text in a one-line message. Returns buf. */
const char *tt_ini_escape(const char *s, char *buf, size_t len);

TT_END_DECLS
#endif
