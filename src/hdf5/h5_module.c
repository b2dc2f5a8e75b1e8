/* The HDF5 module (see src/io/hdf5_module.h): libhdf5 and its high-level dimension
 * scales behind a table of calls, loaded by src/io/hdf5.c on the first HDF5 file.
 * Objects are made without modification times (the same data give the same bytes) and
 * list their attributes in the order written; texts are variable-length UTF-8. */
#include <hdf5.h>
#include <hdf5_hl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/hdf5_module.h"

struct tt_h5_file {
    hid_t file;
    hid_t lcpl; /* links made with their parent groups */
    hid_t ocpl; /* datasets: no times, attributes in creation order */
    hid_t gcpl; /* groups: the same */
    hid_t str;  /* variable-length UTF-8 string type */
    int failed; /* a call failed: the file is discarded */
    int err;    /* the errno of the first failed read or write, 0 if none */
    char why[256];
    /* what HDF5's failed calls said since the current call began: some fail by design
     * (H5Lexists on a path whose parent is missing) */
    int pending_err;
    char pending_why[256];
    H5E_auto2_t saved_func; /* the error handler before this file, restored at close */
    void *saved_data;
};

/* From the innermost error up: the first errno in a description of HDF5's file drivers
 * ("... errno = 27, error message = 'File too large' ..."), and the innermost
 * description as HDF5's own words. */
static herr_t find_reason(unsigned n, const H5E_error2_t *e, void *data)
{
    tt_h5_file *f = data;
    const char *p = e->desc ? strstr(e->desc, "errno = ") : NULL;
    if (p && !f->pending_err)
        f->pending_err = atoi(p + 8);
    if (n == 0 && e->desc)
        snprintf(f->pending_why, sizeof f->pending_why, "%s", e->desc);
    return 0;
}

/* HDF5 calls this as any of its calls fails, before the next call clears the stack;
 * nothing is printed. */
static herr_t on_error(hid_t stack, void *data)
{
    H5Ewalk2(stack, H5E_WALK_UPWARD, find_reason, data);
    return 0;
}

/* A call of the module begins: what failed before it is forgotten. */
static void begin(tt_h5_file *f)
{
    f->pending_err = 0;
    f->pending_why[0] = '\0';
}

/* A call of the module failed: the first failure's reason is kept. */
static int failed(tt_h5_file *f)
{
    if (!f->failed) {
        f->failed = 1;
        f->err = f->pending_err;
        snprintf(f->why, sizeof f->why, "%s", f->pending_why);
    }
    return -1;
}

static void h5_reason(const tt_h5_file *f, int *err, char *why, size_t len)
{
    *err = f->err;
    snprintf(why, len, "%s", f->why);
}

/* The file is made in memory (the core driver, without a file behind it): flushed, its
 * image copied out for the caller, and closed, none of which writes to disk. */
static int h5_close(tt_h5_file *f, void **image, size_t *size, int *err, char *why, size_t len)
{
    *image = NULL;
    *size = 0;
    begin(f);
    if (f->file >= 0 && !f->failed) {
        ssize_t n = H5Fflush(f->file, H5F_SCOPE_LOCAL) < 0 ? -1 : H5Fget_file_image(f->file, NULL, 0);
        void *buf = n > 0 ? malloc((size_t)n) : NULL;
        if (n > 0 && !buf)
            snprintf(f->pending_why, sizeof f->pending_why, "out of memory for its image of %zd bytes", n);
        if (!buf || H5Fget_file_image(f->file, buf, (size_t)n) != n) {
            free(buf);
            failed(f);
        } else {
            *image = buf;
            *size = (size_t)n;
        }
    }
    if (f->str >= 0)
        H5Tclose(f->str);
    if (f->gcpl >= 0)
        H5Pclose(f->gcpl);
    if (f->ocpl >= 0)
        H5Pclose(f->ocpl);
    if (f->lcpl >= 0)
        H5Pclose(f->lcpl);
    begin(f);
    if (f->file >= 0 && H5Fclose(f->file) < 0)
        failed(f);
    int bad = f->failed;
    if (bad) {
        free(*image);
        *image = NULL;
        *size = 0;
    }
    h5_reason(f, err, why, len);
    H5Eset_auto2(H5E_DEFAULT, f->saved_func, f->saved_data);
    free(f);
    return bad ? -1 : 0;
}

static int create_err;
static char create_why[256];

static void h5_create_reason(int *err, char *why, size_t len)
{
    *err = create_err;
    snprintf(why, len, "%s", create_why);
}

static tt_h5_file *h5_create(const char *path)
{
    const unsigned order = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
    tt_h5_file *f = calloc(1, sizeof *f);
    create_err = 0;
    snprintf(create_why, sizeof create_why, "out of memory");
    if (!f)
        return NULL;
    /* failures are told by the caller, in one line, with the reason kept here */
    H5Eget_auto2(H5E_DEFAULT, &f->saved_func, &f->saved_data);
    H5Eset_auto2(H5E_DEFAULT, on_error, f);
    /* in memory, grown a mebibyte at a time, with no file behind it (backing store off) */
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl >= 0 && H5Pset_fapl_core(fapl, (size_t)1 << 20, 0) >= 0)
        f->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    else
        f->file = -1;
    if (fapl >= 0)
        H5Pclose(fapl);
    f->lcpl = H5Pcreate(H5P_LINK_CREATE);
    f->ocpl = H5Pcreate(H5P_DATASET_CREATE);
    f->gcpl = H5Pcreate(H5P_GROUP_CREATE);
    f->str = H5Tcopy(H5T_C_S1);
    if (f->file < 0 || f->lcpl < 0 || f->ocpl < 0 || f->gcpl < 0 || f->str < 0 ||
        H5Pset_create_intermediate_group(f->lcpl, 1) < 0 || H5Pset_obj_track_times(f->ocpl, 0) < 0 ||
        H5Pset_attr_creation_order(f->ocpl, order) < 0 || H5Pset_obj_track_times(f->gcpl, 0) < 0 ||
        H5Pset_attr_creation_order(f->gcpl, order) < 0 || H5Tset_size(f->str, H5T_VARIABLE) < 0 ||
        H5Tset_cset(f->str, H5T_CSET_UTF8) < 0) {
        void *image;
        size_t size;
        failed(f);
        h5_close(f, &image, &size, &create_err, create_why, sizeof create_why);
        return NULL;
    }
    return f;
}

