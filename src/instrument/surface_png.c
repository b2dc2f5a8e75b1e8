/* PNG maps of the surface: a grey height map (type png), a material map (map png), and
 * the 16-bit images a measured surface may come from (see surface_private.h). */
#include "surface_private.h"

#include <fftw3.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/files.h"
#include "tiptap/util/error.h"

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
            rc = tt_error(TT_EINVAL, "[surface] %s: %s: pixel (%zu, %zu) has colour (%u, %u, %u); %s",
                               key, path, k % W, k / W, r, g, b,
                               strstr(key, "map_image") ? "a label or threshold image is grey (map = png names "
                                                          "materials by colour)"
                                                        : "a height map is grey");
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

/* What a PNG of w x h pixels spans (m): w and h times pixel_size when given (key), else
 * the scan area, whose aspect must then be the image's (a stretched map misplaces every
 * feature); an image with a pixel size smaller than the area is refused. */
static int png_span(const char *key, const char *path, int w, int h, double pixel, double sx,
                    double sy, double *span_x, double *span_y)
{
    if (pixel > 0) {
        *span_x = w * pixel;
        *span_y = h * pixel;
        if (*span_x >= sx * (1 - 1e-9) && *span_y >= sy * (1 - 1e-9))
            return TT_OK;
        return tt_error(TT_EINVAL, "[surface] %s: %s: %d x %d pixels of %g nm cover %g x %g nm, less "
                                   "than the %g x %g nm scan area; expected an image at least as large "
                                   "(a larger %s or a smaller [scan] size)",
                        key, path, w, h, pixel * 1e9, *span_x * 1e9, *span_y * 1e9, sx * 1e9, sy * 1e9, key);
    }
    *span_x = sx;
    *span_y = sy;
    double dx = sx / w, dy = sy / h;
    if (fabs(dx / dy - 1) <= 0.01)
        return TT_OK;
    return tt_error(TT_EINVAL, "[surface] %s: %s: %d x %d pixels over the %g x %g nm scan area would "
                               "stretch them %.3g:1; expected square pixels: give %s (e.g. %.3g nm), or "
                               "a scan area of the image's aspect",
                    key, path, w, h, sx * 1e9, sy * 1e9, fmax(dx / dy, dy / dx), key, fmin(dx, dy) * 1e9);
}

int tt_surface_build_png_height(tt_surface *S, const tt_surface_params *p)
{
    double range = p->png_height_range;
    int rc, maxv;
    unsigned short *pix = NULL;
    if ((rc = read_png("png", p->png, 0, &pix, &S->gw, &S->gh, &maxv)))
        return rc;
    if ((rc = png_span("pixel_size", p->png, S->gw, S->gh, p->pixel_size, S->sx, S->sy, &S->gsx, &S->gsy))) {
        free(pix);
        return rc;
    }
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


int tt_surface_read_png16(const char *key, const char *path, unsigned short **pix, int *w, int *h)
{
    /* read_png names the section itself: "[surface] image" once, not twice */
    int maxv, rc = read_png(strncmp(key, "[surface] ", 10) == 0 ? key + 10 : key, path, 0, pix, w, h, &maxv);
    if (rc == TT_OK && maxv != 65535) {
        free(*pix);
        *pix = NULL;
        return tt_error(TT_EINVAL, "%s: %s: an 8-bit PNG (256 levels); expected a 16-bit grey image "
                                   "(or type = png for a drawn map)", key, path);
    }
    return rc;
}

int tt_surface_read_png_grey(const char *key, const char *path, unsigned short **pix, int *w, int *h,
                             int *maxval)
{
    return read_png(key, path, 0, pix, w, h, maxval);
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

/* An anti-aliased pixel c (packed as map_key packs): the material whose colour is nearest,
 * by Euclidean distance in 8-bit levels, when within tol; ties go to the material first
 * in the scene. -1 when none is within tol. */
static int nearest_key(const unsigned long long *key, size_t nm, unsigned long long c, int maxv,
                       double tol)
{
    double unit = maxv == 255 ? 1 : 257, best = tol * unit * (tol * unit);
    int found = -1;
    for (size_t i = 0; i < nm; i++) {
        if (key[i] == ~0ULL)
            continue;
        double d2 = 0;
        for (int sh = 0; sh < 48; sh += 16) {
            double d = (double)(key[i] >> sh & 0xffff) - (double)(c >> sh & 0xffff);
            d2 += d * d;
        }
        if (d2 <= best && (found < 0 || d2 < best)) {
            best = d2;
            found = (int)i;
        }
    }
    return found;
}

int tt_surface_build_png_map(tt_surface *S, const tt_surface_params *p, const tt_material *mat,
                             size_t nm)
{
    int rc, maxv;
    unsigned short *pix = NULL;
    const char *path = p->map_png;
    if ((rc = read_png("map_png", path, 1, &pix, &S->mw, &S->mh, &maxv)))
        return rc;
    if ((rc = png_span("map_pixel_size", path, S->mw, S->mh, p->map_pixel_size, S->sx, S->sy, &S->msx,
                       &S->msy))) {
        free(pix);
        return rc;
    }
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
    char tol[80] = "";
    if (p->map_tolerance > 0)
        snprintf(tol, sizeof tol, " within [surface] map_tolerance = %g levels", p->map_tolerance);
    for (size_t k = 0; k < (size_t)S->mw * S->mh && rc == TT_OK; k++) {
        unsigned long long c = (unsigned long long)pix[3 * k] << 32 |
                               (unsigned long long)pix[3 * k + 1] << 16 | pix[3 * k + 2];
        int found = -1;
        for (size_t i = 0; i < nm; i++)
            if (key[i] == c)
                found = (int)i;
        if (found < 0 && p->map_tolerance > 0)
            found = nearest_key(key, nm, c, maxv, p->map_tolerance);
        if (found < 0 && maxv == 255)
            rc = tt_error(TT_EINVAL, "[surface] map_png: %s: pixel (%zu, %zu) has colour "
                          "#%02x%02x%02x, which no [material] map_value names%s", path,
                          k % (size_t)S->mw, k / (size_t)S->mw, pix[3 * k], pix[3 * k + 1],
                          pix[3 * k + 2], tol);
        else if (found < 0)
            rc = tt_error(TT_EINVAL, "[surface] map_png: %s: pixel (%zu, %zu) has 16-bit level "
                          "(%u, %u, %u), which no [material] map_value names%s", path,
                          k % (size_t)S->mw, k / (size_t)S->mw, pix[3 * k], pix[3 * k + 1],
                          pix[3 * k + 2], tol);
        S->mgrid[k] = found;
    }
    free(key);
    free(pix);
    return rc;
}
