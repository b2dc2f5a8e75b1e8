/* Cairo surfaces to PNG files (see src/io/png_internal.h). */
#include "png_internal.h"

#include <stdio.h>
#include <string.h>

#include "tiptap/io/outfile.h"
#include "tiptap/util/error.h"

static cairo_status_t write_fn(void *closure, const unsigned char *data, unsigned int len)
{
    return fwrite(data, 1, len, (FILE *)closure) == len ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

int tt_png_write_surface(cairo_surface_t *sf, const char *path)
{
    tt_outfile *o;
    int rc = tt_outfile_open(&o, path);
    if (rc)
        return rc;
    int own = tt_png_encode_rgb24(sf, tt_outfile_stream(o));
    cairo_status_t st = own == 1 ? cairo_surface_write_to_png_stream(sf, write_fn, tt_outfile_stream(o))
                        : own ? CAIRO_STATUS_WRITE_ERROR : CAIRO_STATUS_SUCCESS;
    if (st != CAIRO_STATUS_SUCCESS) {
        int e = tt_outfile_errno(o);
        tt_outfile_close(o, 0);
        return tt_error(TT_EIO, "%s: cannot write: %s", path,
                        e ? strerror(e) : cairo_status_to_string(st));
    }
    return tt_outfile_close(o, 1);
}
