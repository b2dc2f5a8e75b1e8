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
