/* Output files written under a temporary name and renamed into place
 * (see include/tiptap/io/outfile.h). */
#include "tiptap/io/outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tiptap/io/files.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

struct tt_outfile {
    FILE *f;
    int fd;
    int err; /* the first write error's errno: stdio keeps only that there was one */
    char *path, *tmp;
};

/* The stream's writes, keeping the reason of the first that fails (EFBIG past
 * ulimit -f, ENOSPC on a full disk) for the message at close. */
static ssize_t cookie_write(void *c, const char *buf, size_t n)
{
    tt_outfile *o = c;
    size_t done = 0;
    while (done < n) {
        ssize_t w = write(o->fd, buf + done, n - done);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            if (!o->err)
                o->err = w < 0 ? errno : EIO;
            return done ? (ssize_t)done : -1;
        }
        done += (size_t)w;
    }
    return (ssize_t)done;
}

/* Temporary files in existence (lock-free, so that a signal handler may read it). */
static atomic_int open_files;

int tt_outfile_open_count(void) { return atomic_load(&open_files); }

static int open_file(tt_outfile **out, const char *path);

int tt_outfile_open(tt_outfile **out, const char *path)
{
    /* counted before the temporary file can exist, uncounted once it cannot */
    atomic_fetch_add(&open_files, 1);
    int rc = open_file(out, path);
    if (rc)
        atomic_fetch_sub(&open_files, 1);
    return rc;
}

static int open_file(tt_outfile **out, const char *path)
{
    *out = NULL;
    int rc = tt_output_check(path);
    if (rc)
        return rc;
    tt_outfile *o = calloc(1, sizeof *o);
    size_t n = strlen(path);
    if (!o)
        return tt_error(TT_ENOMEM, "out of memory");
    o->path = tt_strdup(path);
    o->tmp = malloc(n + 16);
    if (!o->path || !o->tmp) {
        free(o->path);
        free(o->tmp);
        free(o);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    /* beside the target, so that rename() stays within one file system; made with
     * O_CREAT | O_EXCL, which never follows a link put in its place */
    snprintf(o->tmp, n + 16, "%s.tmp.XXXXXX", path);
    int fd = mkostemp(o->tmp, O_CLOEXEC);
    o->fd = fd;
    cookie_io_functions_t io = {NULL, cookie_write, NULL, NULL};
    if (fd < 0 || !(o->f = fopencookie(o, "wb", io))) {
        int e = errno;
        if (fd >= 0) {
            close(fd);
            unlink(o->tmp);
        }
        free(o->path);
        free(o->tmp);
        free(o);
        return tt_error(TT_EIO, "%s: cannot write: %s", path, strerror(e));
    }
    fchmod(fd, 0644);
    *out = o;
    return TT_OK;
}

FILE *tt_outfile_stream(tt_outfile *o) { return o->f; }
int tt_outfile_errno(const tt_outfile *o) { return o->err; }
const char *tt_outfile_tmpname(const tt_outfile *o) { return o->tmp; }

int tt_outfile_close(tt_outfile *o, int keep)
{
    if (!o)
        return TT_OK;
    int rc = TT_OK;
    errno = 0;
    int bad = ferror(o->f) || fflush(o->f) != 0 || fsync(o->fd) != 0;
    int e = o->err ? o->err : errno ? errno : EIO;
    fclose(o->f); /* the cookie stream: it flushed above and closes nothing */
    if (close(o->fd) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (keep && bad) {
        rc = tt_error(TT_EIO, "%s: cannot write: %s", o->path, strerror(e));
        keep = 0;
    }
    /* rename() replaces the directory entry: a link at path is replaced by the file, and
     * the file it pointed to is left as it was */
    if (keep && rename(o->tmp, o->path) != 0) {
        rc = tt_error(TT_EIO, "%s: cannot write: %s", o->path, strerror(errno));
        keep = 0;
    }
    if (!keep)
        unlink(o->tmp);
    atomic_fetch_sub(&open_files, 1);
    free(o->path);
    free(o->tmp);
    free(o);
    return rc;
}

int tt_mkdirs(const char *dir)
{
    char buf[4096];
    size_t n = strlen(dir);
    if (n == 0 || n >= sizeof buf)
        return tt_error(TT_EIO, "%s: not a usable folder name", dir);
    memcpy(buf, dir, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char c = buf[i];
        buf[i] = '\0';
        if (mkdir(buf, 0755) != 0 && errno != EEXIST)
            return tt_error(TT_EIO, "%s: cannot make folder: %s", buf, strerror(errno));
        buf[i] = c;
    }
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return tt_error(TT_EIO, "%s: not a folder", dir);
    if (access(dir, W_OK) != 0)
        return tt_error(TT_EIO, "%s: folder not writable: %s", dir, strerror(errno));
    return TT_OK;
}
