/* The scene schema: every section and key tiptap reads, with unit, default, range and a
 * one-line description. docs/scene-format.md is written from the same facts; keep both
 * in step (tests/test_scene_doc checks that every key here is documented there). */
#include "scene_schema_internal.h"

#define Q(dims) TT_KEY_QUANTITY, (dims)
#define POS TT_KEY_MIN_EXCL
#define INF TT_UNBOUNDED

static const tt_scene_key cantilever_keys[] = {
    {"spring_constant", Q(TT_DIM_STIFFNESS), "40 N/m", 0, INF, POS, NULL,
     "cantilever spring constant k_c"},
    {"resonance_frequency", Q(TT_DIM_FREQUENCY), "300 kHz", 0, INF, POS, NULL,
     "free resonance frequency f_c = w_c / 2 pi"},
    {"quality_factor", Q(TT_DIM_NONE), "400", 0, INF, POS, NULL,
     "quality factor Q_c (c = m* w_c / Q_c)"},
    {"free_amplitude", Q(TT_DIM_LENGTH), "20 nm", 0, INF, POS, NULL,
     "deflection amplitude at the drive frequency far from the sample"},
    {"drive_frequency", Q(TT_DIM_FREQUENCY), NULL, 0, INF, POS, NULL,
     "drive frequency (default: the resonance frequency)"},
    {"drive", TT_KEY_ENUM, 0, "base", 0, 0, 0, "base|force",
     "base: the base moves, as in the seed (eq. 2); force: a force on the tip"},
};

static const tt_scene_key tip_keys[] = {
    {"radius", Q(TT_DIM_LENGTH), "10 nm", 0, INF, POS, NULL, "tip radius R_tip"},
    {"youngs_modulus", Q(TT_DIM_PRESSURE), "169 GPa", 0, INF, POS, NULL,
     "tip Young's modulus (silicon: 169 GPa)"},
    {"poisson_ratio", Q(TT_DIM_NONE), "0.27", -1, 0.5, 0, NULL, "tip Poisson ratio"},
};

static const tt_scene_key material_keys[] = {
    {"youngs_modulus", Q(TT_DIM_PRESSURE), "2 GPa", 0, INF, POS, NULL,
     "sample Young's modulus (ignored when reduced_modulus is given)"},
    {"poisson_ratio", Q(TT_DIM_NONE), "0.35", -1, 0.5, 0, NULL, "sample Poisson ratio"},
    {"reduced_modulus", Q(TT_DIM_PRESSURE), NULL, 0, INF, POS, NULL,
     "reduced modulus K of the tip-sample pair, given directly"},
    {"adhesion_energy", Q(TT_DIM_SURFACE_ENERGY), "0 J/m^2", 0, INF, 0, NULL,
     "Dupre work of adhesion w; 0 means Hertz contact, no van der Waals, no hysteresis"},
    {"interatomic_distance", Q(TT_DIM_LENGTH), "0.265 nm", 0, INF, POS, NULL,
     "equilibrium interatomic distance xi0 (sets lambda and the van der Waals offset)"},
    {"lambda", Q(TT_DIM_NONE), NULL, 0, INF, POS, NULL,
     "Maugis parameter; overrides the value derived from xi0"},
    {"model", TT_KEY_ENUM, 0, "maugis", 0, 0, 0, "maugis|hertz|dmt|jkr",
     "contact model: Maugis-Dugdale (eq. 7) or one of its limits"},
    {"interaction_quality_factor", Q(TT_DIM_NONE), NULL, 0, INF, POS, NULL,
     "Q_i of the interaction damping in contact (c_i = m* w_c / Q_i); absent: none"},
    {"map_value", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "grey level (0-255 or 0-65535) or colour (#rrggbb) of this material in a PNG material map"},
};

static const tt_scene_key approach_keys[] = {
    {"from", Q(TT_DIM_LENGTH), "25 nm", -INF, INF, 0, NULL,
     "first rest separation (gap between undeflected tip and surface; negative: below it)"},
    {"to", Q(TT_DIM_LENGTH), "-5 nm", -INF, INF, 0, NULL, "last rest separation"},
    {"points", TT_KEY_INT, 0, "61", 1, 1e7, 0, NULL, "number of separations"},
    {"mode", TT_KEY_ENUM, 0, "steady", 0, 0, 0, "steady|ramp",
     "steady: settle at each point; ramp: the sample moves continuously at speed"},
    {"retract", TT_KEY_BOOL, 0, "no", 0, 0, 0, NULL,
     "steady mode: follow the approach with the retract branch back to from"},
    {"speed", Q(TT_DIM_VELOCITY), "10 um/s", 0, INF, POS, NULL, "ramp mode: sample speed"},
    {"material", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "material to approach (default: the first [material])"},
    {"max_cycles", TT_KEY_INT, 0, "20000", 10, 1e9, 0, NULL,
     "steady mode: most drive cycles spent settling one point"},
    {"settle_tolerance", Q(TT_DIM_NONE), "1e-7", 0, 1, POS, NULL,
     "steady mode: a point is settled when amplitude (relative) and phase (rad) change less than this per cycle"},
    {"steady", TT_KEY_ENUM, 0, "shooting", 0, 0, 0, "shooting|settle",
     "steady mode: shooting: Newton on the one-period map finds the periodic orbit (falls back to "
     "settling); settle: run cycles until the point settles"},
};

