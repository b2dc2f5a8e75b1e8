/* Inputs opened as regular files only, and outputs that must not replace them
 * (see include/tiptap/io/files.h). */
#include "tiptap/io/files.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

/* ---- inputs: regular files only ---- */

static void note(const char *path, const char *what, int always);

/* What fstat says of an input: TT_OK for a regular file within max_bytes. */
static int check_regular(int fd, const char *path, const char *what, const char *noun,
                         long long max_bytes, long long *size)
{
    struct stat st;
    if (fstat(fd, &st) != 0)
        return tt_error(TT_EIO, "%s: cannot read %s: %s", path, what, strerror(errno));
    if (S_ISDIR(st.st_mode))
        return tt_error(TT_EINVAL, "%s: is a folder, not a %s", path, what);
    if (!S_ISREG(st.st_mode))
        return tt_error(TT_EINVAL, "%s: not a regular file (a device, pipe or socket); a %s is "
                        "a file", path, noun);
    if (st.st_size > max_bytes)
        return tt_error(TT_EINVAL, "%s: %lld bytes is too large for a %s (at most %lld)", path,
                        (long long)st.st_size, what, max_bytes);
    if (size)
        *size = (long long)st.st_size;
    return TT_OK;
}

/* Blocking again once the file is known to be regular: O_NONBLOCK only kept the open
 * of a pipe without a writer from waiting for ever. */
static void make_blocking(int fd)
{
    int fl = fcntl(fd, F_GETFL);
    if (fl >= 0)
        fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
}

int tt_input_open(const char *path, const char *what, const char *noun, long long max_bytes,
                  int *fd, long long *size)
{
    *fd = -1;
    int d = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (d < 0)
        return tt_error(TT_EIO, "%s: cannot open %s: %s", path, what, strerror(errno));
    int rc = check_regular(d, path, what, noun, max_bytes, size);
    if (rc) {
        close(d);
        return rc;
    }
    make_blocking(d);
    note(path, what, 0);
    *fd = d;
    return TT_OK;
}

int tt_input_fopen(const char *path, const char *what, const char *noun, long long max_bytes,
                   FILE **f)
{
    int fd;
    *f = NULL;
    int rc = tt_input_open(path, what, noun, max_bytes, &fd, NULL);
    if (rc)
        return rc;
    if (!(*f = fdopen(fd, "rb"))) {
        close(fd);
        return tt_error(TT_ENOMEM, "%s: out of memory", path);
    }
    return TT_OK;
}

static int link_refused(const char *path, const char *what)
{
    return tt_error(TT_EINVAL, "%s: the %s is a symbolic link; tiptap never writes through a "
                    "link: remove it", path, what);
}

int tt_file_update(const char *path, const char *what, long long max_bytes, FILE **f)
{
    *f = NULL;
    int fd = open(path, O_RDWR | O_CLOEXEC | O_NONBLOCK | O_NOCTTY | O_NOFOLLOW);
    if (fd < 0 && errno == ENOENT)
        return TT_OK;
    if (fd < 0 && (errno == ELOOP || errno == EMLINK))
        return link_refused(path, what);
    if (fd < 0 && errno == EISDIR)
        return tt_error(TT_EINVAL, "%s: is a folder, not a %s", path, what);
    if (fd < 0)
        return tt_error(TT_EIO, "%s: cannot open %s: %s", path, what, strerror(errno));
    int rc = check_regular(fd, path, what, what, max_bytes, NULL);
    if (!rc) {
        make_blocking(fd);
        note(path, what, 0);
        if (!(*f = fdopen(fd, "r+b")))
            rc = tt_error(TT_ENOMEM, "%s: out of memory", path);
    }
    if (rc)
        close(fd);
    return rc;
}

int tt_file_create(const char *path, const char *what, FILE **f)
{
    *f = NULL;
    int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) {
        struct stat st;
        if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode))
            return link_refused(path, what);
        return tt_error(TT_EIO, "%s: cannot write the %s: %s", path, what, strerror(errno));
    }
    if (!(*f = fdopen(fd, "wb"))) {
        close(fd);
        unlink(path);
        return tt_error(TT_ENOMEM, "%s: out of memory", path);
    }
    return TT_OK;
}

/* ---- the inputs of this run ---- */

typedef struct {
    dev_t dev;
    ino_t ino;
    char *path, *abs, *what; /* as named, resolved (NULL if it could not be), its kind */
} input;

static pthread_mutex_t inputs_mutex = PTHREAD_MUTEX_INITIALIZER;
static input *inputs;
static size_t ninputs, inputs_cap;
static int tracking;

/* The absolute path of a file without following a link in its last name: the output
 * replaces a link, not its target; for a name that does not exist yet, its folder's
 * real path and the name. NULL when the folder does not exist either. */
static char *absolute(const char *path, int follow)
{
    if (follow) {
        char *r = realpath(path, NULL);
        if (r)
            return r;
    }
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        n--;
    size_t s = n;
    while (s > 0 && path[s - 1] != '/')
        s--;
    char *dir = malloc(s + 2), *out = NULL;
    if (!dir)
        return NULL;
    if (s == 0)
        strcpy(dir, ".");
    else {
        memcpy(dir, path, s);
        dir[s] = '\0';
    }
    char *rd = realpath(dir, NULL);
    free(dir);
    if (rd && (out = malloc(strlen(rd) + (n - s) + 2)))
        sprintf(out, "%s/%.*s", strcmp(rd, "/") ? rd : "", (int)(n - s), path + s);
    free(rd);
    return out;
}

