/* HDF5 files (see include/tiptap/io/hdf5.h): the temporary name, the messages and one
 * file at a time here; the calls into libhdf5 in the module libtiptap_hdf5.so beside
 * the library (src/hdf5/h5_module.c, src/io/hdf5_module.h), loaded on the first file. */
#include "tiptap/io/hdf5.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hdf5_module.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

struct tt_h5 {
    tt_outfile *tmp; /* the temporary name, renamed at close */
    tt_h5_file *file;
    char *path;
    int failed;
};

/* One file at a time: the dimension-scale calls of HDF5's high-level library and its
 * error-printing switch are process-wide. */
static pthread_mutex_t one_file = PTHREAD_MUTEX_INITIALIZER;

/* The module, found beside the object this code is linked into (libtiptap.so, or the
 * program that links the static library), loaded once. */
static const tt_h5_ops *ops;
static char load_error[1024];
static pthread_once_t load_once = PTHREAD_ONCE_INIT;

static void load(void)
{
    Dl_info info;
    char path[4096];
    if (!dladdr((void *)tt_h5_create, &info) || !info.dli_fname) {
        snprintf(load_error, sizeof load_error, "cannot tell where libtiptap is");
        return;
    }
    const char *slash = strrchr(info.dli_fname, '/');
    snprintf(path, sizeof path, "%.*s%s", slash ? (int)(slash - info.dli_fname + 1) : 0, info.dli_fname,
             TT_H5_MODULE_FILE);
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    const tt_h5_ops *(*get)(void) = NULL;
    if (h)
        *(void **)&get = dlsym(h, TT_H5_MODULE_SYMBOL);
    const tt_h5_ops *o = get ? get() : NULL;
    if (!o || o->version != TT_H5_MODULE_VERSION)
        snprintf(load_error, sizeof load_error, "%s", h ? "the HDF5 module is of another version" : dlerror());
    else
        ops = o;
}

/* The message of a failure: a failed write's reason as for every output ("File too
 * large", "No space left on device"), else what was being written and HDF5's words. */
static int report(const char *path, int err, const char *why, const char *what, const char *object)
{
    if (err)
        return tt_error(TT_EIO, "%s: cannot write: %s", path, strerror(err));
    return tt_error(TT_EIO, "%s: cannot write HDF5: %s %s%s%s", path, what, object, why[0] ? ": " : "",
                    why);
}

static int fail(tt_h5 *f, const char *what, const char *object)
{
    int err;
    char why[256];
    ops->reason(f->file, &err, why, sizeof why);
    f->failed = 1;
    return report(f->path, err, why, what, object);
}

int tt_h5_create(tt_h5 **out, const char *path)
{
    *out = NULL;
    pthread_once(&load_once, load);
    if (!ops)
        return tt_error(TT_EIO, "%s: cannot write HDF5: %s", path, load_error);
    tt_h5 *f = calloc(1, sizeof *f);
    if (!f || !(f->path = tt_strdup(path))) {
        free(f);
        return tt_error_nomem("the HDF5 file %s", path);
    }
    int rc = tt_outfile_open(&f->tmp, path);
    if (rc) {
        free(f->path);
        free(f);
        return rc;
    }
    pthread_mutex_lock(&one_file);
    /* the temporary file exists (made without following links); HDF5 writes it anew */
    if (!(f->file = ops->create(tt_outfile_tmpname(f->tmp)))) {
        int err;
        char why[256];
        ops->create_reason(&err, why, sizeof why);
        f->failed = 1;
        rc = report(path, err, why, "creating", "the file");
        tt_h5_close(f, 0);
        return rc;
    }
    *out = f;
    return TT_OK;
}

