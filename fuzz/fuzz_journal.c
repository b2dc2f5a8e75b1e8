/* Fuzz target: the reader of tiptap sweep's journal (src/cli/journal.c).
 *
 * The input is the journal file of a sweep of 16 combinations by tiptap 0.1.0 with
 * the fingerprint 0123456789abcdef. Oracles: no sanitizer report; every refusal is one
 * non-empty line; an accepted journal keeps no more than the bytes it was given, as
 * many combinations as it counts, and its records written out again read back to the
 * same rows, every byte of them kept. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_common.h"
#include "journal.h"
#include "tiptap/util/error.h"

enum { N = 16 };

static const journal_sweep sweep = {"0.1.0", 0x0123456789abcdefULL, N};

static void free_texts(char **text)
{
    for (size_t i = 0; i < N; i++)
        free(text[i]);
}

/* The accepted rows written out as a journal and read back. */
static void round_trip(char **text, size_t done)
{
    char *buf = NULL, *back[N] = {0};
    size_t len = 0, done2, good2;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return;
    journal_write_header(f, &sweep);
    for (size_t i = 0; i < N; i++)
        if (text[i])
            journal_write_record(f, i, text[i]);
    fclose(f);
    if (journal_read("again.partial", buf, len, &sweep, back, &done2, &good2) != TT_OK)
        fuzz_fail("a journal written again is refused: %s", tt_error_message());
    if (done2 != done || good2 != len)
        fuzz_fail("written again: %zu combinations in %zu of %zu bytes, read first %zu", done2, good2, len, done);
    for (size_t i = 0; i < N; i++)
        if ((text[i] == NULL) != (back[i] == NULL) || (text[i] && strcmp(text[i], back[i]) != 0))
            fuzz_fail("combination %zu reads back otherwise", i);
    free_texts(back);
    free(buf);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text[N] = {0};
    size_t done, good;
    tt_error_clear();
    int rc = journal_read("fuzz.partial", (const char *)data, size, &sweep, text, &done, &good);
    if (rc != TT_OK)
        fuzz_check_refusal("journal");
    else {
        size_t count = 0;
        for (size_t i = 0; i < N; i++)
            count += text[i] != NULL;
        if (good > size || count != done)
            fuzz_fail("accepted: %zu combinations counted, %zu kept; %zu of %zu bytes good", done, count, good,
                      size);
        round_trip(text, done);
    }
    free_texts(text);
    return 0;
}
