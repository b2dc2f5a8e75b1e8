/* The [trace] section (see include/tiptap/config/read_trace.h). */
#include "tiptap/config/read_trace.h"

#include <math.h>

#include <stdio.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/config/solver_scene.h"
#include "tiptap/util/error.h"

/* Parse text as a value of the ramped key "section.key" or "section.name.key": the
 * section is before the first dot, the key after the last. */
static int ramp_value(const tt_scene *s, const char *ramp, const char *text, double *value)
{
    const char *d1 = strchr(ramp, '.'), *d2 = strrchr(ramp, '.');
    char section[128];
    if (!d1)
        return tt_error(TT_EINVAL, "'%s': expected section.key or material.NAME.key", ramp);
    snprintf(section, sizeof section, "%.*s", (int)(d1 - ramp), ramp);
    int rc = tt_scene_parse_value(s, section, d2 + 1, text, value);
    if (rc)
        return rc;
    /* what the run can change between cycles (tt_setup_apply), checked before it starts */
    if (strcmp(section, "cantilever") != 0 && strcmp(section, "tip") != 0 &&
        strcmp(section, "material") != 0)
        return tt_error(TT_EINVAL, "%s: only [cantilever], [tip] and [material] keys can be ramped",
                        ramp);
    if (strcmp(section, "material") == 0) {
        char name[256];
        snprintf(name, sizeof name, "%.*s", d2 > d1 ? (int)(d2 - d1 - 1) : 0, d1 + 1);
        int have = tt_scene_count_named(s, "material") ? tt_scene_has_section(s, "material", name)
                                                        : strcmp(name, "sample") == 0;
        if (!have)
            return tt_error(TT_EINVAL, "%s: no [material %s] in the scene", ramp, name);
    }
    return TT_OK;
}

int tt_config_trace(const tt_scene *s, tt_trace_params *p)
{
    int rc;
    memset(p, 0, sizeof *p);
    p->material = tt_scene_get_string(s, "trace", NULL, "material");
    p->ramp = tt_scene_get_string(s, "trace", NULL, "ramp");
    if ((rc = tt_scene_get_double(s, "trace", NULL, "separation", &p->separation)) ||
        (rc = tt_scene_get_int(s, "trace", NULL, "cycles", &p->cycles)) ||
        (rc = tt_scene_get_int(s, "trace", NULL, "settle_cycles", &p->settle_cycles)) ||
        (rc = tt_scene_get_int(s, "trace", NULL, "samples_per_cycle", &p->samples_per_cycle)))
        return rc;
    p->separation_end = p->separation;
    if (tt_scene_has(s, "trace", NULL, "separation_end") &&
        (rc = tt_scene_get_double(s, "trace", NULL, "separation_end", &p->separation_end)))
        return rc;
    if ((rc = tt_config_check_rk4(s, "trace", fmin(p->separation, p->separation_end))))
        return rc;
    tt_solver solver;
    tt_cantilever c;
    if ((rc = tt_solver_from_scene(&solver, s)) || (rc = tt_config_cantilever(s, &c)) ||
        (rc = tt_config_noise(s, &solver, c.fd, &p->noise)))
        return rc;
    if (!p->ramp)
        return TT_OK;
    const char *from = tt_scene_get_string(s, "trace", NULL, "ramp_from");
    const char *to = tt_scene_get_string(s, "trace", NULL, "ramp_to");
    if (!from || !to)
        return tt_scene_fail(s, "trace", NULL, from ? "ramp_to" : "ramp_from",
                             "missing; a ramp needs ramp_from and ramp_to");
    if (ramp_value(s, p->ramp, from, &p->ramp_from) || ramp_value(s, p->ramp, to, &p->ramp_to))
        return tt_scene_fail(s, "trace", NULL, "ramp", "%s", tt_error_message());
    return TT_OK;
}
