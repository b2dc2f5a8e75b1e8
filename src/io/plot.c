/* Line plots with axes, ticks, labels and a legend, rendered with cairo
 * (see include/tiptap/io/plot.h). */
#include "tiptap/io/plot.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "tiptap/util/str.h"
#include "png_internal.h"

#define MAX_PANELS 8

typedef struct {
    double *x, *y;
    size_t n;
    char *label;
    unsigned style;
} series;

typedef struct {
    double x, y;
    char *text;
} note;

typedef struct {
    char *xlabel, *ylabel, *y2label;
    double xlo, xhi, ylo, yhi;
    int logx, logy;
    series *s;
    size_t ns;
    double *vl, *hl;
    size_t nv, nh;
    note *notes;
    size_t nnotes;
} panel;

struct tt_figure {
    char *title;
    int npanels;
    panel p[MAX_PANELS];
};

/* Okabe-Ito: distinguishable by colour-blind readers. */
static const double palette[][3] = {
    {0.00, 0.45, 0.70}, {0.84, 0.37, 0.00}, {0.00, 0.62, 0.45}, {0.80, 0.47, 0.65},
    {0.34, 0.71, 0.91}, {0.90, 0.62, 0.00}, {0.20, 0.20, 0.20}, {0.94, 0.89, 0.26},
};

tt_figure *tt_figure_alloc(int panels, const char *title)
{
    if (panels < 1 || panels > MAX_PANELS)
        return NULL;
    tt_figure *f = calloc(1, sizeof *f);
    if (!f)
        return NULL;
    f->npanels = panels;
    f->title = tt_strdup(title);
    for (int i = 0; i < panels; i++)
        f->p[i].xlo = f->p[i].xhi = f->p[i].ylo = f->p[i].yhi = NAN;
    return f;
}

void tt_figure_free(tt_figure *f)
{
    if (!f)
        return;
    for (int i = 0; i < f->npanels; i++) {
        panel *p = &f->p[i];
        for (size_t k = 0; k < p->ns; k++) {
            free(p->s[k].x);
            free(p->s[k].y);
            free(p->s[k].label);
        }
        free(p->s);
        free(p->xlabel);
        free(p->ylabel);
        free(p->y2label);
        free(p->vl);
        free(p->hl);
        for (size_t k = 0; k < p->nnotes; k++)
            free(p->notes[k].text);
        free(p->notes);
    }
    free(f->title);
    free(f);
}

static panel *get(tt_figure *f, int i) { return (f && i >= 0 && i < f->npanels) ? &f->p[i] : NULL; }

int tt_figure_axes(tt_figure *f, int i, const char *xlabel, const char *ylabel)
{
    panel *p = get(f, i);
    if (!p)
        return tt_error(TT_EINVAL, "plot: no panel %d", i);
    free(p->xlabel);
    free(p->ylabel);
    p->xlabel = tt_strdup(xlabel);
    p->ylabel = tt_strdup(ylabel);
    return TT_OK;
}

int tt_figure_axis_right(tt_figure *f, int i, const char *ylabel)
{
    panel *p = get(f, i);
    if (!p)
        return tt_error(TT_EINVAL, "plot: no panel %d", i);
    free(p->y2label);
    p->y2label = tt_strdup(ylabel);
    return TT_OK;
}

int tt_figure_xlim(tt_figure *f, int i, double lo, double hi)
{
    panel *p = get(f, i);
    if (!p)
        return tt_error(TT_EINVAL, "plot: no panel %d", i);
    p->xlo = lo;
    p->xhi = hi;
    return TT_OK;
}

int tt_figure_ylim(tt_figure *f, int i, double lo, double hi)
{
    panel *p = get(f, i);
    if (!p)
        return tt_error(TT_EINVAL, "plot: no panel %d", i);
    p->ylo = lo;
    p->yhi = hi;
    return TT_OK;
}

int tt_figure_log(tt_figure *f, int i, int logx, int logy)
{
    panel *p = get(f, i);
    if (!p)
        return tt_error(TT_EINVAL, "plot: no panel %d", i);
    p->logx = logx;
    p->logy = logy;
    return TT_OK;
}

