/* tiptap: sample topography and material map.
 *
 * Heights in metres along the axis pointing out of the sample towards the tip (a bump
 * is positive); x, y in metres in the scan frame, (0, 0) the top-left corner of the
 * scan area. Materials are indices into the scan's material list.
 *
 * Errors name the section and the key, "[surface] key: what is wrong"; the caller that
 * knows the scene file adds it (tt_scene_locate).
 *
 * Ownership: tt_surface_alloc returns an object the caller frees with
 * tt_surface_free; it is read-only after allocation and may be shared between threads.
 */
#ifndef TIPTAP_SURFACE_H
#define TIPTAP_SURFACE_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/physics/contact.h"
#include "tiptap/physics/material.h"

TT_BEGIN_DECLS

typedef enum {
    TT_SURFACE_FLAT, TT_SURFACE_STEPS, TT_SURFACE_GRATING, TT_SURFACE_PARTICLES,
    TT_SURFACE_ROUGH, TT_SURFACE_PNG, TT_SURFACE_MEASURED, TT_SURFACE_LATTICE
} tt_surface_type;

/* A lattice's arrangement and its features (docs/surfaces.md, "Lattices"). */
typedef enum { TT_LATTICE_SQUARE, TT_LATTICE_HEXAGONAL } tt_lattice;
typedef enum { TT_FEATURE_PILLAR, TT_FEATURE_HOLE, TT_FEATURE_SPIKE } tt_feature;

/* A measured image's preparation (docs/surfaces.md, "Measured surfaces"). */
typedef enum { TT_LEVEL_NONE, TT_LEVEL_OFFSET, TT_LEVEL_PLANE } tt_surface_level;
typedef enum {
    TT_LINES_NONE, TT_LINES_OFFSET, TT_LINES_SLOPE, TT_LINES_MEDIAN, TT_LINES_MEDIAN_DIFFERENCE
} tt_surface_lines;
typedef enum { TT_EDGES_REFUSE, TT_EDGES_CLAMP, TT_EDGES_PERIODIC } tt_surface_edges;

typedef enum {
    TT_MAP_UNIFORM, TT_MAP_STRIPES, TT_MAP_DISKS, TT_MAP_CHECKERBOARD, TT_MAP_ISLANDS, TT_MAP_PNG,
    TT_MAP_LABELS, TT_MAP_THRESHOLD
} tt_surface_map;

/* The [surface] section in SI units; only the fields of the chosen type and map are
 * read. Paths are resolved (absolute or relative to the working folder). */
typedef struct {
    tt_surface_type type;
    double step_height, step_width;             /* steps */
    double period, duty, height, edge_width;    /* grating; lattice: period, height, edge_width */
    double offset_x, offset_y;                  /* steps, grating, lattice: the pattern's shift */
    tt_lattice lattice;                         /* lattice */
    tt_feature feature;
    double feature_radius;                      /* lattice pillar, hole: top (rim) radius */
    double spike_radius, spike_half_angle;      /* lattice spike: a sphere-capped cone */
    double particle_radius;                     /* particles */
    long particle_count;
    double rms, correlation_length;             /* rough */
    long seed;                                  /* particles, rough */
    char png[4096];                             /* png: grey height map */
    double png_height_range;                    /* png; measured .png: level 65535's height */
    char image[4096];                           /* measured: .gsf, .gwy or 16-bit .png */
    char channel[256];                          /* measured .gwy: title or number ("": first) */
    double pixel_size;                          /* measured .png, png: m (png 0: the image spans
                                                 * the scan area, whose aspect it must have) */
    tt_surface_level level;                     /* measured: the whole image's levelling */
    tt_surface_lines line_level;                /* measured: each row's, after level */
    long crop[4];                               /* measured: left, top, width, height in
                                                 * pixels (width 0: the whole image) */
    int bicubic;                                /* measured: 1 bicubic, 0 bilinear */
    tt_surface_edges edges;                     /* measured: past the image's edges */
    double z_scale, z_offset;                   /* measured: z = z_scale * levelled + z_offset */
    int measured_tip;                           /* measured: the tt_tip_kind that took the image
                                                 * (point: none), eroded out (erosion.h) */
    double measured_tip_radius, measured_tip_half_angle; /* measured: that tip's R, theta */
    tt_surface_map map;
    int materials[2];                           /* two-material maps: background, other */
    double map_period, map_duty, map_radius;
    char map_png[4096];                         /* png map; colours: tt_material map_rgb */
    double map_tolerance;                       /* png map: a colour no material names takes
                                                 * the nearest within this distance (8-bit
                                                 * levels, Euclidean in RGB; 0: exact only) */
    /* labels, threshold maps (docs/surfaces.md, "Material maps from data"): map_image
     * (.gsf, .gwy, grey .png) taken pixel by pixel (nearest neighbour), past its edges
     * as edges says; labels: each whole-number label is the material whose map_grey it
     * is; threshold: materials[0] below map_threshold, materials[1] at or above it. */
    char map_image[4096];
    char map_channel[256];                      /* .gwy: title or number ("": first) */
    double map_pixel_size;                      /* .png map_image, png map: m (0: the image spans
                                                 * the scan area, whose aspect it must have) */
    double map_threshold;                       /* in map_threshold_unit */
    double visit[4];                            /* measured, labels, threshold: the box a rotated
                                                 * or moved scan visits (x0, y0, x1, y1, m), which
                                                 * edges = refuse asks the image to cover; all 0:
                                                 * the scan area */
    char map_threshold_unit[32];                /* as written: "deg", "nm", "" */
} tt_surface_params;