int tt_h5_close(tt_h5 *f, int keep)
{
    if (!f)
        return TT_OK;
    int rc = f->failed ? TT_EIO : TT_OK, err = 0;
    char why[256] = "";
    void *image = NULL;
    size_t size = 0;
    if (f->file && ops->close(f->file, &image, &size, &err, why, sizeof why) < 0 && rc == TT_OK && keep)
        rc = report(f->path, err, why, "closing", "the file");
    pthread_mutex_unlock(&one_file); /* libhdf5 is done with the file; the image is ours */
    /* a failed write (past ulimit -f, a full disk) is kept by the stream and told by
     * tt_outfile_close, with the reason */
    if (rc == TT_OK && keep)
        fwrite(image, 1, size, tt_outfile_stream(f->tmp));
    free(image);
    int crc = tt_outfile_close(f->tmp, keep && rc == TT_OK);
    if (rc == TT_OK)
        rc = crc;
    free(f->path);
    free(f);
    return rc;
}

/* After a failure nothing more is written: the file is discarded at close, and the
 * first failure's message stands. */
#define SKIP_AFTER_FAILURE(f) \
    do {                     \
        if ((f)->failed)     \
            return TT_EIO;   \
    } while (0)

int tt_h5_group(tt_h5 *f, const char *path)
{
    SKIP_AFTER_FAILURE(f);
    return ops->group(f->file, path) < 0 ? fail(f, "the group", path) : TT_OK;
}

int tt_h5_doubles(tt_h5 *f, const char *path, int rank, const size_t *dims, const double *data)
{
    SKIP_AFTER_FAILURE(f);
    return ops->doubles(f->file, path, rank, dims, data) < 0 ? fail(f, "the dataset", path) : TT_OK;
}

int tt_h5_text(tt_h5 *f, const char *path, const char *text)
{
    SKIP_AFTER_FAILURE(f);
    return ops->texts(f->file, path, 0, NULL, &text) < 0 ? fail(f, "the dataset", path) : TT_OK;
}

int tt_h5_texts(tt_h5 *f, const char *path, int rank, const size_t *dims, const char *const *texts)
{
    SKIP_AFTER_FAILURE(f);
    return ops->texts(f->file, path, rank, dims, texts) < 0 ? fail(f, "the dataset", path) : TT_OK;
}

/* The failure of writing attribute name of object. */
static int attr_failed(tt_h5 *f, const char *object, const char *name)
{
    char what[1200];
    snprintf(what, sizeof what, "%s of %s", name, object);
    return fail(f, "the attribute", what);
}

/* Attribute name of object, of type type, from value. */
static int attribute(tt_h5 *f, const char *object, const char *name, int type, const void *value)
{
    SKIP_AFTER_FAILURE(f);
    return ops->attr(f->file, object, name, type, value) == 0 ? TT_OK : attr_failed(f, object, name);
}

int tt_h5_attr_text(tt_h5 *f, const char *object, const char *name, const char *value)
{
    return attribute(f, object, name, TT_H5_TEXT, &value);
}

int tt_h5_attr_double(tt_h5 *f, const char *object, const char *name, double value)
{
    return attribute(f, object, name, TT_H5_DOUBLE, &value);
}

int tt_h5_attr_long(tt_h5 *f, const char *object, const char *name, long value)
{
    return attribute(f, object, name, TT_H5_LONG, &value);
}

int tt_h5_scale(tt_h5 *f, const char *scale, const char *name)
{
    SKIP_AFTER_FAILURE(f);
    return ops->scale(f->file, scale, name) < 0 ? fail(f, "the dimension scale", scale) : TT_OK;
}

int tt_h5_attach(tt_h5 *f, const char *data, const char *scale, unsigned dim, const char *label)
{
    SKIP_AFTER_FAILURE(f);
    return ops->attach(f->file, data, scale, dim, label) < 0 ? fail(f, "attaching a dimension scale to", data)
                                                           : TT_OK;
}

int tt_h5_link(tt_h5 *f, const char *target, const char *path)
{
    SKIP_AFTER_FAILURE(f);
    return ops->link(f->file, target, path) < 0 ? fail(f, "the link", path) : TT_OK;
}

int tt_h5_attr_texts(tt_h5 *f, const char *object, const char *name, size_t n, const char *const *texts)
{
    SKIP_AFTER_FAILURE(f);
    return ops->attr_texts(f->file, object, name, n, texts) == 0 ? TT_OK : attr_failed(f, object, name);
}
