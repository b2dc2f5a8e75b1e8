/* The configuration layer's physics: [cantilever], [tip] and every [material NAME]
 * (see include/tiptap/config/config.h). */
#include "tiptap/config/config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

/* The drive frequencies a scene may set, relative to the resonance (see below). */
#define TT_DRIVE_RATIO_MIN 0.1
#define TT_DRIVE_RATIO_MAX 10.0

/* [cantilever] modes and the further modes' overrides (NAN: the beam's default). */
static int config_modes(const tt_scene *s, tt_cantilever *c)
{
    static const char *what[3] = {"frequency", "spring_constant", "quality_factor"};
    double v[3][TT_CANTILEVER_MODES_MAX - 1];
    long modes = 1;
    int rc;
    if (tt_scene_has(s, "cantilever", NULL, "modes") &&
        (rc = tt_scene_get_int(s, "cantilever", NULL, "modes", &modes)))
        return rc;
    for (int i = 2; i <= TT_CANTILEVER_MODES_MAX; i++)
        for (int j = 0; j < 3; j++) {
            char key[40];
            snprintf(key, sizeof key, "mode%d_%s", i, what[j]);
            v[j][i - 2] = NAN;
            if (!tt_scene_has(s, "cantilever", NULL, key))
                continue;
            if (i > modes)
                return tt_scene_fail(s, "cantilever", NULL, key,
                                     "is set but modes = %ld: expected modes = %d or more", modes, i);
            if ((rc = tt_scene_get_double(s, "cantilever", NULL, key, &v[j][i - 2])))
                return rc;
        }
    if (modes > 1 && tt_cantilever_set_modes(c, (int)modes, v[0], v[1], v[2]) != TT_OK) {
        /* name the key that was set: a mode's frequency (the order broken) or the mode's
         * first key given */
        char key[40] = "modes";
        for (int i = 2; i <= (int)modes && !strcmp(key, "modes"); i++)
            for (int j = 0; j < 3; j++)
                if (!isnan(v[j][i - 2])) {
                    snprintf(key, sizeof key, "mode%d_%s", i, what[j]);
                    break;
                }
        return tt_scene_fail(s, "cantilever", NULL, key, "%s", tt_error_message());
    }
    return TT_OK;
}

/* [cantilever] mode2_free_amplitude and mode2_drive_frequency: bimodal AM-AM (mode 2
 * driven open loop beside mode 1). */
static int config_drive2(const tt_scene *s, tt_cantilever *c)
{
    double A2 = NAN, f2 = NAN;
    int rc;
    int has_f = tt_scene_has(s, "cantilever", NULL, "mode2_drive_frequency");
    if (!tt_scene_has(s, "cantilever", NULL, "mode2_free_amplitude")) {
        if (has_f)
            return tt_scene_fail(s, "cantilever", NULL, "mode2_drive_frequency",
                                 "is set but mode2_free_amplitude is not: expected both");
        return TT_OK;
    }
    if (c->modes < 2)
        return tt_scene_fail(s, "cantilever", NULL, "mode2_free_amplitude",
                             "drives mode 2: expected modes = 2 or more");
    if ((rc = tt_scene_get_double(s, "cantilever", NULL, "mode2_free_amplitude", &A2)) ||
        (has_f && (rc = tt_scene_get_double(s, "cantilever", NULL, "mode2_drive_frequency", &f2))))
        return rc;
    if (tt_cantilever_set_drive2(c, A2, f2) != TT_OK)
        return tt_scene_fail(s, "cantilever", NULL, has_f ? "mode2_drive_frequency" : "mode2_free_amplitude",
                             "%s", tt_error_message());
    return TT_OK;
}

