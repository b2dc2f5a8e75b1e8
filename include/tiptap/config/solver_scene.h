/* tiptap: the solver settings of a scene ([solver] method, tolerance, steps_per_cycle).
 *
 * Kept in the configuration layer so that the solver reads no scene keys itself. */
#ifndef TIPTAP_SOLVER_SCENE_H
#define TIPTAP_SOLVER_SCENE_H

#include "tiptap/config/scene.h"
#include "tiptap/solver/integrator.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Fill s from the scene's [solver] section (defaults where a key is absent). */
int tt_solver_from_scene(tt_solver *s, const tt_scene *scene);

#ifdef __cplusplus
}
#endif
#endif
