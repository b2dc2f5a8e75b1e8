/* The run's own error estimate outside the scan (approach, trace): the scene again at
 * the companion setting (tt_companion_solver), and the warning every command gives when
 * its estimate says the run is wrong. */
#include <math.h>
#include <stdio.h>

#include "commands.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/util/error.h"

tt_scene *cli_companion_scene(const tt_scene *scene, const tt_solver *s, tt_solver *tight)
{
    *tight = tt_companion_solver(s);
    tt_scene *c = tt_scene_copy(scene);
    char set[2][64];
    snprintf(set[0], sizeof set[0], "solver.tolerance=%.17g", tight->tolerance);
    snprintf(set[1], sizeof set[1], "solver.steps_per_cycle=%d", tight->steps_per_cycle);
    if (c && (tt_scene_set(c, set[0]) || tt_scene_set(c, set[1]))) {
        tt_scene_free(c);
        return NULL;
    }
    return c;
}

/* The key that tightens the run: the method's accuracy knob. */
static void knob(const tt_solver *s, char *buf, size_t len)
{
    if (s->method == TT_METHOD_RK4)
        snprintf(buf, len, "raise [solver] steps_per_cycle (now %d)", s->steps_per_cycle);
    else
        snprintf(buf, len, "tighten [solver] tolerance (now %.3g)", s->tolerance);
}

int cli_warn_estimate(const char *cmd, const tt_solver *s, double A0, double height_m,
                      const char *what, double amplitude_rel, double phase_deg)
{
    double h = height_m / A0;
    int bad_h = h > CLI_WARN_AMPLITUDE_REL, bad_a = amplitude_rel > CLI_WARN_AMPLITUDE_REL,
        bad_p = phase_deg > CLI_WARN_PHASE_DEG;
    if (!bad_h && !bad_a && !bad_p)
        return 0;
    char parts[256] = "", k[96];
    size_t n = 0;
    if (bad_h)
        n += (size_t)snprintf(parts + n, sizeof parts - n, "%.2g nm in height (%.1e of the free "
                              "amplitude)", height_m * 1e9, h);
    if (bad_a && n < sizeof parts)
        n += (size_t)snprintf(parts + n, sizeof parts - n, "%s%.1e of the free amplitude in %s",
                              n ? ", " : "", amplitude_rel, what);
    if (bad_p && n < sizeof parts)
        snprintf(parts + n, sizeof parts - n, "%s%.2g deg in phase", n ? " and " : "", phase_deg);
    knob(s, k, sizeof k);
    fprintf(stderr, "tiptap %s: warning: the run's own error estimate is %s (above 1e-3 of the "
                    "free amplitude or 0.1 deg): %s\n", cmd, parts, k);
    return 1;
}
