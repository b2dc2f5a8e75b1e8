/* Scene keys of the imaging sections [surface], [lockin], [feedback] ([scan]: schema_scan.c). */
#include "scene_schema_internal.h"

#define Q(dims) TT_KEY_QUANTITY, (dims)
#define POS TT_KEY_MIN_EXCL
#define INF TT_UNBOUNDED

const tt_scene_key tt_schema_surface[] = {
    {"type", TT_KEY_ENUM, 0, "flat", 0, 0, 0, "flat|steps|grating|particles|rough|png",
     "topography (docs/surfaces.md)"},
    {"step_height", Q(TT_DIM_LENGTH), "1 nm", -INF, INF, 0, NULL, "steps: height of each step (up along x)"},
    {"step_width", Q(TT_DIM_LENGTH), "250 nm", 0, INF, POS, NULL, "steps: terrace width"},
    {"period", Q(TT_DIM_LENGTH), "500 nm", 0, INF, POS, NULL, "grating: period along x"},
    {"duty", Q(TT_DIM_FRACTION | TT_DIM_NONE), "50 %", 0, 1, TT_KEY_MIN_EXCL | TT_KEY_MAX_EXCL, NULL,
     "grating: raised fraction of a period"},
    {"height", Q(TT_DIM_LENGTH), "20 nm", -INF, INF, 0, NULL, "grating: line height"},
    {"edge_width", Q(TT_DIM_LENGTH), "0 nm", 0, INF, 0, NULL,
     "grating: horizontal width of each sidewall (0: vertical)"},
    {"particle_radius", Q(TT_DIM_LENGTH), "20 nm", 0, INF, POS, NULL,
     "particles: sphere radius (a sphere on the flat rises 2 r)"},
    {"particle_count", TT_KEY_INT, 0, "12", 0, 100000, 0, NULL, "particles: number, placed without overlap"},
    {"rms", Q(TT_DIM_LENGTH), "1 nm", 0, INF, 0, NULL, "rough: RMS height"},
    {"correlation_length", Q(TT_DIM_LENGTH), "50 nm", 0, INF, POS, NULL,
     "rough: Gaussian correlation length (ACF exp(-r^2/L^2))"},
    {"seed", TT_KEY_INT, 0, "1", 0, 2147483647, 0, NULL, "particles, rough: random seed"},
    {"png", TT_KEY_STRING, 0, NULL, 0, 0, TT_KEY_PATH, NULL,
     "png: grey height map (8 or 16 bit) spanning the scan area, top row at y = 0"},
    {"png_height_range", Q(TT_DIM_LENGTH), "10 nm", -INF, INF, 0, NULL, "png: height of white above black"},
    {"map", TT_KEY_ENUM, 0, "uniform", 0, 0, 0, "uniform|stripes|disks|checkerboard|islands|png",
     "material map"},
    {"map_materials", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "materials of the map, background first: \"matrix, disk\" (default: the scene's first two)"},
    {"map_period", Q(TT_DIM_LENGTH), "250 nm", 0, INF, POS, NULL,
     "stripes, disks, checkerboard: period of the pattern"},
    {"map_duty", Q(TT_DIM_FRACTION | TT_DIM_NONE), "50 %", 0, 1, TT_KEY_MIN_EXCL | TT_KEY_MAX_EXCL, NULL,
     "stripes: fraction of a period of the second material"},
    {"map_radius", Q(TT_DIM_LENGTH), "60 nm", 0, INF, POS, NULL, "disks: disk radius"},
    {"map_png", TT_KEY_STRING, 0, NULL, 0, 0, TT_KEY_PATH, NULL,
     "png map: each pixel's grey level or colour names a material through its map_value"},
};
const size_t tt_schema_surface_count = TT_COUNT(tt_schema_surface);

const tt_scene_key tt_schema_lockin[] = {
    {"time_constant", Q(TT_DIM_TIME), "100 us", 0, INF, 0, NULL,
     "low-pass time constant of each filter section (0: none); a 1 Hz, 128-pixel line has 3.9 ms per pixel"},
    {"filter_order", TT_KEY_INT, 0, "2", 1, 8, 0, NULL, "low-pass sections in cascade (6 dB/octave each)"},
    {"samples_per_period", TT_KEY_INT, 0, "32", 8, 1024, 0, NULL, "deflection samples per drive period"},
    {"harmonics", TT_KEY_INT, 0, "1", 1, 16, 0, NULL, "highest harmonic the lock-in offers to [scan] channels (1: the fundamental only)"},
    {"periods_per_block", TT_KEY_INT, 0, "4", 1, 1000, 0, NULL,
     "drive periods per transform, which is also the feedback's update interval"},
};
const size_t tt_schema_lockin_count = TT_COUNT(tt_schema_lockin);

const tt_scene_key tt_schema_feedback[] = {
    {"setpoint", Q(TT_DIM_LENGTH | TT_DIM_FRACTION), "80 %", 0, INF, POS, NULL,
     "amplitude setpoint: a length, or a percentage of the free amplitude"},
    {"proportional_gain", Q(TT_DIM_NONE), "0", 0, 1e6, 0, NULL,
     "z moved per amplitude error, m/m (0: integral control only)"},
    {"integral_gain", Q(TT_DIM_FREQUENCY), "1000 Hz", 0, INF, 0, NULL,
     "z speed per amplitude error, (m/s)/m; keep ki below the amplitude bandwidth pi f0 / Q (2.4 kHz at 300 kHz, Q 400)"},
    {"z_range", Q(TT_DIM_LENGTH), "2 um", 0, INF, POS, NULL,
     "travel of the z piezo, centred on the surface's zero; the height clamps at its ends"},
};
const size_t tt_schema_feedback_count = TT_COUNT(tt_schema_feedback);
