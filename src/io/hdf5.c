/* HDF5 files through libhdf5 and its high-level dimension scales (see
 * include/tiptap/io/hdf5.h). */
#include "tiptap/io/hdf5.h"

#include <hdf5.h>
#include <hdf5_hl.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/outfile.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

struct tt_h5 {
    tt_outfile *tmp; /* the temporary name, renamed at close */
    hid_t file;
    hid_t lcpl;      /* links made with their parent groups */
    hid_t ocpl;      /* objects made without modification times */
    hid_t str;       /* variable-length UTF-8 string type */
    char *path;
    int failed;
};

/* One file at a time: the dimension-scale calls of the high-level library and the
 * error-printing switch are process-wide. */
static pthread_mutex_t one_file = PTHREAD_MUTEX_INITIALIZER;

static int fail(tt_h5 *f, const char *what, const char *object)
{
    f->failed = 1;
    return tt_error(TT_EIO, "%s: cannot write HDF5: %s %s", f->path, what, object);
}

int tt_h5_create(tt_h5 **out, const char *path)
{
    *out = NULL;
    tt_h5 *f = calloc(1, sizeof *f);
    if (!f || !(f->path = tt_strdup(path))) {
        free(f);
        return tt_error_nomem("the HDF5 file %s", path);
    }
    f->file = f->lcpl = f->ocpl = f->str = -1;
    int rc = tt_outfile_open(&f->tmp, path);
    if (rc) {
        free(f->path);
        free(f);
        return rc;
    }
    pthread_mutex_lock(&one_file);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* failures are reported here, in one line */
    /* the temporary file exists (made without following links); HDF5 writes it anew */
    f->file = H5Fcreate(tt_outfile_tmpname(f->tmp), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    f->lcpl = H5Pcreate(H5P_LINK_CREATE);
    f->ocpl = H5Pcreate(H5P_DATASET_CREATE);
    f->str = H5Tcopy(H5T_C_S1);
    if (f->file < 0 || f->lcpl < 0 || f->ocpl < 0 || f->str < 0 ||
        H5Pset_create_intermediate_group(f->lcpl, 1) < 0 || H5Pset_obj_track_times(f->ocpl, 0) < 0 ||
        H5Pset_attr_creation_order(f->ocpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0 ||
        H5Tset_size(f->str, H5T_VARIABLE) < 0 || H5Tset_cset(f->str, H5T_CSET_UTF8) < 0) {
        rc = fail(f, "creating", "the file");
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
    int rc = f->failed ? TT_EIO : TT_OK;
    if (f->str >= 0)
        H5Tclose(f->str);
    if (f->ocpl >= 0)
        H5Pclose(f->ocpl);
    if (f->lcpl >= 0)
        H5Pclose(f->lcpl);
    if (f->file >= 0 && H5Fclose(f->file) < 0 && rc == TT_OK && keep)
        rc = fail(f, "closing", "the file");
    pthread_mutex_unlock(&one_file);
    int crc = tt_outfile_close(f->tmp, keep && rc == TT_OK);
    if (rc == TT_OK)
        rc = crc;
    free(f->path);
    free(f);
    return rc;
}

int tt_h5_group(tt_h5 *f, const char *path)
{
    if (H5Lexists(f->file, path, H5P_DEFAULT) > 0)
        return TT_OK;
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    /* attributes listed in the order written (h5py follows it) */
    hid_t g = gcpl < 0 || H5Pset_obj_track_times(gcpl, 0) < 0 ||
                      H5Pset_attr_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED) < 0
                  ? -1
                  : H5Gcreate2(f->file, path, f->lcpl, gcpl, H5P_DEFAULT);
    if (gcpl >= 0)
        H5Pclose(gcpl);
    if (g < 0)
        return fail(f, "the group", path);
    H5Gclose(g);
    return TT_OK;
}

/* Make the dataset path of type type and shape, write data, close it. */
static int dataset(tt_h5 *f, const char *path, hid_t type, int rank, const hsize_t *dims,
                   const void *data)
{
    hid_t space = rank > 0 ? H5Screate_simple(rank, dims, NULL) : H5Screate(H5S_SCALAR);
    hid_t d = space < 0 ? -1 : H5Dcreate2(f->file, path, type, space, f->lcpl, f->ocpl, H5P_DEFAULT);
    herr_t w = d < 0 ? -1 : H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    if (d >= 0)
        H5Dclose(d);
    if (space >= 0)
        H5Sclose(space);
    return w < 0 ? fail(f, "the dataset", path) : TT_OK;
}

/* dims as HDF5's type; -1 beyond HDF5's 32 dimensions. */
static int shape(int rank, const size_t *dims, hsize_t *d)
{
    if (rank < 0 || rank > 32)
        return -1;
    for (int i = 0; i < rank; i++)
        d[i] = dims[i];
    return 0;
}

int tt_h5_doubles(tt_h5 *f, const char *path, int rank, const size_t *dims, const double *data)
{
    hsize_t d[32];
    if (shape(rank, dims, d))
        return fail(f, "a rank beyond 32 for", path);
    return dataset(f, path, H5T_IEEE_F64LE, rank, d, data);
}

int tt_h5_text(tt_h5 *f, const char *path, const char *text)
{
    return dataset(f, path, f->str, 0, NULL, &text);
}

int tt_h5_texts(tt_h5 *f, const char *path, int rank, const size_t *dims, const char *const *texts)
{
    hsize_t d[32];
    if (shape(rank, dims, d))
        return fail(f, "a rank beyond 32 for", path);
    return dataset(f, path, f->str, rank, d, texts);
}

/* Attribute name of type type (a scalar) on object, written from value. */
static int attribute(tt_h5 *f, const char *object, const char *name, hid_t type, const void *value)
{
    hid_t space = H5Screate(H5S_SCALAR);
    if (space >= 0 && H5Aexists_by_name(f->file, object, name, H5P_DEFAULT) > 0)
        H5Adelete_by_name(f->file, object, name, H5P_DEFAULT);
    hid_t a = space < 0 ? -1
                        : H5Acreate_by_name(f->file, object, name, type, space, H5P_DEFAULT,
                                            H5P_DEFAULT, H5P_DEFAULT);
    herr_t w = a < 0 ? -1 : H5Awrite(a, type, value);
    if (a >= 0)
        H5Aclose(a);
    if (space >= 0)
        H5Sclose(space);
    if (w < 0) {
        char what[1200];
        snprintf(what, sizeof what, "%s of %s", name, object);
        return fail(f, "the attribute", what);
    }
    return TT_OK;
}

int tt_h5_attr_text(tt_h5 *f, const char *object, const char *name, const char *value)
{
    return attribute(f, object, name, f->str, &value);
}

int tt_h5_attr_double(tt_h5 *f, const char *object, const char *name, double value)
{
    return attribute(f, object, name, H5T_NATIVE_DOUBLE, &value);
}

int tt_h5_attr_long(tt_h5 *f, const char *object, const char *name, long value)
{
    return attribute(f, object, name, H5T_NATIVE_LONG, &value);
}

int tt_h5_scale(tt_h5 *f, const char *scale, const char *name)
{
    hid_t d = H5Dopen2(f->file, scale, H5P_DEFAULT);
    herr_t r = d < 0 ? -1 : H5DSset_scale(d, name);
    if (d >= 0)
        H5Dclose(d);
    return r < 0 ? fail(f, "the dimension scale", scale) : TT_OK;
}

int tt_h5_attach(tt_h5 *f, const char *data, const char *scale, unsigned dim, const char *label)
{
    hid_t d = H5Dopen2(f->file, data, H5P_DEFAULT), s = H5Dopen2(f->file, scale, H5P_DEFAULT);
    herr_t r = d < 0 || s < 0 || H5DSattach_scale(d, s, dim) < 0 ? -1 : H5DSset_label(d, dim, label);
    if (d >= 0)
        H5Dclose(d);
    if (s >= 0)
        H5Dclose(s);
    return r < 0 ? fail(f, "attaching a dimension scale to", data) : TT_OK;
}