int tt_config_cantilever(const tt_scene *s, tt_cantilever *c)
{
    double k, f0, Q, A0, fd;
    int rc;
    if ((rc = tt_scene_get_double(s, "cantilever", NULL, "spring_constant", &k)) ||
        (rc = tt_scene_get_double(s, "cantilever", NULL, "resonance_frequency", &f0)) ||
        (rc = tt_scene_get_double(s, "cantilever", NULL, "quality_factor", &Q)) ||
        (rc = tt_scene_get_double(s, "cantilever", NULL, "free_amplitude", &A0)))
        return rc;
    fd = f0;
    if (tt_scene_has(s, "cantilever", NULL, "drive_frequency") &&
        (rc = tt_scene_get_double(s, "cantilever", NULL, "drive_frequency", &fd)))
        return rc;
    /* Tapping drives near resonance. Beyond a factor of 10 below it the base must swing
     * over 100 free amplitudes (a_d = A0 |1 - r^2| / r^2), which crushes the sample as a
     * force curve would, each drive cycle costs f0 / fd resonance periods, and the
     * energy balance loses its scale (the drive work falls with fd): at 100 Hz it read
     * 2.7e11. Beyond 10 above it the tip stands still (it swings A0 / (r^2 - 1), under
     * 1 % of A0) and does not tap. */
    if (tt_scene_has(s, "cantilever", NULL, "drive_frequency") && f0 > 0 &&
        !(fd >= TT_DRIVE_RATIO_MIN * f0 && fd <= TT_DRIVE_RATIO_MAX * f0)) {
        /* in Hz below 1 kHz: a mHz drive reads as such */
        double u = fd < 1e3 ? 1 : 1e3;
        return tt_scene_fail(s, "cantilever", NULL, "drive_frequency",
                             "%.4g %s is outside %.4g to %.4g kHz (%g to %g times the "
                             "resonance_frequency: tapping drives near resonance, docs/physics.md)",
                             fd / u, u > 1 ? "kHz" : "Hz", TT_DRIVE_RATIO_MIN * f0 * 1e-3,
                             TT_DRIVE_RATIO_MAX * f0 * 1e-3, TT_DRIVE_RATIO_MIN, TT_DRIVE_RATIO_MAX);
    }
    const char *drive = tt_scene_get_string(s, "cantilever", NULL, "drive");
    tt_drive d = (drive && strcmp(drive, "force") == 0) ? TT_DRIVE_FORCE : TT_DRIVE_BASE;
    if (tt_cantilever_init(c, k, f0, Q, A0, fd, d) != TT_OK)
        return tt_scene_fail(s, "cantilever", NULL, NULL, "%s", tt_error_message());
    rc = config_modes(s, c);
    return rc ? rc : config_drive2(s, c);
}

int tt_config_tip(const tt_scene *s, tt_tip *tip)
{
    int rc;
    if ((rc = tt_scene_get_double(s, "tip", NULL, "radius", &tip->radius)) ||
        (rc = tt_scene_get_double(s, "tip", NULL, "youngs_modulus", &tip->youngs_modulus)) ||
        (rc = tt_scene_get_double(s, "tip", NULL, "poisson_ratio", &tip->poisson_ratio)))
        return rc;
    return TT_OK;
}

/* A colour #rrggbb as 0xrrggbb, or a grey level 0-65535 (matched at the map's own
 * depth once the map is read: 16-bit maps are not converted to 8 bits). */
static int parse_map_value(const char *v, int *rgb, long *grey)
{
    unsigned r, g, b;
    char *end;
    if (v[0] == '#' && strlen(v) == 7 && sscanf(v + 1, "%2x%2x%2x", &r, &g, &b) == 3) {
        *rgb = (int)(r << 16 | g << 8 | b);
        return 0;
    }
    long l = strtol(v, &end, 10);
    if (end != v && *end == '\0' && l >= 0 && l <= 65535) {
        *grey = l;
        return 0;
    }
    return -1;
}

/* A derived lambda out of range is refused on a key the user set, never on a default
 * (interatomic_distance named in a scene that never set it): of the keys set, the one
 * that pushes lambda furthest out, judged by its exponent in eq. 3 (K^(-2/3), w^(2/3),
 * 1/xi0) and its distance from a typical value; the message gives the others and the
 * values of that key that would do. */
