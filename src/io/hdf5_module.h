/* The HDF5 module's interface (src/hdf5/h5_module.c), private to the library: the
 * calls into libhdf5 live in a separate shared module, libtiptap_hdf5.so, that
 * src/io/hdf5.c loads on the first HDF5 file, so that every other run (and every start
 * of the program) does without loading libhdf5 and the thirty libraries it pulls in
 * (curl, crypto, ...). The module calls nothing of tiptap's: it reports a failure by
 * returning -1, and hdf5.c words the message from the reason the module kept (the
 * errno of the first failed write, else HDF5's own words).
 *
 * libhdf5 never meets a failed write: its 1.10 frees a file whose flush fails at close
 * but keeps it in its table (and a failed H5Fflush leaves the close failing too), so
 * that its exit handler crashes on it (exit 139, also at the end of a Python
 * interpreter). The module has libhdf5 make the file in memory (the core driver, no
 * file behind it) and hands the caller the finished image, which src/io/hdf5.c writes
 * through its output file: a failed write is then reported as for every output. */
#ifndef TIPTAP_HDF5_MODULE_H
#define TIPTAP_HDF5_MODULE_H

#include <stddef.h>

/* What tt_h5_module() returns; version changes with the table. */
#define TT_H5_MODULE_VERSION 3

enum { TT_H5_TEXT = 0, TT_H5_DOUBLE = 1, TT_H5_LONG = 2 };

typedef struct tt_h5_file tt_h5_file;

typedef struct {
    int version;
    /* A new file, named path in HDF5's messages (made in memory); NULL on failure. */
    tt_h5_file *(*create)(const char *path);
    /* Closes and frees; -1 when the file could not be completed (a call before failed, or
     * the close), with the reason as reason() gives it. Else *image (malloc'd, the
     * caller's to free) holds the whole file, *size bytes. */
    int (*close)(tt_h5_file *f, void **image, size_t *size, int *err, char *why, size_t len);
    int (*group)(tt_h5_file *f, const char *path);
    int (*doubles)(tt_h5_file *f, const char *path, int rank, const size_t *dims, const double *data);
    /* rank 0: one text */
    int (*texts)(tt_h5_file *f, const char *path, int rank, const size_t *dims, const char *const *texts);
    /* a scalar attribute of type TT_H5_TEXT (value: a const char *const *), _DOUBLE, _LONG */
    int (*attr)(tt_h5_file *f, const char *object, const char *name, int type, const void *value);
    int (*scale)(tt_h5_file *f, const char *path, const char *name);
    int (*attach)(tt_h5_file *f, const char *data, const char *scale, unsigned dim, const char *label);
    /* Why the first failed call failed: *err the errno of a failed read or write (0:
     * none known), why HDF5's innermost description ("" if none). */
    void (*reason)(const tt_h5_file *f, int *err, char *why, size_t len);
    /* The reason of a failed create, whose file is gone. */
    void (*create_reason)(int *err, char *why, size_t len);
    /* path: a hard link to the object at target */
    int (*link)(tt_h5_file *f, const char *target, const char *path);
    /* a one-dimensional attribute of n texts */
    int (*attr_texts)(tt_h5_file *f, const char *object, const char *name, size_t n, const char *const *texts);
} tt_h5_ops;

/* The module's one exported function. */
__attribute__((visibility("default"))) const tt_h5_ops *tt_h5_module(void);
#define TT_H5_MODULE_SYMBOL "tt_h5_module"
#define TT_H5_MODULE_FILE "libtiptap_hdf5.so"

#endif
