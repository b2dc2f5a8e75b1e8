/* The surface's inside, shared by its files: surface.c (shapes, evaluation), surface_png.c
 * (PNG height and material maps) and surface_measured.c (measured height images). */
#ifndef TIPTAP_SURFACE_PRIVATE_H
#define TIPTAP_SURFACE_PRIVATE_H

#include <gsl/gsl_interp2d.h>

#include "tiptap/instrument/surface.h"

typedef enum { S_FLAT, S_STEPS, S_GRATING, S_PARTICLES, S_ROUGH, S_PNG, S_MEASURED, S_LATTICE } shape;
typedef enum { M_UNIFORM, M_STRIPES, M_DISKS, M_CHECKER, M_ISLANDS, M_PNG, M_LABELS, M_THRESHOLD } mapkind;

struct tt_surface {
    shape type;
    mapkind map;
    double sx, sy;
    /* shapes */
    double step_h, step_w, period, duty, height, edge;
    double ox, oy;          /* steps, grating, lattice: the pattern's offset */
    int lattice, feature;   /* lattice: tt_lattice, tt_feature */
    double fr;              /* lattice: feature radius (pillar, hole) */
    double spike_r, spike_a, spike_reach; /* lattice spike: apex radius, half-angle, base radius */
    double pr;              /* particle radius */
    double *px, *py;        /* particle centres */
    long np;
    int *cell_start, *cell_list; /* particles binned on a grid of cells at least 2 r wide */
    int ncx, ncy;
    double cw;              /* cell width, m */
    /* height grid (rough, png) */
    double *grid;
    int gw, gh, periodic;
    double gsx, gsy;        /* the grid's span (m): the scan area, or a png's pixels times
                             * its pixel_size */
    /* map */
    int mat[2];             /* background, second material */
    double map_period, map_duty, map_radius;
    int *mgrid;             /* png, labels, threshold material map */
    int mw, mh;
    double msx, msy;        /* png map: its span (m), as gsx, gsy */
    double mdx, mdy;        /* labels, threshold: the image's pixel (m) */
    int medges;             /* labels, threshold: tt_surface_edges past the image */
    /* measured image (surface_measured.c): GSL's interpolation over nodes xa, ya */
    gsl_interp2d *interp;
    double *xa, *ya, *za;
    size_t nx, ny;
    double lo_x, hi_x, lo_y, hi_y; /* the nodes' span: queries are clamped into it */
    double wrap_x, wrap_y;         /* periodic edges: the image's size (0: clamped) */
    unsigned char *certain;        /* the erosion's certainty map, cert_w x cert_h pixels of
                                    * cdx x cdy (NULL: no measured_tip) */
    size_t cert_w, cert_h;
    double cdx, cdy;
};

/* surface_lattice.c: pillars, holes or spikes on a square or hexagonal lattice. */
void tt_surface_lattice_init(tt_surface *S, const tt_surface_params *p);
double tt_surface_lattice_at(const tt_surface *S, double x, double y);

/* surface_png.c: a PNG height map (type png) and a PNG material map (map png). */
int tt_surface_build_png_height(tt_surface *S, const tt_surface_params *p);
int tt_surface_build_png_map(tt_surface *S, const tt_surface_params *p, const tt_material *mat,
                             size_t nm);
/* A 16-bit grey PNG's levels (0 to 65535) into *pix (w * h, caller frees); errors name
 * the key and the file. */
int tt_surface_read_png16(const char *key, const char *path, unsigned short **pix, int *w, int *h);

/* An 8- or 16-bit grey PNG's levels into *pix (w * h, caller frees), *maxval 255 or 65535. */
int tt_surface_read_png_grey(const char *key, const char *path, unsigned short **pix, int *w, int *h,
                             int *maxval);

/* surface_labels.c: a material map from a label image or a thresholded channel. */
int tt_surface_build_map_image(tt_surface *S, const tt_surface_params *p, const tt_material *mat,
                               size_t nm);
int tt_surface_map_image_at(const tt_surface *S, double x, double y);

/* surface_measured.c: a measured height image, read, prepared and interpolated. */
int tt_surface_build_measured(tt_surface *S, const tt_surface_params *p);
double tt_surface_measured_at(const tt_surface *S, double x, double y);
void tt_surface_measured_free(tt_surface *S);

#endif
