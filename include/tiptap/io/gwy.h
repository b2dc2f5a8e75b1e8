/* tiptap: Gwyddion native files (.gwy): every channel of a scan in one file.
 *
 * Layout (gwyddion.net/documentation/user-guide-en/gwyfile-format.html): the magic
 * "GWYP", then one serialised GwyContainer. A serialised object is its type name
 * (NUL-terminated), the size of its components in bytes (uint32, little-endian) and the
 * components, each a name (NUL-terminated), a type letter and the value: 'i' int32,
 * 'd' double, 's' NUL-terminated string, 'o' an object, 'D' uint32 count and doubles;
 * all numbers little-endian. The container holds, for channel N, "/N/data" (a
 * GwyDataField: xres, yres, xreal, yreal, xoff, yoff, si_unit_xy and si_unit_z as
 * GwySIUnit objects with "unitstr", data row by row, the first row at the top),
 * "/N/data/title" and "/N/meta" (a GwyContainer of strings: the run's parameters,
 * which Gwyddion shows in its metadata browser).
 *
 * Ownership: the writer copies nothing and keeps nothing; tt_gwy_read allocates a
 * tt_gwy_file the caller frees with tt_gwy_file_free.
 */
#ifndef TIPTAP_GWY_H
#define TIPTAP_GWY_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct {
    const char *title;
    size_t xres, yres;
    double xreal, yreal;      /* physical size, m */
    double xoffset, yoffset;  /* m */
    const char *xyunits;      /* "m" */
    const char *zunits;       /* "m", "deg", "N", "J", ... */
    const double *data;       /* xres * yres values, row 0 = top row; NaN allowed */
} tt_gwy_channel;

/* The title of a scan channel's image in a .gwy file, by which TopoStats and AFMReader
 * select it (an exact match with the title string): the channel's name with a capital
 * and spaces for underscores, "Height" for the height trace (TopoStats' default
 * channel) and "Height (retrace)" for its retrace; "Peak force", "Harmonic2 phase".
 * Writes at most n bytes to out, NUL-terminated; returns out. */
char *tt_gwy_title(char *out, size_t n, const char *channel, int retrace);

/* Write n channels, each with the same metadata (nmeta key/value strings), through a
 * temporary file (outfile.h). */
int tt_gwy_write(const char *path, const tt_gwy_channel *ch, size_t n, const char *const *keys,
                 const char *const *values, size_t nmeta);

/* What tt_gwy_read found: the channels (0, 1, ... in order) and channel 0's metadata. */
typedef struct {
    size_t nch;
    struct tt_gwy_read_channel {
        char *title, *xyunits, *zunits;
        size_t xres, yres;
        double xreal, yreal;
        double *data;
        size_t ndata;           /* values stored: xres * yres in a sound file */
    } *ch;
    size_t nmeta;
    char **keys, **values;
} tt_gwy_file;

/* Read a file written as above (for tests and tools): TT_EIO naming what is wrong. */
int tt_gwy_read(const char *path, tt_gwy_file **out);
void tt_gwy_file_free(tt_gwy_file *f);

TT_END_DECLS
#endif