typedef struct tt_surface tt_surface;

/* size_x, size_y: the scan area (m), which tiled shapes and PNG maps cover; the
 * materials (their map_rgb) are those a PNG map may name. Fails naming the key when the
 * surface cannot be made (particles that do not fit, an unreadable PNG, a map colour
 * no material names). */
int tt_surface_alloc(tt_surface **out, const tt_surface_params *p, const tt_material *materials,
                     size_t nmaterials, double size_x, double size_y);
void tt_surface_free(tt_surface *s);
/* A PNG material map (p->map is png) whose materials' map_values name one pixel at the
 * map's depth (read from its header) is refused, naming both materials, their values and
 * the map; so is a map file that is not a regular file. Cheap: for the configuration
 * layer to refuse before a run is estimated. TT_OK for other maps and for a header it
 * cannot make out (tt_surface_alloc then says why). */
int tt_surface_check_map_values(const tt_surface_params *p, const tt_material *materials,
                                size_t nmaterials);

/* A labels or threshold map read and built as tt_surface_alloc would, and dropped: a bad
 * file, a label no material names, a non-integer label, a threshold in another unit than
 * the image's, an image smaller than the scan area (edges refuse) or a PNG whose aspect
 * differs from the area's is refused in one line. TT_OK for other maps. */
int tt_surface_check_map_image(const tt_surface_params *p, const tt_material *materials,
                               size_t nmaterials, double size_x, double size_y);

/* A measured surface (p->type measured) read and prepared as tt_surface_alloc would, and
 * dropped: so that a bad file, key or crop is refused, in one line naming the key, the
 * file and what is expected, before a run is estimated. TT_OK for other types. */
int tt_surface_check_measured(const tt_surface_params *p, double size_x, double size_y);

double tt_surface_height(const tt_surface *s, double x, double y);
/* A measured surface eroded by its measuring tip (measured_tip): 1 where the erosion is
 * certain to be the sample (tt_erosion_certainty), 0 where it is only an upper bound,
 * at the nearest pixel of the prepared image; NAN for any other surface. */
double tt_surface_certainty(const tt_surface *s, double x, double y);
int tt_surface_material(const tt_surface *s, double x, double y);
/* 1 when the whole surface is one material (no map look-ups needed). */
int tt_surface_uniform(const tt_surface *s);
/* 1 when the topography is flat everywhere. */
int tt_surface_flat(const tt_surface *s);

/* The contact law's local geometry (tt_contact_geometry) for a tip of apex radius R (m)
 * touching the surface at (x, y), the contact point tt_dilation_contact gives: the
 * slope's cosine and the principal normal curvatures from central differences of the
 * height, step (m) apart (the surface's own scale: a fraction of its features' radius
 * or its pixel), so a sphere of radius r reads 1/r to O(step^2 / r^2). A flat reads
 * exactly cos a = 1 and R_eff = R. A wall or kink inside the stencil reads as a steep
 * slope (tt_surface_turn finds it; the scan takes the tip's normal there,
 * docs/surfaces.md). */
tt_contact_geometry tt_surface_contact_geometry(const tt_surface *s, double x, double y,
                                                double step, double R);

/* The largest turn (rad) of the surface's slope across the same stencil: the angle
 * between the one-sided differences (h(x + step) - h(x)) / step and (h(x) - h(x - step))
 * / step, along x and along y. A curved surface of radius r turns about step / (r cos a)
 * on a slope a; a wall or kink inside the stencil turns by the kink's angle. */
double tt_surface_turn(const tt_surface *s, double x, double y, double step);

/* Surfaces that vary along x only and are made of straight pieces (steps, grating):
 * calls fn(user, xa, ha, xb, hb) for each piece of the profile, from (xa, ha) to
 * (xb, hb) with xa < xb, that overlaps [x0, x1], and returns 1. A vertical sidewall is
 * no piece: the ends of the pieces beside it stand for it. Returns 0, calling nothing,
 * for the other surfaces. The tip's dilation uses it to be exact (tip.h). */
typedef void (*tt_surface_piece_fn)(void *user, double xa, double ha, double xb, double hb);
int tt_surface_pieces(const tt_surface *s, double x0, double x1, tt_surface_piece_fn fn,
                      void *user);

TT_END_DECLS
#endif
