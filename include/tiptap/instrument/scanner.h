/* tiptap: the raster of a scan ([scan] section): where the tip is over the sample at
 * each drive cycle, for trace and retrace, and which pixel that cycle belongs to.
 *
 * The fast axis runs along x (or y) across the scan size in 1 / (2 line_rate) seconds
 * one way (trace) and as long back (retrace); the slow axis steps one line at a time
 * through line centres. The sample moves continuously: the position is evaluated at
 * every cycle, so height and material change within a pixel, as on an instrument.
 *
 * Plain struct, no ownership.
 */
#ifndef TIPTAP_SCANNER_H
#define TIPTAP_SCANNER_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct {
    double size_x, size_y;  /* m */
    long pixels, lines;     /* pixels per line along the fast axis; lines */
    double line_rate;       /* Hz: lines per second, each a trace and a retrace */
    int fast_y;             /* 1: the fast axis is y */
    int retrace;            /* 1: record the retrace too */
    /* the scan frame on the sample: rotated by angle (rad, counter-clockwise) about the
     * scan area's centre, then moved by offset (m); 0, 0, 0: the area [0, size]^2 */
    double angle, offset_x, offset_y;
} tt_raster;

/* Drive cycles one way along a line. */
long tt_raster_cycles_per_direction(const tt_raster *r, double period);

/* Tip position (m) over the sample at the start of cycle k (0 .. nc) of direction dir
 * (0 trace, 1 retrace) on a line. */
void tt_raster_position(const tt_raster *r, long line, int dir, long nc, long k, double *x,
                        double *y);
/* The tip's distance along the fast axis (m) from the trace's start, at the same cycle. */
double tt_raster_fast_position(const tt_raster *r, int dir, long nc, long k);
/* The box on the sample the scan visits: x0, y0, x1, y1 (m); the area [0, size] when the
 * frame is neither rotated nor moved. */
void tt_raster_bounds(const tt_raster *r, double *box);

/* Pixel (0 .. pixels - 1, counted along the trace) of cycle k of direction dir. */
long tt_raster_pixel(const tt_raster *r, int dir, long nc, long k);

/* Index into an image stored in the sample's orientation (see scan.h). */
long tt_raster_index(const tt_raster *r, long line, long pixel);

TT_END_DECLS
#endif
