/* Sample topography and material map (see include/tiptap/instrument/surface.h, docs/surfaces.md).
 * Analytic shapes are evaluated directly; rough surfaces and PNG maps live on grids. */
#include "tiptap/instrument/surface.h"

#include <errno.h>
#include <fftw3.h>
#include <math.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/files.h"
#include "tiptap/util/error.h"

typedef enum { S_FLAT, S_STEPS, S_GRATING, S_PARTICLES, S_ROUGH, S_PNG } shape;
typedef enum { M_UNIFORM, M_STRIPES, M_DISKS, M_CHECKER, M_ISLANDS, M_PNG } mapkind;

struct tt_surface {
    shape type;
    mapkind map;
    double sx, sy;
    /* shapes */
    double step_h, step_w, period, duty, height, edge;
    double pr;              /* particle radius */
    double *px, *py;        /* particle centres */
    long np;
    int *cell_start, *cell_list; /* particles binned on a grid of cells at least 2 r wide */
    int ncx, ncy;
    double cw;              /* cell width, m */
    /* height grid (rough, png) */
    double *grid;
    int gw, gh, periodic;
    /* map */
    int mat[2];             /* background, second material */
    double map_period, map_duty, map_radius;
    int *mgrid;             /* png material map */
    int mw, mh;
};

/* ---- PNG input ---- */

/* The material map's memory refusal for its materials' levels. */
static int levels_nomem(const char *path, size_t nm)
{
    return tt_error(TT_ENOMEM, "[surface] map_png: %s: out of memory for the levels of %zu materials", path, nm);
}

/* A map larger than this is refused before it is decoded: 8192 x 8192 pixels. */
#define TT_PNG_MAX_PIXELS ((size_t)1 << 26)

/* libpng reports errors by longjmp; the handler keeps the message for ours. */
typedef struct {
    char msg[200];
    double nomem; /* the bytes the decoded image would take, when they were not there */
} png_fault;

/* A map's memory refusal: the key, the file, what would not fit and its size. */
static int png_nomem(const char *key, const char *path, const char *what, size_t w, size_t h,
                     double bytes)
{
    return tt_error(TT_ENOMEM, "[surface] %s: %s: out of memory for %s of %zu x %zu pixels (%.3g MB)",
                    key, path, what, w, h, bytes / 1e6);
}

static void on_png_error(png_structp png, png_const_charp msg)
{
    png_fault *e = png_get_error_ptr(png);
    snprintf(e->msg, sizeof e->msg, "%s", msg);
    png_longjmp(png, 1);
}

static void on_png_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg;
}

/* The samples as the file stores them (palettes expanded to RGB, grey below 8 bits to 8
 * bits, tRNS to an alpha channel), big-endian when 16 bit. No gamma or colour-space
 * conversion: a map's levels are labels and heights, not light. */
static int decode_png(FILE *f, png_fault *e, unsigned char **data, png_uint_32 *w,
                      png_uint_32 *h, int *channels, int *depth)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, e, on_png_error, on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    unsigned char *volatile buf = NULL;
    png_bytep *volatile rows = NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        snprintf(e->msg, sizeof e->msg, "out of memory");
        return -1;
    }
    if (setjmp(png_jmpbuf(png))) {
        free(buf);
        free(rows);
        png_destroy_read_struct(&png, &info, NULL);
        return -1;
    }
    png_init_io(png, f);
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    /* fuzzing only (TT_FUZZ): mutated files get past the checksums to the decoder */
    png_set_crc_action(png, PNG_CRC_QUIET_USE, PNG_CRC_QUIET_USE);
