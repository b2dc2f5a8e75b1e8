/* The configuration layer's [surface] section: the topography's type and its keys, a
 * measured image's preparation and the material map (see include/tiptap/config/config.h,
 * docs/surfaces.md). */
#include "tiptap/config/config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "scene_private.h"
#include "tiptap/instrument/tip.h"
#include "tiptap/io/files.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

static int get_d(const tt_scene *s, const char *key, double *v)
{
    return tt_scene_get_double(s, "surface", NULL, key, v);
}

/* The height map is a regular file (a pipe or a link to /dev/zero is refused), told
 * before the run is estimated; tt_surface_alloc reads it. */
static int check_png_file(const tt_scene *s, const char *path)
{
    int fd;
    if (tt_input_open(path, "PNG map", "map", TT_PNG_MAX_BYTES, &fd, NULL) == TT_OK) {
        close(fd);
        return TT_OK;
    }
    char why[1024];
    snprintf(why, sizeof why, "%s", tt_error_message());
    return tt_scene_locate(s, tt_error(TT_EINVAL, "[surface] png: %s", why));
}

/* The index of an enum key's value among choices. */
static int enum_of(const tt_scene *s, const char *key, const char *const *choices, int n)
{
    const char *v = tt_scene_get_string(s, "surface", NULL, key);
    for (int i = 0; v && i < n; i++)
        if (strcmp(v, choices[i]) == 0)
            return i;
    return 0;
}

/* A measured image's keys; the file itself is read by check_measured, once the scan
 * area is known. */
static int read_measured(const tt_scene *s, tt_surface_params *p)
{
    static const char *const levels[] = {"none", "offset", "plane"};
    static const char *const lines[] = {"none", "offset", "slope", "median", "median_difference"};
    static const char *const edges[] = {"refuse", "clamp", "periodic"};
    int rc;
    if (!tt_scene_has(s, "surface", NULL, "image"))
        return tt_scene_fail(s, "surface", NULL, "type",
                             "measured needs [surface] image = a .gsf, .gwy or 16-bit .png height image");
    if ((rc = tt_scene_get_path(s, "surface", NULL, "image", p->image, sizeof p->image)) ||
        (rc = get_d(s, "z_scale", &p->z_scale)) || (rc = get_d(s, "z_offset", &p->z_offset)))
        return rc;
    const char *ch = tt_scene_get_string(s, "surface", NULL, "channel");
    snprintf(p->channel, sizeof p->channel, "%s", ch ? ch : "");
    if (tt_scene_has(s, "surface", NULL, "pixel_size") && (rc = get_d(s, "pixel_size", &p->pixel_size)))
        return rc;
    /* a PNG's levels have no height of their own: the range is not left to a default */
    if (tt_scene_has(s, "surface", NULL, "png_height_range") &&
        (rc = get_d(s, "png_height_range", &p->png_height_range)))
        return rc;
    size_t n = strlen(p->image);
    if (n > 4 && strcasecmp(p->image + n - 4, ".png") == 0 &&
        !tt_scene_has(s, "surface", NULL, "png_height_range"))
        return tt_scene_fail(s, "surface", NULL, "png_height_range",
                             "a PNG's levels carry no height: expected the height of level 65535 "
                             "(e.g. 20 nm) for %s", p->image);
    p->level = (tt_surface_level)enum_of(s, "level", levels, 3);
    p->line_level = (tt_surface_lines)enum_of(s, "line_level", lines, 5);
    p->edges = (tt_surface_edges)enum_of(s, "edges", edges, 3);
    static const char *const tips[] = {"none", "sphere", "cone"};
    /* the enum's order is tt_tip_kind's: none is the point tip, which erodes nothing */
    p->measured_tip = enum_of(s, "measured_tip_shape", tips, 3);
    /* a tip's size without the shape that uses it would be ignored silently */
    if (p->measured_tip != TT_TIP_CONE && tt_scene_has(s, "surface", NULL, "measured_tip_half_angle"))
        return tt_scene_fail(s, "surface", NULL, "measured_tip_half_angle",
                             "given for a tip that is no cone; expected measured_tip_shape = cone with it");
    if (p->measured_tip == TT_TIP_POINT && tt_scene_has(s, "surface", NULL, "measured_tip_radius"))
        return tt_scene_fail(s, "surface", NULL, "measured_tip_radius",
                             "given without a tip; expected measured_tip_shape = sphere or cone with it");
    if ((rc = get_d(s, "measured_tip_radius", &p->measured_tip_radius)) ||
        (rc = get_d(s, "measured_tip_half_angle", &p->measured_tip_half_angle)))
        return rc;
    const char *interp = tt_scene_get_string(s, "surface", NULL, "interpolation");
    p->bicubic = interp && strcmp(interp, "bicubic") == 0;
    const char *c = tt_scene_get_string(s, "surface", NULL, "crop");
    if (c) {
        char tail;
        if (sscanf(c, "%ld %ld %ld %ld %c", &p->crop[0], &p->crop[1], &p->crop[2], &p->crop[3], &tail) != 4 ||
            p->crop[0] < 0 || p->crop[1] < 0 || p->crop[2] < 2 || p->crop[3] < 2)
            return tt_scene_fail(s, "surface", NULL, "crop",
                                 "'%s'; expected four whole numbers of pixels: left top width height "
                                 "(width and height at least 2)", c);
    }
    return TT_OK;
}

