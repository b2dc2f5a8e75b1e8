/* PNG previews of image channels with colour bar and scale bar, via cairo
 * (see include/tiptap/io/image.h). */
#include "tiptap/io/image.h"

#include <cairo.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "png_internal.h"

/* Colour maps as a few anchors, interpolated linearly. */
static void cmap(tt_colormap m, double t, double *r, double *g, double *b)
{
    static const double gold[][3] = {{0, 0, 0}, {0.5, 0.2, 0.05}, {0.85, 0.55, 0.15}, {1, 0.85, 0.5}, {1, 1, 1}};
    static const double viridis[][3] = {{0.267, 0.005, 0.329}, {0.229, 0.322, 0.546}, {0.128, 0.567, 0.551},
                                        {0.369, 0.789, 0.383}, {0.993, 0.906, 0.144}};
    static const double div[][3] = {{0.23, 0.30, 0.75}, {0.55, 0.69, 1.0}, {0.87, 0.87, 0.87},
                                    {0.96, 0.6, 0.49}, {0.71, 0.02, 0.15}};
    const double(*a)[3] = m == TT_CMAP_VIRIDIS ? viridis : m == TT_CMAP_DIVERGING ? div : gold;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double u = t * 4;
    int i = (int)u;
    if (i > 3)
        i = 3;
    double f = u - i;
    *r = a[i][0] + f * (a[i + 1][0] - a[i][0]);
    *g = a[i][1] + f * (a[i + 1][1] - a[i][1]);
    *b = a[i][2] + f * (a[i + 1][2] - a[i][2]);
}

static double nice(double span)
{
    double raw = span / 5, mag = pow(10, floor(log10(raw))), r = raw / mag;
    return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * mag;
}

int tt_image_write_png(const char *path, const tt_image *im)
{
    if (!im->xres || !im->yres || !im->data)
        return tt_error(TT_EINVAL, "%s: empty image", path);
    double lo = INFINITY, hi = -INFINITY;
    size_t n = im->xres * im->yres;
    for (size_t i = 0; i < n; i++)
        if (isfinite(im->data[i])) {
            lo = fmin(lo, im->data[i] * im->unit_scale);
            hi = fmax(hi, im->data[i] * im->unit_scale);
        }
    if (!isfinite(lo)) {
        lo = 0;
        hi = 1;
    }
    /* a diverging map's middle colour (white) means zero: its range is symmetric */
    if (im->cmap == TT_CMAP_DIVERGING) {
        hi = fmax(fabs(lo), fabs(hi));
        lo = -hi;
    }
    if (hi - lo < 1e-12 * fmax(1, fabs(hi))) {
        lo -= 0.5;
        hi += 0.5;
    }
    /* the image area: at least 512 px on its longer side, square pixels */
    double aspect = im->yreal / im->xreal;
    int W = 512, H = (int)lrint(512 * aspect);
    if (H > 768) {
        H = 768;
        W = (int)lrint(768 / aspect);
    }
    int ml = 20, mt = 50, mb = 60, bar = 24, mr = 130;
    int width = ml + W + 20 + bar + mr, height = mt + H + mb;
    cairo_surface_t *data = cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)im->xres, (int)im->yres);
    unsigned char *px = cairo_image_surface_get_data(data);
    int stride = cairo_image_surface_get_stride(data);
    for (size_t j = 0; j < im->yres; j++)
        for (size_t i = 0; i < im->xres; i++) {
            double v = im->data[j * im->xres + i] * im->unit_scale, r = 0.5, g = 0.5, b = 0.5;
            if (isfinite(v))
                cmap(im->cmap, (v - lo) / (hi - lo), &r, &g, &b);
            uint32_t c = (uint32_t)lrint(r * 255) << 16 | (uint32_t)lrint(g * 255) << 8 | (uint32_t)lrint(b * 255);
            memcpy(px + j * (size_t)stride + 4 * i, &c, 4);
        }
    cairo_surface_mark_dirty(data);
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t *cr = cairo_create(sf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_save(cr);
    cairo_translate(cr, ml, mt);
    cairo_scale(cr, (double)W / im->xres, (double)H / im->yres);
    cairo_set_source_surface(cr, data, 0, 0);
    cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
    cairo_paint(cr);
    cairo_restore(cr);
    /* a frame, so that an image whose edge colour is white still shows where it ends */
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, ml - 0.5, mt - 0.5, W + 1, H + 1);
    cairo_stroke(cr);
    /* title */
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_font_size(cr, 18);
    cairo_move_to(cr, ml, 30);
    cairo_show_text(cr, im->title ? im->title : "");
    /* colour bar with ticks in the display unit */
    int bx = ml + W + 20;
    for (int y = 0; y < H; y++) {
        double r, g, b;
        cmap(im->cmap, 1 - (y + 0.5) / H, &r, &g, &b);
        cairo_set_source_rgb(cr, r, g, b);
        cairo_rectangle(cr, bx, mt + y, bar, 1);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, bx + 0.5, mt + 0.5, bar, H);
    cairo_stroke(cr);
    cairo_set_font_size(cr, 13);
    double step = nice(hi - lo);
    char buf[64];
    for (double v = ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) {
        double y = mt + H * (1 - (v - lo) / (hi - lo));
        cairo_move_to(cr, bx + bar, y);
        cairo_line_to(cr, bx + bar + 5, y);
        cairo_stroke(cr);
        snprintf(buf, sizeof buf, "%.4g", fabs(v) < 1e-9 * step ? 0.0 : v);
        cairo_move_to(cr, bx + bar + 8, y + 4);
        cairo_show_text(cr, buf);
    }
    cairo_move_to(cr, bx, mt + H + 20);
    cairo_show_text(cr, im->unit ? im->unit : "");
    /* scale bar: a round length about a fifth of the width */
    double len = im->xreal / 5, mag = pow(10, floor(log10(len))), r = len / mag;
    len = (r < 2 ? 1 : r < 5 ? 2 : 5) * mag;
    double lpx = len / im->xreal * W;
    cairo_set_line_width(cr, 4);
    cairo_move_to(cr, ml, mt + H + 25);
    cairo_line_to(cr, ml + lpx, mt + H + 25);
    cairo_stroke(cr);
    if (len >= 1e-6)
        snprintf(buf, sizeof buf, "%g um", len * 1e6);
    else
        snprintf(buf, sizeof buf, "%g nm", len * 1e9);
    cairo_move_to(cr, ml, mt + H + 48);
    cairo_show_text(cr, buf);
    cairo_destroy(cr);
    cairo_surface_destroy(data);
    int rc = tt_png_write_surface(sf, path);
    cairo_surface_destroy(sf);
    return rc;
}