static int derived_lambda_fail(const tt_scene *s, const char *name, const tt_contact_params *p,
                               double lambda)
{
    const char *modulus = tt_scene_has(s, "material", name, "reduced_modulus") ? "reduced_modulus"
                                                                              : "youngs_modulus";
    const struct {
        const char *key;
        double value, typical, exponent;
    } c[] = {{modulus, p->K, 3e9, -2.0 / 3}, {"adhesion_energy", p->w, 0.1, 2.0 / 3},
             {"interatomic_distance", p->xi0, 0.265e-9, -1}};
    double side = lambda > 1e4 ? 1 : -1, best = -INFINITY;
    size_t k = 1; /* adhesion_energy is set whenever lambda is derived (w > 0) */
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
        double push = side * c[i].exponent * log(c[i].value / c[i].typical);
        if (tt_scene_has(s, "material", name, c[i].key) && push > best) {
            best = push;
            k = i;
        }
    }
    /* lambda goes as value^exponent: the range of this key that brings it within 1e-4 to 1e4 */
    double lo = c[k].value * pow(1e-4 / lambda, 1 / c[k].exponent);
    double hi = c[k].value * pow(1e4 / lambda, 1 / c[k].exponent);
    char fix[160];
    const char *unit[] = {"Pa", "J/m^2", "nm"};
    double scale = k == 2 ? 1e9 : 1;
    snprintf(fix, sizeof fix, "%s would have to lie from %.3g to %.3g %s", k == 0 ? "the reduced modulus" : c[k].key,
             fmin(lo, hi) * scale, fmax(lo, hi) * scale, unit[k]);
    return tt_scene_fail(s, "material", name, c[k].key,
                         "%s gives lambda = %.3g (Burnham et al. eq. 3, from the reduced modulus "
                         "%.3g Pa, adhesion_energy %g J/m^2, interatomic_distance %g nm and [tip] "
                         "radius %g nm), outside 1e-4 to 1e4: %s; or use model = dmt or jkr for "
                         "the limits",
                         tt_scene_get_string(s, "material", name, c[k].key), lambda, p->K, p->w,
                         p->xi0 * 1e9, p->R * 1e9, fix);
}

/* The contact law's model and its lambda: given (Maugis needs it within 1e-4 to 1e4)
 * or derived from xi0 by Burnham et al. eq. 3 (the same range). */
static int read_model(const tt_scene *s, const char *name, tt_contact_params *p)
{
    int rc;
    p->lambda = NAN;
    int given = tt_scene_has(s, "material", name, "lambda");
    if (given && (rc = tt_scene_get_double(s, "material", name, "lambda", &p->lambda)))
        return rc;
    const char *model = tt_scene_get_string(s, "material", name, "model");
    tt_contact_model m = TT_CONTACT_MAUGIS;
    if (model && tt_contact_model_parse(model, &m) != 0)
        return tt_scene_fail(s, "material", name, "model", "unknown model '%s'", model);
    p->model = m;
    if (p->model != TT_CONTACT_MAUGIS || !(p->w > 0))
        return TT_OK;
    if (given && isfinite(p->lambda) && (p->lambda < 1e-4 || p->lambda > 1e4))
        return tt_scene_fail(s, "material", name, "lambda",
                             "%g is outside 1e-4 to 1e4; use model = dmt or jkr for the limits",
                             p->lambda);
    double derived = tt_material_lambda(p);
    if (!given && !(derived >= 1e-4 && derived <= 1e4))
        return derived_lambda_fail(s, name, p, derived);
    return TT_OK;
}

/* The relaxation arms: arm1 .. arm4 in order, each a modulus with its time, converted
 * to the reduced modulus's units with the sample's Poisson ratio (the tip's compliance
 * stays with the relaxed modulus alone: docs/physics.md). */
static int read_arms(const tt_scene *s, const char *name, tt_contact_params *p)
{
    int rc;
    p->arms = 0;
    for (int i = 0; i < TT_CONTACT_ARMS_MAX; i++) {
        char km[32], kt[32];
        snprintf(km, sizeof km, "arm%d_modulus", i + 1);
        snprintf(kt, sizeof kt, "arm%d_relaxation_time", i + 1);
        int hm = tt_scene_has(s, "material", name, km), ht = tt_scene_has(s, "material", name, kt);
        if (!hm && !ht)
            continue;
        if (hm != ht)
            return tt_scene_fail(s, "material", name, hm ? km : kt, "needs %s too: an arm is a modulus and a relaxation time",
                                 hm ? kt : km);
        if (p->arms != i)
            return tt_scene_fail(s, "material", name, km, "arm%d is missing: number the arms from 1", p->arms + 1);
        double E, nu;
        if ((rc = tt_scene_get_double(s, "material", name, km, &E)) ||
            (rc = tt_scene_get_double(s, "material", name, kt, &p->arm_time[i])) ||
            (rc = tt_scene_get_double(s, "material", name, "poisson_ratio", &nu)))
            return rc;
        p->arm_modulus[i] = E / (0.75 * (1 - nu * nu));
        p->arms = i + 1;
    }
    if (p->arms && ((p->w > 0 && p->model != TT_CONTACT_HERTZ) || p->viscosity > 0 || p->film_thickness > 0))
        return tt_scene_fail(s, "material", name, "arm1_modulus",
                             "relaxation arms need the Hertz law alone: adhesion_energy = 0 or "
                             "model = hertz, and no viscosity or film_thickness");
    return TT_OK;
}