int tt_figure_line(tt_figure *f, int i, const double *x, const double *y, size_t n, const char *label,
                   unsigned style)
{
    panel *p = get(f, i);
    if (!p)
        return tt_error(TT_EINVAL, "plot: no panel %d", i);
    series *ns = realloc(p->s, (p->ns + 1) * sizeof *ns);
    if (!ns)
        return tt_error_nomem("a plot's lines");
    p->s = ns;
    series *s = &p->s[p->ns];
    memset(s, 0, sizeof *s);
    s->x = malloc((n ? n : 1) * sizeof(double));
    s->y = malloc((n ? n : 1) * sizeof(double));
    if (!s->x || !s->y) {
        free(s->x);
        free(s->y);
        return tt_error_nomem("a plot line of %zu points", n);
    }
    if (n) {
        memcpy(s->x, x, n * sizeof(double));
        memcpy(s->y, y, n * sizeof(double));
    }
    s->n = n;
    s->label = tt_strdup(label);
    if ((style & TT_PLOT_COLOR_MASK) == 0)
        style |= (unsigned)(p->ns % 8) + 1;
    s->style = style;
    p->ns++;
    return TT_OK;
}

static int add_ref(double **arr, size_t *n, double v)
{
    double *a = realloc(*arr, (*n + 1) * sizeof *a);
    if (!a)
        return tt_error_nomem("a plot's reference lines");
    a[(*n)++] = v;
    *arr = a;
    return TT_OK;
}

int tt_figure_vline(tt_figure *f, int i, double x, const char *label)
{
    (void)label;
    panel *p = get(f, i);
    return p ? add_ref(&p->vl, &p->nv, x) : tt_error(TT_EINVAL, "plot: no panel %d", i);
}

int tt_figure_hline(tt_figure *f, int i, double y, const char *label)
{
    (void)label;
    panel *p = get(f, i);
    return p ? add_ref(&p->hl, &p->nh, y) : tt_error(TT_EINVAL, "plot: no panel %d", i);
}

int tt_figure_text(tt_figure *f, int i, double x, double y, const char *text)
{
    panel *p = get(f, i);
    if (!p)
        return tt_error(TT_EINVAL, "plot: no panel %d", i);
    note *n = realloc(p->notes, (p->nnotes + 1) * sizeof *n);
    if (!n)
        return tt_error_nomem("a plot's notes");
    p->notes = n;
    n[p->nnotes].x = x;
    n[p->nnotes].y = y;
    n[p->nnotes].text = tt_strdup(text);
    if (!n[p->nnotes].text)
        return tt_error_nomem("a plot's notes");
    p->nnotes++;
    return TT_OK;
}

/* ---- rendering ---- */

typedef struct {
    double lo, hi;
    int log;
} axis;

static double tf(const axis *a, double v) { return a->log ? log10(v) : v; }

/* Data range of a panel's series on one side (right = 0/1) and coordinate (0 x, 1 y). */
static void range(const panel *p, int coord, int right, int logscale, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t k = 0; k < p->ns; k++) {
        const series *s = &p->s[k];
        if (coord == 1 && (!!(s->style & TT_PLOT_RIGHT)) != right)
            continue;
        const double *v = coord ? s->y : s->x;
        for (size_t i = 0; i < s->n; i++) {
            double x = v[i];
            if (!isfinite(x) || (logscale && x <= 0))
                continue;
            if (x < *lo)
                *lo = x;
            if (x > *hi)
                *hi = x;
        }
    }
    if (!isfinite(*lo)) {
        *lo = logscale ? 1 : 0;
        *hi = logscale ? 10 : 1;
    }
}

