/* The tip's shape and the surface dilated by it (see include/tiptap/instrument/tip.h,
 * docs/surfaces.md). */
#include "tiptap/instrument/tip.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

/* Grids larger than this a side coarsen their step instead (128 MiB of heights). */
#define TT_DILATION_MAX_SIDE 4096

struct tt_dilation {
    const tt_surface *surface;
    tt_tip_shape tip;
    int exact;
    double reach; /* exact: the half-width of the window of pieces a look-up reads */
    double x0, y0, dx;
    long nx, ny;
    double *grid; /* nx * ny apex heights, row j at y0 + j dx */
    int16_t *touch; /* nx * ny pairs: the node offset (a, b) where the tip touches;
                     * NULL for a surface of one material unless contacts (asked for
                     * by a scan that reads the contact's geometry there) */
    int contacts;
};

/* ---- exact: profiles along x made of straight pieces ---- */

typedef struct {
    const tt_tip_shape *tip;
    double x, best;
    double lo, hi; /* range of the heights met */
    double xc;     /* where the best apex touches */
} piece_ctx;

/* The highest apex over one straight piece: h - t along the piece is concave (the tip
 * is convex), so its maximum is where the tip's slope equals the piece's, or the end
 * of the piece nearest to it. */
static void apex_over_piece(void *user, double xa, double ha, double xb, double hb)
{
    piece_ctx *c = user;
    double s = (hb - ha) / (xb - xa);
    double u = copysign(tt_tip_shape_slope_at(c->tip, fabs(s)), s);
    double lo = xa - c->x, hi = xb - c->x;
    u = u < lo ? lo : u > hi ? hi : u;
    double v = ha + s * (c->x + u - xa) - tt_tip_shape_height(c->tip, u);
    if (v > c->best) {
        c->best = v;
        /* an end of the piece is taken just inside it, so that at a wall's top corner
         * the material read is the top's, not the one across the wall */
        double in = 1e-9 * (xb - xa);
        c->xc = u == lo ? xa + in : u == hi ? xb - in : c->x + u;
    }
}

static void height_range(void *user, double xa, double ha, double xb, double hb)
{
    piece_ctx *c = user;
    (void)xa;
    (void)xb;
    c->lo = fmin(c->lo, fmin(ha, hb));
    c->hi = fmax(c->hi, fmax(ha, hb));
}

/* The window a look-up must read: features further than the reach of the surface's
 * height range cannot touch the tip. Steps rise without end, so the range is that of
 * the window itself, grown twice; a staircase steeper than the cone stops there. */
static void exact_reach(tt_dilation *D, double x0, double x1)
{
    double m = 0;
    for (int pass = 0; pass < 3; pass++) {
        piece_ctx c = {&D->tip, 0, 0, INFINITY, -INFINITY, 0};
        tt_surface_pieces(D->surface, x0 - m, x1 + m, height_range, &c);
        m = fmin(tt_tip_shape_reach(&D->tip, c.hi - c.lo), 2 * (x1 - x0) + D->tip.radius);
    }
    D->reach = m;
}

/* ---- grid: every other surface ---- */

typedef struct {
    long a, b;  /* node offset */
    double t;   /* the tip's height there */
} offset;

/* The offsets in squares of TILE by TILE nodes: a node skips a whole square when the
 * highest sample under it, less the tip's lowest point over it, is no better than the
 * best apex found. */
#define TILE 8
typedef struct {
    long a, b;        /* the square's corner offset */
    double t;         /* the tip's lowest point over it */
    long start, n;    /* its offsets */
} tile;

static int by_height(const void *p, const void *q)
{
    double a = ((const tile *)p)->t, b = ((const tile *)q)->t;
    return (a > b) - (a < b);
}

/* The surface's heights on the region's nodes widened by m nodes on every side. */
static double *sample(const tt_dilation *D, long m, double *lo, double *hi)
{
    long w = D->nx + 2 * m, h = D->ny + 2 * m;
    double *g = malloc((size_t)w * (size_t)h * sizeof *g);
    if (!g)
        return NULL;
#pragma omp parallel for
    for (long j = 0; j < h; j++)
        for (long i = 0; i < w; i++)
            g[j * w + i] = tt_surface_height(D->surface, D->x0 + (double)(i - m) * D->dx,
                                             D->y0 + (double)(j - m) * D->dx);
    *lo = INFINITY;
    *hi = -INFINITY;
    for (long k = 0; k < w * h; k++) {
        *lo = fmin(*lo, g[k]);
        *hi = fmax(*hi, g[k]);
    }
    return g;
}

