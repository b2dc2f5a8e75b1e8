/* tiptap: PNG previews of image channels, with a colour map, a colour bar with its
 * unit and a scale bar, for a person to look at (the data live in the GSF files). */
#ifndef TIPTAP_IMAGE_H
#define TIPTAP_IMAGE_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* TT_CMAP_DIVERGING: white at zero, its range symmetric about it (error images) */
typedef enum { TT_CMAP_GOLD = 0, TT_CMAP_VIRIDIS, TT_CMAP_DIVERGING } tt_colormap;

typedef struct {
    size_t xres, yres;
    double xreal, yreal;  /* m, for the scale bar */
    const double *data;   /* row 0 = top; NaN drawn grey */
    const char *title;    /* "height (trace)" */
    const char *unit;     /* unit shown on the colour bar, e.g. "nm" */
    double unit_scale;    /* SI value * unit_scale = shown value (1e9 for nm) */
    tt_colormap cmap;
} tt_image;

int tt_image_write_png(const char *path, const tt_image *im);

TT_END_DECLS
#endif
