/* A scan's NeXus entry (NXafm) in the HDF5 file beside its NSID measurement
 * (docs/hdf5.md), private to the library: src/instrument/scan_nexus.c. */
#ifndef TIPTAP_SCAN_NEXUS_H
#define TIPTAP_SCAN_NEXUS_H

#include <stddef.h>

#include "tiptap/instrument/scan.h"
#include "tiptap/io/hdf5.h"

/* The group entry (NXentry, definition NXafm) of an open file: the scene's n metadata
 * pairs mapped onto NXafm's instrument, cantilever, lock-in, z controller, scan region
 * and sample, and an NXdata whose images are links to measurement's channels (written
 * before, in tt_scan_hdf5_group's order), stored once. */
int tt_scan_nexus_entry(tt_h5 *f, const char *entry, const char *measurement, const tt_scan *s,
                        const char *const *keys, const char *const *values, size_t n);

#endif