void tt_inputs_track(int on)
{
    pthread_mutex_lock(&inputs_mutex);
    tracking = on;
    if (!on) {
        for (size_t i = 0; i < ninputs; i++) {
            free(inputs[i].path);
            free(inputs[i].abs);
            free(inputs[i].what);
        }
        free(inputs);
        inputs = NULL;
        ninputs = inputs_cap = 0;
    }
    pthread_mutex_unlock(&inputs_mutex);
}

void tt_input_note(const char *path, const char *what) { note(path, what, 1); }

/* An input remembered: always when the caller names it (tt_input_note), while tracking
 * when it is only opened. */
static void note(const char *path, const char *what, int always)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return;
    pthread_mutex_lock(&inputs_mutex);
    int known = !tracking && !always;
    for (size_t i = 0; i < ninputs && !known; i++)
        known = inputs[i].dev == st.st_dev && inputs[i].ino == st.st_ino;
    if (!known && ninputs == inputs_cap) {
        size_t cap = inputs_cap ? 2 * inputs_cap : 16;
        input *grown = realloc(inputs, cap * sizeof *grown);
        if (grown) {
            inputs = grown;
            inputs_cap = cap;
        }
    }
    if (!known && ninputs < inputs_cap) {
        input *e = &inputs[ninputs];
        e->dev = st.st_dev;
        e->ino = st.st_ino;
        e->path = tt_strdup(path);
        e->what = tt_strdup(what);
        e->abs = absolute(path, 1);
        if (e->path && e->what)
            ninputs++;
        else {
            free(e->path);
            free(e->what);
            free(e->abs);
        }
    }
    pthread_mutex_unlock(&inputs_mutex);
}

/* What lies at an output's name: nothing, a regular file, or a link to one (rename()
 * replaces the link) may be replaced; a folder, a pipe, a device or a socket, a link to
 * one, or a link into /proc, may not (the rename would put a file in place of
 * /dev/null, a FIFO or /dev/stdout). */
static int check_kind(const char *out)
{
    struct stat st;
    char to[256] = "";
    if (lstat(out, &st) != 0 || S_ISREG(st.st_mode))
        return TT_OK;
    /* /dev/stdout names the file behind a descriptor, through /proc: replacing the link
     * would replace /dev/stdout itself */
    if (S_ISLNK(st.st_mode) && readlink(out, to, sizeof to - 1) > 0 && !strncmp(to, "/proc/", 6))
        return tt_error(TT_EINVAL, "%s: a link into /proc (%s), to a process's open file; the "
                        "output would replace the link: name the file itself", out, to);
    if (S_ISLNK(st.st_mode) && (stat(out, &st) != 0 || S_ISREG(st.st_mode)))
        return TT_OK;
    if (S_ISDIR(st.st_mode))
        return tt_error(TT_EINVAL, "%s: is a folder; the output is a file: name another", out);
    return tt_error(TT_EINVAL, "%s: not a regular file (a device, pipe or socket); an output "
                    "replaces only a regular file: name another", out);
}

int tt_output_check(const char *out)
{
    int rc = check_kind(out);
    return rc ? rc : tt_output_check_inputs(out);
}

int tt_output_check_inputs(const char *out)
{
    pthread_mutex_lock(&inputs_mutex);
    int none = ninputs == 0;
    pthread_mutex_unlock(&inputs_mutex);
    if (none)
        return TT_OK;
    struct stat st;
    int have = stat(out, &st) == 0;
    char *abs = absolute(out, 1), *lexical = absolute(out, 0);
    char found[PATH_MAX + 64] = "";
    pthread_mutex_lock(&inputs_mutex);
    for (size_t i = 0; i < ninputs && !found[0]; i++) {
        const input *e = &inputs[i];
        if ((have && e->dev == st.st_dev && e->ino == st.st_ino) ||
            (e->abs && ((abs && !strcmp(abs, e->abs)) || (lexical && !strcmp(lexical, e->abs)))))
            snprintf(found, sizeof found, "%s %s", e->what, e->path);
    }
    pthread_mutex_unlock(&inputs_mutex);
    free(abs);
    free(lexical);
    if (found[0])
        return tt_error(TT_EINVAL, "%s: the same file as the %s that this run reads; write the "
                        "output elsewhere", out, found);
    return TT_OK;
}

/* Whether two output names are one file: the same file if both exist, else the same
 * resolved path (the folder's links, "." and ".." resolved; a link at the name itself
 * is what the output replaces). */
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char *ra = absolute(a, 1), *rb = absolute(b, 1), *la = absolute(a, 0), *lb = absolute(b, 0);
    int same = (ra && rb && !strcmp(ra, rb)) || (la && lb && !strcmp(la, lb));
    free(ra);
    free(rb);
    free(la);
    free(lb);
    return same;
}

int tt_outputs_distinct(const tt_output *outs, size_t n)
{
    for (size_t j = 1; j < n; j++)
        for (size_t i = 0; i < j; i++)
            if (outs[i].path && outs[j].path && same_file(outs[i].path, outs[j].path))
                return tt_error(TT_EINVAL, "%s %s: the same file as %s %s; give each its own name",
                                outs[j].what, outs[j].path, outs[i].what, outs[i].path);
    return TT_OK;
}
