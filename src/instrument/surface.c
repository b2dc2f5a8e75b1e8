/* Sample topography and material map (see include/tiptap/instrument/surface.h, docs/surfaces.md).
 * Analytic shapes are evaluated directly; rough surfaces and PNG maps live on grids. */
#include "surface_private.h"

#include <errno.h>
#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/files.h"
#include "tiptap/util/error.h"

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
    S->gsx = S->sx;
    S->gsy = S->sy;
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

/* Bilinear interpolation on the grid, pixel centres at (i + 1/2) size / n. Defined
 * everywhere, as the tip's dilation samples past the scan area by the tip's reach: a
 * periodic grid (rough) repeats, a PNG map continues its edge pixels. The node index is
 * reduced in floating point before it becomes an int, so no distance overflows it. */
static double grid_at(const tt_surface *S, double x, double y)
{
    double u = x / S->gsx * S->gw - 0.5, v = y / S->gsy * S->gh - 0.5;
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
        return S->step_h * floor((x - S->ox) / S->step_w);
    case S_GRATING: {
        /* trapezoidal lines along y: up-edge, top, down-edge, bottom */
        x -= S->ox;
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
    case S_MEASURED:
        return tt_surface_measured_at(S, x, y);
    case S_LATTICE:
        return tt_surface_lattice_at(S, x - S->ox, y - S->oy);
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
        double u = x / S->msx * S->mw, v = y / S->msy * S->mh;
        int i = u < 0 ? 0 : u >= S->mw ? S->mw - 1 : (int)u;
        int j = v < 0 ? 0 : v >= S->mh ? S->mh - 1 : (int)v;
        return S->mgrid[(size_t)j * S->mw + i];
    }
    case M_LABELS:
    case M_THRESHOLD:
        return tt_surface_map_image_at(S, x, y);
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
    /* in the pattern's own frame (offset_x taken off), its pieces moved back */
    const double s = S->ox;
    x0 -= s;
    x1 -= s;
    if (S->type == S_STEPS) {
        double w = S->step_w;
        for (double n = floor(x0 / w); n <= floor(x1 / w); n++)
            fn(user, n * w + s, n * S->step_h, (n + 1) * w + s, n * S->step_h);
        return 1;
    }
    if (S->type != S_GRATING)
        return 0;
    double p = S->period, top = S->duty * p, e = S->edge, H = S->height;
    for (double n = floor(x0 / p); n <= floor(x1 / p); n++) {
        double o = n * p + s;
        if (e > 0)
            fn(user, o, 0, o + e, H);
        fn(user, o + e, H, o + top, H);
        if (e > 0)
            fn(user, o + top, H, o + top + e, 0);
        fn(user, o + top + e, 0, o + p, 0);
    }
    return 1;
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
        S->ox = p->offset_x;
        break;
    case S_GRATING:
        S->period = p->period;
        S->duty = p->duty;
        S->height = p->height;
        S->edge = p->edge_width;
        S->ox = p->offset_x;
        break;
    case S_LATTICE:
        tt_surface_lattice_init(S, p);
        break;
    case S_PARTICLES:
        rc = build_particles(S, p);
        break;
    case S_ROUGH:
        rc = build_rough(S, p);
        break;
    case S_PNG:
        rc = tt_surface_build_png_height(S, p);
        break;
    case S_MEASURED:
        rc = tt_surface_build_measured(S, p);
        break;
    default:
        break;
    }
    if (S->map != M_UNIFORM && S->map != M_PNG && S->map != M_LABELS) {
        S->mat[0] = p->materials[0];
        S->mat[1] = p->materials[1];
        S->map_period = p->map_period;
        S->map_duty = p->map_duty;
        S->map_radius = p->map_radius;
    }
    if (rc == TT_OK && S->map == M_PNG)
        rc = tt_surface_build_png_map(S, p, materials, nmaterials);
    if (rc == TT_OK && (S->map == M_LABELS || S->map == M_THRESHOLD))
        rc = tt_surface_build_map_image(S, p, materials, nmaterials);
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
    tt_surface_measured_free(S);
    free(S->mgrid);
    free(S);
}