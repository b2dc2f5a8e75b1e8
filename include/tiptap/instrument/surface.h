/* tiptap: sample topography and material map ([surface] section).
 *
 * Heights in metres along the axis pointing out of the sample towards the tip (a bump
 * is positive); x, y in metres in the scan frame, (0, 0) the top-left corner of the
 * scan area. Materials are indices into the scene's [material NAME] sections in order
 * of appearance (tt_scene_named).
 *
 * Ownership: tt_surface_alloc returns an object the caller frees with
 * tt_surface_free; it is read-only after allocation and may be shared between threads.
 */
#ifndef TIPTAP_SURFACE_H
#define TIPTAP_SURFACE_H

#include "tiptap/config/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tt_surface tt_surface;

/* Build from the scene's [surface] section; size_x, size_y: the scan area (m), which
 * tiled shapes and PNG maps cover. Errors name the file, section and key. */
int tt_surface_alloc(tt_surface **out, const tt_scene *scene, double size_x, double size_y);
void tt_surface_free(tt_surface *s);

double tt_surface_height(const tt_surface *s, double x, double y);
int tt_surface_material(const tt_surface *s, double x, double y);
/* 1 when the whole surface is one material (no map look-ups needed). */
int tt_surface_uniform(const tt_surface *s);
/* 1 when the topography is flat everywhere. */
int tt_surface_flat(const tt_surface *s);

#ifdef __cplusplus
}
#endif
#endif
