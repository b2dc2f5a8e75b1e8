/* A measured height image as the surface: read (.gsf, .gwy, 16-bit .png), cropped,
 * levelled as Gwyddion levels, scaled, and interpolated with GSL's gsl_interp2d
 * (see docs/surfaces.md, "Measured surfaces"). */
#include "surface_private.h"

#include <gsl/gsl_interp2d.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/instrument/erosion.h"
#include "tiptap/io/height_image.h"
#include "tiptap/util/error.h"

#define KEY "[surface] image"

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    if (n < m)
        return 0;
    for (size_t i = 0; i < m; i++)
        if ((s[n - m + i] | 0x20) != tail[i])
            return 0;
    return 1;
}

/* A 16-bit grey PNG: it carries no size or unit, so the scene's pixel_size and
 * png_height_range give them. */
static int read_png_image(const tt_surface_params *p, tt_height_image *im)
{
    unsigned short *pix;
    int w, h;
    if (!(p->pixel_size > 0))
        return tt_error(TT_EINVAL, "[surface] pixel_size: %s: a PNG carries no pixel size; expected "
                                   "pixel_size = the image's pixel (e.g. 2 nm)",
                        p->image);
    int rc = tt_surface_read_png16(KEY, p->image, &pix, &w, &h);
    if (rc)
        return rc;
    im->xres = (size_t)w;
    im->yres = (size_t)h;
    im->dx = im->dy = p->pixel_size;
    im->z = malloc(im->xres * im->yres * sizeof *im->z);
    if (!im->z) {
        free(pix);
        return tt_error_nomem("the height image %s", p->image);
    }
    for (size_t k = 0; k < im->xres * im->yres; k++)
        im->z[k] = p->png_height_range * (double)pix[k] / 65535.0;
    free(pix);
    return tt_height_image_check(KEY, p->image, im);
}

static int read_image(const tt_surface_params *p, tt_height_image *im)
{
    memset(im, 0, sizeof *im);
    if (ends_with(p->image, ".gsf"))
        return tt_gsf_read_height(KEY, p->image, im);
    if (ends_with(p->image, ".gwy"))
        return tt_gwy_read_height(KEY, p->image, p->channel, im);
    if (ends_with(p->image, ".png"))
        return read_png_image(p, im);
    return tt_error(TT_EINVAL, KEY ": %s: expected a .gsf, .gwy or 16-bit .png height image", p->image);
}

/* crop = left top width height, in the image's pixels. */
static int crop(const tt_surface_params *p, tt_height_image *im)
{
    const long *c = p->crop;
    if (c[2] == 0)
        return TT_OK;
    /* compared by subtraction: left + width could overflow */
    if (c[0] < 0 || c[1] < 0 || c[2] < 2 || c[3] < 2 || (size_t)c[0] >= im->xres ||
        (size_t)c[1] >= im->yres || (size_t)c[2] > im->xres - (size_t)c[0] ||
        (size_t)c[3] > im->yres - (size_t)c[1])
        return tt_error(TT_EINVAL, "[surface] crop: %s: %ld %ld %ld %ld; expected left top width height "
                                   "within the image's %zu x %zu pixels, at least 2 x 2",
                        p->image, c[0], c[1], c[2], c[3], im->xres, im->yres);
    size_t w = (size_t)c[2], h = (size_t)c[3];
    for (size_t j = 0; j < h; j++)
        memmove(im->z + j * w, im->z + ((size_t)c[1] + j) * im->xres + (size_t)c[0], w * sizeof *im->z);
    im->xres = w;
    im->yres = h;
    return TT_OK;
}

/* Least squares: the full regular grid makes the plane's normal equations separate
 * about the image's centre, so mean and slopes come in one pass. */
