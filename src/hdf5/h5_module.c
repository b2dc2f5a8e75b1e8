/* The HDF5 module (see src/io/hdf5_module.h): libhdf5 and its high-level dimension
 * scales behind a table of calls, loaded by src/io/hdf5.c on the first HDF5 file.
 * Objects are made without modification times (the same data give the same bytes) and
 * list their attributes in the order written; texts are variable-length UTF-8. */
#include <hdf5.h>
#include <hdf5_hl.h>
#include <stdlib.h>

#include "io/hdf5_module.h"

struct tt_h5_file {
    hid_t file;
    hid_t lcpl; /* links made with their parent groups */
    hid_t ocpl; /* datasets: no times, attributes in creation order */
    hid_t gcpl; /* groups: the same */
    hid_t str;  /* variable-length UTF-8 string type */
};

static int h5_close(tt_h5_file *f)
{
    int bad = 0;
    if (f->str >= 0)
        H5Tclose(f->str);
    if (f->gcpl >= 0)
        H5Pclose(f->gcpl);
    if (f->ocpl >= 0)
        H5Pclose(f->ocpl);
    if (f->lcpl >= 0)
        H5Pclose(f->lcpl);
    if (f->file >= 0 && H5Fclose(f->file) < 0)
        bad = 1;
    free(f);
    return bad ? -1 : 0;
}

static tt_h5_file *h5_create(const char *path)
{
    const unsigned order = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
    tt_h5_file *f = malloc(sizeof *f);
    if (!f)
        return NULL;
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* failures are told by the caller, in one line */
    f->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    f->lcpl = H5Pcreate(H5P_LINK_CREATE);
    f->ocpl = H5Pcreate(H5P_DATASET_CREATE);
    f->gcpl = H5Pcreate(H5P_GROUP_CREATE);
    f->str = H5Tcopy(H5T_C_S1);
    if (f->file < 0 || f->lcpl < 0 || f->ocpl < 0 || f->gcpl < 0 || f->str < 0 ||
        H5Pset_create_intermediate_group(f->lcpl, 1) < 0 || H5Pset_obj_track_times(f->ocpl, 0) < 0 ||
        H5Pset_attr_creation_order(f->ocpl, order) < 0 || H5Pset_obj_track_times(f->gcpl, 0) < 0 ||
        H5Pset_attr_creation_order(f->gcpl, order) < 0 || H5Tset_size(f->str, H5T_VARIABLE) < 0 ||
        H5Tset_cset(f->str, H5T_CSET_UTF8) < 0) {
        h5_close(f);
        return NULL;
    }
    return f;
}

static int h5_group(tt_h5_file *f, const char *path)
{
    if (H5Lexists(f->file, path, H5P_DEFAULT) > 0)
        return 0;
    hid_t g = H5Gcreate2(f->file, path, f->lcpl, f->gcpl, H5P_DEFAULT);
    if (g < 0)
        return -1;
    H5Gclose(g);
    return 0;
}

/* Make the dataset path of type type and shape, write data, close it. */
static int dataset(tt_h5_file *f, const char *path, hid_t type, int rank, const size_t *dims,
                   const void *data)
{
    hsize_t d[32];
    if (rank < 0 || rank > 32)
        return -1;
    for (int i = 0; i < rank; i++)
        d[i] = dims[i];
    hid_t space = rank > 0 ? H5Screate_simple(rank, d, NULL) : H5Screate(H5S_SCALAR);
    hid_t s = space < 0 ? -1 : H5Dcreate2(f->file, path, type, space, f->lcpl, f->ocpl, H5P_DEFAULT);
    herr_t w = s < 0 ? -1 : H5Dwrite(s, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    if (s >= 0)
        H5Dclose(s);
    if (space >= 0)
        H5Sclose(space);
    return w < 0 ? -1 : 0;
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
    hid_t space = H5Screate(H5S_SCALAR);
    if (space >= 0 && H5Aexists_by_name(f->file, object, name, H5P_DEFAULT) > 0)
        H5Adelete_by_name(f->file, object, name, H5P_DEFAULT);
    hid_t a = space < 0 ? -1
                        : H5Acreate_by_name(f->file, object, name, t, space, H5P_DEFAULT, H5P_DEFAULT,
                                            H5P_DEFAULT);
    herr_t w = a < 0 ? -1 : H5Awrite(a, t, value);
    if (a >= 0)
        H5Aclose(a);
    if (space >= 0)
        H5Sclose(space);
    return w < 0 ? -1 : 0;
}

static int h5_scale(tt_h5_file *f, const char *path, const char *name)
{
    hid_t d = H5Dopen2(f->file, path, H5P_DEFAULT);
    herr_t r = d < 0 ? -1 : H5DSset_scale(d, name);
    if (d >= 0)
        H5Dclose(d);
    return r < 0 ? -1 : 0;
}

static int h5_attach(tt_h5_file *f, const char *data, const char *scale, unsigned dim, const char *label)
{
    hid_t d = H5Dopen2(f->file, data, H5P_DEFAULT), s = H5Dopen2(f->file, scale, H5P_DEFAULT);
    herr_t r = d < 0 || s < 0 || H5DSattach_scale(d, s, dim) < 0 ? -1 : H5DSset_label(d, dim, label);
    if (d >= 0)
        H5Dclose(d);
    if (s >= 0)
        H5Dclose(s);
    return r < 0 ? -1 : 0;
}

const tt_h5_ops *tt_h5_module(void)
{
    static const tt_h5_ops ops = {TT_H5_MODULE_VERSION, h5_create, h5_close, h5_group, h5_doubles,
                                  h5_texts, h5_attr, h5_scale, h5_attach};
    return &ops;
}
