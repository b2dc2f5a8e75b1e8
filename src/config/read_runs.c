/* The configuration layer's runs: [approach] and the accuracy study's subject
 * (see include/tiptap/config/config.h). */
#include "tiptap/config/config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

int tt_config_approach(const tt_scene *s, tt_approach_params *p)
{
    int rc;
    memset(p, 0, sizeof *p);
    const char *mode = tt_scene_get_string(s, "approach", NULL, "mode");
    p->mode = (mode && strcmp(mode, "ramp") == 0) ? TT_APPROACH_RAMP : TT_APPROACH_STEADY;
    const char *steady = tt_scene_get_string(s, "approach", NULL, "steady");
    p->steady = (steady && strcmp(steady, "settle") == 0) ? TT_STEADY_SETTLE : TT_STEADY_SHOOTING;
    if ((rc = tt_scene_get_double(s, "approach", NULL, "from", &p->from)) ||
        (rc = tt_scene_get_double(s, "approach", NULL, "to", &p->to)) ||
        (rc = tt_scene_get_int(s, "approach", NULL, "points", &p->points)) ||
        (rc = tt_scene_get_bool(s, "approach", NULL, "retract", &p->retract)) ||
        (rc = tt_scene_get_double(s, "approach", NULL, "speed", &p->speed)) ||
        (rc = tt_scene_get_int(s, "approach", NULL, "max_cycles", &p->max_cycles)) ||
        (rc = tt_scene_get_double(s, "approach", NULL, "settle_tolerance", &p->settle_tolerance)))
        return rc;
    if (p->points > 1 && p->from == p->to)
        return tt_scene_fail(s, "approach", NULL, "to", "equals 'from'; an approach needs a range");
    return tt_config_check_rk4(s, "approach", fmin(p->from, p->to));
}

int tt_config_approach_setup(tt_setup *st, const tt_scene *s, tt_approach_params *p)
{
    size_t mat = 0;
    int rc;
    if ((rc = tt_config_approach(s, p)) ||
        (rc = tt_config_material_index(s, "approach", tt_setup_material(st, 0),
                                       tt_setup_materials(st), &mat)))
        return rc;
    p->material = tt_setup_material(st, mat)->name; /* for tt_approach_warn */
    /* shooting's Newton iterates the tip's (d, v): a sample with a state of its own
     * (relaxation arms) settles instead */
    if (tt_setup_material(st, mat)->contact.arms > 0)
        p->steady = TT_STEADY_SETTLE;
    /* nor has a cantilever with mode 2 driven a periodic orbit: it settles its lock-ins */
    if (tt_setup_cantilever(st)->A2 > 0)
        p->steady = TT_STEADY_SETTLE;
    p->tip_radius = tt_setup_material(st, mat)->contact.R;
    return tt_setup_use_material(st, mat);
}

int tt_config_approach_alloc(tt_approach **out, tt_setup *st, const tt_scene *s,
                             tt_approach_params *p)
{
    *out = NULL;
    int rc = tt_config_approach_setup(st, s, p);
    return rc ? rc : tt_scene_locate(s, tt_approach_alloc(out, tt_setup_sim(st), p));
}

int tt_config_accuracy(const tt_scene *s, tt_accuracy_subject *subject)
{
    memset(subject, 0, sizeof *subject);
    subject->approach_point = NAN;
    tt_material *m = NULL;
    size_t n = 0, mat = 0;
    int rc;
    if ((rc = tt_config_cantilever(s, &subject->cantilever)) ||
        (rc = tt_solver_from_scene(&subject->solver, s)) || (rc = tt_config_materials(s, &m, &n)) ||
        (rc = tt_config_material_index(s, "approach", m, n, &mat))) {
        free(m);
        return rc;
    }
    subject->material = m[mat];
    free(m);
    if (tt_scene_has_section(s, "approach", NULL)) {
        long points;
        if ((rc = tt_scene_get_int(s, "approach", NULL, "points", &points)) ||
            (points == 1 && (rc = tt_scene_get_double(s, "approach", NULL, "from", &subject->approach_point))))
            return rc;
    }
    subject->has_scan = tt_scene_has_section(s, "scan", NULL);
    if (subject->has_scan && (rc = tt_config_scan(s, &subject->scan)))
        return rc;
    return TT_OK;
}

void tt_config_accuracy_free(tt_accuracy_subject *subject)
{
    if (subject->has_scan)
        tt_config_scan_free(&subject->scan);
}

int tt_config_accuracy_alloc(tt_accuracy **out, const tt_scene *s, const tt_accuracy_params *p)
{
    tt_accuracy_subject subject;
    *out = NULL;
    int rc = tt_config_accuracy(s, &subject);
    if (rc)
        return rc;
    rc = tt_scene_locate(s, tt_accuracy_alloc(out, &subject, p));
    tt_config_accuracy_free(&subject);
    return rc;
}
