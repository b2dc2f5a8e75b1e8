/* Parsing of "value unit" quantities with SI prefixes (see include/tiptap/config/units.h). */
#include "tiptap/config/units.h"
#include "tiptap/util/str.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A table of spellings: each base unit, its dimension and its factor to SI.
 * Prefixes apply to the first factor of the unit ("mJ/m^2" = 1e-3 J/m^2). */
static const struct {
    const char *symbol;
    tt_dim dim;
    double factor;
} base_units[] = {
    {"m", TT_DIM_LENGTH, 1.0},
    {"Å", TT_DIM_LENGTH, 1e-10},
    {"Hz", TT_DIM_FREQUENCY, 1.0},
    {"1/s", TT_DIM_FREQUENCY, 1.0},
    {"/s", TT_DIM_FREQUENCY, 1.0},
    {"N/m", TT_DIM_STIFFNESS, 1.0},
    {"J/m^2", TT_DIM_SURFACE_ENERGY, 1.0},
    {"J/m2", TT_DIM_SURFACE_ENERGY, 1.0},
    {"N/m", TT_DIM_SURFACE_ENERGY, 1.0},
    {"Pa", TT_DIM_PRESSURE, 1.0},
    {"N", TT_DIM_FORCE, 1.0},
    {"s", TT_DIM_TIME, 1.0},
    {"J", TT_DIM_ENERGY, 1.0},
    {"eV", TT_DIM_ENERGY, 1.602176634e-19},
    {"m/s", TT_DIM_VELOCITY, 1.0},
    {"rad", TT_DIM_ANGLE, 1.0},
    {"deg", TT_DIM_ANGLE, M_PI / 180.0},
    {"°", TT_DIM_ANGLE, M_PI / 180.0},
    {"%", TT_DIM_FRACTION, 0.01},
    {"K", TT_DIM_TEMPERATURE, 1.0},
    {"m/sqrt(Hz)", TT_DIM_NOISE_DENSITY, 1.0},
    {"m/rtHz", TT_DIM_NOISE_DENSITY, 1.0},
    {"Pa s", TT_DIM_VISCOSITY, 1.0},
    {"Pa*s", TT_DIM_VISCOSITY, 1.0},
    {"Pa.s", TT_DIM_VISCOSITY, 1.0},
};

static const struct {
    const char *symbol;
    double factor;
} prefixes[] = {
    {"y", 1e-24}, {"z", 1e-21}, {"a", 1e-18}, {"f", 1e-15}, {"p", 1e-12},
    {"n", 1e-9},  {"u", 1e-6},  {"µ", 1e-6},  {"μ", 1e-6},  {"m", 1e-3},
    {"c", 1e-2},  {"k", 1e3},   {"M", 1e6},   {"G", 1e9},   {"T", 1e12},
    {"P", 1e15},
};

static const struct {
    tt_dim dim;
    const char *symbol;
    const char *example;
} dim_names[] = {
    {TT_DIM_NONE, "", "a number, no unit"},
    {TT_DIM_LENGTH, "m", "a length such as '0.265 nm'"},
    {TT_DIM_FREQUENCY, "Hz", "a frequency such as '52 kHz'"},
    {TT_DIM_STIFFNESS, "N/m", "a stiffness such as '0.58 N/m'"},
    {TT_DIM_SURFACE_ENERGY, "J/m^2", "a surface energy such as '100 mJ/m^2'"},
    {TT_DIM_PRESSURE, "Pa", "a modulus or pressure such as '70 GPa'"},
    {TT_DIM_FORCE, "N", "a force such as '2 nN'"},
    {TT_DIM_TIME, "s", "a time such as '10 us'"},
    {TT_DIM_ENERGY, "J", "an energy such as '1 aJ'"},
    {TT_DIM_VELOCITY, "m/s", "a speed such as '1 um/s'"},
    {TT_DIM_ANGLE, "rad", "an angle such as '90 deg'"},
    {TT_DIM_FRACTION, "", "a percentage such as '80 %'"},
    {TT_DIM_TEMPERATURE, "K", "a temperature such as '300 K'"},
    {TT_DIM_NOISE_DENSITY, "m/sqrt(Hz)", "a noise density such as '50 fm/sqrt(Hz)'"},
    {TT_DIM_VISCOSITY, "Pa s", "a viscosity such as '5 Pa s'"},
};

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