static const tt_scene_key trace_keys[] = {
    {"separation", Q(TT_DIM_LENGTH), "10 nm", -INF, INF, 0, NULL,
     "rest separation at the start of the trace"},
    {"separation_end", Q(TT_DIM_LENGTH), NULL, -INF, INF, 0, NULL,
     "rest separation at the end (default: fixed separation)"},
    {"cycles", TT_KEY_INT, 0, "20", 1, 1e9, 0, NULL, "drive cycles recorded"},
    {"settle_cycles", TT_KEY_INT, 0, "0", 0, 1e9, 0, NULL,
     "drive cycles run before recording (from the free steady state)"},
    {"samples_per_cycle", TT_KEY_INT, 0, "100", 4, 1e6, 0, NULL, "output rows per drive cycle"},
    {"material", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "material under the tip (default: the first [material])"},
    {"ramp", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "a key ramped linearly over the recorded cycles: material.NAME.key or cantilever.key"},
    {"ramp_from", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL, "ramped key's first value, with unit"},
    {"ramp_to", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL, "ramped key's last value, with unit"},
};

static const tt_scene_key solver_keys[] = {
    {"method", TT_KEY_ENUM, 0, "dopri5", 0, 0, 0, "dopri5|rk4|radau",
     "dopri5: adaptive explicit 5(4) with dense output; rk4: classic, fixed steps; "
     "radau: adaptive implicit Radau IIA (order 5, L-stable) for very stiff or heavily damped "
     "contacts"},
    {"tolerance", Q(TT_DIM_NONE), "1e-8", 1e-14, 1e-1, 0, NULL,
     "adaptive methods (dopri5, radau): local error tolerance relative to the free amplitude"},
    {"steps_per_cycle", TT_KEY_INT, 0, "512", 8, 1e7, 0, NULL,
     "rk4: fixed steps per drive cycle"},
};

static const tt_scene_section sections[] = {
    {"cantilever", 0, cantilever_keys, TT_COUNT(cantilever_keys),
     "the cantilever and its drive (seed eqs. 1, 2)"},
    {"tip", 0, tip_keys, TT_COUNT(tip_keys), "the tip"},
    {"material", 1, material_keys, TT_COUNT(material_keys),
     "a sample material and its contact with the tip (seed eqs. 3-10)"},
    {"approach", 0, approach_keys, TT_COUNT(approach_keys), "tiptap approach"},
    {"trace", 0, trace_keys, TT_COUNT(trace_keys), "tiptap trace"},
    {"solver", 0, solver_keys, TT_COUNT(solver_keys), "time integration"},
    {"surface", 0, tt_schema_surface, 0, "sample topography and material map (tiptap scan)"},
    {"scan", 0, tt_schema_scan, 0, "raster scan (tiptap scan)"},
    {"lockin", 0, tt_schema_lockin, 0, "lock-in demodulator (tiptap scan)"},
    {"feedback", 0, tt_schema_feedback, 0, "PI amplitude feedback (tiptap scan)"},
};

const tt_scene_section *tt_scene_schema(size_t *count)
{
    /* The imaging tables' sizes live in another translation unit; fill them in once. */
    static tt_scene_section table[TT_COUNT(sections)];
    static int ready = 0;
    if (!ready) {
        for (size_t i = 0; i < TT_COUNT(sections); i++)
            table[i] = sections[i];
        for (size_t i = 0; i < TT_COUNT(sections); i++) {
            if (table[i].keys == tt_schema_surface)
                table[i].nkeys = tt_schema_surface_count;
            else if (table[i].keys == tt_schema_scan)
                table[i].nkeys = tt_schema_scan_count;
            else if (table[i].keys == tt_schema_lockin)
                table[i].nkeys = tt_schema_lockin_count;
            else if (table[i].keys == tt_schema_feedback)
                table[i].nkeys = tt_schema_feedback_count;
        }
        ready = 1;
    }
    *count = TT_COUNT(sections);
    return table;
}
