/* The scene schema: every section and key tiptap reads, with unit, default, range and a
 * one-line description. docs/scene-format.md is written from the same facts; keep both
 * in step (tests/test_scene_doc checks that every key here is documented there). */
#include <math.h>
#include <string.h>

#include "tiptap/config/scene.h"
#include "tiptap/config/units.h"

#define TT_COUNT(a) (sizeof(a) / sizeof((a)[0]))
#define TT_UNBOUNDED INFINITY

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
     "base: the base moves, as in Burnham et al. (eq. 2); force: a force on the tip"},
    {"modes", TT_KEY_INT, 0, NULL, 1, 3, 0, NULL,
     "flexural eigenmodes (default 1, the point mass; 2, 3: Euler-Bernoulli modes added at the tip)"},
    {"mode2_frequency", Q(TT_DIM_FREQUENCY), NULL, 0, INF, POS, NULL,
     "mode 2's resonance (default: 6.267 f_c, a rectangular beam's)"},
    {"mode2_spring_constant", Q(TT_DIM_STIFFNESS), NULL, 0, INF, POS, NULL,
     "mode 2's stiffness at the tip (default: k_c (f_2 / f_c)^2)"},
    {"mode2_quality_factor", Q(TT_DIM_NONE), NULL, 0, INF, POS, NULL,
     "mode 2's quality factor (default: Q_c f_2 / f_c, uniform viscous damping)"},
    {"mode2_free_amplitude", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL,
     "bimodal AM-AM: drive mode 2 too, open loop, to this free amplitude (needs modes >= 2, tier = every)"},
    {"mode2_drive_frequency", Q(TT_DIM_FREQUENCY), NULL, 0, INF, POS, NULL,
     "mode 2's drive frequency (default: mode 2's resonance; needs mode2_free_amplitude)"},
    {"mode3_frequency", Q(TT_DIM_FREQUENCY), NULL, 0, INF, POS, NULL,
     "mode 3's resonance (default: 17.55 f_c, a rectangular beam's)"},
    {"mode3_spring_constant", Q(TT_DIM_STIFFNESS), NULL, 0, INF, POS, NULL,
     "mode 3's stiffness at the tip (default: k_c (f_3 / f_c)^2)"},
    {"mode3_quality_factor", Q(TT_DIM_NONE), NULL, 0, INF, POS, NULL,
     "mode 3's quality factor (default: Q_c f_3 / f_c, uniform viscous damping)"},
};

/* Moduli up to a thousand times diamond's (1.2 TPa): far past any material, and short of
 * where the force law's scales underflow (a reduced modulus of 1e300 Pa gave a depth
 * scale of 1e-200 m and a cycle that never ended). */
#define TT_MODULUS_MAX 1e15

static const tt_scene_key tip_keys[] = {
    {"radius", Q(TT_DIM_LENGTH), "10 nm", 0, INF, POS, NULL, "tip radius R_tip"},
    {"youngs_modulus", Q(TT_DIM_PRESSURE), "169 GPa", 0, TT_MODULUS_MAX, POS, NULL,
     "tip Young's modulus (silicon: 169 GPa)"},
    {"poisson_ratio", Q(TT_DIM_NONE), "0.27", -1, 0.5, 0, NULL, "tip Poisson ratio"},
    {"shape", TT_KEY_ENUM, 0, "point", 0, 0, 0, "point|sphere|cone",
     "tiptap scan: the shape that meets the topography: point: the apex alone; sphere: the apex "
     "sphere of radius R_tip; cone: that sphere on a cone of half_angle (docs/surfaces.md); "
     "contact mechanics keeps R_tip"},
    {"half_angle", Q(TT_DIM_ANGLE), "20 deg", 0, M_PI / 2, TT_KEY_MIN_EXCL | TT_KEY_MAX_EXCL, NULL,
     "cone: half-angle of the cone, tangent to the apex sphere"},
    {"contact_geometry", TT_KEY_ENUM, 0, "axis", 0, 0, 0, "axis|local",
     "tiptap scan: the contact law's geometry: axis: each material's law for a flat; local: the "
     "law rebuilt for the slope and curvature where the tip touches (tier = every; "
     "docs/surfaces.md)"},
};

