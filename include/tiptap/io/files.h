/* tiptap: the files a run reads, and outputs that must not replace them.
 *
 * Inputs (scene files, PNG maps, the sweep's journal, profile CSVs, GSF and GWY files)
 * are opened through tt_input_open: only a regular file is read, after links are
 * resolved (a folder, a pipe, a socket, a device, a link to /dev/zero are refused by
 * name, without blocking on a pipe), and at most a bounded number of bytes.
 *
 * With tracking on (tt_inputs_track; the tiptap program turns it on), every input
 * opened is remembered, and so is every input a caller notes, tracking or not (a scene's
 * files and maps, tt_config_note_inputs); tt_output_check refuses an output that is the
 * same file (device and inode) or the same path as one of them (a sweep's -o s.ini, or
 * Python's hdf5="s.ini", would otherwise replace the scene it ran), and one whose name
 * holds a folder, a pipe, a device or a socket. tt_outfile_open checks every output it
 * opens. The list is shared by the process's threads (guarded by a mutex).
 *
 * tt_outputs_distinct checks all of a run's outputs at once: no two may name one file.
 */
#ifndef TIPTAP_FILES_H
#define TIPTAP_FILES_H

#include <stdio.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* The largest input of any kind but PNG maps: far above a real scene, journal or
 * profile (50,000 materials take 5 MB). */
#define TT_INPUT_MAX_BYTES (256LL << 20)

/* GSF and GWY files read back (a scan of 42 images of 8192 x 8192 doubles: 22 GB) and
 * PNG maps (8192 x 8192 pixels of 16-bit RGBA stored uncompressed: 512 MiB). */
#define TT_IMAGE_FILE_MAX_BYTES (64LL << 30)
#define TT_PNG_MAX_BYTES (1LL << 30)

/* Open path for reading as an input named what ("scene file", "PNG map") whose
 * refusal of a non-regular file reads "a NOUN is a file". Messages:
 *   "path: cannot open WHAT: reason", "path: is a folder, not a WHAT",
 *   "path: not a regular file (a device, pipe or socket); a NOUN is a file",
 *   "path: N bytes is too large for a WHAT (at most M)".
 * *size is the file's size (may be NULL). The descriptor is blocking and close-on-exec. */
int tt_input_open(const char *path, const char *what, const char *noun, long long max_bytes,
                  int *fd, long long *size);
/* The same as a stdio stream ("rb"). */
int tt_input_fopen(const char *path, const char *what, const char *noun, long long max_bytes,
                   FILE **f);

/* A file the run reads and then appends to in place (the sweep's journal): never
 * through a link ("path: is a symbolic link; tiptap never writes through a link"),
 * a regular file of at most max_bytes. TT_OK with *f NULL when it does not exist. */
int tt_file_update(const char *path, const char *what, long long max_bytes, FILE **f);
/* Create a new file for writing ("wb"): never through a link, never over a file there. */
int tt_file_create(const char *path, const char *what, FILE **f);

/* Remember every input opened from now on (1), or forget all inputs and stop (0). Off
 * by default, so that a program using the library may write a file it opened; the
 * inputs a caller names (tt_input_note, tt_config_note_inputs: a scene's files and
 * maps) are remembered either way, until tt_inputs_track(0). */
void tt_inputs_track(int on);
/* Remember path as an input named what, if it exists (a file the run will read). */
void tt_input_note(const char *path, const char *what);
/* A file output at out, checked before anything is written there (tt_outfile_open checks
 * every file it opens so): TT_EINVAL when
 *   - something other than a regular file is there (rename() would replace it): "out:
 *     is a folder; ...", "out: not a regular file (a device, pipe or socket); ...", also
 *     through a link (a link to a regular file is replaced by the output, as is any link);
 *   - out names an input (tt_output_check_inputs). */
int tt_output_check(const char *out);
/* TT_EINVAL, "out: the same file as the WHAT in that this run reads; ...", when out
 * names a remembered input (the same device and inode, or the same absolute path). For
 * an output folder, and names a run may remove. */
int tt_output_check_inputs(const char *out);

/* One output of a run: its name, and what the run calls it in messages ("-o",
 * "--plot"). */
typedef struct {
    const char *path, *what;
} tt_output;
/* Every output of a run at once, before any is written: TT_EINVAL, "WHAT2 PATH2: the
 * same file as WHAT1 PATH1; give each its own name", when two name one file (the same
 * file if both exist; else the same path once the folders' links, "." and ".." are
 * resolved). NULL paths are skipped. */
int tt_outputs_distinct(const tt_output *outs, size_t n);

TT_END_DECLS
#endif
