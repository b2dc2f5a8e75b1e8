/* Schema tables defined by the modules that own their sections. Private to libtiptap. */
#ifndef TIPTAP_SCENE_SCHEMA_INTERNAL_H
#define TIPTAP_SCENE_SCHEMA_INTERNAL_H

#include <math.h>

#include "tiptap/config/scene.h"

#define TT_COUNT(a) (sizeof(a) / sizeof((a)[0]))
#define TT_UNBOUNDED INFINITY

/* Imaging sections, in schema_imaging.c: [surface], [scan], [lockin], [feedback]. */
extern const tt_scene_key tt_schema_surface[];
extern const size_t tt_schema_surface_count;
extern const tt_scene_key tt_schema_scan[];
extern const size_t tt_schema_scan_count;
extern const tt_scene_key tt_schema_lockin[];
extern const size_t tt_schema_lockin_count;
extern const tt_scene_key tt_schema_feedback[];
extern const size_t tt_schema_feedback_count;

#endif
