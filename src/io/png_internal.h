/* tiptap: cairo surfaces written as PNG files, shared by the plots and the image
 * previews (internal to the io layer: it names cairo types).
 *
 * Ownership: the surface stays the caller's.
 */
#ifndef TIPTAP_PNG_INTERNAL_H
#define TIPTAP_PNG_INTERNAL_H

#include <cairo.h>

/* Write sf to path through a temporary file renamed into place (tt_outfile), so that
 * a failed write leaves no truncated PNG. TT_EIO with "path: cannot write: reason". */
int tt_png_write_surface(cairo_surface_t *sf, const char *path);

#endif
