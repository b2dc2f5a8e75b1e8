/* The configuration layer's imaging instrument: the tip's shape ([tip] shape,
 * half_angle) and the instrument's imperfections ([instrument]) (see
 * include/tiptap/config/config.h). */
#include "tiptap/config/config.h"

#include <string.h>

#include "tiptap/util/error.h"

int tt_config_tip_shape(const tt_scene *s, tt_tip_shape *t)
{
    memset(t, 0, sizeof *t);
    const char *shape = tt_scene_get_string(s, "tip", NULL, "shape");
    t->kind = !shape || strcmp(shape, "point") == 0 ? TT_TIP_POINT
              : strcmp(shape, "sphere") == 0       ? TT_TIP_SPHERE
                                                   : TT_TIP_CONE;
    int rc;
    if ((rc = tt_scene_get_double(s, "tip", NULL, "radius", &t->radius)) ||
        (rc = tt_scene_get_double(s, "tip", NULL, "half_angle", &t->half_angle)))
        return rc;
    return TT_OK;
}

static int get(const tt_scene *s, const char *key, double *v)
{
    return tt_scene_get_double(s, "instrument", NULL, key, v);
}

int tt_config_instrument(const tt_scene *s, tt_instrument_params *p)
{
    memset(p, 0, sizeof *p);
    tt_piezo_params *z = &p->piezo;
    int rc;
    if ((rc = get(s, "tilt_x", &p->tilt_x)) || (rc = get(s, "tilt_y", &p->tilt_y)) ||
        (rc = get(s, "drift_x", &p->drift_x)) || (rc = get(s, "drift_y", &p->drift_y)) ||
        (rc = get(s, "drift_z", &p->drift_z)) || (rc = get(s, "piezo_resonance", &z->resonance)) ||
        (rc = get(s, "piezo_damping", &z->damping)) || (rc = get(s, "creep", &z->creep)) ||
        (rc = get(s, "creep_time", &z->creep_time)))
        return rc;
    return TT_OK;
}
