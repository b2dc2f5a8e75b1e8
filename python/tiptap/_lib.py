"""The shared library libtiptap through cffi's ABI mode (no compiler needed).

The declarations below are copied from the public headers (include/tiptap/); the tests
check them against the headers (python/tests/test_binding.py): every prototype as the
compiler reads it, and every struct's size and field offsets. cffi releases the GIL
for the length of each call, so other Python threads run while the library works.

Where the library is: $TIPTAP_LIBRARY when set (the tests use the build tree's), else
the path `cmake --install` wrote into _install.py beside this file, else the dynamic
loader's search (ldconfig: libtiptap.so.MAJOR).
"""

import ctypes.util
import os

import cffi

CDEF = r"""
/* util/error.h, util/cancel.h, util/str.h, version.h */
enum { TT_OK = 0, TT_EINVAL = 1, TT_ENOMEM = 2, TT_EIO = 3, TT_ENUM = 4, TT_EINTR = 5,
       TT_ECAPTURE = 6 };
const char *tt_strerror(int status);
const char *tt_error_message(void);
void tt_error_clear(void);
void tt_cancel_request(void);
int tt_cancel_requested(void);
void tt_cancel_reset(void);
void tt_free(void *p);
const char *tt_version(void);
int tt_version_number(void);

/* util/warning.h */
typedef void (*tt_warning_fn)(const char *category, const char *message, void *data);
typedef struct {
    tt_warning_fn fn;
    void *data;
} tt_warning_sink;
tt_warning_sink tt_warning_push(tt_warning_fn fn, void *data);
void tt_warning_pop(tt_warning_sink previous);

/* config/units.h */
typedef enum {
    TT_DIM_NONE = 1, TT_DIM_LENGTH = 2, TT_DIM_FREQUENCY = 4, TT_DIM_STIFFNESS = 8,
    TT_DIM_SURFACE_ENERGY = 16, TT_DIM_PRESSURE = 32, TT_DIM_FORCE = 64, TT_DIM_TIME = 128,
    TT_DIM_ENERGY = 256, TT_DIM_VELOCITY = 512, TT_DIM_ANGLE = 1024, TT_DIM_FRACTION = 2048,
    TT_DIM_TEMPERATURE = 4096, TT_DIM_NOISE_DENSITY = 8192, TT_DIM_VISCOSITY = 16384
} tt_dim;
const char *tt_units_describe(unsigned dims);
const char *tt_units_symbol(tt_dim dim);

/* config/scene.h */
typedef enum { TT_KEY_QUANTITY, TT_KEY_INT, TT_KEY_ENUM, TT_KEY_STRING, TT_KEY_BOOL } tt_key_kind;
typedef struct {
    const char *key;
    tt_key_kind kind;
    unsigned dims;
    const char *def;
    double min, max;
    unsigned flags;
    const char *choices;
    const char *doc;
} tt_scene_key;
typedef struct {
    const char *name;
    int named;
    const tt_scene_key *keys;
    size_t nkeys;
    const char *doc;
} tt_scene_section;
const tt_scene_section *tt_scene_schema(size_t *count);
typedef struct tt_scene tt_scene;
tt_scene *tt_scene_alloc(void);
void tt_scene_free(tt_scene *s);
tt_scene *tt_scene_copy(const tt_scene *s);
int tt_scene_load(tt_scene *s, const char *path);
int tt_scene_load_string(tt_scene *s, const char *text, const char *origin);
int tt_scene_set(tt_scene *s, const char *assignment);
const char *tt_scene_origin(const tt_scene *s);
char *tt_scene_write_string(const tt_scene *s, const char *sections);

/* config/meta.h */
typedef struct {
    char **keys, **values;
    size_t n, cap;
} tt_meta;
int tt_meta_scene(tt_meta *m, const tt_scene *scene, const char *const *first_keys,
                  const char *const *first_values, size_t nfirst);
int tt_meta_add(tt_meta *m, const char *key, const char *value);
void tt_meta_free(tt_meta *m);

/* instrument/scan.h, config/config.h */
typedef struct tt_scan tt_scan;
const char *tt_scan_channel_name(int i);
const char *tt_scan_channel_unit(int i);
int tt_scan_channel_harmonic(int i);
int tt_scan_channel_count(void);
int tt_config_scan_alloc(tt_scan **out, const tt_scene *s);
int tt_config_check_rk4(const tt_scene *s, const char *section, double s_min);
void tt_config_note_inputs(const tt_scene *s);
void tt_scan_free(tt_scan *s);
int tt_scan_run(tt_scan *s, int threads, void (*progress)(void *user, long done, long total),
                void *user);
long tt_scan_xres(const tt_scan *s);
long tt_scan_yres(const tt_scan *s);
int tt_scan_fast_y(const tt_scan *s);
long tt_scan_lines(const tt_scan *s);
double tt_scan_size_x(const tt_scan *s);
double tt_scan_size_y(const tt_scan *s);
unsigned tt_scan_channels(const tt_scan *s);
int tt_scan_has_retrace(const tt_scan *s);
long tt_scan_lines_done(const tt_scan *s);
const double *tt_scan_image(const tt_scan *s, int channel_index, int retrace);
long tt_scan_profile_line(const tt_scan *s);
double tt_scan_instrument_time(const tt_scan *s);
long tt_scan_cycles(const tt_scan *s);
long tt_scan_cycles_integrated(const tt_scan *s);
double tt_scan_error_estimate(const tt_scan *s);
int tt_scan_clamped(const tt_scan *s);
size_t tt_scan_materials(const tt_scan *s);
const char *tt_scan_material_name(const tt_scan *s, size_t i);
typedef struct {
    double height_max, height_rms;
    double amplitude_max, amplitude_rms;
    double phase_max, phase_rms;
    long line;
    double tolerance;
    long pixels, pixels_line;
    long first;
    double step;
    double signal;
    long cycles;
    long work;
    long scan_work, budget;
    long lines;
    double seconds;
    long stretches;
    int over;
} tt_scan_error;
int tt_scan_estimate_error(tt_scan *s, tt_scan_error *e);

/* instrument/scan_scope.h */
typedef struct tt_scan_scope tt_scan_scope;
int tt_scan_scope_alloc(tt_scan_scope **out);
void tt_scan_scope_free(tt_scan_scope *sc);
void tt_scan_scope_attach(tt_scan *s, long line, tt_scan_scope *sc);

/* util/table.h */
typedef struct tt_table tt_table;
void tt_table_free(tt_table *t);
size_t tt_table_columns(const tt_table *t);
size_t tt_table_rows(const tt_table *t);
const char *tt_table_name(const tt_table *t, size_t col);
const char *tt_table_unit(const tt_table *t, size_t col);
int tt_table_is_text(const tt_table *t, size_t col);
const double *tt_table_numbers(const tt_table *t, size_t col);
const char *tt_table_text(const tt_table *t, size_t col, size_t row);
size_t tt_table_metas(const tt_table *t);
const char *tt_table_meta_key(const tt_table *t, size_t i);
const char *tt_table_meta_value(const tt_table *t, size_t i);

/* physics/contact.h */
typedef enum { TT_CONTACT_MAUGIS = 0, TT_CONTACT_HERTZ, TT_CONTACT_DMT, TT_CONTACT_JKR } tt_contact_model;
typedef struct {
    tt_contact_model model;
    double K;
    double R;
    double w;
    double xi0;
    double lambda;
    double viscosity;
    double film_thickness;
    int arms;
    double arm_modulus[4];
    double arm_time[4];
} tt_contact_params;
typedef struct tt_contact tt_contact;
int tt_contact_model_parse(const char *name, tt_contact_model *out);
int tt_contact_alloc_normalised(tt_contact **out, tt_contact_model model, double lambda,
                                double xi0n);
void tt_contact_free(tt_contact *c);

/* solver/integrator.h, instrument/accuracy.h */
typedef enum { TT_METHOD_DOPRI5 = 0, TT_METHOD_RK4 = 1, TT_METHOD_RADAU = 2 } tt_method;
typedef enum { TT_TIER_EVERY = 0, TT_TIER_ENVELOPE = 1, TT_TIER_AVERAGED = 2, TT_TIER_COUNT = 3 } tt_tier;
const char *tt_tier_name(tt_tier t);
int tt_tier_count(void);
typedef struct {
    tt_method method;
    const char *knob;
    const double *values;
    size_t nvalues;
    tt_tier tier;
    const char *name;
} tt_accuracy_ladder;
typedef enum { TT_ACCURACY_AUTO = 0, TT_ACCURACY_POINT = 1, TT_ACCURACY_LINE = 2 } tt_accuracy_kind;
typedef struct {
    tt_accuracy_kind kind;
    double point;
    long cycles;
    long line_pixels;
    int repeats;
    double repeat_below;
    int cpu_clock;
    double ref_tolerance;
    double check_tolerance;
    const tt_accuracy_ladder *ladders;
    size_t nladders;
} tt_accuracy_params;
void tt_accuracy_params_default(tt_accuracy_params *p);
int tt_accuracy_pick(const char *list, tt_accuracy_ladder *out, size_t max, size_t *n);

/* run/run.h */
typedef void (*tt_progress_fn)(void *user, long done, long total);
int tt_run_approach(const tt_scene *s, tt_table **out, tt_progress_fn progress, void *user);
int tt_run_trace(const tt_scene *s, tt_table **out, tt_progress_fn progress, void *user);
int tt_run_contact_alloc(const tt_scene *s, const char *material, const char *model,
                         tt_contact **out, tt_contact_params *params, double *Qi);
int tt_run_contact_table(const tt_contact *c, const tt_contact_params *params, double Qi,
                         size_t n, double Amax, tt_table **out);
int tt_run_accuracy(const tt_scene *s, const tt_accuracy_params *p, tt_table **out,
                    tt_progress_fn progress, void *user);

/* run/force.h, run/tune.h */
typedef struct {
    double speed;
    long cycles;
    double jumpin_z;
    double jumpin_force;
    double jumpin_gap;
    double contact_z;
    double pulloff_z;
    double pulloff_force;
    double adhesion;
    double max_force;
    double slope;
    double slope_deflection;
    double slope_retract;
    double k;
    double indentation;
} tt_force_summary;
int tt_run_force(const tt_scene *s, tt_table **out, tt_force_summary *sum, tt_progress_fn progress,
                 void *user);
typedef struct {
    double f0, f0_err;
    double Q, Q_err;
    double k, k_err;
    double chi;
    double noise_factor;
    double chi2_dof;
    double fit_low, fit_high;
} tt_tune_mode;
typedef struct {
    double temperature;
    double fs, bin_width;
    long segments;
    double averages;
    double f0, f0_err;
    double Q, Q_err;
    double k, k_err;
    double chi;
    double white, white_err;
    double chi2_dof;
    double fit_low, fit_high;
    double variance;
    double variance_err;
    double noise_factor;
    long cycles;
    int modes;
    tt_tune_mode mode[3];
} tt_tune_result;
int tt_run_tune(const tt_scene *s, tt_table **out, tt_tune_result *r, tt_progress_fn progress, void *user);

/* run/force_volume.h */
typedef enum {
    TT_FV_HEIGHT, TT_FV_ADHESION, TT_FV_STIFFNESS, TT_FV_PULLOFF_DISTANCE, TT_FV_PULLOFF_FORCE,
    TT_FV_INDENTATION, TT_FV_MAX_FORCE, TT_FV_MATERIAL, TT_FV_COUNT
} tt_force_volume_channel;
typedef struct tt_force_volume tt_force_volume;
const char *tt_force_volume_channel_name(int ch);
const char *tt_force_volume_channel_unit(int ch);
typedef struct {
    int threads;
    const char *folder;
    int hdf5;
    tt_progress_fn progress;
    void *user;
} tt_force_volume_job;
int tt_run_force_volume(const tt_scene *s, const tt_force_volume_job *job, tt_force_volume **out,
                        int *written);
void tt_force_volume_free(tt_force_volume *v);
long tt_force_volume_xres(const tt_force_volume *v);
long tt_force_volume_yres(const tt_force_volume *v);
double tt_force_volume_size_x(const tt_force_volume *v);
double tt_force_volume_size_y(const tt_force_volume *v);
long tt_force_volume_lines(const tt_force_volume *v);
long tt_force_volume_lines_done(const tt_force_volume *v);
long tt_force_volume_cycles(const tt_force_volume *v);
const double *tt_force_volume_map(const tt_force_volume *v, int ch);
typedef struct {
    long pixels, lines;
    int threads;
    int upper_bound;
    int envelope;
    int averaged;
    double cycles;
    double seconds;
    double seconds_low;
    double integrated_low, integrated_high;
    double bytes;
    double available;
    double f0, fd;
} tt_run_scan_cost;
int tt_run_scan_alloc(const tt_scene *s, int threads, tt_scan **out, tt_run_scan_cost *cost);
int tt_run_scan_warn_inputs(const tt_scene *s, const tt_run_scan_cost *cost);
int tt_run_scan_warn_result(const tt_scan *scan);
int tt_run_scan_warn_oscillation(const tt_scan *scan, const tt_scan_scope *scope,
                                 const char *files);
int tt_run_scan_warn_error(const tt_scan *scan, const tt_run_scan_cost *cost,
                           const tt_scan_error *e);
typedef struct {
    int threads;
    tt_progress_fn progress;
    void *user;
    tt_scan_scope *scope;
    const char *scope_files;
    const char *folder;
    int hdf5;
    const char *hdf5_file;
    int estimate;
    int (*made)(void *user, const tt_scan *scan, const tt_run_scan_cost *cost);
    int (*ready)(void *user, tt_scan *scan);
    int (*finished)(void *user, tt_scan *scan, int status);
    void (*summary)(void *user, const tt_scan *scan, const void *r);
    int (*files)(void *user, const tt_scan *scan, int j, int *written);
} tt_run_scan_job;
typedef struct {
    tt_scan *scan;
    tt_run_scan_cost cost;
    int written;
    int oscillating;
    double scan_seconds;
    double seconds;
    int estimate_status;
    tt_scan_error est;
    double cpu_seconds;
} tt_run_scan_result;
int tt_run_scan(const tt_scene *s, const tt_run_scan_job *job, tt_run_scan_result *r);
int tt_run_scan_write_outputs(const tt_scan *scan, const tt_scene *scene, const char *dir,
                              int hdf5, int threads, int *written);

/* config/sweep.h, run/sweep.h */
typedef struct tt_sweep tt_sweep;
int tt_sweep_check_size(const char *const *specs, size_t n);
int tt_sweep_alloc(tt_sweep **out, const tt_scene *base);
void tt_sweep_free(tt_sweep *sw);
int tt_sweep_vary(tt_sweep *sw, const char *spec);
size_t tt_sweep_count(const tt_sweep *sw);
typedef enum { TT_SWEEP_STEADY, TT_SWEEP_SETPOINT, TT_SWEEP_APPROACH, TT_SWEEP_SCAN } tt_sweep_kind;
int tt_sweep_kind_parse(const char *name, tt_sweep_kind *kind);
int tt_run_sweep(const tt_sweep *grid, tt_sweep_kind kind, int threads, tt_table **out,
                 tt_progress_fn progress, void *user);
int tt_run_sweep_hdf5(const char *path, const tt_sweep *grid, tt_sweep_kind kind,
                      const tt_scene *base, const tt_table *t);

/* io/hdf5.h, instrument/scan_hdf5.h */
typedef struct tt_h5 tt_h5;
int tt_h5_create(tt_h5 **out, const char *path);
int tt_h5_close(tt_h5 *f, int keep);
int tt_scan_write_hdf5(const char *path, const tt_scan *s, const char *const *keys,
                       const char *const *values, size_t n, const char *scene);
"""

ffi = cffi.FFI()
ffi.cdef(CDEF)


def _library_path():
    path = os.environ.get("TIPTAP_LIBRARY")
    if path:
        return path
    try:
        from . import _install
    except ImportError:
        _install = None
    if _install is not None:
        return os.path.normpath(os.path.join(os.path.dirname(__file__), _install.LIBRARY))
    found = ctypes.util.find_library("tiptap")
    if found:
        return found
    raise ImportError(
        "tiptap: libtiptap not found: install it (cmake --install, docs/python.md) or set "
        "TIPTAP_LIBRARY to the path of libtiptap.so"
    )


lib = ffi.dlopen(_library_path())


def text(p):
    """A C string from the library as str ("" for NULL)."""
    return ffi.string(p).decode("utf-8", "replace") if p != ffi.NULL else ""


def owned_text(p):
    """A string the library allocated for the caller: copied, then freed."""
    try:
        return text(p)
    finally:
        lib.tt_free(p)
