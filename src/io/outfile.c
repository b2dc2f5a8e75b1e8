/* Output files written under a temporary name and renamed into place
 * (see include/tiptap/io/outfile.h). */
#include "tiptap/io/outfile.h"

#include <errno.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

struct tt_outfile {
    FILE *f;
    char *path, *tmp;
};

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
    /* beside the target, so that rename() stays within one file system */
    snprintf(o->tmp, n + 16, "%s.tmp.XXXXXX", path);
    int fd = mkstemp(o->tmp);
    if (fd < 0 || !(o->f = fdopen(fd, "wb"))) {
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
const char *tt_outfile_tmpname(const tt_outfile *o) { return o->tmp; }

int tt_outfile_close(tt_outfile *o, int keep)
{
    if (!o)
        return TT_OK;
    int rc = TT_OK;
    int bad = ferror(o->f) || fflush(o->f) != 0 || fsync(fileno(o->f)) != 0;
    int e = errno;
    if (fclose(o->f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (keep && bad) {
        rc = tt_error(TT_EIO, "%s: cannot write: %s", o->path, strerror(e));
        keep = 0;
    }
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
