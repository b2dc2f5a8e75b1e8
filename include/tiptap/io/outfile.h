/* tiptap: output files that never exist half-written.
 *
 * tt_outfile_open writes to a temporary name beside the target; tt_outfile_close with
 * keep = 1 flushes, closes and renames it into place, with keep = 0 removes it. A run
 * that fails or is killed between the two leaves at most the temporary file, never a
 * truncated target. Every write error (a full disk, EFBIG past ulimit -f once SIGXFSZ
 * is ignored) fails the close with "path: cannot write: reason" and removes the
 * temporary file.
 *
 * Ownership: the tt_outfile and its FILE belong to the library until
 * tt_outfile_close, which frees both whatever it returns.
 */
#ifndef TIPTAP_OUTFILE_H
#define TIPTAP_OUTFILE_H

#include <stdio.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct tt_outfile tt_outfile;

/* Fails with TT_EIO and "path: cannot write: reason" (for example a missing or
 * unwritable folder), and with TT_EINVAL when path holds a folder, a pipe, a device or
 * a socket (or a link to one), or is an input of the run (tt_output_check in
 * include/tiptap/io/files.h). The temporary file is made with
 * O_CREAT | O_EXCL, so a link planted in its place is never followed; rename() at close
 * replaces a link at path itself, never the file it points to. */
int tt_outfile_open(tt_outfile **out, const char *path);
FILE *tt_outfile_stream(tt_outfile *o);
/* The errno of the stream's first failed write (0: none), for writers whose own
 * library reports a failure without the reason (cairo). */
int tt_outfile_errno(const tt_outfile *o);
const char *tt_outfile_tmpname(const tt_outfile *o);
int tt_outfile_close(tt_outfile *o, int keep);
/* How many temporary files exist now, from the start of tt_outfile_open to the end of
 * tt_outfile_close, over all threads. Async-signal-safe: a signal handler that would
 * end the program at once asks it first, so as never to leave a temporary file. */
int tt_outfile_open_count(void);

/* Make a folder (and its parents) if missing; TT_EIO with "dir: reason" if it cannot
 * be made or written. */
int tt_mkdirs(const char *dir);

TT_END_DECLS
#endif