/* line_width, the critical dimension, instead of duty: as the fraction of the period it
 * is (p->duty, 0 when not given). */
static int read_line_width(const tt_scene *s, tt_surface_params *p)
{
    double w, period;
    int rc;
    if (!tt_scene_has(s, "surface", NULL, "line_width"))
        return TT_OK;
    if (tt_scene_has(s, "surface", NULL, "duty"))
        return tt_scene_fail_set(s, (const char *const[]){"surface.line_width", "surface.duty", NULL},
                                 "line_width and duty both give the line's width; give one");
    if ((rc = get_d(s, "line_width", &w)) || (rc = get_d(s, "period", &period)))
        return rc;
    if (!(w < period))
        return tt_scene_fail_set(s, (const char *const[]){"surface.line_width", "surface.period", NULL},
                                 "a line %g nm wide fills the %g nm period; expected a narrower line",
                                 w * 1e9, period * 1e9);
    p->duty = w / period;
    return TT_OK;
}

/* A lattice's keys; features that would reach past their neighbours' are refused (the
 * surface looks at the nearest nine centres only). */
static int read_lattice(const tt_scene *s, tt_surface_params *p)
{
    static const char *const lattices[] = {"square", "hexagonal"}, *const features[] = {"pillar", "hole", "spike"};
    int rc;
    p->lattice = (tt_lattice)enum_of(s, "lattice", lattices, 2);
    p->feature = (tt_feature)enum_of(s, "feature", features, 3);
    if ((rc = get_d(s, "period", &p->period)) || (rc = get_d(s, "height", &p->height)) ||
        (rc = get_d(s, "edge_width", &p->edge_width)) || (rc = get_d(s, "offset_x", &p->offset_x)) ||
        (rc = get_d(s, "offset_y", &p->offset_y)) || (rc = get_d(s, "feature_radius", &p->feature_radius)) ||
        (rc = get_d(s, "spike_radius", &p->spike_radius)) ||
        (rc = get_d(s, "spike_half_angle", &p->spike_half_angle)))
        return rc;
    if (!(p->height > 0))
        return tt_scene_fail(s, "surface", NULL, "height", "a lattice's features rise %g nm; expected a "
                             "height above 0 (holes: their depth)", p->height * 1e9);
    if (p->feature == TT_FEATURE_SPIKE) {
        tt_tip_shape cone = {TT_TIP_CONE, p->spike_radius, p->spike_half_angle};
        double base = tt_tip_shape_reach(&cone, p->height);
        if (base > p->period)
            return tt_scene_fail_set(s, (const char *const[]){"surface.spike_half_angle", "surface.height",
                                                              "surface.period", NULL},
                                     "spikes %g nm high at %g deg stand on bases %g nm wide, more than "
                                     "twice the %g nm period; expected a narrower or lower spike",
                                     p->height * 1e9, p->spike_half_angle * 180 / M_PI, 2 * base * 1e9,
                                     p->period * 1e9);
        return TT_OK;
    }
    if (2 * (p->feature_radius + p->edge_width) >= p->period)
        return tt_scene_fail_set(s, (const char *const[]){"surface.feature_radius", "surface.edge_width",
                                                          "surface.period", NULL},
                                 "features %g nm across (feature_radius %g nm, edge_width %g nm) touch "
                                 "at the %g nm period; expected them narrower than the period",
                                 2 * (p->feature_radius + p->edge_width) * 1e9, p->feature_radius * 1e9,
                                 p->edge_width * 1e9, p->period * 1e9);
    return TT_OK;
}