/* A relaxation arm's two keys (docs/physics.md, the generalised Maxwell sample). */
#define ARM_KEYS(i)                                                                                \
    {"arm" i "_modulus", Q(TT_DIM_PRESSURE), NULL, 0, TT_MODULUS_MAX, 0, NULL,                    \
     "Young's modulus E_" i " of relaxation arm " i " (a Maxwell element beside the relaxed "      \
     "youngs_modulus: the standard linear solid with one arm, generalised Maxwell with more; "    \
     "Hertz law only); absent: no such arm"},                                                      \
    {"arm" i "_relaxation_time", Q(TT_DIM_TIME), NULL, 0, INF, POS, NULL,                          \
     "relaxation time tau_" i " of arm " i ": its dashpot's viscosity over its modulus"}

static const tt_scene_key material_keys[] = {
    {"youngs_modulus", Q(TT_DIM_PRESSURE), "2 GPa", 0, TT_MODULUS_MAX, POS, NULL,
     "sample Young's modulus (ignored when reduced_modulus is given)"},
    {"poisson_ratio", Q(TT_DIM_NONE), "0.35", -1, 0.5, 0, NULL, "sample Poisson ratio"},
    {"reduced_modulus", Q(TT_DIM_PRESSURE), NULL, 0, TT_MODULUS_MAX, POS, NULL,
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
    {"viscosity", Q(TT_DIM_VISCOSITY), NULL, 0, INF, 0, NULL,
     "Kelvin-Voigt sample viscosity eta: the force eta a d(delta)/dt in contact, a the "
     "contact radius (docs/physics.md); absent or 0: elastic"},
    {"film_thickness", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL,
     "thickness h of a film bonded to a rigid substrate (Garcia & Garcia's bottom effect on "
     "the Hertz load and the viscous force; Hertz law only); absent: bulk"},
    {"map_value", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "grey level (0-255 or 0-65535) or colour (#rrggbb) of this material in a PNG material map"},
    ARM_KEYS("1"), ARM_KEYS("2"), ARM_KEYS("3"), ARM_KEYS("4"),
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
     "steady mode: a point is settled when amplitude (relative) and phase (rad) change less than this per cycle, "
     "or per period of an orbit of up to 64 cycles"},
    {"steady", TT_KEY_ENUM, 0, "shooting", 0, 0, 0, "shooting|settle",
     "steady mode: shooting: Newton on the one-period map finds the periodic orbit (falls back to "
     "settling; a sample with relaxation arms, or mode 2 driven, settles); settle: run cycles until the point settles"},
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

/* [force]: tiptap force, a force-distance curve of the undriven lever. */
static const tt_scene_key force_keys[] = {
    {"from", Q(TT_DIM_LENGTH), "20 nm", -INF, INF, 0, NULL,
     "rest separation where the ramp starts and ends (gap of the undeflected tip)"},
    {"to", Q(TT_DIM_LENGTH), "-2 nm", -INF, INF, 0, NULL,
     "rest separation where the ramp turns (negative: the base pushes past the surface)"},
    {"range", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL, "instead of from: from = to + range"},
    {"speed", Q(TT_DIM_VELOCITY), "1 um/s", 0, INF, POS, NULL, "ramp speed, both ways"},
    {"dwell", Q(TT_DIM_TIME), "0 s", 0, INF, 0, NULL, "pause at the turn"},
    {"samples", TT_KEY_INT, 0, "1000", 10, 1e7, 0, NULL, "output rows per leg (approach, dwell, retract)"},
    {"material", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "material under the tip (default: the first [material])"},
};

/* [tune]: tiptap tune, the free lever's thermal spectrum. */
static const tt_scene_key tune_keys[] = {
    {"duration", Q(TT_DIM_TIME), "0.2 s", 0, 1e4, POS, NULL, "length of the deflection record"},
    {"samples_per_cycle", TT_KEY_INT, 0, "8", 4, 1024, 0, NULL,
     "deflection samples per drive period (sample rate = this times the drive frequency)"},
    {"bin_width", Q(TT_DIM_FREQUENCY), "0 Hz", 0, INF, 0, NULL,
     "the spectrum's resolution at most (segments of a power of two samples; 0: the scene's f0 / 16 Q)"},
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
    {"tier", TT_KEY_ENUM, 0, "envelope", 0, 0, 0, "every|envelope|averaged",
     "scans: every: integrate every drive cycle; envelope: integrate some cycles and follow "
     "the others on the cycle map's local linear model, under error control; averaged: a "
     "preview from the averaged slow flow of amplitude and phase, integrating only where it "
     "fails (impacts, a ringing loop), errors stated against every cycle (docs/dynamics.md)"},
};

/* [surface], [lockin], [feedback]: imaging (tiptap scan). */
static const tt_scene_key surface_keys[] = {
    {"type", TT_KEY_ENUM, 0, "flat", 0, 0, 0, "flat|steps|grating|particles|rough|png|measured|lattice",
     "topography (docs/surfaces.md)"},
    {"step_height", Q(TT_DIM_LENGTH), "1 nm", -INF, INF, 0, NULL, "steps: height of each step (up along x)"},
    {"step_width", Q(TT_DIM_LENGTH), "250 nm", 0, INF, POS, NULL, "steps: terrace width"},
    {"period", Q(TT_DIM_LENGTH), "500 nm", 0, INF, POS, NULL,
     "grating: period along x; lattice: distance between neighbouring features"},
    {"duty", Q(TT_DIM_FRACTION | TT_DIM_NONE), "50 %", 0, 1, TT_KEY_MIN_EXCL | TT_KEY_MAX_EXCL, NULL,
     "grating: raised fraction of a period"},
    {"height", Q(TT_DIM_LENGTH), "20 nm", -INF, INF, 0, NULL,
     "grating: line height; lattice: pillar and spike height, hole depth (above 0)"},
    {"edge_width", Q(TT_DIM_LENGTH), "0 nm", 0, INF, 0, NULL,
     "grating, lattice pillar and hole: horizontal width of each sidewall (0: vertical)"},
    {"line_width", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL,
     "grating: the line's width at its top (the critical dimension), instead of duty"},
    {"offset_x", Q(TT_DIM_LENGTH), "0 nm", -INF, INF, 0, NULL,
     "steps, grating, lattice: the pattern shifted along x"},
    {"offset_y", Q(TT_DIM_LENGTH), "0 nm", -INF, INF, 0, NULL, "lattice: the pattern shifted along y"},
    {"lattice", TT_KEY_ENUM, 0, "square", 0, 0, 0, "square|hexagonal",
     "lattice: square, or hexagonal (rows period sqrt(3)/2 apart, every other shifted by half a period)"},
    {"feature", TT_KEY_ENUM, 0, "pillar", 0, 0, 0, "pillar|hole|spike",
     "lattice: pillars (cylinders of feature_radius), holes (the same cut into a plane at height) "
     "or spikes (sphere-capped cones, a tip-check grating)"},
    {"feature_radius", Q(TT_DIM_LENGTH), "100 nm", 0, INF, POS, NULL,
     "lattice pillar, hole: radius at the top (a hole's rim)"},
    {"spike_radius", Q(TT_DIM_LENGTH), "10 nm", 0, INF, POS, NULL, "lattice spike: apex radius"},
    {"spike_half_angle", Q(TT_DIM_ANGLE), "25 deg", 0, M_PI / 2, TT_KEY_MIN_EXCL | TT_KEY_MAX_EXCL, NULL,
     "lattice spike: the cone's half-angle"},
    {"particle_radius", Q(TT_DIM_LENGTH), "20 nm", 0, INF, POS, NULL,
     "particles: sphere radius (a sphere on the flat rises 2 r)"},
    {"particle_count", TT_KEY_INT, 0, "12", 0, 100000, 0, NULL, "particles: number, placed without overlap"},
    {"rms", Q(TT_DIM_LENGTH), "1 nm", 0, INF, 0, NULL, "rough: RMS height"},
    {"correlation_length", Q(TT_DIM_LENGTH), "50 nm", 0, INF, POS, NULL,
     "rough: Gaussian correlation length (ACF exp(-r^2/L^2))"},
    {"seed", TT_KEY_INT, 0, "1", 0, 2147483647, 0, NULL, "particles, rough: random seed"},
    {"png", TT_KEY_STRING, 0, NULL, 0, 0, TT_KEY_PATH, NULL,
     "png: grey height map (8 or 16 bit) spanning the scan area, top row at y = 0"},
    {"png_height_range", Q(TT_DIM_LENGTH), "10 nm", -INF, INF, 0, NULL,
     "png: height of white above black; measured .png: height of level 65535 (required)"},
    {"image", TT_KEY_STRING, 0, NULL, 0, 0, TT_KEY_PATH, NULL,
     "measured: height image, .gsf, .gwy or 16-bit grey .png, top row at y = 0"},
    {"channel", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "measured .gwy: the channel's title or number (default: the first)"},
    {"pixel_size", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL,
     "measured .png, png: the image's pixel (square; png default: the scan area over its pixels, "
     "refused when that is not square); .gsf and .gwy carry their own"},
    {"level", TT_KEY_ENUM, 0, "none", 0, 0, 0, "none|offset|plane",
     "measured: offset: the mean taken off; plane: the least-squares plane taken off"},
    {"line_level", TT_KEY_ENUM, 0, "none", 0, 0, 0, "none|offset|slope|median|median_difference",
     "measured: each row levelled after level: its mean, line or median taken off, or "
     "median_difference: the median step from the row above taken off"},
    {"crop", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "measured: left top width height, in the image's pixels (default: the whole image)"},
    {"interpolation", TT_KEY_ENUM, 0, "bilinear", 0, 0, 0, "bilinear|bicubic",
     "measured: between pixel centres (GSL gsl_interp2d); bilinear stays within the pixels' "
     "heights, bicubic has continuous slopes but overshoots at steps"},
    {"edges", TT_KEY_ENUM, 0, "refuse", 0, 0, 0, "refuse|clamp|periodic",
     "measured, and labels and threshold maps: refuse an image smaller than the scan area, "
     "or continue its edge pixels (clamp) or repeat it (periodic)"},
    {"z_scale", Q(TT_DIM_NONE), "1", -1e6, 1e6, 0, NULL, "measured: factor on the levelled heights"},
    {"z_offset", Q(TT_DIM_LENGTH), "0 nm", -1e-3, 1e-3, 0, NULL, "measured: added after z_scale"},
    {"measured_tip_shape", TT_KEY_ENUM, 0, "none", 0, 0, 0, "none|sphere|cone",
     "measured: the tip that took the image, eroded out of it after levelling and z_scale "
     "(Villarrubia's reconstruction, docs/surfaces.md): none keeps the image as it is"},
    {"measured_tip_radius", Q(TT_DIM_LENGTH), "10 nm", 0, INF, POS, NULL,
     "measured_tip_shape sphere or cone: that tip's apex radius"},
    {"measured_tip_half_angle", Q(TT_DIM_ANGLE), "20 deg", 0, M_PI / 2, TT_KEY_MIN_EXCL | TT_KEY_MAX_EXCL,
     NULL, "measured_tip_shape cone: that tip's cone half-angle"},
    {"map", TT_KEY_ENUM, 0, "uniform", 0, 0, 0, "uniform|stripes|disks|checkerboard|islands|png|labels|threshold",
     "material map (labels, threshold: from map_image, docs/surfaces.md)"},
    {"map_materials", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "materials of the map, background first: \"matrix, disk\" (default: the scene's first two); "
     "threshold: below, then at or above"},
    {"map_period", Q(TT_DIM_LENGTH), "250 nm", 0, INF, POS, NULL,
     "stripes, disks, checkerboard: period of the pattern"},
    {"map_duty", Q(TT_DIM_FRACTION | TT_DIM_NONE), "50 %", 0, 1, TT_KEY_MIN_EXCL | TT_KEY_MAX_EXCL, NULL,
     "stripes: fraction of a period of the second material"},
    {"map_radius", Q(TT_DIM_LENGTH), "60 nm", 0, INF, POS, NULL, "disks: disk radius"},
    {"map_png", TT_KEY_STRING, 0, NULL, 0, 0, TT_KEY_PATH, NULL,
     "png map: each pixel's grey level or colour names a material through its map_value"},
    {"map_tolerance", Q(TT_DIM_NONE), "0", 0, 442, 0, NULL,
     "png map: a pixel whose colour no map_value names takes the nearest material's within "
     "this distance in 8-bit levels (Euclidean in RGB; ties: the first material); 0: exact"},
    {"map_image", TT_KEY_STRING, 0, NULL, 0, 0, TT_KEY_PATH, NULL,
     "labels, threshold: .gsf, .gwy or grey .png image, taken pixel by pixel (nearest), top row "
     "at y = 0; labels: each whole number is the material whose map_value it is"},
    {"map_channel", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "labels, threshold, .gwy map_image: the channel's title or number (default: the first)"},
    {"map_pixel_size", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL,
     "labels, threshold, .png map_image, png map: its pixel (square; default: the scan area "
     "over its pixels, refused when that is not square)"},
    {"map_threshold", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL,
     "threshold: value and the image's unit (e.g. 60 deg); map_materials' first below it, "
     "second at or above"},
};

static const tt_scene_key lockin_keys[] = {
    {"time_constant", Q(TT_DIM_TIME), "100 us", 0, INF, 0, NULL,
     "low-pass time constant of each filter section (0: none); a 1 Hz, 128-pixel line has 3.9 ms per pixel"},
    {"filter_order", TT_KEY_INT, 0, "2", 1, 8, 0, NULL, "low-pass sections in cascade (6 dB/octave each)"},
    {"samples_per_period", TT_KEY_INT, 0, "32", 8, 1024, 0, NULL, "deflection samples per drive period"},
    {"harmonics", TT_KEY_INT, 0, "1", 1, 16, 0, NULL, "highest harmonic the lock-in offers to [scan] channels (1: the fundamental only)"},
    {"periods_per_block", TT_KEY_INT, 0, "4", 1, 1000, 0, NULL,
     "drive periods per transform, which is also the feedback's update interval"},
};

static const tt_scene_key feedback_keys[] = {
    {"setpoint", Q(TT_DIM_LENGTH | TT_DIM_FRACTION), "80 %", 0, INF, POS, NULL,
     "amplitude setpoint: a length, or a percentage of the free amplitude"},
    {"proportional_gain", Q(TT_DIM_NONE), "0", 0, 1e6, 0, NULL,
     "z moved per amplitude error, m/m (0: integral control only)"},
    {"integral_gain", Q(TT_DIM_FREQUENCY), "1000 Hz", 0, INF, 0, NULL,
     "z speed per amplitude error, (m/s)/m; keep ki below the amplitude bandwidth pi f0 / Q (2.4 kHz at 300 kHz, Q 400)"},
    {"z_range", Q(TT_DIM_LENGTH), "2 um", 0, INF, POS, NULL,
     "travel of the z piezo, centred on the surface's zero; the height clamps at its ends"},
};

/* [scan]: the raster and what a scan records. */
static const tt_scene_key scan_keys[] = {
    {"size", Q(TT_DIM_LENGTH), "1 um", 0, INF, POS, NULL, "scan size along x (and y unless size_y)"},
    {"size_y", Q(TT_DIM_LENGTH), NULL, 0, INF, POS, NULL, "scan size along y (default: size)"},
    {"pixels", TT_KEY_INT, 0, "128", 2, 16384, 0, NULL, "pixels per line (fast axis)"},
    {"lines", TT_KEY_INT, 0, "128", 1, 16384, 0, NULL, "lines (slow axis)"},
    {"line_rate", Q(TT_DIM_FREQUENCY), "1 Hz", 0, INF, POS, NULL,
     "lines per second; each line is a trace and a retrace, half the period each"},
    {"fast_axis", TT_KEY_ENUM, 0, "x", 0, 0, 0, "x|y", "direction of the fast scan (before angle)"},
    {"angle", Q(TT_DIM_ANGLE), "0 deg", -2 * M_PI, 2 * M_PI, 0, NULL,
     "scan angle: the scan frame rotated counter-clockwise on the sample about the area's centre"},
    {"offset_x", Q(TT_DIM_LENGTH), "0 nm", -1e-3, 1e-3, 0, NULL,
     "the scan area moved on the sample along x (after angle)"},
    {"offset_y", Q(TT_DIM_LENGTH), "0 nm", -1e-3, 1e-3, 0, NULL, "the scan area moved along y"},
    {"retrace", TT_KEY_BOOL, 0, "yes", 0, 0, 0, NULL, "record the retrace images too"},
    {"channels", TT_KEY_STRING, 0, "height, error, amplitude, phase, peak_force, indentation, dissipation", 0,
     0, 0, NULL,
     "what to record: height, error (amplitude - setpoint), amplitude (the lock-in's), phase, "
     "peak_force, indentation, dissipation, topography, "
     "harmonic2 to harmonic8 (need [lockin] harmonics >= h), harmonic2_phase to harmonic8_phase, artefact (height - topography; added by default on a measured surface), "
     "dissipation_hysteresis, dissipation_damping, dissipation_viscous (the loss per mechanism; added by default where a material is viscous), dilation (the surface as the tip's shape images it), certainty (1 where a measured image's erosion is the sample; added by default with measured_tip_shape)"},
    {"profile_line", TT_KEY_INT, 0, "-1", -1, 16383, 0, NULL,
     "line written to profile.csv (-1: the middle line)"},
    {"settle_cycles", TT_KEY_INT, 0, "3000", 0, 1e9, 0, NULL,
     "drive cycles the feedback settles at each line's first pixel before the trace"},
    {"lines_mode", TT_KEY_ENUM, 0, "independent", 0, 0, 0, "independent|continuous",
     "independent: each line settles at its first pixel (lines in parallel); continuous: as an "
     "instrument, each line starts where the last retrace ended (one thread)"},
};

/* [noise]: seeded noise of a scan (docs/dynamics.md). */
static const tt_scene_key noise_keys[] = {
    {"seed", TT_KEY_INT, 0, "1", 0, 2147483647, 0, NULL,
     "seed of every noise; the same seed gives the same images on any number of threads"},
    {"temperature", Q(TT_DIM_TEMPERATURE), "0 K", 0, INF, 0, NULL,
     "temperature of the cantilever's thermal (Langevin) force, PSD 2 c kB T (0: none)"},
    {"points", TT_KEY_INT, 0, "64", 4, 65536, 0, NULL,
     "thermal force points per drive cycle (linear between; rk4's steps_per_cycle must be a multiple)"},
    {"detector", Q(TT_DIM_NOISE_DENSITY), "0 m/sqrt(Hz)", 0, INF, 0, NULL,
     "deflection detector noise density (one-sided), added to the samples the lock-in reads"},
    {"z_piezo", Q(TT_DIM_NOISE_DENSITY), "0 m/sqrt(Hz)", 0, INF, 0, NULL,
     "z piezo position noise density (one-sided) below the z piezo's bandwidth"},
    {"z_piezo_bandwidth", Q(TT_DIM_FREQUENCY), "2 kHz", 0, INF, POS, NULL,
     "bandwidth of the z piezo's noise, the corner of a first-order low-pass (the stage and its "
     "high-voltage amplifier); at most half the drive frequency"},
};

/* [instrument]: the imperfections of a real instrument (tiptap scan), each off by default. */
static const tt_scene_key instrument_keys[] = {
    {"tilt_x", Q(TT_DIM_NONE | TT_DIM_FRACTION), "0", -10, 10, 0, NULL,
     "sample tilt: slope dz/dx of the sample plane (1 % = 10 nm per um)"},
    {"tilt_y", Q(TT_DIM_NONE | TT_DIM_FRACTION), "0", -10, 10, 0, NULL, "sample tilt: slope dz/dy"},
    {"drift_x", Q(TT_DIM_VELOCITY), "0 m/s", -INF, INF, 0, NULL,
     "thermal drift of the sample along x (the image of a feature moves by +drift_x t)"},
    {"drift_y", Q(TT_DIM_VELOCITY), "0 m/s", -INF, INF, 0, NULL, "thermal drift of the sample along y"},
    {"drift_z", Q(TT_DIM_VELOCITY), "0 m/s", -INF, INF, 0, NULL,
     "thermal drift of the sample towards the tip (the height image rises by drift_z t)"},
    {"piezo_resonance", Q(TT_DIM_FREQUENCY), "0 Hz", 0, INF, 0, NULL,
     "z piezo: resonance of its second-order response to the feedback's command (0: ideal)"},
    {"piezo_damping", Q(TT_DIM_NONE), "0.3", 0, 100, POS, NULL, "z piezo: damping ratio zeta"},
    {"creep", Q(TT_DIM_NONE | TT_DIM_FRACTION), "0", 0, 1, 0, NULL,
     "z piezo creep gamma: after a move dz it creeps gamma dz log10(1 + t / creep_time) (0: none)"},
    {"creep_time", Q(TT_DIM_TIME), "10 ms", 0, INF, POS, NULL,
     "z piezo creep: time t0 after a move from which the creep grows as log10(t)"},
};

static const tt_scene_section sections[] = {
    {"cantilever", 0, cantilever_keys, TT_COUNT(cantilever_keys),
     "the cantilever and its drive (Burnham et al. eqs. 1, 2)"},
    {"tip", 0, tip_keys, TT_COUNT(tip_keys), "the tip"},
    {"material", 1, material_keys, TT_COUNT(material_keys),
     "a sample material and its contact with the tip (Burnham et al. eqs. 3-10)"},
    {"approach", 0, approach_keys, TT_COUNT(approach_keys), "tiptap approach"},
    {"trace", 0, trace_keys, TT_COUNT(trace_keys), "tiptap trace"},
    {"force", 0, force_keys, TT_COUNT(force_keys), "tiptap force"},
    {"tune", 0, tune_keys, TT_COUNT(tune_keys), "tiptap tune"},
    {"solver", 0, solver_keys, TT_COUNT(solver_keys), "time integration"},
    {"surface", 0, surface_keys, TT_COUNT(surface_keys), "sample topography and material map (tiptap scan)"},
    {"scan", 0, scan_keys, TT_COUNT(scan_keys), "raster scan (tiptap scan)"},
    {"lockin", 0, lockin_keys, TT_COUNT(lockin_keys), "lock-in demodulator (tiptap scan)"},
    {"feedback", 0, feedback_keys, TT_COUNT(feedback_keys), "PI amplitude feedback (tiptap scan)"},
    {"instrument", 0, instrument_keys, TT_COUNT(instrument_keys),
     "the instrument's imperfections: tilt, drift, z piezo dynamics and creep (tiptap scan)"},
    {"noise", 0, noise_keys, TT_COUNT(noise_keys), "thermal, detector and z piezo noise (tiptap scan)"},
};

/* Static and constant: nothing to initialise, safe from any thread. */
const tt_scene_section *tt_scene_schema(size_t *count)
{
    *count = TT_COUNT(sections);
    return sections;
}

/* Keys without a unit: what their values look like, each with an example of its own (a
 * default of 0 or in percent shows no number, and lambda has none). Keys of one name
 * (poisson_ratio of the tip and of a material) share one. */
static const struct {
    const char *key, *text;
} unitless[] = {
    {"quality_factor", "a number, no unit, such as '400'"},
    {"poisson_ratio", "a number, no unit, such as '0.3'"},
    {"lambda", "a number, no unit, such as '1'"},
    {"interaction_quality_factor", "a number, no unit, such as '10'"},
    {"settle_tolerance", "a number, no unit, such as '1e-7'"},
    {"tolerance", "a number, no unit, such as '1e-8'"},
    {"duty", "a fraction such as '0.5' or a percentage such as '50 %'"},
    {"map_duty", "a fraction such as '0.5' or a percentage such as '50 %'"},
    {"proportional_gain", "a number, no unit (m/m), such as '0.1'"},
    {"tilt_x", "a slope, no unit, such as '0.01', or a percentage such as '1 %'"},
    {"tilt_y", "a slope, no unit, such as '0.01', or a percentage such as '1 %'"},
    {"piezo_damping", "a number, no unit, such as '0.7'"},
    {"creep", "a fraction such as '0.02' or a percentage such as '2 %'"},
    {"z_scale", "a number, no unit, such as '1.5'"},
    {"map_tolerance", "a number of 8-bit levels, no unit, such as '40'"},
    {"mode2_quality_factor", "a number, no unit, such as '2500'"},
    {"mode3_quality_factor", "a number, no unit, such as '7000'"},
};

const char *tt_scene_key_describe(const tt_scene_key *k)
{
    switch (k->kind) {
    case TT_KEY_ENUM:
        return k->choices;
    case TT_KEY_INT:
        return "integer";
    case TT_KEY_BOOL:
        return "yes|no";
    case TT_KEY_STRING:
        return "text";
    default:
        break;
    }
    for (size_t i = 0; (k->dims & TT_DIM_NONE) && i < TT_COUNT(unitless); i++)
        if (strcmp(unitless[i].key, k->key) == 0)
            return unitless[i].text;
    return tt_units_describe(k->dims);
}
