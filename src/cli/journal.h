/* tiptap sweep: the text of a sweep's journal, OUT.partial (docs/sweeps.md), written
 * and read here; opening, appending and resuming it are sweep_journal.c's.
 *
 * A header line names the format, the program version and the sweep:
 *     tiptap-sweep-journal 2 VERSION HASH N
 * (HASH: the sweep's fingerprint, 16 hex digits; N: its combinations), then one record
 * per finished combination, its rows after a line with its index from 0, their length
 * in bytes and a CRC-32 of that line's first two fields and the rows:
 *     @INDEX BYTES CRC
 *     ROWS
 * A record cut short at the end (a sweep killed while writing it) is dropped; any
 * other damage, a journal of another version or sweep, and an empty file are refused.
 *
 * Internal to the tiptap program (and its fuzz target fuzz/fuzz_journal.c). */
#ifndef TIPTAP_CLI_JOURNAL_H
#define TIPTAP_CLI_JOURNAL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* What a journal must be to be resumed. */
typedef struct {
    const char *version;     /* of this program, one word */
    unsigned long long hash; /* the sweep's fingerprint */
    size_t n;                /* its combinations */
} journal_sweep;

/* CRC-32 (IEEE 802.3, as zlib's crc32) of len bytes, continuing crc (0 to start). */
uint32_t journal_crc32(uint32_t crc, const void *data, size_t len);

/* Write the header, or a record of combination i's rows; 0, or -1 with errno set. */
int journal_write_header(FILE *f, const journal_sweep *sw);
int journal_write_record(FILE *f, size_t i, const char *rows);

/* Read the journal bytes buf[0, len) of the file path (named in messages) into
 * text[0, sw->n) (malloc'd rows; a combination recorded twice keeps its last record),
 * counting the combinations found in *done and the bytes up to the end of the last
 * whole record in *good (what is kept when the journal goes on). TT_EINVAL with one
 * line naming path (and the line, for a damaged record) when the journal cannot be
 * resumed; TT_ENOMEM. Texts read before a refusal stay in text for the caller to free. */
int journal_read(const char *path, const char *buf, size_t len, const journal_sweep *sw, char **text,
                 size_t *done, size_t *good);

#endif