static int read_shape(const tt_scene *s, tt_surface_params *p)
{
    int rc = TT_OK;
    switch (p->type) {
    case TT_SURFACE_STEPS:
        if (!(rc = get_d(s, "step_height", &p->step_height)) && !(rc = get_d(s, "offset_x", &p->offset_x)))
            rc = get_d(s, "step_width", &p->step_width);
        return rc;
    case TT_SURFACE_LATTICE:
        return read_lattice(s, p);
    case TT_SURFACE_GRATING:
        if ((rc = get_d(s, "offset_x", &p->offset_x)) || (rc = read_line_width(s, p)))
            return rc;
        if (!(rc = get_d(s, "period", &p->period)) && (p->duty > 0 || !(rc = get_d(s, "duty", &p->duty))) &&
            !(rc = get_d(s, "height", &p->height)) && !(rc = get_d(s, "edge_width", &p->edge_width)) &&
            2 * p->edge_width > p->period * fmin(p->duty, 1 - p->duty) * 2)
            rc = tt_scene_fail_set(s, (const char *const[]){"surface.edge_width", "surface.period", "surface.duty", NULL},
                                   "edge_width %g nm is wider than the line or the gap allows "
                                   "(period %g nm, duty %g %%)",
                                   p->edge_width * 1e9, p->period * 1e9, p->duty * 100);
        return rc;
    case TT_SURFACE_PARTICLES:
        if ((rc = get_d(s, "particle_radius", &p->particle_radius)) ||
            (rc = tt_scene_get_int(s, "surface", NULL, "particle_count", &p->particle_count)))
            return rc;
        return tt_scene_get_int(s, "surface", NULL, "seed", &p->seed);
    case TT_SURFACE_ROUGH:
        if ((rc = get_d(s, "rms", &p->rms)) || (rc = get_d(s, "correlation_length", &p->correlation_length)))
            return rc;
        return tt_scene_get_int(s, "surface", NULL, "seed", &p->seed);
    case TT_SURFACE_PNG:
        if ((rc = tt_scene_get_path(s, "surface", NULL, "png", p->png, sizeof p->png)) ||
            (rc = check_png_file(s, p->png)))
            return rc;
        if (tt_scene_has(s, "surface", NULL, "pixel_size") && (rc = get_d(s, "pixel_size", &p->pixel_size)))
            return rc;
        return get_d(s, "png_height_range", &p->png_height_range);
    case TT_SURFACE_MEASURED:
        return read_measured(s, p);
    default:
        return TT_OK;
    }
}