const char *tt_units_symbol(tt_dim dim)
{
    for (size_t i = 0; i < COUNT(dim_names); i++)
        if (dim_names[i].dim == dim)
            return dim_names[i].symbol;
    return "?";
}

const char *tt_units_describe(unsigned dims)
{
    /* Compound masks are described by their first dimension plus "or ..."; the
     * few we use get a fixed phrase. */
    if (dims == (TT_DIM_LENGTH | TT_DIM_FRACTION))
        return "a length such as '16 nm' or a percentage of the free amplitude such as '80 %'";
    if (dims == (TT_DIM_NONE | TT_DIM_FRACTION))
        return "a number, no unit, or a percentage such as '50 %'";
    for (size_t i = 0; i < COUNT(dim_names); i++)
        if (dims & dim_names[i].dim)
            return dim_names[i].example;
    return "a value";
}

/* Look up unit text (already trimmed) among the base units, with an optional prefix. */
static int lookup_unit(const char *u, unsigned dims, double *factor, tt_dim *dim)
{
    int seen_other = 0;
    /* Exact base spellings first, so that "m" is metres and "Pa" is not peta-a. */
    for (size_t i = 0; i < COUNT(base_units); i++) {
        if (strcmp(u, base_units[i].symbol) == 0) {
            if (dims & base_units[i].dim) {
                *factor = base_units[i].factor;
                *dim = base_units[i].dim;
                return 0;
            }
            seen_other = 1;
        }
    }
    for (size_t p = 0; p < COUNT(prefixes); p++) {
        size_t pl = strlen(prefixes[p].symbol);
        if (strncmp(u, prefixes[p].symbol, pl) != 0 || u[pl] == '\0')
            continue;
        for (size_t i = 0; i < COUNT(base_units); i++) {
            if (base_units[i].dim == TT_DIM_FRACTION || base_units[i].symbol[0] == '/' ||
                base_units[i].symbol[0] == '1')
                continue;
            if (strcmp(u + pl, base_units[i].symbol) != 0)
                continue;
            if (dims & base_units[i].dim) {
                *factor = prefixes[p].factor * base_units[i].factor;
                *dim = base_units[i].dim;
                return 0;
            }
            seen_other = 1;
        }
    }
    return seen_other ? -2 : -1;
}

int tt_units_parse(const char *text, unsigned dims, double *value, tt_dim *found,
                   char *why, size_t whylen)
{
    char *end;
    const char *p = text;
    while (isspace((unsigned char)*p))
        p++;
    if (*p == '\0') {
        snprintf(why, whylen, "empty value; expected %s", tt_units_describe(dims));
        return -1;
    }
    double v = tt_strtod(p, &end);
    if (end == p) {
        snprintf(why, whylen, "'%s' is not a number; expected %s", text, tt_units_describe(dims));
        return -1;
    }
    if (!isfinite(v)) {
        snprintf(why, whylen, "'%s' is not a finite number; expected %s", text,
                 tt_units_describe(dims));
        return -1;
    }
    char unit[64];
    while (isspace((unsigned char)*end))
        end++;
    size_t n = strlen(end);
    while (n > 0 && isspace((unsigned char)end[n - 1]))
        n--;
    if (n >= sizeof unit) {
        snprintf(why, whylen, "unit too long in '%s'", text);
        return -1;
    }
    memcpy(unit, end, n);
    unit[n] = '\0';

    if (n == 0) {
        if (dims & TT_DIM_NONE) {
            *value = v;
            if (found)
                *found = TT_DIM_NONE;
            return 0;
        }
        snprintf(why, whylen, "missing unit in '%s'; expected %s", text, tt_units_describe(dims));
        return -1;
    }
    double factor;
    tt_dim dim;
    int rc = lookup_unit(unit, dims, &factor, &dim);
    if (rc != 0) {
        if (dims == TT_DIM_NONE)
            snprintf(why, whylen, "'%s' takes no unit; expected %s", text, tt_units_describe(dims));
        else if (rc == -2)
            snprintf(why, whylen, "wrong unit '%s'; expected %s", unit, tt_units_describe(dims));
        else
            snprintf(why, whylen, "unknown unit '%s'; expected %s", unit, tt_units_describe(dims));
        return -1;
    }
    if (!isfinite(v * factor)) {
        snprintf(why, whylen, "'%s' is beyond the largest number in SI units; expected %s", text,
                 tt_units_describe(dims));
        return -1;
    }
    *value = v * factor;
    if (found)
        *found = dim;
    return 0;
}
