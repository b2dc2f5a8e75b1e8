/* Material maps from data (map = labels, threshold): a label image whose whole-number
 * labels are materials' map_values, or a channel (a measured phase image) split at a
 * threshold; taken pixel by pixel, never interpolated (docs/surfaces.md). */
#include "surface_private.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/height_image.h"
#include "tiptap/util/error.h"

#define KEY "[surface] map_image"

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && strcasecmp(s + n - m, tail) == 0;
}

/* A grey PNG: its levels are the values; its pixel is map_pixel_size, or the scan area
 * divided among its pixels when the aspects agree (a stretched map would misplace every
 * domain). */
static int read_png_values(const tt_surface_params *p, tt_height_image *im, double sx, double sy)
{
    unsigned short *pix;
    int w, h, maxv, rc = tt_surface_read_png_grey("map_image", p->map_image, &pix, &w, &h, &maxv);
    if (rc)
        return rc;
    im->xres = (size_t)w;
    im->yres = (size_t)h;
    if (p->map_pixel_size > 0)
        im->dx = im->dy = p->map_pixel_size;
    else {
        im->dx = sx / w;
        im->dy = sy / h;
        if (fabs(im->dx / im->dy - 1) > 0.01) {
            free(pix);
            return tt_error(TT_EINVAL, "[surface] map_pixel_size: %s: %d x %d pixels over the %g x %g nm "
                                       "scan area would stretch them %.3g:1; expected square pixels: "
                                       "give map_pixel_size (e.g. 2 nm)",
                            p->map_image, w, h, sx * 1e9, sy * 1e9, fmax(im->dx / im->dy, im->dy / im->dx));
        }
    }
    im->z = malloc(im->xres * im->yres * sizeof *im->z);
    if (!im->z) {
        free(pix);
        return tt_error_nomem("the map image %s", p->map_image);
    }
    for (size_t k = 0; k < im->xres * im->yres; k++)
        im->z[k] = pix[k];
    free(pix);
    return TT_OK;
}

/* The image as stored and its unit. */
static int read_values(const tt_surface_params *p, tt_height_image *im, char *unit, size_t nu,
                       double sx, double sy)
{
    memset(im, 0, sizeof *im);
    unit[0] = 0;
    if (ends_with(p->map_image, ".gsf"))
        return tt_gsf_read_values(KEY, p->map_image, im, unit, nu);
    if (ends_with(p->map_image, ".gwy"))
        return tt_gwy_read_values(KEY, p->map_image, p->map_channel, im, unit, nu);
    if (ends_with(p->map_image, ".png"))
        return read_png_values(p, im, sx, sy);
    return tt_error(TT_EINVAL, KEY ": %s: expected a .gsf, .gwy or grey .png image", p->map_image);
}

/* Sizes and cover, as a measured height image's: the image must cover the scan area
 * unless its edges continue (clamp, periodic). */
static int check_image(const tt_surface_params *p, const tt_height_image *im, double sx, double sy)
{
    const char *name = p->map_image;
    if (im->xres < 1 || im->yres < 1 || !(im->dx >= 1e-12 && im->dx <= 1e-3 && im->dy >= 1e-12 && im->dy <= 1e-3))
        return tt_error(TT_EINVAL, KEY ": %s: %zu x %zu pixels of %g x %g m; expected pixels of 1 pm to 1 mm",
                        name, im->xres, im->yres, im->dx, im->dy);
    double w = (double)im->xres * im->dx, h = (double)im->yres * im->dy;
    if (p->edges != TT_EDGES_REFUSE || (w >= sx * (1 - 1e-9) && h >= sy * (1 - 1e-9)))
        return TT_OK;
    return tt_error(TT_EINVAL, "[surface] edges: %s: the map image covers %g x %g nm (%zu x %zu pixels of "
                               "%g x %g nm), the scan area %g x %g nm; expected an image at least as "
                               "large, or edges = clamp or periodic",
                    name, w * 1e9, h * 1e9, im->xres, im->yres, im->dx * 1e9, im->dy * 1e9, sx * 1e9, sy * 1e9);
}

/* Label v's material: the one whose map_value (a grey level) it is; -1 when none. */
static int label_material(double v, const tt_material *mat, size_t nm)
{
    for (size_t i = 0; i < nm; i++)
        if (mat[i].map_grey >= 0 && (double)mat[i].map_grey == v)
            return (int)i;
    return -1;
}