/* map_materials: the background, then the other, by name. */
static int read_map_materials(const tt_scene *s, const char *list, const tt_material *m, size_t n,
                              tt_surface_params *p)
{
    const char *q = list;
    int k = 0;
    while (*q) {
        while (*q == ' ' || *q == ',')
            q++;
        const char *e = q;
        while (*e && *e != ',' && *e != ' ')
            e++;
        if (e == q)
            break;
        if (k >= 2)
            return tt_scene_fail(s, "surface", NULL, "map_materials",
                                 "names more than two materials; this map takes a background and one other");
        size_t i = 0;
        while (i < n && !(strlen(m[i].name) == (size_t)(e - q) && strncmp(m[i].name, q, (size_t)(e - q)) == 0))
            i++;
        if (i == n)
            return tt_scene_fail(s, "surface", NULL, "map_materials", "no [material %.*s] in the scene",
                                 (int)(e - q), q);
        p->materials[k++] = (int)i;
        q = e;
    }
    if (k < 2)
        return tt_scene_fail(s, "surface", NULL, "map_materials",
                             "needs two materials: the background, then the other");
    return TT_OK;
}

static const char *const surface_maps[] = {"uniform", "stripes", "disks", "checkerboard", "islands", "png",
                                           "labels", "threshold"};

/* A labels or threshold map's keys; the image itself is read by check_map_image, once the
 * scan area is known. */
static int read_map_image(const tt_scene *s, tt_surface_params *p)
{
    static const char *const edges[] = {"refuse", "clamp", "periodic"};
    int rc;
    if (!tt_scene_has(s, "surface", NULL, "map_image"))
        return tt_scene_fail(s, "surface", NULL, "map", "%s needs [surface] map_image = a .gsf, .gwy or grey .png image",
                             surface_maps[p->map]);
    if ((rc = tt_scene_get_path(s, "surface", NULL, "map_image", p->map_image, sizeof p->map_image)))
        return rc;
    const char *ch = tt_scene_get_string(s, "surface", NULL, "map_channel");
    snprintf(p->map_channel, sizeof p->map_channel, "%s", ch ? ch : "");
    if (tt_scene_has(s, "surface", NULL, "map_pixel_size") && (rc = get_d(s, "map_pixel_size", &p->map_pixel_size)))
        return rc;
    p->edges = (tt_surface_edges)enum_of(s, "edges", edges, 3);
    if (p->map == TT_MAP_LABELS)
        return TT_OK;
    const char *t = tt_scene_get_string(s, "surface", NULL, "map_threshold");
    char *end;
    if (!t)
        return tt_scene_fail(s, "surface", NULL, "map", "threshold needs [surface] map_threshold = a value "
                             "in the image's unit (e.g. 60 deg)");
    p->map_threshold = tt_strtod(t, &end);
    while (*end == ' ')
        end++;
    if (end == t || !isfinite(p->map_threshold) || strlen(end) >= sizeof p->map_threshold_unit || strchr(end, ' '))
        return tt_scene_fail(s, "surface", NULL, "map_threshold",
                             "'%s'; expected a number and the image's unit (e.g. 60 deg)", t);
    snprintf(p->map_threshold_unit, sizeof p->map_threshold_unit, "%s", end);
    return TT_OK;
}

/* A two-material map: which materials, its period, duty and disk radius. */
static int read_two_material_map(const tt_scene *s, const tt_material *m, size_t n,
                                 tt_surface_params *p)
{
    int rc;
    const char *list = tt_scene_get_string(s, "surface", NULL, "map_materials");
    if (list)
        rc = read_map_materials(s, list, m, n, p);
    else if (n < 2)
        rc = tt_scene_fail(s, "surface", NULL, "map", "a %s map needs two [material NAME] sections",
                           surface_maps[p->map]);
    else {
        p->materials[0] = 0;
        p->materials[1] = 1;
        rc = TT_OK;
    }
    if (rc || (rc = get_d(s, "map_period", &p->map_period)) || (rc = get_d(s, "map_duty", &p->map_duty)) ||
        (rc = get_d(s, "map_radius", &p->map_radius)))
        return rc;
    if (p->map == TT_MAP_DISKS && 2 * p->map_radius >= p->map_period)
        return tt_scene_fail_set(s, (const char *const[]){"surface.map_radius", "surface.map_period", NULL},
                                 "disks of radius %g nm overlap at period %g nm",
                                 p->map_radius * 1e9, p->map_period * 1e9);
    if (p->map == TT_MAP_ISLANDS && p->type != TT_SURFACE_PARTICLES)
        return tt_scene_fail(s, "surface", NULL, "map", "islands need type = particles");
    return TT_OK;
}

