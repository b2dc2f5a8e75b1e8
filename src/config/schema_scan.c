/* Scene keys of the [scan] section (the raster and what a scan records). */
#include "scene_schema_internal.h"

#define Q(dims) TT_KEY_QUANTITY, (dims)
#define POS TT_KEY_MIN_EXCL
#define INF TT_UNBOUNDED

const tt_scene_key tt_schema_scan[] = {
    {"size", Q(TT_DIM_LENGTH), "1 um", 0, INF, POS, NULL, "scan size along x (and y unless size_y)"},
    {"size_y", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL, "scan size along y (default: size)"},
    {"pixels", TT_KEY_INT, 0, "128", 2, 16384, 0, NULL, "pixels per line (fast axis)"},
    {"lines", TT_KEY_INT, 0, "128", 1, 16384, 0, NULL, "lines (slow axis)"},
    {"line_rate", Q(TT_DIM_FREQUENCY), "1 Hz", 0, INF, POS, NULL,
     "lines per second; each line is a trace and a retrace, half the period each"},
    {"fast_axis", TT_KEY_ENUM, 0, "x", 0, 0, 0, "x|y", "direction of the fast scan"},
    {"retrace", TT_KEY_BOOL, 0, "yes", 0, 0, 0, NULL, "record the retrace images too"},
    {"channels", TT_KEY_STRING, 0, "height, amplitude, phase, peak_force, indentation, dissipation", 0,
     0, 0, NULL,
     "what to record: height, amplitude, phase, peak_force, indentation, dissipation, topography, "
     "harmonic2 to harmonic8 (need [lockin] harmonics >= h), harmonic2_phase to harmonic8_phase"},
    {"profile_line", TT_KEY_INT, 0, "-1", -1, 16383, 0, NULL,
     "line written to profile.csv (-1: the middle line)"},
    {"settle_cycles", TT_KEY_INT, 0, "3000", 0, 1e9, 0, NULL,
     "drive cycles the feedback settles at each line's first pixel before the trace"},
};
const size_t tt_schema_scan_count = TT_COUNT(tt_schema_scan);