#endif
    png_read_info(png, info);
    int type = png_get_color_type(png, info);
    if (type == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    *w = png_get_image_width(png, info);
    *h = png_get_image_height(png, info);
    *channels = png_get_channels(png, info);
    *depth = png_get_bit_depth(png, info);
    if (*channels < 1 || *channels > 4 || (*depth != 8 && *depth != 16))
        png_error(png, "unexpected sample layout");
    if ((size_t)*w * *h > TT_PNG_MAX_PIXELS)
        png_error(png, "more pixels than a map may have (8192 x 8192)");
    size_t rowbytes = png_get_rowbytes(png, info);
    buf = malloc(rowbytes * *h);
    rows = malloc(*h * sizeof *rows);
    if (!buf || !rows) {
        e->nomem = (double)rowbytes * *h;
        png_error(png, "out of memory");
    }
    for (png_uint_32 y = 0; y < *h; y++)
        rows[y] = buf + y * rowbytes;
    png_read_image(png, rows);
    png_read_end(png, NULL);
    free(rows);
    png_destroy_read_struct(&png, &info, NULL);
    *data = buf;
    return 0;
}

/* Read a PNG map into a freshly allocated array at the file's own depth (maxval 255 or
 * 65535), without gamma conversion: as RGB (want_rgb) or as grey, where a colour pixel is
 * refused. A transparent pixel is refused: there is no height or material behind it.
 * Errors name the file, the section and the key. */
static int read_png(const char *key, const char *path, int want_rgb,
                    unsigned short **pix, int *w, int *h, int *maxval)
{
    /* a regular file only: a pipe or a link to /dev/zero would be read for ever */
    FILE *f;
    if (tt_input_fopen(path, "PNG map", "map", TT_PNG_MAX_BYTES, &f)) {
        char why[1024];
        snprintf(why, sizeof why, "%s", tt_error_message());
        return tt_error(TT_EINVAL, "[surface] %s: %s", key, why);
    }
    png_fault e = {"", 0};
    unsigned char *data = NULL;
    png_uint_32 W = 0, H = 0;
    int nch = 0, depth = 0;
    int bad = decode_png(f, &e, &data, &W, &H, &nch, &depth);
    fclose(f);
    if (bad && e.nomem > 0)
        return png_nomem(key, path, "the decoded image", W, H, e.nomem);
    if (bad)
        return tt_error(TT_EINVAL, "[surface] %s: %s: cannot read as PNG: %s", key, path, e.msg);
    size_t n = (size_t)W * H, ch = want_rgb ? 3 : 1;
    unsigned max = depth == 16 ? 65535 : 255;
    int alpha = nch == 2 || nch == 4, rc = TT_OK;
    *pix = malloc((n ? n : 1) * ch * sizeof **pix);
    if (!*pix) {
        free(data);
        return png_nomem(key, path, "its levels", W, H, (double)n * ch * sizeof **pix);
    }
    for (size_t k = 0; k < n && rc == TT_OK; k++) {
        unsigned s[4] = {0, 0, 0, 0};
        for (int c = 0; c < nch; c++) {
            const unsigned char *p = data + (k * (size_t)nch + (size_t)c) * (depth == 16 ? 2 : 1);
            s[c] = depth == 16 ? (unsigned)(p[0] << 8 | p[1]) : p[0];
        }
        unsigned r = s[0], g = nch >= 3 ? s[1] : s[0], b = nch >= 3 ? s[2] : s[0];
        if (alpha && s[nch - 1] != max)
            rc = tt_error(TT_EINVAL, "[surface] %s: %s: pixel (%zu, %zu) is transparent (alpha %u of %u); a map must "
                               "be opaque", key, path, k % W, k / W, s[nch - 1], max);
        else if (!want_rgb && (r != g || g != b))
            rc = tt_error(TT_EINVAL, "[surface] %s: %s: pixel (%zu, %zu) has colour (%u, %u, %u); a height map is grey",
                               key, path, k % W, k / W, r, g, b);
        else if (want_rgb) {
            (*pix)[3 * k] = (unsigned short)r;
            (*pix)[3 * k + 1] = (unsigned short)g;
            (*pix)[3 * k + 2] = (unsigned short)b;
        } else
            (*pix)[k] = (unsigned short)r;
    }
    free(data);
    if (rc) {
        free(*pix);
        *pix = NULL;
        return rc;
    }
    *w = (int)W;
    *h = (int)H;
    *maxval = (int)max;
    return TT_OK;
}

