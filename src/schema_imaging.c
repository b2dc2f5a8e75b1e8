/* Scene keys of the imaging sections [surface], [lockin], [feedback] ([scan]: schema_scan.c). */
#include "scene_schema_internal.h"

#define Q(dims) TT_KEY_QUANTITY, (dims)
#define POS TT_KEY_MIN_EXCL
#define INF TT_UNBOUNDED

const tt_scene_key tt_schema_surface[] = {
    {"type", TT_KEY_ENUM, 0, "flat", 0, 0, 0, "flat|steps|grating|particles|rough|png",
     "topography"},
};
const size_t tt_schema_surface_count = TT_COUNT(tt_schema_surface);

const tt_scene_key tt_schema_lockin[] = {
    {"time_constant", Q(TT_DIM_TIME), "100 us", 0, INF, POS, NULL, "low-pass time constant"},
};
const size_t tt_schema_lockin_count = TT_COUNT(tt_schema_lockin);

const tt_scene_key tt_schema_feedback[] = {
    {"setpoint", Q(TT_DIM_LENGTH | TT_DIM_FRACTION), "80 %", 0, INF, POS, NULL,
     "amplitude setpoint: a length, or a percentage of the free amplitude"},
};
const size_t tt_schema_feedback_count = TT_COUNT(tt_schema_feedback);
