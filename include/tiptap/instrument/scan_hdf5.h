/* tiptap: a scan as HDF5 (docs/hdf5.md): every channel trace and retrace as a float64
 * dataset (lines along y, pixels along x, row 0 at y = 0) with x and y as dimension
 * scales in metres, the run's parameters and figures as attributes, the effective scene
 * as text, in the layout of pycroscopy's NSID files (Measurement_NNN/Channel_NNN).
 *
 * Ownership: everything is borrowed for the call.
 */
#ifndef TIPTAP_SCAN_HDF5_H
#define TIPTAP_SCAN_HDF5_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/io/hdf5.h"

TT_BEGIN_DECLS

/* The scan as the group at group ("/Measurement_000") of an open file: n metadata
 * pairs (tiptap/config/meta.h: the version, lines finished and every scene key) as
 * the group's attributes, with the run's figures; scene: the effective scene's text
 * (NULL: none). */
int tt_scan_hdf5_group(tt_h5 *f, const char *group, const tt_scan *s, const char *const *keys,
                       const char *const *values, size_t n, const char *scene);

/* A file holding the one scan as /Measurement_000, written under a temporary name and
 * renamed into place. */
int tt_scan_write_hdf5(const char *path, const tt_scan *s, const char *const *keys,
                       const char *const *values, size_t n, const char *scene);

TT_END_DECLS
#endif
