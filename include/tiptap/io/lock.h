/* tiptap: one run at a time in an output folder.
 *
 * tt_folder_lock holds DIR/.tiptap.lock (flock) for the run and writes the run's pid and
 * command into it; a second run into DIR is refused at once, naming the folder, the
 * command and the pid of the first. The lock ends with the process, however it ends, so
 * a lock file left by a killed run (a dead pid) is taken over. The lock file is opened
 * without following links: a link or a file with other hard links in its place is
 * refused, never written through.
 */
#ifndef TIPTAP_LOCK_H
#define TIPTAP_LOCK_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* Lock dir for command cmd ("scan", "sweep"); *fd holds the lock. Fails with TT_EIO:
 * "DIR is in use by another tiptap CMD (pid N)", "DIR/.tiptap.lock: ...". */
int tt_folder_lock(const char *dir, const char *cmd, int *fd);
/* Remove the lock file and release it (fd < 0: nothing to do). */
void tt_folder_unlock(const char *dir, int fd);

TT_END_DECLS
#endif
