/* tiptap: HDF5 files (libhdf5), written the no-half-written-file way.
 *
 * A small writer of what tiptap's HDF5 files hold (docs/hdf5.md): groups, float64
 * datasets of any rank, text datasets, attributes (text, numbers), and dimension scales
 * (HDF5's H5DS convention, which h5py shows as dataset.dims). Paths are absolute inside
 * the file ("/Measurement_000/Channel_000/height_trace"); groups are made with their
 * parents. The file is written under a temporary name beside the target
 * (tiptap/io/outfile.h) and renamed into place by tt_h5_close with keep = 1, so a run
 * that fails or is stopped leaves no truncated file. libhdf5 makes the file in memory
 * and tt_h5_close writes it (libhdf5 1.10 crashed at exit after a failed write of its
 * own): a failed write is "path: cannot write: reason" ("File too large", "No space
 * left on device"), as for every output; the file is held in memory twice at the end. Objects carry no modification
 * times, so that the same data give the same bytes, and list their attributes in the
 * order written. Texts are variable-length UTF-8 strings (h5py reads attributes as str,
 * datasets as bytes: dataset.asstr()).
 *
 * HDF5's high-level library (the dimension scales) is not thread-safe: one file is
 * written at a time in the process (tt_h5_create waits for the previous tt_h5_close).
 *
 * Ownership: the tt_h5 belongs to the library until tt_h5_close, which frees it
 * whatever it returns. Every failure is TT_EIO: "path: cannot write: reason" for a
 * failed write, else "path: cannot write HDF5: WHAT OBJECT: HDF5's words".
 */
#ifndef TIPTAP_HDF5_H
#define TIPTAP_HDF5_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct tt_h5 tt_h5;

/* Fails as tt_outfile_open does (an unwritable folder, a folder, pipe or device at
 * path, an input of the run). */
int tt_h5_create(tt_h5 **out, const char *path);
/* keep = 1: write the file, close and rename it into place; 0: remove the temporary
 * file. After a failed call nothing more is written and keep = 1 returns TT_EIO. */
int tt_h5_close(tt_h5 *f, int keep);

int tt_h5_group(tt_h5 *f, const char *path);
/* rank dimensions dims[0..rank) (C order), rank * ... values; rank 0 is a scalar. */
int tt_h5_doubles(tt_h5 *f, const char *path, int rank, const size_t *dims, const double *data);
/* One text, or texts in rank dimensions dims[0..rank) (labels of a dimension, a table's
 * text column over a grid; NULL texts are ""). */
int tt_h5_text(tt_h5 *f, const char *path, const char *text);
int tt_h5_texts(tt_h5 *f, const char *path, int rank, const size_t *dims, const char *const *texts);

/* Attributes of the group or dataset at object. */
int tt_h5_attr_text(tt_h5 *f, const char *object, const char *name, const char *value);
int tt_h5_attr_double(tt_h5 *f, const char *object, const char *name, double value);
int tt_h5_attr_long(tt_h5 *f, const char *object, const char *name, long value);

/* Make the one-dimensional dataset at scale a dimension scale named name, and attach
 * it to dimension dim of the dataset at data, labelling that dimension. */
int tt_h5_scale(tt_h5 *f, const char *scale, const char *name);
int tt_h5_attach(tt_h5 *f, const char *data, const char *scale, unsigned dim, const char *label);

/* A one-dimensional attribute of n texts. */
int tt_h5_attr_texts(tt_h5 *f, const char *object, const char *name, size_t n, const char *const *texts);

/* A second name, path, for the existing object at target (a hard link: stored once). */
int tt_h5_link(tt_h5 *f, const char *target, const char *path);

TT_END_DECLS
#endif
