/* tiptap: line plots with axes, ticks, labels and a legend, written as PNG (cairo).
 *
 * A figure has one or more panels stacked vertically sharing nothing but the width;
 * each panel has its own axes and series. NaN in a series breaks the line (a gap).
 *
 * Ownership: the figure copies the data and strings it is given; the caller frees the
 * figure with tt_figure_free.
 */
#ifndef TIPTAP_PLOT_H
#define TIPTAP_PLOT_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

enum {
    TT_PLOT_COLOR_MASK = 0xff, /* low bits: colour index (0 = next in the palette) */
    TT_PLOT_DASHED = 1 << 8,
    TT_PLOT_POINTS = 1 << 9,   /* markers instead of a line */
    TT_PLOT_RIGHT = 1 << 10,   /* against the panel's right-hand axis */
    TT_PLOT_THICK = 1 << 11
};

typedef struct tt_figure tt_figure;

tt_figure *tt_figure_alloc(int panels, const char *title);
void tt_figure_free(tt_figure *f);

int tt_figure_axes(tt_figure *f, int panel, const char *xlabel, const char *ylabel);
/* A right-hand axis for series drawn with TT_PLOT_RIGHT. */
int tt_figure_axis_right(tt_figure *f, int panel, const char *ylabel);
/* Axis limits; NaN for automatic. */
int tt_figure_xlim(tt_figure *f, int panel, double lo, double hi);
int tt_figure_ylim(tt_figure *f, int panel, double lo, double hi);
int tt_figure_log(tt_figure *f, int panel, int logx, int logy);
/* Add a series; label NULL for none (no legend entry). style: TT_PLOT_* flags. */
int tt_figure_line(tt_figure *f, int panel, const double *x, const double *y, size_t n,
                   const char *label, unsigned style);
/* A vertical or horizontal reference line across the panel. */
int tt_figure_vline(tt_figure *f, int panel, double x, const char *label);
int tt_figure_hline(tt_figure *f, int panel, double y, const char *label);

/* A short note at data point (x, y), drawn just right of and above it (labels of
 * points, such as the setting a work-precision point stands for). */
int tt_figure_text(tt_figure *f, int panel, double x, double y, const char *text);

/* Render to PNG through a temporary file (see outfile.h). */
int tt_figure_write_png(const tt_figure *f, const char *path, int width, int height);

TT_END_DECLS
#endif
