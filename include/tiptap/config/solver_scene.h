/* tiptap: the solver settings of a scene ([solver] method, tolerance, steps_per_cycle).
 *
 * Kept in the configuration layer so that the solver reads no scene keys itself. */
#ifndef TIPTAP_SOLVER_SCENE_H
#define TIPTAP_SOLVER_SCENE_H

#include "tiptap/export.h"
#include "tiptap/config/scene.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

/* Fill s from the scene's [solver] section (defaults where a key is absent). */
int tt_solver_from_scene(tt_solver *s, const tt_scene *scene);

TT_END_DECLS
#endif