static void nice_axis(axis *a, double lo, double hi, double flo, double fhi, int logscale)
{
    a->log = logscale;
    if (isfinite(flo))
        lo = flo;
    if (isfinite(fhi))
        hi = fhi;
    if (logscale) {
        /* a little room, so that a value on a decade is not drawn on the frame */
        lo = floor(log10(lo) - 0.02);
        hi = ceil(log10(hi) + 0.02);
        if (hi <= lo)
            hi = lo + 1;
        a->lo = pow(10, lo);
        a->hi = pow(10, hi);
        return;
    }
    if (hi <= lo) {
        double d = fabs(lo) > 0 ? 0.1 * fabs(lo) : 1;
        lo -= d;
        hi += d;
    } else if (!isfinite(flo) && !isfinite(fhi)) {
        double pad = 0.04 * (hi - lo);
        lo -= pad;
        hi += pad;
    }
    a->lo = lo;
    a->hi = hi;
}

static double nice_step(double span)
{
    double raw = span / 6, mag = pow(10, floor(log10(raw))), r = raw / mag;
    return (r < 1.5 ? 1 : r < 3.5 ? 2 : r < 7.5 ? 5 : 10) * mag;
}

static void text(cairo_t *cr, double x, double y, const char *s, double ax, double ay, double angle)
{
    cairo_text_extents_t e;
    cairo_text_extents(cr, s, &e);
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rotate(cr, angle);
    cairo_move_to(cr, -e.x_bearing - ax * e.width, -e.y_bearing - ay * e.height);
    cairo_show_text(cr, s);
    cairo_restore(cr);
}

static void fmt_tick(char *buf, size_t n, double v, double step)
{
    /* zero is "0" whatever the step: on an axis of tiny steps the other ticks are in
     * %g form, and a zero with the step's decimals ("0.000000000") is clipped */
    if (fabs(v) < 1e-12 * step) {
        snprintf(buf, n, "0");
        return;
    }
    if ((fabs(v) >= 1e5 || (fabs(v) < 1e-3 && v != 0)))
        snprintf(buf, n, "%.3g", v);
    else {
        int dec = step >= 1 ? 0 : (int)ceil(-log10(step) - 1e-9);
        snprintf(buf, n, "%.*f", dec, v);
    }
}

/* Ticks on one axis: positions in data units through a callback. */
static void draw_ticks(cairo_t *cr, const axis *a, int vertical, double x0, double y0, double len,
                       int label_side, double other0, double other1)
{
    char buf[64];
    double lo = tf(a, a->lo), hi = tf(a, a->hi);
    double step = a->log ? 1 : nice_step(hi - lo);
    if (a->log && hi - lo > 8)
        step = ceil((hi - lo) / 8);
    double first = ceil(lo / step - 1e-9) * step;
    for (double v = first; v <= hi + 1e-9 * step; v += step) {
        double frac = (v - lo) / (hi - lo);
        double pos = vertical ? y0 - frac * len : x0 + frac * len;
        /* grid line */
        cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
        cairo_set_line_width(cr, 1);
        if (vertical) {
            cairo_move_to(cr, other0, pos);
            cairo_line_to(cr, other1, pos);
        } else {
            cairo_move_to(cr, pos, other0);
            cairo_line_to(cr, pos, other1);
        }
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0, 0, 0);
        if (a->log)
            snprintf(buf, sizeof buf, "1e%d", (int)lrint(v));
        else
            fmt_tick(buf, sizeof buf, v, step);
        if (vertical)
            text(cr, label_side < 0 ? x0 - 6 : x0 + 6, pos, buf, label_side < 0 ? 1 : 0, 0.5, 0);
        else
            text(cr, pos, y0 + 6, buf, 0.5, 0, 0);
    }
}

/* The frame of a panel in device units and its axes' data-to-device maps. */
typedef struct {
    double x0, x1, y0, y1; /* left, right, bottom, top */
    const axis *ax, *ay, *ay2;
} frame;

static double px_of(const frame *f, double v)
{
    double l = tf(f->ax, f->ax->lo), h = tf(f->ax, f->ax->hi);
    return f->x0 + (tf(f->ax, v) - l) / (h - l) * (f->x1 - f->x0);
}