static int h5_group(tt_h5_file *f, const char *path)
{
    begin(f);
    if (H5Lexists(f->file, path, H5P_DEFAULT) > 0)
        return 0;
    hid_t g = H5Gcreate2(f->file, path, f->lcpl, f->gcpl, H5P_DEFAULT);
    if (g < 0 || H5Gclose(g) < 0)
        return failed(f);
    return 0;
}

/* Make the dataset path of type type and shape, write data, close it. */
static int dataset(tt_h5_file *f, const char *path, hid_t type, int rank, const size_t *dims,
                   const void *data)
{
    hsize_t d[32];
    begin(f);
    if (rank < 0 || rank > 32)
        return failed(f);
    for (int i = 0; i < rank; i++)
        d[i] = dims[i];
    hid_t space = rank > 0 ? H5Screate_simple(rank, d, NULL) : H5Screate(H5S_SCALAR);
    hid_t s = space < 0 ? -1 : H5Dcreate2(f->file, path, type, space, f->lcpl, f->ocpl, H5P_DEFAULT);
    herr_t w = s < 0 ? -1 : H5Dwrite(s, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    if (s >= 0 && H5Dclose(s) < 0)
        w = -1;
    if (space >= 0)
        H5Sclose(space);
    return w < 0 ? failed(f) : 0;
}

static int h5_doubles(tt_h5_file *f, const char *path, int rank, const size_t *dims, const double *data)
{
    return dataset(f, path, H5T_IEEE_F64LE, rank, dims, data);
}

static int h5_texts(tt_h5_file *f, const char *path, int rank, const size_t *dims, const char *const *texts)
{
    return dataset(f, path, f->str, rank, dims, texts);
}

static int h5_attr(tt_h5_file *f, const char *object, const char *name, int type, const void *value)
{
    hid_t t = type == TT_H5_TEXT ? f->str : type == TT_H5_DOUBLE ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LONG;
    begin(f);
    hid_t space = H5Screate(H5S_SCALAR);
    if (space >= 0 && H5Aexists_by_name(f->file, object, name, H5P_DEFAULT) > 0)
        H5Adelete_by_name(f->file, object, name, H5P_DEFAULT);
    hid_t a = space < 0 ? -1
                        : H5Acreate_by_name(f->file, object, name, t, space, H5P_DEFAULT, H5P_DEFAULT,
                                            H5P_DEFAULT);
    herr_t w = a < 0 ? -1 : H5Awrite(a, t, value);
    if (a >= 0 && H5Aclose(a) < 0)
        w = -1;
    if (space >= 0)
        H5Sclose(space);
    return w < 0 ? failed(f) : 0;
}

static int h5_scale(tt_h5_file *f, const char *path, const char *name)
{
    begin(f);
    hid_t d = H5Dopen2(f->file, path, H5P_DEFAULT);
    herr_t r = d < 0 ? -1 : H5DSset_scale(d, name);
    if (d >= 0 && H5Dclose(d) < 0)
        r = -1;
    return r < 0 ? failed(f) : 0;
}

static int h5_attach(tt_h5_file *f, const char *data, const char *scale, unsigned dim, const char *label)
{
    begin(f);
    hid_t d = H5Dopen2(f->file, data, H5P_DEFAULT), s = H5Dopen2(f->file, scale, H5P_DEFAULT);
    herr_t r = d < 0 || s < 0 || H5DSattach_scale(d, s, dim) < 0 ? -1 : H5DSset_label(d, dim, label);
    if (d >= 0 && H5Dclose(d) < 0)
        r = -1;
    if (s >= 0 && H5Dclose(s) < 0)
        r = -1;
    return r < 0 ? failed(f) : 0;
}

static int h5_link(tt_h5_file *f, const char *target, const char *path)
{
    begin(f);
    return H5Lcreate_hard(f->file, target, f->file, path, f->lcpl, H5P_DEFAULT) < 0 ? failed(f) : 0;
}

static int h5_attr_texts(tt_h5_file *f, const char *object, const char *name, size_t n, const char *const *texts)
{
    hsize_t d = n;
    begin(f);
    hid_t space = H5Screate_simple(1, &d, NULL);
    hid_t a = space < 0 ? -1
                        : H5Acreate_by_name(f->file, object, name, f->str, space, H5P_DEFAULT, H5P_DEFAULT,
                                            H5P_DEFAULT);
    herr_t w = a < 0 ? -1 : H5Awrite(a, f->str, texts);
    if (a >= 0 && H5Aclose(a) < 0)
        w = -1;
    if (space >= 0)
        H5Sclose(space);
    return w < 0 ? failed(f) : 0;
}

const tt_h5_ops *tt_h5_module(void)
{
    static const tt_h5_ops ops = {TT_H5_MODULE_VERSION, h5_create, h5_close,  h5_group,
                                  h5_doubles,           h5_texts,  h5_attr,   h5_scale,
                                  h5_attach,            h5_reason, h5_create_reason, h5_link,
                                  h5_attr_texts};
    return &ops;
}