/* The tip's nodes that can touch, square by square, the squares lowest first, so a
 * node's search stops at the first square whose tip height leaves no room above the
 * best apex found. */
static offset *offsets(const tt_dilation *D, long m, double range, tile **tiles, long *ntiles)
{
    long side = (2 * m + TILE) / TILE;
    offset *o = malloc((size_t)(2 * m + 1) * (size_t)(2 * m + 1) * sizeof *o);
    tile *T = malloc((size_t)side * (size_t)side * sizeof *T);
    if (!o || !T) {
        free(o);
        free(T);
        return NULL;
    }
    long n = 0, nt = 0;
    for (long b0 = -m; b0 <= m; b0 += TILE)
        for (long a0 = -m; a0 <= m; a0 += TILE) {
            tile q = {a0, b0, INFINITY, n, 0};
            for (long b = b0; b < b0 + TILE && b <= m; b++)
                for (long a = a0; a < a0 + TILE && a <= m; a++) {
                    double t = tt_tip_shape_height(&D->tip, D->dx * hypot((double)a, (double)b));
                    if (t <= range) {
                        o[n++] = (offset){a, b, t};
                        q.t = fmin(q.t, t);
                    }
                }
            q.n = n - q.start;
            if (q.n)
                T[nt++] = q;
        }
    qsort(T, (size_t)nt, sizeof *T, by_height);
    *tiles = T;
    *ntiles = nt;
    return o;
}

/* The highest of TILE values onwards from each (clipped at the end), along one axis:
 * the rows when step is 1, the columns when it is the row length w. */
static void run_max(const double *in, double *out, long w, long h, long step)
{
    long len = step == 1 ? w : h;
    for (long j = 0; j < h; j++)
        for (long i = 0; i < w; i++) {
            long at = j * w + i, pos = step == 1 ? i : j;
            double v = in[at];
            for (long k = 1; k < TILE && pos + k < len; k++)
                v = fmax(v, in[at + k * step]);
            out[at] = v;
        }
}

/* The highest sample over each node's square of TILE by TILE nodes onwards (clipped at
 * the sample's end), for the squares of offsets: the maximum along rows, then columns. */
static double *tile_max(const double *g, long w, long h)
{
    double *r = malloc((size_t)w * (size_t)h * sizeof *r), *G = malloc((size_t)w * (size_t)h * sizeof *G);
    if (!r || !G) {
        free(r);
        free(G);
        return NULL;
    }
    run_max(g, r, w, h, 1);
    run_max(r, G, w, h, w);
    free(r);
    return G;
}

/* Sliding maximum over 2 m + 1 values centred on each of n (clipped at the ends), read
 * with stride si and written with stride so: a monotone deque, O(n) whatever m. */
static void slide_max(const double *in, long si, double *out, long so, long n, long m, long *dq)
{
    long head = 0, tail = 0;
    for (long i = 0; i < n + m; i++) {
        if (i < n) {
            while (tail > head && in[dq[tail - 1] * si] <= in[i * si])
                tail--;
            dq[tail++] = i;
        }
        long c = i - m;
        if (c < 0)
            continue;
        while (dq[head] < c - m)
            head++;
        out[c * so] = in[dq[head] * si];
    }
}

/* The highest sample within m nodes along both axes of each node of the region (nx by
 * ny of the w-wide sample g, offset by m): a bound on what the tip's footprint can
 * meet there, far tighter than the global one away from the tallest features. */
