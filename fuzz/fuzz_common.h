/* Shared by the fuzz targets: the input as a file, and the oracles.
 *
 * The targets read their input through a path, as tiptap does; the bytes go into an
 * anonymous in-memory file (memfd) named /proc/self/fd/N, which is a regular file.
 * Every oracle that fails aborts with one line on stderr, which libFuzzer and the
 * replay driver report as a finding. */
#ifndef TT_FUZZ_COMMON_H
#define TT_FUZZ_COMMON_H

#include <stddef.h>
#include <stdint.h>

/* The path of an in-memory regular file holding exactly data[0, size). */
const char *fuzz_file(const uint8_t *data, size_t size);

/* Abort unless the last tt_error message is one non-empty line. */
void fuzz_check_refusal(const char *what);

/* Abort with a message (an oracle failed). */
void fuzz_fail(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2), noreturn))
#endif
    ;

#endif
