/* A scene's materials as contact parameters (see include/tiptap/physics/material.h). */
#include "tiptap/physics/material.h"

#include <math.h>
#include <string.h>

#include "tiptap/util/error.h"

size_t tt_material_count(const tt_scene *s)
{
    size_t n = tt_scene_count_named(s, "material");
    return n ? n : 1;
}

const char *tt_material_name(const tt_scene *s, size_t i)
{
    if (tt_scene_count_named(s, "material") == 0)
        return i == 0 ? "sample" : NULL;
    return tt_scene_named(s, "material", i);
}

int tt_material_params(const tt_scene *s, const char *name, tt_contact_params *p, double *Qi)
{
    int rc;
    double Et, nut, R, w, xi0;
    if ((rc = tt_scene_get_double(s, "tip", NULL, "radius", &R)) ||
        (rc = tt_scene_get_double(s, "tip", NULL, "youngs_modulus", &Et)) ||
        (rc = tt_scene_get_double(s, "tip", NULL, "poisson_ratio", &nut)) ||
        (rc = tt_scene_get_double(s, "material", name, "adhesion_energy", &w)) ||
        (rc = tt_scene_get_double(s, "material", name, "interatomic_distance", &xi0)))
        return rc;
    memset(p, 0, sizeof *p);
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
        p->K = 1.0 / (0.75 * ((1 - nut * nut) / Et + (1 - nus * nus) / Es));
    }
    p->R = R;
    p->w = w;
    p->xi0 = xi0;
    p->lambda = NAN;
    if (tt_scene_has(s, "material", name, "lambda") &&
        (rc = tt_scene_get_double(s, "material", name, "lambda", &p->lambda)))
        return rc;
    const char *model = tt_scene_get_string(s, "material", name, "model");
    tt_contact_model m = TT_CONTACT_MAUGIS;
    if (model && tt_contact_model_parse(model, &m) != 0)
        return tt_scene_fail(s, "material", name, "model", "unknown model '%s'", model);
    p->model = m;
    if (p->model == TT_CONTACT_MAUGIS && w > 0 && isfinite(p->lambda) &&
        (p->lambda < 1e-4 || p->lambda > 1e4))
        return tt_scene_fail(s, "material", name, "lambda",
                             "%g is outside 1e-4 to 1e4; use model = dmt or jkr for the limits",
                             p->lambda);
    *Qi = NAN;
    if (tt_scene_has(s, "material", name, "interaction_quality_factor") &&
        (rc = tt_scene_get_double(s, "material", name, "interaction_quality_factor", Qi)))
        return rc;
    return TT_OK;
}
