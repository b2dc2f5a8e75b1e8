/* tiptap: cairo surfaces written as PNG files, shared by the plots and the image
 * previews (internal to the io layer: it names cairo types).
 *
 * Ownership: the surface stays the caller's.
 */
#ifndef TIPTAP_PNG_INTERNAL_H
#define TIPTAP_PNG_INTERNAL_H

#include <cairo.h>
#include <stdio.h>

/* Write sf to path through a temporary file renamed into place (tt_outfile), so that
 * a failed write leaves no truncated PNG. TT_EIO with "path: cannot write: reason". */
int tt_png_write_surface(cairo_surface_t *sf, const char *path);

/* An RGB24 surface's PNG into f, the bytes cairo_surface_write_to_png_stream writes
 * through libpng 1.6 (src/io/png_encode.c), faster: 0, or -1 on a failure (errno or
 * zlib's), or 1 where it leaves the surface to cairo (another format, rows under 16 kB,
 * where libpng narrows zlib's window, or one pixel wide or high, where it tries fewer
 * filters) with nothing written. */
int tt_png_encode_rgb24(cairo_surface_t *sf, FILE *f);

#endif
