/* tiptap: Gwyddion Simple Field (.gsf) files.
 *
 * Layout (gwyddion.net/documentation/user-guide-en/gsf.html): the line
 * "Gwyddion Simple Field 1.0\n", "Key = Value\n" header lines, then 1 to 4 NUL bytes
 * so that the binary part starts at a multiple of 4, then XRes * YRes little-endian
 * IEEE float32 values, row by row, the first row at the top of the image.
 * Numbers in the header are written in the C locale; units are SI ("m", "deg", "N", "J").
 */
#ifndef TIPTAP_GSF_H
#define TIPTAP_GSF_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct {
    size_t xres, yres;
    double xreal, yreal;        /* physical size, m */
    double xoffset, yoffset;    /* m */
    const char *xyunits;        /* "m" */
    const char *zunits;         /* "m", "deg", "N", "J", ... */
    const char *title;
    const double *data;         /* xres * yres values, row 0 = top row; NaN allowed */
    const char *const *keys;    /* extra header keys (run parameters), may be NULL */
    const char *const *values;
    size_t nextra;
} tt_gsf_field;

/* Write through a temporary file (outfile.h). */
int tt_gsf_write(const char *path, const tt_gsf_field *field);

/* Read a GSF file (for tests): allocates *data (xres*yres doubles, caller frees). */
int tt_gsf_read(const char *path, size_t *xres, size_t *yres, double *xreal, double *yreal,
                double **data);

TT_END_DECLS
#endif