/* The topography's keys and the types that read them (bit t: tt_surface_type t); the
 * material map's keys are any type's. */
#define T(t) (1u << TT_SURFACE_##t)
static const struct {
    const char *key;
    unsigned types;
} type_keys[] = {
    {"step_height", T(STEPS)}, {"step_width", T(STEPS)},
    {"period", T(GRATING) | T(LATTICE)}, {"duty", T(GRATING)}, {"line_width", T(GRATING)},
    {"height", T(GRATING) | T(LATTICE)}, {"edge_width", T(GRATING) | T(LATTICE)},
    {"offset_x", T(STEPS) | T(GRATING) | T(LATTICE)}, {"offset_y", T(LATTICE)},
    {"lattice", T(LATTICE)}, {"feature", T(LATTICE)}, {"feature_radius", T(LATTICE)},
    {"spike_radius", T(LATTICE)}, {"spike_half_angle", T(LATTICE)},
    {"particle_radius", T(PARTICLES)}, {"particle_count", T(PARTICLES)},
    {"seed", T(PARTICLES) | T(ROUGH)}, {"rms", T(ROUGH)}, {"correlation_length", T(ROUGH)},
    {"png", T(PNG)}, {"png_height_range", T(PNG) | T(MEASURED)},
    {"image", T(MEASURED)}, {"channel", T(MEASURED)}, {"pixel_size", T(MEASURED) | T(PNG)},
    {"level", T(MEASURED)}, {"line_level", T(MEASURED)}, {"crop", T(MEASURED)},
    {"interpolation", T(MEASURED)}, {"z_scale", T(MEASURED)}, {"z_offset", T(MEASURED)},
    {"measured_tip_shape", T(MEASURED)}, {"measured_tip_radius", T(MEASURED)},
    {"measured_tip_half_angle", T(MEASURED)},
};
#undef T

static const char *const surface_types[] = {"flat", "steps", "grating", "particles", "rough", "png", "measured",
                                            "lattice"};
enum { NTYPES = sizeof surface_types / sizeof *surface_types };

/* Whether the scene's type reads a [surface] key: the effective scene leaves the other
 * types' keys out (particle_radius on a grating), which nothing would read. Keys of no
 * type (the material map's) apply to every type. */
int scene_surface_key_applies(const tt_scene *s, const char *key)
{
    const char *t = tt_scene_get_string(s, "surface", NULL, "type");
    unsigned type = 0;
    for (unsigned i = 0; i < NTYPES; i++)
        if (t && strcmp(t, surface_types[i]) == 0)
            type = i;
    for (size_t i = 0; i < sizeof type_keys / sizeof *type_keys; i++)
        if (strcmp(type_keys[i].key, key) == 0)
            return (type_keys[i].types & (1u << type)) != 0;
    return 1;
}

/* Whether a given key holds its default: compared as the getters read it (20 nm and
 * 2e-8 m are one value), against a scene of defaults alone. */
static int holds_default(const tt_scene *s, const tt_scene *defaults, const char *key)
{
    const tt_scene_key *k = scene_find_key(scene_find_section("surface"), key);
    if (!k || !k->def)
        return 0;
    if (k->kind == TT_KEY_QUANTITY) {
        double a, b;
        return tt_scene_get_double(s, "surface", NULL, key, &a) == TT_OK &&
               tt_scene_get_double(defaults, "surface", NULL, key, &b) == TT_OK && a == b;
    }
    if (k->kind == TT_KEY_INT) {
        long a, b;
        return tt_scene_get_int(s, "surface", NULL, key, &a) == TT_OK &&
               tt_scene_get_int(defaults, "surface", NULL, key, &b) == TT_OK && a == b;
    }
    const char *a = tt_scene_get_string(s, "surface", NULL, key);
    return a && strcmp(a, k->def) == 0;
}