static double *local_max(const tt_dilation *D, const double *g, long m)
{
    long w = D->nx + 2 * m, h = D->ny + 2 * m;
    double *rows = malloc((size_t)D->nx * (size_t)h * sizeof *rows);
    double *M = malloc((size_t)D->nx * (size_t)D->ny * sizeof *M);
    long *dq = malloc((size_t)(w > h ? w : h) * sizeof *dq);
    double *tmp = malloc((size_t)w * sizeof *tmp);
    if (!rows || !M || !dq || !tmp) {
        free(rows);
        free(M);
        M = NULL;
    } else {
        for (long j = 0; j < h; j++) { /* along x, kept for the region's columns */
            slide_max(g + j * w, 1, tmp, 1, w, m, dq);
            for (long i = 0; i < D->nx; i++)
                rows[j * D->nx + i] = tmp[i + m];
        }
        for (long i = 0; i < D->nx; i++) { /* then along y, kept for its rows */
            slide_max(rows + i, D->nx, tmp, 1, h, m, dq);
            for (long j = 0; j < D->ny; j++)
                M[j * D->nx + i] = tmp[j + m];
        }
        free(rows);
    }
    free(dq);
    free(tmp);
    return M;
}

/* Each node's apex height: the squares of offsets lowest first, until the tip rises
 * above the highest sample within its footprint by more than the best apex found,
 * passing over squares whose highest sample is no better. Every offset left out is one
 * that cannot beat the best (rounding is monotone), so the maximum is exactly that
 * over all. */
static int search_nodes(tt_dilation *D, const double *g, const double *M, const double *G,
                        long m, const offset *o, const tile *T, long nt)
{
    long w = D->nx + 2 * m;
    int stop = 0;
#pragma omp parallel for schedule(dynamic, 16)
    for (long j = 0; j < D->ny; j++) {
        int quit;
#pragma omp atomic read
        quit = stop;
        if (quit)
            continue;
        if (tt_cancel_requested()) { /* a row takes well under a second */
#pragma omp atomic write
            stop = 1;
            continue;
        }
        for (long i = 0; i < D->nx; i++) {
            const double *c = g + (j + m) * w + (i + m);
            const double *cg = G + (j + m) * w + (i + m);
            double best = -INFINITY, top = M[j * D->nx + i];
            long ba = 0, bb = 0;
            for (long k = 0; k < nt && top - T[k].t > best; k++) {
                if (cg[T[k].b * w + T[k].a] - T[k].t <= best)
                    continue;
                for (const offset *q = o + T[k].start; q < o + T[k].start + T[k].n; q++) {
                    double v = c[q->b * w + q->a] - q->t;
                    if (v > best) {
                        best = v;
                        ba = q->a;
                        bb = q->b;
                    }
                }
            }
            D->grid[j * D->nx + i] = best;
            if (D->touch) { /* |a|, |b| <= m <= TT_DILATION_MAX_SIDE: an int16 holds them */
                D->touch[2 * (j * D->nx + i)] = (int16_t)ba;
                D->touch[2 * (j * D->nx + i) + 1] = (int16_t)bb;
            }
        }
    }
    return stop ? tt_error(TT_EINTR, "interrupted while making the tip's dilation grid") : TT_OK;
}

static int build_grid(tt_dilation *D)
{
    double lo, hi;
    double *g = sample(D, 0, &lo, &hi);
    long m = 0;
    /* the margin: the reach of the height range, grown until the range it sees holds */
    for (int pass = 0; g && pass < 3; pass++) {
        long need = (long)ceil(tt_tip_shape_reach(&D->tip, hi - lo) / D->dx);
        if (need <= m)
            break;
        m = need < TT_DILATION_MAX_SIDE ? need : TT_DILATION_MAX_SIDE;
        free(g);
        g = sample(D, m, &lo, &hi);
    }
    long nt = 0;
    tile *T = NULL;
    offset *o = g ? offsets(D, m, hi - lo, &T, &nt) : NULL;
    double *M = o ? local_max(D, g, m) : NULL;
    double *G = M ? tile_max(g, D->nx + 2 * m, D->ny + 2 * m) : NULL;
    D->grid = G ? malloc((size_t)D->nx * (size_t)D->ny * sizeof *D->grid) : NULL;
    if (D->grid && (D->contacts || !tt_surface_uniform(D->surface))) {
        D->touch = malloc((size_t)D->nx * (size_t)D->ny * 2 * sizeof *D->touch);
        if (!D->touch) {
            free(D->grid);
            D->grid = NULL;
        }
    }
    int rc = D->grid ? search_nodes(D, g, M, G, m, o, T, nt)
                     : tt_error(TT_ENOMEM, "out of memory for the tip's dilation grid");
    free(g);
    free(o);
    free(T);
    free(M);
    free(G);
    return rc;
}

