/* tiptap: measured height images read for a [surface] of type measured.
 *
 * Each reader takes the file's own pixel size and units and refuses, in one line naming
 * the key, the file and what is expected, a file without units, of zero size, with a
 * non-finite pixel, truncated, or without the channel asked for. Lengths come back in
 * metres: a unit is "m" with an optional SI prefix (pm, nm, um or µm, mm).
 *
 * Ownership: a reader fills *out with an array the caller frees with
 * tt_height_image_free.
 */
#ifndef TIPTAP_HEIGHT_IMAGE_H
#define TIPTAP_HEIGHT_IMAGE_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct {
    size_t xres, yres;   /* pixels along x (a row) and y (rows) */
    double dx, dy;       /* pixel size, m */
    double *z;           /* xres * yres heights, m, row 0 at the top (y = 0) */
} tt_height_image;

void tt_height_image_free(tt_height_image *im);

/* The factor that turns unit into metres (1e-9 for "nm"); -1 when unit is no length. */
double tt_length_unit(const char *unit);

/* The checks every reader makes once the image is in: a pixel size between 1 pm and
 * 1 mm, at least 2 x 2 pixels, every height finite and within 1 mm. key names the scene
 * key in messages ("[surface] image"). */
int tt_height_image_check(const char *key, const char *path, const tt_height_image *im);

/* A Gwyddion Simple Field file (gsf.h): XRes, YRes, XReal, YReal, XYUnits and ZUnits
 * are required here (the format makes the last four optional). */
int tt_gsf_read_height(const char *key, const char *path, tt_height_image *out);

/* A channel of a Gwyddion native file (gwy.h), tiptap's or Gwyddion's: channel is its
 * title (as Gwyddion shows it), its number N (the container's "/N/data"), or NULL or ""
 * for the first. A missing channel is refused listing those the file holds. */
int tt_gwy_read_height(const char *key, const char *path, const char *channel,
                       tt_height_image *out);

/* The same files read as a channel of any quantity (a label or phase image): the values
 * as stored, their unit (ZUnits, si_unit_z; "" when the file gives none) copied into
 * zunit; lateral sizes in metres as above. No checks on the values: the caller makes
 * its own. */
int tt_gsf_read_values(const char *key, const char *path, tt_height_image *out, char *zunit,
                       size_t nzunit);
int tt_gwy_read_values(const char *key, const char *path, const char *channel,
                       tt_height_image *out, char *zunit, size_t nzunit);

TT_END_DECLS
#endif
