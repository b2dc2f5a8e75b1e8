/* The raster of a scan: timing and tip position (see include/tiptap/instrument/scanner.h). */
#include "tiptap/instrument/scanner.h"

#include <math.h>

long tt_raster_cycles_per_direction(const tt_raster *r, double period)
{
    long n = lround(1.0 / (2.0 * r->line_rate * period));
    return n < r->pixels ? r->pixels : n;
}

void tt_raster_position(const tt_raster *r, long line, int dir, long nc, long k, double *x,
                        double *y)
{
    double fast_size = r->fast_y ? r->size_y : r->size_x;
    double slow_size = r->fast_y ? r->size_x : r->size_y;
    double f = (double)k / (double)nc;
    double u = fast_size * (dir ? 1.0 - f : f);
    double v = slow_size * ((double)line + 0.5) / (double)r->lines;
    *x = r->fast_y ? v : u;
    *y = r->fast_y ? u : v;
    if (r->angle != 0) { /* about the area's centre; unrotated scans keep their bits */
        double cx = 0.5 * r->size_x, cy = 0.5 * r->size_y, c = cos(r->angle), s = sin(r->angle);
        double dx = *x - cx, dy = *y - cy;
        *x = cx + c * dx - s * dy;
        *y = cy + s * dx + c * dy;
    }
    *x += r->offset_x;
    *y += r->offset_y;
}

double tt_raster_fast_position(const tt_raster *r, int dir, long nc, long k)
{
    double f = (double)k / (double)nc;
    return (r->fast_y ? r->size_y : r->size_x) * (dir ? 1.0 - f : f);
}

void tt_raster_bounds(const tt_raster *r, double *box)
{
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (int i = 0; i < 4; i++) {
        double x = (i & 1) * r->size_x, y = (i >> 1) * r->size_y;
        if (r->angle != 0) {
            double cx = 0.5 * r->size_x, cy = 0.5 * r->size_y, c = cos(r->angle), s = sin(r->angle);
            double dx = x - cx, dy = y - cy;
            x = cx + c * dx - s * dy;
            y = cy + s * dx + c * dy;
        }
        box[0] = fmin(box[0], x + r->offset_x);
        box[1] = fmin(box[1], y + r->offset_y);
        box[2] = fmax(box[2], x + r->offset_x);
        box[3] = fmax(box[3], y + r->offset_y);
    }
}

long tt_raster_pixel(const tt_raster *r, int dir, long nc, long k)
{
    long p = (long)((double)k * (double)r->pixels / (double)nc);
    if (p >= r->pixels)
        p = r->pixels - 1;
    if (p < 0)
        p = 0;
    return dir ? r->pixels - 1 - p : p;
}

long tt_raster_index(const tt_raster *r, long line, long pixel)
{
    return r->fast_y ? pixel * r->lines + line : line * r->pixels + pixel;
}