static double py_of(const frame *f, const axis *a, double v)
{
    double l = tf(a, a->lo), h = tf(a, a->hi);
    return f->y0 - (tf(a, v) - l) / (h - l) * (f->y0 - f->y1);
}

/* The legend's size: widest label and entries. */
static size_t legend_size(cairo_t *cr, const panel *p, double *lw)
{
    size_t nl = 0;
    *lw = 0;
    cairo_set_font_size(cr, 13);
    for (size_t k = 0; k < p->ns; k++)
        if (p->s[k].label) {
            cairo_text_extents_t e;
            cairo_text_extents(cr, p->s[k].label, &e);
            if (e.width > *lw)
                *lw = e.width;
            nl++;
        }
    return nl;
}

/* How much of the data a box (device units) would hide: the points of every series
 * inside it, and of every segment between two points a few points along it. */
static long covered(const panel *p, const frame *f, double bx0, double by0, double bx1, double by1)
{
    long n = 0;
    for (size_t k = 0; k < p->ns; k++) {
        const series *s = &p->s[k];
        const axis *ya = (s->style & TT_PLOT_RIGHT) ? f->ay2 : f->ay;
        double qx = NAN, qy = NAN;
        for (size_t i = 0; i < s->n; i++) {
            double xv = s->x[i], yv = s->y[i];
            if (!isfinite(xv) || !isfinite(yv) || (f->ax->log && xv <= 0) || (ya->log && yv <= 0)) {
                qx = NAN;
                continue;
            }
            double x = px_of(f, xv), y = py_of(f, ya, yv);
            int steps = isfinite(qx) && !(s->style & TT_PLOT_POINTS) ? 8 : 1;
            for (int j = 1; j <= steps; j++) {
                double u = (double)j / steps, cx = isfinite(qx) ? qx + (x - qx) * u : x,
                       cy = isfinite(qx) ? qy + (y - qy) * u : y;
                n += cx >= bx0 && cx <= bx1 && cy >= by0 && cy <= by1;
            }
            qx = x;
            qy = y;
        }
    }
    return n;
}

/* The legend's corner (0 top right, 1 top left, 2 bottom right, 3 bottom left): the
 * first that hides no data, else the one that hides least; *hidden: what it hides. */
static int legend_corner(const panel *p, const frame *f, double w, double h, long *hidden)
{
    int best = 0;
    *hidden = -1;
    for (int c = 0; c < 4; c++) {
        double bx0 = c % 2 ? f->x0 + 2 : f->x1 - w - 2, by0 = c < 2 ? f->y1 + 2 : f->y0 - h - 2;
        long n = covered(p, f, bx0, by0, bx0 + w, by0 + h);
        if (*hidden < 0 || n < *hidden) {
            *hidden = n;
            best = c;
        }
        if (n == 0)
            break;
    }
    return best;
}

static void draw_legend(cairo_t *cr, const panel *p, const frame *f, int corner, double lw, size_t nl)
{
    double w = lw + 54, h = 18.0 * (double)nl + 8;
    double bx = corner % 2 ? f->x0 + 2 : f->x1 - w - 2, by = corner < 2 ? f->y1 + 2 : f->y0 - h - 2;
    double lx = bx + 8, ly = by + 14;
    cairo_set_font_size(cr, 13);
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_rectangle(cr, bx, by, w, h);
    cairo_fill(cr);
    for (size_t k = 0; k < p->ns; k++) {
        const series *s = &p->s[k];
        if (!s->label)
            continue;
        const double *c = palette[((s->style & TT_PLOT_COLOR_MASK) - 1) % 8];
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_set_line_width(cr, 2);
        double d2[] = {8, 5};
        cairo_set_dash(cr, d2, (s->style & TT_PLOT_DASHED) ? 2 : 0, 0);
        if (s->style & TT_PLOT_POINTS) {
            cairo_arc(cr, lx + 14, ly, 3.5, 0, 2 * M_PI);
            cairo_fill(cr);
        } else {
            cairo_move_to(cr, lx, ly);
            cairo_line_to(cr, lx + 30, ly);
            cairo_stroke(cr);
        }
        cairo_set_dash(cr, NULL, 0, 0);
        cairo_set_source_rgb(cr, 0, 0, 0);
        text(cr, lx + 38, ly, s->label, 0, 0.5, 0);
        ly += 18;
    }
}

