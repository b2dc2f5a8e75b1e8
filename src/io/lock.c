/* Output folders locked for a run (see include/tiptap/io/lock.h). */
#include "tiptap/io/lock.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tiptap/util/error.h"

/* Who holds the lock, from the file: "PID CMD\n" ("PID\n" from older versions). */
static int refuse_busy(int fd, const char *dir)
{
    char buf[64] = "", cmd[32] = "";
    ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
    buf[n > 0 ? n : 0] = '\0';
    long pid = 0;
    int got = sscanf(buf, "%ld %31[a-z]", &pid, cmd);
    if (got >= 1 && pid > 0)
        return tt_error(TT_EIO, "%s is in use by another tiptap %s (pid %ld)", dir,
                        got == 2 ? cmd : "run", pid);
    return tt_error(TT_EIO, "%s is in use by another tiptap run", dir);
}

int tt_folder_lock(const char *dir, const char *cmd, int *out)
{
    char path[4096];
    *out = -1;
    snprintf(path, sizeof path, "%s/.tiptap.lock", dir);
    for (int tries = 0; tries < 100; tries++) {
        /* O_NOFOLLOW: a link planted here would have the pid written into (and the file
         * it names truncated) */
        int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY, 0644);
        if (fd < 0 && (errno == ELOOP || errno == EMLINK))
            return tt_error(TT_EIO, "%s: is a symbolic link; tiptap never writes through a link: "
                            "remove it", path);
        if (fd < 0)
            return tt_error(TT_EIO, "%s: cannot open: %s", path, strerror(errno));
        struct stat held, named;
        if (fstat(fd, &held) != 0 || !S_ISREG(held.st_mode) || held.st_nlink > 1) {
            close(fd);
            return tt_error(TT_EIO, "%s: not a plain file of its own (a device, pipe or a file "
                            "with other hard links); tiptap never writes through it: remove it",
                            path);
        }
        if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
            int err = errno, rc = err == EWOULDBLOCK ? refuse_busy(fd, dir)
                                                     : tt_error(TT_EIO, "%s: cannot lock: %s", path,
                                                                strerror(err));
            close(fd);
            return rc;
        }
        /* The last run removes the file when it finishes (tt_folder_unlock): a lock taken
         * on a file that was removed meanwhile guards nothing, so take the new one. */
        if (lstat(path, &named) != 0 || held.st_ino != named.st_ino || held.st_dev != named.st_dev) {
            close(fd);
            continue;
        }
        char buf[64];
        int n = snprintf(buf, sizeof buf, "%ld %s\n", (long)getpid(), cmd);
        if (ftruncate(fd, 0) != 0 || pwrite(fd, buf, (size_t)n, 0) != n) {
            int rc = tt_error(TT_EIO, "%s: cannot write: %s", path, strerror(errno));
            close(fd);
            return rc;
        }
        *out = fd;
        return TT_OK;
    }
    return tt_error(TT_EIO, "%s: the lock file keeps being replaced", path);
}

void tt_folder_unlock(const char *dir, int fd)
{
    if (fd < 0)
        return;
    char path[4096];
    snprintf(path, sizeof path, "%s/.tiptap.lock", dir);
    unlink(path); /* while still held, so that no run locks the file being removed */
    close(fd);
}