int tt_dilation_alloc(tt_dilation **out, const tt_surface *s, const tt_tip_shape *t, double x0,
                      double y0, double x1, double y1, double spacing)
{
    return tt_dilation_alloc_contacts(out, s, t, x0, y0, x1, y1, spacing, 0);
}

int tt_dilation_alloc_contacts(tt_dilation **out, const tt_surface *s, const tt_tip_shape *t,
                               double x0, double y0, double x1, double y1, double spacing,
                               int contacts)
{
    *out = NULL;
    if (t->kind == TT_TIP_POINT)
        return tt_error(TT_EINVAL, "[tip] shape: a point tip dilates nothing");
    tt_dilation *D = calloc(1, sizeof *D);
    if (!D)
        return tt_error(TT_ENOMEM, "out of memory");
    D->surface = s;
    D->tip = *t;
    D->contacts = contacts;
    D->x0 = x0;
    D->y0 = y0;
    piece_ctx probe = {t, 0, 0, 0, 0, 0};
    D->exact = tt_surface_pieces(s, x0, x0, height_range, &probe);
    if (D->exact) {
        exact_reach(D, x0, x1);
        *out = D;
        return TT_OK;
    }
    double side = fmax(x1 - x0, y1 - y0);
    D->dx = fmax(spacing, side / (TT_DILATION_MAX_SIDE - 1));
    D->nx = (long)ceil((x1 - x0) / D->dx) + 1;
    D->ny = (long)ceil((y1 - y0) / D->dx) + 1;
    int rc = build_grid(D);
    if (rc) {
        tt_dilation_free(D);
        return rc;
    }
    *out = D;
    return TT_OK;
}

void tt_dilation_free(tt_dilation *D)
{
    if (!D)
        return;
    free(D->grid);
    free(D->touch);
    free(D);
}

double tt_dilation_contact(const tt_dilation *D, double x, double y, double *xc, double *yc)
{
    *xc = x;
    *yc = y;
    if (D->exact) {
        piece_ctx c = {&D->tip, x, -INFINITY, 0, 0, x};
        tt_surface_pieces(D->surface, x - D->reach, x + D->reach, apex_over_piece, &c);
        *xc = c.xc;
        return c.best;
    }
    if (D->touch) { /* the nearest node's offset, clamped to the region as the heights are */
        double u = (x - D->x0) / D->dx, v = (y - D->y0) / D->dx;
        u = u < 0 ? 0 : u > (double)(D->nx - 1) ? (double)(D->nx - 1) : u;
        v = v < 0 ? 0 : v > (double)(D->ny - 1) ? (double)(D->ny - 1) : v;
        const int16_t *o = D->touch + 2 * ((long)(v + 0.5) * D->nx + (long)(u + 0.5));
        *xc = x + (double)o[0] * D->dx;
        *yc = y + (double)o[1] * D->dx;
    }
    return tt_dilation_height(D, x, y);
}

double tt_dilation_height(const tt_dilation *D, double x, double y)
{
    if (D->exact) {
        piece_ctx c = {&D->tip, x, -INFINITY, 0, 0, x};
        tt_surface_pieces(D->surface, x - D->reach, x + D->reach, apex_over_piece, &c);
        return c.best;
    }
    /* bilinear between the nodes, clamped to the region */
    double u = (x - D->x0) / D->dx, v = (y - D->y0) / D->dx;
    u = u < 0 ? 0 : u > (double)(D->nx - 1) ? (double)(D->nx - 1) : u;
    v = v < 0 ? 0 : v > (double)(D->ny - 1) ? (double)(D->ny - 1) : v;
    long i = (long)u, j = (long)v;
    long i1 = i + 1 < D->nx ? i + 1 : i, j1 = j + 1 < D->ny ? j + 1 : j;
    double fu = u - (double)i, fv = v - (double)j;
    const double *g = D->grid;
    return (1 - fu) * (1 - fv) * g[j * D->nx + i] + fu * (1 - fv) * g[j * D->nx + i1] +
           (1 - fu) * fv * g[j1 * D->nx + i] + fu * fv * g[j1 * D->nx + i1];
}

double tt_dilation_spacing(const tt_dilation *D) { return D->exact ? 0 : D->dx; }
long tt_dilation_nodes(const tt_dilation *D) { return D->exact ? 0 : D->nx * D->ny; }