static void draw_panel(cairo_t *cr, const panel *p, double X, double Y, double W, double H)
{
    axis ax, ay, ay2;
    double lo, hi;
    range(p, 0, 0, p->logx, &lo, &hi);
    nice_axis(&ax, lo, hi, p->xlo, p->xhi, p->logx);
    range(p, 1, 0, p->logy, &lo, &hi);
    for (size_t i = 0; i < p->nh; i++)
        if (isfinite(p->hl[i]) && !p->logy) {
            if (p->hl[i] < lo)
                lo = p->hl[i];
            if (p->hl[i] > hi)
                hi = p->hl[i];
        }
    nice_axis(&ay, lo, hi, p->ylo, p->yhi, p->logy);
    range(p, 1, 1, 0, &lo, &hi);
    nice_axis(&ay2, lo, hi, NAN, NAN, 0);
    int has_right = p->y2label != NULL;
    double ml = 80, mr = has_right ? 80 : 20, mt = 10, mb = 50;
    double x0 = X + ml, x1 = X + W - mr, y0 = Y + H - mb, y1 = Y + mt;
    /* the legend goes where it hides no data; where every corner would, the y axis
     * (linear, not fixed) grows at the top by the legend's height, and it goes there */
    double lw;
    size_t nl = legend_size(cr, p, &lw);
    frame fr = {x0, x1, y0, y1, &ax, &ay, &ay2};
    long hidden = 0;
    int corner = nl ? legend_corner(p, &fr, lw + 54, 18.0 * (double)nl + 8, &hidden) : 0;
    if (hidden > 0 && !p->logy && !isfinite(p->yhi) && !has_right) {
        double frac = (18.0 * (double)nl + 14) / (y0 - y1);
        if (frac < 0.6) {
            ay.hi += (ay.hi - ay.lo) * frac / (1 - frac);
            corner = legend_corner(p, &fr, lw + 54, 18.0 * (double)nl + 8, &hidden);
        }
    }
    cairo_set_font_size(cr, 13);
    draw_ticks(cr, &ax, 0, x0, y0, x1 - x0, 0, y0, y1);
    draw_ticks(cr, &ay, 1, x0, y0, y0 - y1, -1, x0, x1);
    if (has_right)
        draw_ticks(cr, &ay2, 1, x1, y0, y0 - y1, 1, x1, x1);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.2);
    cairo_rectangle(cr, x0, y1, x1 - x0, y0 - y1);
    cairo_stroke(cr);
    cairo_set_font_size(cr, 15);
    if (p->xlabel)
        text(cr, 0.5 * (x0 + x1), y0 + 28, p->xlabel, 0.5, 0, 0);
    if (p->ylabel)
        text(cr, X + 14, 0.5 * (y0 + y1), p->ylabel, 0.5, 0, -M_PI / 2);
    if (has_right)
        text(cr, X + W - 14, 0.5 * (y0 + y1), p->y2label, 0.5, 1, -M_PI / 2);
    /* data, clipped to the frame */
    cairo_save(cr);
    cairo_rectangle(cr, x0, y1, x1 - x0, y0 - y1);
    cairo_clip(cr);
    double xl = tf(&ax, ax.lo), xh = tf(&ax, ax.hi);
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_set_line_width(cr, 1);
    double dash[] = {3, 3};
    cairo_set_dash(cr, dash, 2, 0);
    for (size_t i = 0; i < p->nv; i++) {
        double px = x0 + (tf(&ax, p->vl[i]) - xl) / (xh - xl) * (x1 - x0);
        cairo_move_to(cr, px, y0);
        cairo_line_to(cr, px, y1);
        cairo_stroke(cr);
    }
    for (size_t i = 0; i < p->nh; i++) {
        double yl = tf(&ay, ay.lo), yh = tf(&ay, ay.hi);
        double py = y0 - (tf(&ay, p->hl[i]) - yl) / (yh - yl) * (y0 - y1);
        cairo_move_to(cr, x0, py);
        cairo_line_to(cr, x1, py);
        cairo_stroke(cr);
    }
    cairo_set_dash(cr, NULL, 0, 0);
    for (size_t k = 0; k < p->ns; k++) {
        const series *s = &p->s[k];
        const axis *ya = (s->style & TT_PLOT_RIGHT) ? &ay2 : &ay;
        double yl = tf(ya, ya->lo), yh = tf(ya, ya->hi);
        const double *c = palette[((s->style & TT_PLOT_COLOR_MASK) - 1) % 8];
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_set_line_width(cr, (s->style & TT_PLOT_THICK) ? 3.0 : 2.0);
        double d2[] = {8, 5};
        cairo_set_dash(cr, d2, (s->style & TT_PLOT_DASHED) ? 2 : 0, 0);
        int pen = 0;
        for (size_t i = 0; i < s->n; i++) {
            double xv = s->x[i], yv = s->y[i];
            if (!isfinite(xv) || !isfinite(yv) || (ax.log && xv <= 0) || (ya->log && yv <= 0)) {
                pen = 0;
                continue;
            }
            double px = x0 + (tf(&ax, xv) - xl) / (xh - xl) * (x1 - x0);
            double py = y0 - (tf(ya, yv) - yl) / (yh - yl) * (y0 - y1);
            if (s->style & TT_PLOT_POINTS) {
                cairo_new_sub_path(cr);
                cairo_arc(cr, px, py, 3.5, 0, 2 * M_PI);
                cairo_fill(cr);
                continue;
            }
            if (pen)
                cairo_line_to(cr, px, py);
            else
                cairo_move_to(cr, px, py);
            pen = 1;
        }
        if (!(s->style & TT_PLOT_POINTS))
            cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0);
    }
    cairo_set_source_rgb(cr, 0.25, 0.25, 0.25);
    cairo_set_font_size(cr, 10);
    for (size_t k = 0; k < p->nnotes; k++) {
        const note *nt = &p->notes[k];
        if (!isfinite(nt->x) || !isfinite(nt->y) || (ax.log && nt->x <= 0) || (ay.log && nt->y <= 0))
            continue;
        double yl = tf(&ay, ay.lo), yh = tf(&ay, ay.hi);
        double px = x0 + (tf(&ax, nt->x) - xl) / (xh - xl) * (x1 - x0);
        double py = y0 - (tf(&ay, nt->y) - yl) / (yh - yl) * (y0 - y1);
        cairo_text_extents_t e;
        cairo_text_extents(cr, nt->text, &e);
        /* near the right-hand frame the note goes to the left of its point */
        if (px + 4 + e.width > x1)
            text(cr, px - 4, py - 4, nt->text, 1, 1, 0);
        else
            text(cr, px + 4, py - 4, nt->text, 0, 1, 0);
    }
    cairo_restore(cr);
    if (nl)
        draw_legend(cr, p, &fr, corner, lw, nl);
}

int tt_figure_write_png(const tt_figure *f, const char *path, int width, int height)
{
    if (!f || width < 100 || height < 100)
        return tt_error(TT_EINVAL, "plot: bad figure or size");
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cairo_t *cr = cairo_create(sf);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    double top = 0;
    if (f->title) {
        cairo_set_source_rgb(cr, 0, 0, 0);
        cairo_set_font_size(cr, 18);
        text(cr, width / 2.0, 10, f->title, 0.5, 0, 0);
        top = 36;
    }
    double ph = (height - top) / f->npanels;
    for (int i = 0; i < f->npanels; i++)
        draw_panel(cr, &f->p[i], 0, top + ph * i, width, ph);
    cairo_destroy(cr);
    int rc = tt_png_write_surface(sf, path);
    cairo_surface_destroy(sf);
    return rc;
}
