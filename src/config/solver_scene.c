/* The solver settings of a scene (see include/tiptap/config/solver_scene.h). */
#include "tiptap/config/solver_scene.h"

#include <string.h>

#include "tiptap/util/error.h"

int tt_solver_from_scene(tt_solver *s, const tt_scene *scene)
{
    tt_solver_default(s);
    const char *m = tt_scene_get_string(scene, "solver", NULL, "method");
    s->method = TT_METHOD_DOPRI5;
    if (m && strcmp(m, "rk4") == 0)
        s->method = TT_METHOD_RK4;
    else if (m && strcmp(m, "radau") == 0)
        s->method = TT_METHOD_RADAU;
    const char *t = tt_scene_get_string(scene, "solver", NULL, "tier");
    if (tt_tier_parse(t, &s->tier)) /* the schema allows only the tiers' names */
        s->tier = TT_TIER_EVERY;
    long n;
    int rc;
    if ((rc = tt_scene_get_double(scene, "solver", NULL, "tolerance", &s->tolerance)) ||
        (rc = tt_scene_get_int(scene, "solver", NULL, "steps_per_cycle", &n)))
        return rc;
    s->steps_per_cycle = (int)n;
    return TT_OK;
}