static void level_plane(tt_height_image *im, int slopes)
{
    size_t W = im->xres, H = im->yres;
    double ic = 0.5 * (double)(W - 1), jc = 0.5 * (double)(H - 1);
    double s = 0, si = 0, sj = 0, ii = 0, jj = 0;
    for (size_t j = 0; j < H; j++)
        for (size_t i = 0; i < W; i++) {
            double z = im->z[j * W + i], u = (double)i - ic, v = (double)j - jc;
            s += z;
            si += u * z;
            sj += v * z;
            ii += u * u;
            jj += v * v;
        }
    double a = s / (double)(W * H), b = slopes ? si / ii : 0, c = slopes ? sj / jj : 0;
    for (size_t j = 0; j < H; j++)
        for (size_t i = 0; i < W; i++)
            im->z[j * W + i] -= a + b * ((double)i - ic) + c * ((double)j - jc);
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of n values (sorted in place): the mean of the middle two for even n. */
static double median(double *v, size_t n)
{
    qsort(v, n, sizeof *v, by_value);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Each row (the fast axis) on its own: its mean, line or median taken off; or, for the
 * median of differences, shifted so that the median step from the row above is zero
 * (the first row stays): Gwyddion's "Align rows". */
static int level_lines(tt_height_image *im, tt_surface_lines how)
{
    size_t W = im->xres, H = im->yres;
    double *tmp = malloc(W * sizeof *tmp);
    if (!tmp)
        return tt_error_nomem("a row of the height image (%zu pixels)", W);
    double ic = 0.5 * (double)(W - 1), ii = 0;
    for (size_t i = 0; i < W; i++)
        ii += ((double)i - ic) * ((double)i - ic);
    for (size_t j = 0; j < H; j++) {
        double *r = im->z + j * W, a = 0, b = 0;
        switch (how) {
        case TT_LINES_OFFSET:
        case TT_LINES_SLOPE:
            for (size_t i = 0; i < W; i++) {
                a += r[i] / (double)W;
                b += how == TT_LINES_SLOPE ? ((double)i - ic) * r[i] / ii : 0;
            }
            break;
        case TT_LINES_MEDIAN:
            memcpy(tmp, r, W * sizeof *tmp);
            a = median(tmp, W);
            break;
        case TT_LINES_MEDIAN_DIFFERENCE:
            if (j == 0)
                continue;
            for (size_t i = 0; i < W; i++)
                tmp[i] = r[i] - r[i - W];
            a = median(tmp, W);
            break;
        default:
            break;
        }
        for (size_t i = 0; i < W; i++)
            r[i] -= a + b * ((double)i - ic);
    }
    free(tmp);
    return TT_OK;
}

/* The image must cover the scan area unless its edges may continue (clamp, periodic). */
static int check_cover(const tt_surface_params *p, const tt_height_image *im, double sx, double sy)
{
    double w = (double)im->xres * im->dx, h = (double)im->yres * im->dy;
    const double *v = p->visit;
    if (p->edges == TT_EDGES_REFUSE && (v[0] != 0 || v[1] != 0 || v[2] != 0 || v[3] != 0) &&
        !(v[0] >= -1e-9 * sx && v[1] >= -1e-9 * sy && v[2] <= w * (1 + 1e-9) && v[3] <= h * (1 + 1e-9)))
        return tt_error(TT_EINVAL, "[surface] edges: %s: the image covers 0 to %g nm by 0 to %g nm, the "
                                   "scan (its angle and offset) visits %g to %g nm by %g to %g nm; "
                                   "expected an image covering it, or edges = clamp or periodic",
                        p->image, w * 1e9, h * 1e9, v[0] * 1e9, v[2] * 1e9, v[1] * 1e9, v[3] * 1e9);
    if (p->edges != TT_EDGES_REFUSE || (w >= sx * (1 - 1e-9) && h >= sy * (1 - 1e-9)))
        return TT_OK;
    return tt_error(TT_EINVAL, "[surface] edges: %s: the image covers %g x %g nm (%zu x %zu pixels of "
                               "%g x %g nm), the scan area %g x %g nm; expected an image at least as "
                               "large, or edges = clamp or periodic",
                    p->image, w * 1e9, h * 1e9, im->xres, im->yres, im->dx * 1e9, im->dy * 1e9,
                    sx * 1e9, sy * 1e9);
}

/* The tip that took the image eroded out of it (Villarrubia's reconstruction): the
 * greatest surface that tip could have imaged so; with certain, its certainty map too
 * (W x H, the caller frees; NULL without erosion). Two heights within 1e-6 of the
 * image's range are one contact: a float GSF rounds to 6e-8 of it. */
static int erode_tip(const tt_surface_params *p, tt_height_image *im, unsigned char **certain)
{
    if (certain)
        *certain = NULL;
    if (p->measured_tip == TT_TIP_POINT)
        return TT_OK;
    tt_tip_shape t = {(tt_tip_kind)p->measured_tip, p->measured_tip_radius, p->measured_tip_half_angle};
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = 0; k < im->xres * im->yres; k++) {
        lo = fmin(lo, im->z[k]);
        hi = fmax(hi, im->z[k]);
    }
    tt_tip_image tip;
    int rc = tt_tip_image_make(&tip, &t, im->dx, im->dy, hi - lo);
    if (rc) {
        char why[512];
        snprintf(why, sizeof why, "%s", tt_error_message());
        return tt_error(rc, "[surface] measured_tip_radius: %s: %s", p->image, why);
    }
    double *r = malloc(im->xres * im->yres * sizeof *r);
    if (!r) {
        tt_tip_image_free(&tip);
        return tt_error_nomem("the eroded height image (%zu x %zu pixels)", im->xres, im->yres);
    }
    tt_erosion_erode(im->z, im->xres, im->yres, &tip, r);
    if (certain && !(*certain = malloc(im->xres * im->yres))) {
        tt_tip_image_free(&tip);
        free(r);
        return tt_error_nomem("the erosion's certainty map (%zu x %zu pixels)", im->xres, im->yres);
    }
    if (certain)
        tt_erosion_certainty(im->z, r, im->xres, im->yres, &tip, 1e-6 * (hi - lo), *certain);
    tt_tip_image_free(&tip);
    free(im->z);
    im->z = r;
    return TT_OK;
}

/* The image read and prepared: cropped, levelled, scaled, the measuring tip eroded out
 * (certain: as erode_tip's). */
static int prepare(const tt_surface_params *p, tt_height_image *im, double sx, double sy,
                   unsigned char **certain)
{
    if (certain)
        *certain = NULL;
    int rc;
    if ((rc = read_image(p, im)) || (rc = crop(p, im)) || (rc = check_cover(p, im, sx, sy)))
        return rc;
    if (p->level != TT_LEVEL_NONE)
        level_plane(im, p->level == TT_LEVEL_PLANE);
    if (p->line_level != TT_LINES_NONE && (rc = level_lines(im, p->line_level)))
        return rc;
    for (size_t k = 0; k < im->xres * im->yres; k++)
        im->z[k] = p->z_scale * im->z[k] + p->z_offset;
    return erode_tip(p, im, certain);
}

int tt_surface_check_measured(const tt_surface_params *p, double sx, double sy)
{
    if (p->type != TT_SURFACE_MEASURED)
        return TT_OK;
    tt_height_image im;
    int rc = prepare(p, &im, sx, sy, NULL);
    tt_height_image_free(&im);
    return rc;
}

/* Periodic edges pad the nodes with this many wrapped pixels each side: enough for the
 * bicubic's neighbours at the image's seam. */
#define PAD 2

int tt_surface_build_measured(tt_surface *S, const tt_surface_params *p)
{
    tt_height_image im;
    int rc = prepare(p, &im, S->sx, S->sy, &S->certain);
    S->cert_w = im.xres;
    S->cert_h = im.yres;
    S->cdx = im.dx;
    S->cdy = im.dy;
    const gsl_interp2d_type *T = p->bicubic ? gsl_interp2d_bicubic : gsl_interp2d_bilinear;
    size_t W = im.xres, H = im.yres, pad = p->edges == TT_EDGES_PERIODIC ? PAD : 0;
    if (!rc && (W < gsl_interp2d_type_min_size(T) || H < gsl_interp2d_type_min_size(T)))
        rc = tt_error(TT_EINVAL, "[surface] interpolation: %s: %zu x %zu pixels; bicubic needs at "
                                 "least %zu x %zu",
                      p->image, W, H, gsl_interp2d_type_min_size(T), gsl_interp2d_type_min_size(T));
    if (rc) {
        tt_height_image_free(&im);
        return rc;
    }
    S->nx = W + 2 * pad;
    S->ny = H + 2 * pad;
    S->xa = malloc(S->nx * sizeof *S->xa);
    S->ya = malloc(S->ny * sizeof *S->ya);
    S->za = malloc(S->nx * S->ny * sizeof *S->za);
    S->interp = S->xa && S->ya && S->za ? gsl_interp2d_alloc(T, S->nx, S->ny) : NULL;
    if (!S->interp) {
        tt_height_image_free(&im);
        return tt_error_nomem("the height image's interpolation (%zu x %zu nodes)", S->nx, S->ny);
    }
    /* nodes at the pixels' centres, (i + 1/2) dx, as the scan's own pixels */
    for (size_t k = 0; k < S->nx; k++)
        S->xa[k] = ((double)k - (double)pad + 0.5) * im.dx;
    for (size_t k = 0; k < S->ny; k++)
        S->ya[k] = ((double)k - (double)pad + 0.5) * im.dy;
    for (size_t l = 0; l < S->ny; l++)
        for (size_t k = 0; k < S->nx; k++) {
            size_t i = (k + W - pad) % W, j = (l + H - pad) % H;
            S->za[l * S->nx + k] = im.z[j * W + i];
        }
    S->lo_x = S->xa[0];
    S->hi_x = S->xa[S->nx - 1];
    S->lo_y = S->ya[0];
    S->hi_y = S->ya[S->ny - 1];
    S->wrap_x = pad ? (double)W * im.dx : 0;
    S->wrap_y = pad ? (double)H * im.dy : 0;
    tt_height_image_free(&im);
    gsl_interp2d_init(S->interp, S->xa, S->ya, S->za, S->nx, S->ny);
    return TT_OK;
}

double tt_surface_measured_at(const tt_surface *S, double x, double y)
{
    if (S->wrap_x > 0) {
        x -= S->wrap_x * floor(x / S->wrap_x);
        y -= S->wrap_y * floor(y / S->wrap_y);
    }
    /* clamped into the nodes' span (GSL refuses a point outside it); fmax takes a NaN
     * to the low end */
    x = fmin(fmax(x, S->lo_x), S->hi_x);
    y = fmin(fmax(y, S->lo_y), S->hi_y);
    return gsl_interp2d_eval(S->interp, S->xa, S->ya, S->za, x, y, NULL, NULL);
}

double tt_surface_certainty(const tt_surface *S, double x, double y)
{
    if (!S->certain)
        return NAN;
    if (S->wrap_x > 0) {
        x -= S->wrap_x * floor(x / S->wrap_x);
        y -= S->wrap_y * floor(y / S->wrap_y);
    }
    /* the nearest pixel, clamped as the heights are */
    double u = floor(x / S->cdx), v = floor(y / S->cdy);
    size_t i = u < 0 ? 0 : u >= (double)S->cert_w ? S->cert_w - 1 : (size_t)u;
    size_t j = v < 0 ? 0 : v >= (double)S->cert_h ? S->cert_h - 1 : (size_t)v;
    return S->certain[j * S->cert_w + i];
}

void tt_surface_measured_free(tt_surface *S)
{
    free(S->certain);
    if (S->interp)
        gsl_interp2d_free(S->interp);
    free(S->xa);
    free(S->ya);
    free(S->za);
}