/* ---- helpers ---- */

static unsigned long long rng_next(unsigned long long *s)
{
    /* splitmix64: deterministic across platforms for a given seed */
    unsigned long long z = (*s += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static double rng_uniform(unsigned long long *s) { return (double)(rng_next(s) >> 11) * 0x1.0p-53; }

static double rng_gauss(unsigned long long *s)
{
    double u = rng_uniform(s), v = rng_uniform(s);
    return sqrt(-2 * log(u + 1e-300)) * cos(2 * M_PI * v);
}

/* ---- topography ---- */

/* Cells of the particle grid: at least 2 r wide, so that a sphere meets only its own
 * and the neighbouring cells, and no more of them than about 4 per particle (at most
 * PARTICLE_MAX_CELLS), so that a tiny radius cannot size the grid beyond the memory
 * (at 14 pm over 1 um it was 5.1 GB) or beyond an int. */
#define PARTICLE_MAX_CELLS ((size_t)1 << 22)

static void particle_grid(tt_surface *S, long n)
{
    double cells = fmin(4.0 * (double)(n + 1), (double)PARTICLE_MAX_CELLS);
    double w = fmax(2 * S->pr, sqrt(S->sx * S->sy / cells));
    w = fmax(w, fmax(S->sx, S->sy) / cells);
    S->cw = w;
    S->ncx = (int)fmin(S->sx / w + 1, cells);
    S->ncy = (int)fmin(S->sy / w + 1, cells);
}

static size_t particle_cell(const tt_surface *S, double x, double y)
{
    long cx = (long)(x / S->cw), cy = (long)(y / S->cw);
    cx = cx < 0 ? 0 : cx >= S->ncx ? S->ncx - 1 : cx;
    cy = cy < 0 ? 0 : cy >= S->ncy ? S->ncy - 1 : cy;
    return (size_t)cy * (size_t)S->ncx + (size_t)cx;
}

/* 1 when a sphere at (x, y) keeps clear of those placed (head/next: each cell's list). */
static int particle_clear(const tt_surface *S, const int *head, const int *next, double x, double y)
{
    double r = S->pr;
    long cx = (long)(x / S->cw), cy = (long)(y / S->cw);
    for (long j = cy - 1; j <= cy + 1; j++)
        for (long i = cx - 1; i <= cx + 1; i++) {
            if (i < 0 || j < 0 || i >= S->ncx || j >= S->ncy)
                continue;
            for (int k = head[(size_t)j * (size_t)S->ncx + (size_t)i]; k >= 0; k = next[k])
                if (hypot(x - S->px[k], y - S->py[k]) < 2 * r)
                    return 0;
        }
    return 1;
}

/* Random sequential placement without overlap, each try checked against the nearby
 * cells only: near-linear in the count (100,000 spheres had been quadratic). */
static int build_particles(tt_surface *S, const tt_surface_params *p)
{
    long n = p->particle_count, seed = p->seed;
    S->pr = p->particle_radius;
    particle_grid(S, n);
    size_t nc = (size_t)S->ncx * (size_t)S->ncy;
    S->px = malloc(((size_t)n + 1) * sizeof *S->px);
    S->py = malloc(((size_t)n + 1) * sizeof *S->py);
    int *head = malloc(nc * sizeof *head), *next = malloc(((size_t)n + 1) * sizeof *next);
    S->cell_start = calloc(nc + 1, sizeof *S->cell_start);
    S->cell_list = malloc(((size_t)n + 1) * sizeof *S->cell_list);
    if (!S->px || !S->py || !head || !next || !S->cell_start || !S->cell_list) {
        free(head);
        free(next);
        return tt_error_nomem("the particles' placement grid");
    }
    for (size_t c = 0; c < nc; c++)
        head[c] = -1;
    unsigned long long st = (unsigned long long)seed * 7919ULL + 1;
    double r = S->pr;
    for (long tries = 0; S->np < n && tries < 1000 * (n + 1); tries++) {
        double x = rng_uniform(&st) * S->sx, y = rng_uniform(&st) * S->sy;
        if (!particle_clear(S, head, next, x, y))
            continue;
        size_t c = particle_cell(S, x, y);
        S->px[S->np] = x;
        S->py[S->np] = y;
        next[S->np] = head[c];
        head[c] = (int)S->np;
        S->np++;
    }
    free(head);
    free(next);
    if (S->np < n)
        return tt_error(TT_EINVAL,
                        "[surface] particle_count: %ld spheres of radius %g nm do not fit in the "
                        "scan area without overlap",
                        n, r * 1e9);
    /* the centres binned cell by cell for the look-ups during the scan */
    for (long j = 0; j < S->np; j++)
        S->cell_start[particle_cell(S, S->px[j], S->py[j]) + 1]++;
    for (size_t c = 0; c < nc; c++)
        S->cell_start[c + 1] += S->cell_start[c];
    int *fill = calloc(nc, sizeof *fill);
    if (!fill)
        return tt_error_nomem("the particles' placement grid");
    for (long j = 0; j < S->np; j++) {
        size_t c = particle_cell(S, S->px[j], S->py[j]);
        S->cell_list[S->cell_start[c] + fill[c]++] = (int)j;
    }
    free(fill);
    return TT_OK;
}

/* Height of the sphere under (x, y), or -1 when none. */
static double particle_at(const tt_surface *S, double x, double y)
{
    if (!S->np)
        return -1;
    double r = S->pr;
    long cx = (long)floor(x / S->cw), cy = (long)floor(y / S->cw);
    double best = -1;
    for (long j = cy - 1; j <= cy + 1; j++)
        for (long i = cx - 1; i <= cx + 1; i++) {
            if (i < 0 || j < 0 || i >= S->ncx || j >= S->ncy)
                continue;
            size_t c = (size_t)j * (size_t)S->ncx + (size_t)i;
            for (int k = S->cell_start[c]; k < S->cell_start[c + 1]; k++) {
                int p = S->cell_list[k];
                double d2 = (x - S->px[p]) * (x - S->px[p]) + (y - S->py[p]) * (y - S->py[p]);
                if (d2 < r * r) {
                    double h = r + sqrt(r * r - d2); /* a sphere resting on the flat */
                    if (h > best)
                        best = h;
                }
            }
        }
    return best;
}

static int build_rough(tt_surface *S, const tt_surface_params *sp)
{
    double rms = sp->rms, L = sp->correlation_length;
    long seed = sp->seed;
    /* a periodic grid fine enough to resolve the correlation length */
    int n = 256;
    while (n < 2048 && fmax(S->sx, S->sy) / n > L / 4)
        n *= 2;
    S->gw = S->gh = n;
    S->periodic = 1;
    S->grid = fftw_alloc_real((size_t)n * n);
    fftw_complex *F = fftw_alloc_complex((size_t)n * (n / 2 + 1));
    if (!S->grid || !F) {
        fftw_free(F);
        return tt_error_nomem("the rough surface's grid of %d x %d points", n, n);
    }
    fftw_plan p;
#pragma omp critical(tt_fftw_planner)
    p = fftw_plan_dft_c2r_2d(n, n, F, S->grid, FFTW_ESTIMATE);
    unsigned long long st = (unsigned long long)seed * 104729ULL + 7;
    /* white noise filtered by the square root of a Gaussian spectrum: the result has
     * the Gaussian autocorrelation exp(-r^2 / L^2) */
    for (int j = 0; j < n; j++)
        for (int i = 0; i <= n / 2; i++) {
            double kx = 2 * M_PI * i / S->sx, ky = 2 * M_PI * (j <= n / 2 ? j : j - n) / S->sy;
            double a = exp(-(kx * kx + ky * ky) * L * L / 8);
            size_t k = (size_t)j * (n / 2 + 1) + i;
            F[k][0] = a * rng_gauss(&st);
            F[k][1] = (i == 0 && (j == 0 || j == n / 2)) || (i == n / 2) ? 0 : a * rng_gauss(&st);
        }
    F[0][0] = F[0][1] = 0;
    fftw_execute(p);
#pragma omp critical(tt_fftw_planner)
    fftw_destroy_plan(p);
    fftw_free(F);
    double s2 = 0, m = 0;
    size_t N = (size_t)n * n;
    for (size_t k = 0; k < N; k++)
        m += S->grid[k];
    m /= (double)N;
    for (size_t k = 0; k < N; k++)
        s2 += (S->grid[k] - m) * (S->grid[k] - m);
    double scale = s2 > 0 ? rms / sqrt(s2 / (double)N) : 0;
    for (size_t k = 0; k < N; k++)
        S->grid[k] = (S->grid[k] - m) * scale;
    return TT_OK;
}

static int build_png_height(tt_surface *S, const tt_surface_params *p)
{
    double range = p->png_height_range;
    int rc, maxv;
    unsigned short *pix = NULL;
    if ((rc = read_png("png", p->png, 0, &pix, &S->gw, &S->gh, &maxv)))
        return rc;
    S->grid = fftw_alloc_real((size_t)S->gw * S->gh);
    if (!S->grid) {
        free(pix);
        return png_nomem("png", p->png, "its height grid", (size_t)S->gw, (size_t)S->gh,
                         (double)S->gw * S->gh * sizeof *S->grid);
    }
    for (size_t k = 0; k < (size_t)S->gw * S->gh; k++)
        S->grid[k] = range * ((double)pix[k] / maxv); /* the brightest pixel is range exactly */
    free(pix);
    return TT_OK;
}

/* Bilinear interpolation on the grid, pixel centres at (i + 1/2) size / n. Defined
 * everywhere, as the tip's dilation samples past the scan area by the tip's reach: a
 * periodic grid (rough) repeats, a PNG map continues its edge pixels. The node index is
 * reduced in floating point before it becomes an int, so no distance overflows it. */
static double grid_at(const tt_surface *S, double x, double y)
{
    double u = x / S->sx * S->gw - 0.5, v = y / S->sy * S->gh - 0.5;
    double fi = floor(u), fj = floor(v);
    double fu = u - fi, fv = v - fj;
    int i, j, i1, j1;
    if (S->periodic) {
        fi -= S->gw * floor(fi / S->gw);
        fj -= S->gh * floor(fj / S->gh);
        i = fi >= S->gw ? 0 : (int)fi; /* fi / gw may round up to the next period */
        j = fj >= S->gh ? 0 : (int)fj;
        i1 = i + 1 == S->gw ? 0 : i + 1;
        j1 = j + 1 == S->gh ? 0 : j + 1;
    } else {
        i = fi < 0 ? 0 : fi >= S->gw - 1 ? S->gw - 1 : (int)fi;
        i1 = fi < -1 ? 0 : fi >= S->gw - 2 ? S->gw - 1 : (int)fi + 1;
        j = fj < 0 ? 0 : fj >= S->gh - 1 ? S->gh - 1 : (int)fj;
        j1 = fj < -1 ? 0 : fj >= S->gh - 2 ? S->gh - 1 : (int)fj + 1;
    }
    const double *g = S->grid;
    double a = g[(size_t)j * S->gw + i], b = g[(size_t)j * S->gw + i1];
    double c = g[(size_t)j1 * S->gw + i], d = g[(size_t)j1 * S->gw + i1];
    double h = (1 - fu) * (1 - fv) * a + fu * (1 - fv) * b + (1 - fu) * fv * c + fu * fv * d;
    /* rounding must not lift the surface above its highest pixel (or below its lowest):
     * a map's brightest grey is its [surface] height exactly (found by fuzz_png) */
    double lo = fmin(fmin(a, b), fmin(c, d)), hi = fmax(fmax(a, b), fmax(c, d));
    return h < lo ? lo : h > hi ? hi : h;
}

double tt_surface_height(const tt_surface *S, double x, double y)
{
    switch (S->type) {
    case S_STEPS:
        return S->step_h * floor(x / S->step_w);
    case S_GRATING: {
        /* trapezoidal lines along y: up-edge, top, down-edge, bottom */
        double u = x - S->period * floor(x / S->period), top = S->duty * S->period, e = S->edge;
        if (e > 0 && u < e)
            return S->height * u / e;
        if (u < top)
            return S->height;
        if (e > 0 && u < top + e)
            return S->height * (1 - (u - top) / e);
        return 0;
    }
    case S_PARTICLES: {
        double h = particle_at(S, x, y);
        return h > 0 ? h : 0;
    }
    case S_ROUGH:
    case S_PNG:
        return grid_at(S, x, y);
    default:
        return 0;
    }
}

int tt_surface_material(const tt_surface *S, double x, double y)
{
    switch (S->map) {
    case M_STRIPES: {
        double u = x / S->map_period;
        return (u - floor(u)) < S->map_duty ? S->mat[1] : S->mat[0];
    }
    case M_DISKS: {
        /* a square lattice of disks centred in each period cell */
        double p = S->map_period;
        double dx = x - p * (floor(x / p) + 0.5), dy = y - p * (floor(y / p) + 0.5);
        return dx * dx + dy * dy < S->map_radius * S->map_radius ? S->mat[1] : S->mat[0];
    }
    case M_CHECKER: {
        long c = (long)floor(2 * x / S->map_period) + (long)floor(2 * y / S->map_period);
        return (c & 1) ? S->mat[1] : S->mat[0];
    }
    case M_ISLANDS:
        return particle_at(S, x, y) > 0 ? S->mat[1] : S->mat[0];
    case M_PNG: {
        /* clamped before the conversion: past the area the edge pixels continue */
        double u = x / S->sx * S->mw, v = y / S->sy * S->mh;
        int i = u < 0 ? 0 : u >= S->mw ? S->mw - 1 : (int)u;
        int j = v < 0 ? 0 : v >= S->mh ? S->mh - 1 : (int)v;
        return S->mgrid[(size_t)j * S->mw + i];
    }
    default:
        return S->mat[0];
    }
}

int tt_surface_uniform(const tt_surface *S) { return S->map == M_UNIFORM; }
int tt_surface_flat(const tt_surface *S) { return S->type == S_FLAT; }

/* The straight pieces of steps and gratings, as tt_surface_height draws them. */
int tt_surface_pieces(const tt_surface *S, double x0, double x1, tt_surface_piece_fn fn,
                      void *user)
{
    if (S->type == S_STEPS) {
        double w = S->step_w;
        for (double n = floor(x0 / w); n <= floor(x1 / w); n++)
            fn(user, n * w, n * S->step_h, (n + 1) * w, n * S->step_h);
        return 1;
    }
    if (S->type != S_GRATING)
        return 0;
    double p = S->period, top = S->duty * p, e = S->edge, H = S->height;
    for (double n = floor(x0 / p); n <= floor(x1 / p); n++) {
        double o = n * p;
        if (e > 0)
            fn(user, o, 0, o + e, H);
        fn(user, o + e, H, o + top, H);
        if (e > 0)
            fn(user, o + top, H, o + top + e, 0);
        fn(user, o + top + e, 0, o + p, 0);
    }
    return 1;
}

/* ---- material map ---- */

/* A material's map_value as the pixel it names in a map of maxval (255 or 65535),
 * packed r, g, b: a grey level is taken at the map's own depth, a colour #rrggbb scaled
 * to it. -1 when the grey level is beyond the map's depth. */
static int map_key(const tt_material *m, unsigned maxval, unsigned long long *key)
{
    if (m->map_grey >= 0) {
        unsigned long long l = (unsigned long long)m->map_grey;
        *key = l << 32 | l << 16 | l;
        return m->map_grey <= (long)maxval ? 0 : -1;
    }
    unsigned long long k = maxval / 255, c = (unsigned long long)m->map_rgb;
    *key = (c >> 16 & 255) * k << 32 | (c >> 8 & 255) * k << 16 | (c & 255) * k;
    return 0;
}

/* A material's map_value as written: a grey level or #rrggbb. */
static void map_value_text(const tt_material *m, char *buf, size_t len)
{
    if (m->map_grey >= 0)
        snprintf(buf, len, "%ld", m->map_grey);
    else
        snprintf(buf, len, "#%06x", (unsigned)m->map_rgb);
}

typedef struct {
    unsigned long long key;
    size_t index;
} keyed;

static int by_key(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index;
}

/* Two materials naming one pixel value: the map would silently give every such pixel
 * to one of them. Refused, naming both (sorted, so many materials stay fast). */
static int check_map_values(const unsigned long long *key, const tt_material *mat, size_t nm,
                            int maxv, const char *path)
{
    keyed *k = malloc((nm ? nm : 1) * sizeof *k);
    size_t n = 0;
    if (!k)
        return levels_nomem(path, nm);
    for (size_t i = 0; i < nm; i++)
        if (key[i] != ~0ULL)
            k[n++] = (keyed){key[i], i};
    qsort(k, n, sizeof *k, by_key);
    int rc = TT_OK;
    for (size_t j = 1; j < n && !rc; j++)
        if (k[j].key == k[j - 1].key) {
            const tt_material *a = &mat[k[j - 1].index], *b = &mat[k[j].index];
            char va[24], vb[24];
            map_value_text(a, va, sizeof va);
            map_value_text(b, vb, sizeof vb);
            rc = tt_error(TT_EINVAL, "[material %s] map_value: %s names the same pixel as "
                          "[material %s] map_value %s in the %d-bit map %s; give each material "
                          "a value of its own", b->name, vb, a->name, va, maxv == 255 ? 8 : 16,
                          path);
        }
    free(k);
    return rc;
}

/* The largest level of the map at path as read_png gives it (255, or 65535 for 16 bits),
 * from the IHDR chunk, which the PNG format puts first; -1 when it is not there. */
static int png_header_maxval(FILE *f)
{
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char h[26];
    if (fread(h, 1, sizeof h, f) != sizeof h || memcmp(h, sig, 8) != 0 || memcmp(h + 12, "IHDR", 4) != 0)
        return -1;
    return h[24] == 16 ? 65535 : 255;
}

int tt_surface_check_map_values(const tt_surface_params *p, const tt_material *mat, size_t nm)
{
    if ((mapkind)p->map != M_PNG)
        return TT_OK;
    FILE *f;
    if (tt_input_fopen(p->map_png, "PNG map", "map", TT_PNG_MAX_BYTES, &f)) {
        char why[1024];
        snprintf(why, sizeof why, "%s", tt_error_message());
        return tt_error(TT_EINVAL, "[surface] map_png: %s", why);
    }
    int maxv = png_header_maxval(f);
    fclose(f);
    unsigned long long *key = malloc((nm ? nm : 1) * sizeof *key);
    if (!key)
        return levels_nomem(p->map_png, nm);
    for (size_t i = 0; i < nm; i++)
        if ((mat[i].map_grey < 0 && mat[i].map_rgb < 0) || map_key(&mat[i], (unsigned)maxv, &key[i]))
            key[i] = ~0ULL; /* a level beyond the depth: tt_surface_alloc says so */
    int rc = maxv > 0 ? check_map_values(key, mat, nm, maxv, p->map_png) : TT_OK;
    free(key);
    return rc;
}

static int build_png_map(tt_surface *S, const tt_surface_params *p, const tt_material *mat,
                         size_t nm)
{
    int rc, maxv;
    unsigned short *pix = NULL;
    const char *path = p->map_png;
    if ((rc = read_png("map_png", path, 1, &pix, &S->mw, &S->mh, &maxv)))
        return rc;
    unsigned long long *key = malloc((nm ? nm : 1) * sizeof *key), none = ~0ULL;
    if (!key) {
        free(pix);
        return levels_nomem(path, nm);
    }
    for (size_t i = 0; i < nm && !rc; i++) {
        key[i] = none;
        if (mat[i].map_grey >= 0 || mat[i].map_rgb >= 0) {
            if (map_key(&mat[i], (unsigned)maxv, &key[i]) != 0)
                rc = tt_error(TT_EINVAL, "[material %s] map_value: %ld is above %d, the largest "
                              "level of the %d-bit map %s", mat[i].name, mat[i].map_grey, maxv,
                              maxv == 255 ? 8 : 16, path);
        }
    }
    if (!rc)
        rc = check_map_values(key, mat, nm, maxv, path);
    S->mgrid = rc ? NULL : malloc((size_t)S->mw * S->mh * sizeof *S->mgrid);
    if (!S->mgrid) {
        free(key);
        free(pix);
        return rc ? rc : png_nomem("map_png", path, "its material grid", (size_t)S->mw, (size_t)S->mh,
                                   (double)S->mw * S->mh * sizeof *S->mgrid);
    }
    for (size_t k = 0; k < (size_t)S->mw * S->mh && rc == TT_OK; k++) {
        unsigned long long c = (unsigned long long)pix[3 * k] << 32 |
                               (unsigned long long)pix[3 * k + 1] << 16 | pix[3 * k + 2];
        int found = -1;
        for (size_t i = 0; i < nm; i++)
            if (key[i] == c)
                found = (int)i;
        if (found < 0 && maxv == 255)
            rc = tt_error(TT_EINVAL, "[surface] map_png: %s: pixel (%zu, %zu) has colour "
                          "#%02x%02x%02x, which no [material] map_value names", path,
                          k % (size_t)S->mw, k / (size_t)S->mw, pix[3 * k], pix[3 * k + 1],
                          pix[3 * k + 2]);
        else if (found < 0)
            rc = tt_error(TT_EINVAL, "[surface] map_png: %s: pixel (%zu, %zu) has 16-bit level "
                          "(%u, %u, %u), which no [material] map_value names", path,
                          k % (size_t)S->mw, k / (size_t)S->mw, pix[3 * k], pix[3 * k + 1],
                          pix[3 * k + 2]);
        S->mgrid[k] = found;
    }
    free(key);
    free(pix);
    return rc;
}

int tt_surface_alloc(tt_surface **out, const tt_surface_params *p, const tt_material *materials,
                     size_t nmaterials, double size_x, double size_y)
{
    *out = NULL;
    tt_surface *S = calloc(1, sizeof *S);
    if (!S)
        return tt_error_nomem("the surface");
    S->sx = size_x;
    S->sy = size_y;
    S->type = (shape)p->type;
    S->map = (mapkind)p->map;
    int rc = TT_OK;
    switch (S->type) {
    case S_STEPS:
        S->step_h = p->step_height;
        S->step_w = p->step_width;
        break;
    case S_GRATING:
        S->period = p->period;
        S->duty = p->duty;
        S->height = p->height;
        S->edge = p->edge_width;
        break;
    case S_PARTICLES:
        rc = build_particles(S, p);
        break;
    case S_ROUGH:
        rc = build_rough(S, p);
        break;
    case S_PNG:
        rc = build_png_height(S, p);
        break;
    default:
        break;
    }
    if (S->map != M_UNIFORM && S->map != M_PNG) {
        S->mat[0] = p->materials[0];
        S->mat[1] = p->materials[1];
        S->map_period = p->map_period;
        S->map_duty = p->map_duty;
        S->map_radius = p->map_radius;
    }
    if (rc == TT_OK && S->map == M_PNG)
        rc = build_png_map(S, p, materials, nmaterials);
    if (rc) {
        tt_surface_free(S);
        return rc;
    }
    *out = S;
    return TT_OK;
}

void tt_surface_free(tt_surface *S)
{
    if (!S)
        return;
    free(S->px);
    free(S->py);
    free(S->cell_start);
    free(S->cell_list);
    fftw_free(S->grid);
    free(S->mgrid);
    free(S);
}
