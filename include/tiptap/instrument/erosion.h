/* tiptap: grey-scale morphology of a height image by a tip (Villarrubia, J. Res. NIST
 * 102 (1997) 425): the image a tip makes of a surface (dilation), the greatest surface
 * consistent with an image (erosion, the reconstruction), and the pixels where that
 * reconstruction is certain (the certainty map).
 *
 * Conventions as in tip.h: the tip's surface t(u, v) >= 0 above its apex, the apex at
 * the image's height. On a grid of W x H pixels (row-major, row 0 first):
 *   dilation  I(x) = max over u of s(x + u) - t(u),
 *   erosion   r(y) = min over u of I(y - u) + t(u),
 * both over the pixels inside the image (nothing is assumed beyond its edges). The
 * erosion of a dilation is a closing of s: an upper bound, s <= r <= I everywhere,
 * r = s where the tip touched (docs/surfaces.md, "The tip already in a measured image").
 *
 * Ownership: tt_tip_image_make fills a tip image the caller frees with
 * tt_tip_image_free; the other functions write into arrays the caller provides.
 */
#ifndef TIPTAP_EROSION_H
#define TIPTAP_EROSION_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/instrument/tip.h"

TT_BEGIN_DECLS

/* A tip sampled on the image's pixels: t at (i dx, j dy) for |i| <= rx, |j| <= ry, in
 * t[(j + ry) (2 rx + 1) + i + rx]; INFINITY where the tip has no surface or rises more
 * than the height range it was made for. */
typedef struct {
    long rx, ry;
    double dx, dy;
    double *t;
} tt_tip_image;

/* The tip t on pixels dx x dy (m), kept where it rises no more than dh (m) above its
 * apex: parts higher than an image's height range cannot touch it. At most 1024 pixels
 * each side of the apex (fails beyond, naming the tip and the pixel). */
int tt_tip_image_make(tt_tip_image *out, const tt_tip_shape *t, double dx, double dy, double dh);
void tt_tip_image_free(tt_tip_image *ti);

/* out (W x H) = the image of surface s by the tip. */
void tt_erosion_dilate(const double *s, size_t W, size_t H, const tt_tip_image *tip, double *out);

/* out (W x H) = Villarrubia's reconstruction of the image im by the tip; out may not be
 * im. */
void tt_erosion_erode(const double *im, size_t W, size_t H, const tt_tip_image *tip, double *out);

/* certain (W x H) = 1 where the reconstruction r = tt_erosion_erode(im) is the true
 * surface: some tip position, its whole kept part inside the image, touches r at that
 * pixel alone (r within tol (m) of the tip's surface nowhere else); 0 elsewhere.
 * Returns the number of certain pixels. */
size_t tt_erosion_certainty(const double *im, const double *r, size_t W, size_t H,
                            const tt_tip_image *tip, double tol, unsigned char *certain);

TT_END_DECLS
#endif
