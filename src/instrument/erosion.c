/* Grey-scale dilation, Villarrubia's erosion and certainty map of a height image by a
 * tip sampled on its pixels (erosion.h; J. S. Villarrubia, J. Res. NIST 102 (1997) 425,
 * the certainty map as Gwyddion's libprocess/tip.c computes it). */
#include "tiptap/instrument/erosion.h"

#include <math.h>
#include <stdlib.h>

#include "tiptap/util/error.h"

/* A tip wider than this many pixels each side is refused: its cost grows as its area. */
#define MAX_HALF 1024

int tt_tip_image_make(tt_tip_image *out, const tt_tip_shape *t, double dx, double dy, double dh)
{
    out->t = NULL;
    out->dx = dx;
    out->dy = dy;
    double reach = t->kind == TT_TIP_POINT ? 0 : tt_tip_shape_reach(t, dh);
    double hx = floor(reach / dx), hy = floor(reach / dy);
    if (!(hx <= MAX_HALF && hy <= MAX_HALF))
        return tt_error(TT_EINVAL, "a tip image: the tip reaches %g nm within the image's %g nm "
                                   "height range, over %d pixels of %g x %g nm; expected a larger "
                                   "pixel or a sharper tip",
                        reach * 1e9, dh * 1e9, MAX_HALF, dx * 1e9, dy * 1e9);
    out->rx = (long)hx;
    out->ry = (long)hy;
    size_t nx = (size_t)(2 * out->rx + 1), ny = (size_t)(2 * out->ry + 1);
    out->t = malloc(nx * ny * sizeof *out->t);
    if (!out->t)
        return tt_error_nomem("a tip image (%zu x %zu pixels)", nx, ny);
    for (long j = -out->ry; j <= out->ry; j++)
        for (long i = -out->rx; i <= out->rx; i++) {
            double rho = hypot((double)i * dx, (double)j * dy);
            double h = i == 0 && j == 0 ? 0 : t->kind == TT_TIP_POINT ? INFINITY : tt_tip_shape_height(t, rho);
            out->t[(size_t)(j + out->ry) * nx + (size_t)(i + out->rx)] = h <= dh ? h : INFINITY;
        }
    return TT_OK;
}

void tt_tip_image_free(tt_tip_image *ti)
{
    free(ti->t);
    ti->t = NULL;
}

static double tip_at(const tt_tip_image *tip, long i, long j)
{
    return tip->t[(size_t)(j + tip->ry) * (size_t)(2 * tip->rx + 1) + (size_t)(i + tip->rx)];
}

void tt_erosion_dilate(const double *s, size_t W, size_t H, const tt_tip_image *tip, double *out)
{
    for (long y = 0; y < (long)H; y++)
        for (long x = 0; x < (long)W; x++) {
            double m = -INFINITY;
            for (long j = -tip->ry; j <= tip->ry; j++) {
                if (y + j < 0 || y + j >= (long)H)
                    continue;
                for (long i = -tip->rx; i <= tip->rx; i++) {
                    if (x + i < 0 || x + i >= (long)W)
                        continue;
                    double v = s[(size_t)(y + j) * W + (size_t)(x + i)] - tip_at(tip, i, j);
                    m = v > m ? v : m;
                }
            }
            out[(size_t)y * W + (size_t)x] = m;
        }
}

void tt_erosion_erode(const double *im, size_t W, size_t H, const tt_tip_image *tip, double *out)
{
    for (long y = 0; y < (long)H; y++)
        for (long x = 0; x < (long)W; x++) {
            double m = INFINITY;
            for (long j = -tip->ry; j <= tip->ry; j++) {
                if (y - j < 0 || y - j >= (long)H)
                    continue;
                for (long i = -tip->rx; i <= tip->rx; i++) {
                    if (x - i < 0 || x - i >= (long)W)
                        continue;
                    double v = im[(size_t)(y - j) * W + (size_t)(x - i)] + tip_at(tip, i, j);
                    m = v < m ? v : m;
                }
            }
            out[(size_t)y * W + (size_t)x] = m;
        }
}

/* Why one contact is enough (Villarrubia, sec. 4): the tip at x touched the true surface
 * s somewhere, s <= r <= I(x) + t there, so that point is a contact of r too; when r has
 * only one, it is that one, and r = s there. */
size_t tt_erosion_certainty(const double *im, const double *r, size_t W, size_t H,
                            const tt_tip_image *tip, double tol, unsigned char *certain)
{
    size_t n = 0;
    for (size_t k = 0; k < W * H; k++)
        certain[k] = 0;
    for (long y = tip->ry; y + tip->ry < (long)H; y++)
        for (long x = tip->rx; x + tip->rx < (long)W; x++) {
            double top = im[(size_t)y * W + (size_t)x];
            long count = 0;
            size_t at = 0;
            for (long j = -tip->ry; j <= tip->ry && count < 2; j++)
                for (long i = -tip->rx; i <= tip->rx && count < 2; i++) {
                    size_t k = (size_t)(y + j) * W + (size_t)(x + i);
                    if (r[k] >= top + tip_at(tip, i, j) - tol) {
                        count++;
                        at = k;
                    }
                }
            if (count == 1 && !certain[at]) {
                certain[at] = 1;
                n++;
            }
        }
    return n;
}