/* When an entry was given: its file's place in the loading, --set (load 0) last. */
static unsigned long given_at(const tt_scene *s, const char *key)
{
    const entry *e = scene_find_entry(s, "surface", NULL, key);
    return !e ? 0 : e->load ? e->load : (unsigned long)-1;
}

/* A key of another type than the scene's (particle_radius on a grating) would be read
 * by nothing: refused, naming the types that read it. Two pass: one at its default, so
 * that an effective scene written back (every key, defaults included) reads again, and
 * one given before a later file or --set changed the type (surfaces/grating.ini, then
 * --set surface.type=flat: the later type replaces the sample the earlier file drew). */
static int check_type_keys(const tt_scene *s, tt_surface_type type)
{
    tt_scene *defaults = tt_scene_alloc();
    if (!defaults)
        return tt_error_nomem("a scene of defaults");
    const unsigned long typed = given_at(s, "type");
    size_t i = 0;
    for (; i < sizeof type_keys / sizeof *type_keys; i++)
        if (!(type_keys[i].types & (1u << type)) && tt_scene_has(s, "surface", NULL, type_keys[i].key) &&
            given_at(s, type_keys[i].key) >= typed && !holds_default(s, defaults, type_keys[i].key))
            break;
    tt_scene_free(defaults);
    if (i < sizeof type_keys / sizeof *type_keys) {
        char list[128] = "";
        size_t len = 0;
        for (int t = 0; t < NTYPES; t++)
            if (type_keys[i].types & (1u << t))
                len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", len ? " or " : "",
                                        surface_types[t]);
        return tt_scene_fail(s, "surface", NULL, type_keys[i].key,
                             "a key of type = %s, not of this surface's type = %s (remove it, or "
                             "set the type that reads it)",
                             list, surface_types[type]);
    }
    return TT_OK;
}

int tt_config_surface(const tt_scene *s, const tt_material *m, size_t n, tt_surface_params *p)
{
    memset(p, 0, sizeof *p);
    const char *t = tt_scene_get_string(s, "surface", NULL, "type");
    const char *mp = tt_scene_get_string(s, "surface", NULL, "map");
    for (int i = 0; i < NTYPES; i++)
        if (t && strcmp(t, surface_types[i]) == 0)
            p->type = (tt_surface_type)i;
    for (int i = 0; i < 8; i++)
        if (mp && strcmp(mp, surface_maps[i]) == 0)
            p->map = (tt_surface_map)i;
    int rc = check_type_keys(s, p->type);
    if (rc || (rc = read_shape(s, p)))
        return rc;
    /* two materials on one pixel value: refused before the run is estimated */
    if (p->map == TT_MAP_PNG && tt_scene_has(s, "surface", NULL, "map_pixel_size") &&
        (rc = get_d(s, "map_pixel_size", &p->map_pixel_size)))
        return rc;
    if (p->map == TT_MAP_PNG && !(rc = get_d(s, "map_tolerance", &p->map_tolerance)) &&
        !(rc = tt_scene_get_path(s, "surface", NULL, "map_png", p->map_png, sizeof p->map_png)))
        rc = tt_scene_locate(s, tt_surface_check_map_values(p, m, n));
    if (p->map == TT_MAP_PNG)
        return rc;
    if ((p->map == TT_MAP_LABELS || p->map == TT_MAP_THRESHOLD) && (rc = read_map_image(s, p)))
        return rc;
    if (p->map == TT_MAP_LABELS)
        return TT_OK;
    if (p->map != TT_MAP_UNIFORM)
        return read_two_material_map(s, m, n, p);
    return TT_OK;
}

