/* tiptap: physical quantities written as "value unit" with SI prefixes.
 *
 * "52 kHz", "0.58 N/m", "100 mJ/m^2", "0.265 nm", "80 %". Numbers are read in the
 * C locale whatever the program's locale. The result is always in SI units.
 */
#ifndef TIPTAP_UNITS_H
#define TIPTAP_UNITS_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* Dimensions, as bit flags so that a key may accept more than one
 * (a setpoint is a length or a fraction). */
typedef enum {
    TT_DIM_NONE = 1 << 0,           /* a pure number, written without a unit */
    TT_DIM_LENGTH = 1 << 1,         /* m */
    TT_DIM_FREQUENCY = 1 << 2,      /* Hz (also 1/s) */
    TT_DIM_STIFFNESS = 1 << 3,      /* N/m */
    TT_DIM_SURFACE_ENERGY = 1 << 4, /* J/m^2 (also N/m) */
    TT_DIM_PRESSURE = 1 << 5,       /* Pa */
    TT_DIM_FORCE = 1 << 6,          /* N */
    TT_DIM_TIME = 1 << 7,           /* s */
    TT_DIM_ENERGY = 1 << 8,         /* J, eV */
    TT_DIM_VELOCITY = 1 << 9,       /* m/s */
    TT_DIM_ANGLE = 1 << 10,         /* rad, deg (stored in radians) */
    TT_DIM_FRACTION = 1 << 11,      /* %, stored as a fraction (80 % -> 0.8) */
    TT_DIM_TEMPERATURE = 1 << 12,   /* K */
    TT_DIM_NOISE_DENSITY = 1 << 13, /* m/sqrt(Hz): a length noise's spectral density */
    TT_DIM_VISCOSITY = 1 << 14      /* Pa s (also Pa*s, Pa.s): a dynamic viscosity */
} tt_dim;

/* Parse text into an SI value of one of the dimensions in the mask.
 * On success returns 0, stores the value and, if found is not NULL, the dimension
 * that matched. On failure returns -1 and writes a short reason into why
 * (for example "expected a length such as '0.265 nm', got unit 'kHz'"). */
int tt_units_parse(const char *text, unsigned dims, double *value, tt_dim *found,
                   char *why, size_t whylen);

/* An example of the dimension's spelling for messages ("a length such as '2 nm'"). */
const char *tt_units_describe(unsigned dims);

/* The SI unit symbol of one dimension ("m", "Hz", "N/m", ...; "" for none). */
const char *tt_units_symbol(tt_dim dim);

TT_END_DECLS
#endif