static int build_labels(tt_surface *S, const tt_surface_params *p, const tt_height_image *im,
                        const tt_material *mat, size_t nm)
{
    const char *name = p->map_image;
    for (size_t i = 0; i < nm; i++)
        for (size_t j = i + 1; j < nm; j++)
            if (mat[i].map_grey >= 0 && mat[i].map_grey == mat[j].map_grey)
                return tt_error(TT_EINVAL, "[material %s] map_value: label %ld is [material %s]'s too; "
                                           "give each material a label of its own",
                                mat[j].name, mat[j].map_grey, mat[i].name);
    for (size_t k = 0; k < im->xres * im->yres; k++) {
        double v = im->z[k];
        if (!(v >= 0 && v <= 65535 && v == floor(v)))
            return tt_error(TT_EINVAL, KEY ": %s: pixel (%zu, %zu) is %g; a label image holds whole "
                                       "numbers 0 to 65535 (use map = threshold for a measured channel)",
                            name, k % im->xres, k / im->xres, v);
        if ((S->mgrid[k] = label_material(v, mat, nm)) < 0)
            return tt_error(TT_EINVAL, KEY ": %s: pixel (%zu, %zu) has label %g, which no [material] "
                                       "map_value names",
                            name, k % im->xres, k / im->xres, v);
    }
    return TT_OK;
}

static int build_threshold(tt_surface *S, const tt_surface_params *p, tt_height_image *im,
                           const char *unit)
{
    const char *name = p->map_image, *tu = p->map_threshold_unit;
    double t = p->map_threshold, fu = tt_length_unit(unit), ft = tt_length_unit(tu);
    /* lengths compare across prefixes; any other unit must be the image's as written */
    if (fu > 0 && ft > 0) {
        t *= ft / fu;
    } else if (strcmp(unit, tu) != 0)
        return tt_error(TT_EINVAL, "[surface] map_threshold: %g %s, but %s is in '%s'; expected a "
                                   "threshold in the image's unit",
                        p->map_threshold, *tu ? tu : "(no unit)", name, *unit ? unit : "(no unit)");
    for (size_t k = 0; k < im->xres * im->yres; k++) {
        if (!isfinite(im->z[k]))
            return tt_error(TT_EINVAL, KEY ": %s: pixel (%zu, %zu) is %g; expected finite values "
                                       "(fill or crop missing pixels first)",
                            name, k % im->xres, k / im->xres, im->z[k]);
        S->mgrid[k] = im->z[k] >= t ? p->materials[1] : p->materials[0];
    }
    return TT_OK;
}

int tt_surface_build_map_image(tt_surface *S, const tt_surface_params *p, const tt_material *mat,
                               size_t nm)
{
    tt_height_image im;
    char unit[64];
    int rc = read_values(p, &im, unit, sizeof unit, S->sx, S->sy);
    if (!rc)
        rc = check_image(p, &im, S->sx, S->sy);
    if (!rc && !(S->mgrid = malloc(im.xres * im.yres * sizeof *S->mgrid)))
        rc = tt_error_nomem("the material map (%zu x %zu pixels)", im.xres, im.yres);
    if (!rc)
        rc = p->map == TT_MAP_LABELS ? build_labels(S, p, &im, mat, nm) : build_threshold(S, p, &im, unit);
    S->mw = (int)im.xres;
    S->mh = (int)im.yres;
    S->mdx = im.dx;
    S->mdy = im.dy;
    S->medges = (int)p->edges;
    tt_height_image_free(&im);
    return rc;
}

/* Pixel i covers [i dx, (i + 1) dx), as the scan's own pixels and a measured image's. */
static int pixel_of(double u, int n, int periodic)
{
    double i = floor(u);
    if (periodic)
        i -= n * floor(i / n);
    return !(i >= 0) ? 0 : i >= n ? n - 1 : (int)i; /* clamped (NaN too): past the image its edge continues */
}

int tt_surface_map_image_at(const tt_surface *S, double x, double y)
{
    int per = S->medges == TT_EDGES_PERIODIC;
    int i = pixel_of(x / S->mdx, S->mw, per), j = pixel_of(y / S->mdy, S->mh, per);
    return S->mgrid[(size_t)j * S->mw + i];
}

int tt_surface_check_map_image(const tt_surface_params *p, const tt_material *mat, size_t nm,
                               double sx, double sy)
{
    if (p->map != TT_MAP_LABELS && p->map != TT_MAP_THRESHOLD)
        return TT_OK;
    tt_surface S;
    memset(&S, 0, sizeof S);
    S.sx = sx;
    S.sy = sy;
    int rc = tt_surface_build_map_image(&S, p, mat, nm);
    free(S.mgrid);
    return rc;
}
