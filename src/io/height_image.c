/* Measured height images: units and the checks every reader makes (see
 * include/tiptap/io/height_image.h). */
#include "tiptap/io/height_image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

void tt_height_image_free(tt_height_image *im)
{
    if (!im)
        return;
    free(im->z);
    im->z = NULL;
}

double tt_length_unit(const char *u)
{
    static const struct {
        const char *name;
        double f;
    } units[] = {{"m", 1}, {"mm", 1e-3}, {"um", 1e-6}, {"\xc2\xb5m", 1e-6}, {"nm", 1e-9}, {"pm", 1e-12}};
    for (size_t i = 0; u && i < sizeof units / sizeof units[0]; i++)
        if (strcmp(u, units[i].name) == 0)
            return units[i].f;
    return -1;
}

/* Bounds of a sound image: a pixel from 1 pm (below any instrument's sampling) to 1 mm
 * (above any scanner's range), heights within 1 mm. */
#define PIXEL_MIN 1e-12
#define PIXEL_MAX 1e-3
#define HEIGHT_MAX 1e-3

int tt_height_image_check(const char *key, const char *path, const tt_height_image *im)
{
    if (im->xres < 2 || im->yres < 2)
        return tt_error(TT_EINVAL, "%s: %s: %zu x %zu pixels; a height image needs at least 2 x 2",
                        key, path, im->xres, im->yres);
    if (!(im->dx >= PIXEL_MIN && im->dx <= PIXEL_MAX && im->dy >= PIXEL_MIN && im->dy <= PIXEL_MAX))
        return tt_error(TT_EINVAL, "%s: %s: pixel size %g x %g m; expected 1 pm to 1 mm a pixel",
                        key, path, im->dx, im->dy);
    for (size_t k = 0; k < im->xres * im->yres; k++)
        if (!(fabs(im->z[k]) <= HEIGHT_MAX))
            return tt_error(TT_EINVAL, "%s: %s: pixel (%zu, %zu) is %g m; expected a finite height "
                                       "within 1 mm (no missing pixels: fill or crop them first)",
                            key, path, k % im->xres, k / im->xres, im->z[k]);
    return TT_OK;
}