static int read_material(const tt_scene *s, const tt_tip *tip, const char *name, tt_material *m)
{
    int rc;
    tt_contact_params *p = &m->contact;
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    if ((rc = tt_scene_get_double(s, "material", name, "adhesion_energy", &p->w)) ||
        (rc = tt_scene_get_double(s, "material", name, "interatomic_distance", &p->xi0)))
        return rc;
    if (tt_scene_has(s, "material", name, "reduced_modulus")) {
        if (tt_scene_has(s, "material", name, "youngs_modulus"))
            return tt_scene_fail(s, "material", name, "reduced_modulus",
                                 "given together with youngs_modulus; give one of them");
        if ((rc = tt_scene_get_double(s, "material", name, "reduced_modulus", &p->K)))
            return rc;
    } else {
        double Es, nus;
        if ((rc = tt_scene_get_double(s, "material", name, "youngs_modulus", &Es)) ||
            (rc = tt_scene_get_double(s, "material", name, "poisson_ratio", &nus)))
            return rc;
        p->K = tt_material_reduced_modulus(tip, Es, nus);
    }
    p->R = tip->radius;
    if ((rc = read_model(s, name, p)))
        return rc;
    m->Qi = NAN;
    if (tt_scene_has(s, "material", name, "interaction_quality_factor") &&
        (rc = tt_scene_get_double(s, "material", name, "interaction_quality_factor", &m->Qi)))
        return rc;
    if (tt_scene_has(s, "material", name, "viscosity") &&
        (rc = tt_scene_get_double(s, "material", name, "viscosity", &p->viscosity)))
        return rc;
    if (tt_scene_has(s, "material", name, "film_thickness")) {
        if ((rc = tt_scene_get_double(s, "material", name, "film_thickness", &p->film_thickness)))
            return rc;
        if (p->w > 0 && p->model != TT_CONTACT_HERTZ)
            return tt_scene_fail(s, "material", name, "film_thickness",
                                 "the bottom-effect series is for the Hertz law: give "
                                 "adhesion_energy = 0 or model = hertz");
    }
    if ((rc = read_arms(s, name, p)))
        return rc;
    m->map_rgb = -1;
    m->map_grey = -1;
    const char *v = tt_scene_get_string(s, "material", name, "map_value");
    if (v && parse_map_value(v, &m->map_rgb, &m->map_grey) != 0)
        return tt_scene_fail(s, "material", name, "map_value",
                             "'%s' is neither a grey level 0-65535 nor a colour #rrggbb", v);
    return TT_OK;
}

int tt_config_materials(const tt_scene *s, tt_material **out, size_t *n)
{
    *out = NULL;
    *n = 0;
    tt_tip tip;
    int rc = tt_config_tip(s, &tip);
    if (rc)
        return rc;
    size_t count = tt_scene_count_named(s, "material");
    tt_material *m = calloc(count ? count : 1, sizeof *m);
    if (!m)
        return tt_error_nomem("the %zu materials of %s", count ? count : 1, tt_scene_origin(s));
    for (size_t i = 0; i < (count ? count : 1) && rc == TT_OK; i++)
        rc = read_material(s, &tip, count ? tt_scene_named(s, "material", i) : "sample", &m[i]);
    if (rc) {
        free(m);
        return rc;
    }
    *out = m;
    *n = count ? count : 1;
    return TT_OK;
}

int tt_config_material_index(const tt_scene *s, const char *section, const tt_material *m,
                             size_t n, size_t *index)
{
    const char *name = tt_scene_get_string(s, section, NULL, "material");
    *index = 0;
    if (!name)
        return TT_OK;
    for (size_t i = 0; i < n; i++)
        if (strcmp(m[i].name, name) == 0) {
            *index = i;
            return TT_OK;
        }
    return tt_scene_fail(s, section, NULL, "material", "no [material %s] section in the scene", name);
}
