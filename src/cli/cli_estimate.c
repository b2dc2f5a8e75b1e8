/* The run's own error estimate outside the scan (approach, trace): the scene again at
 * the companion setting (tt_companion_solver); the warning when its estimate says the run
 * is wrong is the library's (tt_run_warn_estimate). */
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
