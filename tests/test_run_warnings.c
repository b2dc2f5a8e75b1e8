/* The run layer's tables (tiptap/run/run.h, what Python calls) raise the contact
 * validity warning as the program does, through the caller's handler: a trace whose
 * ramp softens the sample from 10 GPa to 1 MPa widens the contact past 0.5 R, and an
 * approach 10 nm into 50 MPa under a 1 nm tip; the stiff ones do not. A scan stepped
 * pass after pass (tt_run_scan_begin, _step, _end: tiptap live) warns of each pass's
 * collapsed pixels on the averaged tier as tiptap scan of that pass would. */
#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/run/run.h"
#include "tiptap/util/error.h"
#include "tiptap/util/warning.h"

typedef struct {
    int validity, other;
    char message[1024];
} heard;

static void hear(const char *category, const char *message, void *data)
{
    heard *h = data;
    if (strcmp(category, TT_WARN_VALIDITY) == 0) {
        h->validity++;
        snprintf(h->message, sizeof h->message, "%s", message);
    } else
        h->other++;
}

typedef int (*run_fn)(const tt_scene *, tt_table **, tt_progress_fn, void *);

static heard run(run_fn f, const char *text, const char *set)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "scene"), TT_OK);
    if (set)
        assert_int_equal(tt_scene_set(s, set), TT_OK);
    heard h = {0};
    tt_table *t = NULL;
    tt_warning_sink old = tt_warning_push(hear, &h);
    assert_int_equal(f(s, &t, NULL, NULL), TT_OK);
    tt_warning_pop(old);
    tt_table_free(t);
    tt_scene_free(s);
    return h;
}

static void trace_ramp_warns(void **st)
{
    (void)st;
    static const char *text =
        "[cantilever]\nfree_amplitude = 20 nm\n[material soft]\nyoungs_modulus = 100 MPa\n"
        "[trace]\nseparation = -5 nm\nsettle_cycles = 3000\ncycles = 200\nsamples_per_cycle = 4\n"
        "ramp = material.soft.youngs_modulus\nramp_from = 10 GPa\nramp_to = 1 MPa\n";
    heard h = run(tt_run_trace, text, NULL);
    print_message("%s\n", h.message);
    assert_int_equal(h.validity, 1);
    assert_non_null(strstr(h.message, "[material soft]: contact radius up to 7.6"));
    assert_non_null(strstr(h.message, "on a tip of radius 10 nm"));
    h = run(tt_run_trace, text, "trace.ramp_to=100 GPa");
    assert_int_equal(h.validity, 0);
}

static void approach_warns(void **st)
{
    (void)st;
    static const char *text =
        "[cantilever]\nquality_factor = 100\n[tip]\nradius = 1 nm\n[material soft]\n"
        "youngs_modulus = 50 MPa\n[approach]\nfrom = 5 nm\nto = -10 nm\npoints = 4\n";
    heard h = run(tt_run_approach, text, NULL);
    print_message("%s\n", h.message);
    assert_int_equal(h.validity, 1);
    assert_non_null(strstr(h.message, "[material soft]: contact radius up to"));
    assert_non_null(strstr(h.message, "on a tip of radius 1 nm"));
    assert_non_null(strstr(h.message, "[approach] to"));
    h = run(tt_run_approach, text, "material.soft.youngs_modulus=200 GPa");
    assert_int_equal(h.validity, 1); /* still 1 nm: the indentation passes R */
    h = run(tt_run_approach, "[material stiff]\nyoungs_modulus = 200 GPa\n[approach]\nfrom = 5 nm\nto = -5 nm\npoints = 3\n", NULL);
    assert_int_equal(h.validity, 0);
}

/* Two passes of the same two lines, each ended (tt_run_scan_end): the averaged tier's
 * collapse warning names the same count and first pixel after each, the pass's own (a
 * setpoint of 10 % presses the oscillation below a quarter of the free amplitude); the
 * count once grew by a pass's at each end, as the console's passes summed them. */
static void collapse_per_pass(void **st)
{
    (void)st;
    static const char *text =
        "[material matrix]\nyoungs_modulus = 2 GPa\npoisson_ratio = 0.35\n"
        "[scan]\nsize = 1 um\npixels = 16\nlines = 2\nline_rate = 8 Hz\n"
        "channels = height, error, phase\nlines_mode = continuous\n"
        "[feedback]\nsetpoint = 10 %\n[solver]\ntier = averaged\n";
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "scene"), TT_OK);
    tt_run_scan_lines r;
    assert_int_equal(tt_run_scan_begin(s, &r), TT_OK);
    char said[2][1024];
    for (int pass = 0; pass < 2; pass++) {
        heard h = {0};
        tt_warning_sink old = tt_warning_push(hear, &h);
        for (long line = 0; line < 2; line++)
            assert_int_equal(tt_run_scan_step(&r, s, line, NULL), TT_OK);
        tt_run_scan_end(&r, NULL, NULL);
        tt_warning_pop(old);
        tt_scan_disengage(r.scan);
        print_message("pass %d: %s\n", pass, h.message);
        assert_non_null(strstr(h.message, "the oscillation collapsed in "));
        snprintf(said[pass], sizeof said[pass], "%s", h.message);
    }
    assert_string_equal(said[1], said[0]);
    tt_scan_free(r.scan);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(trace_ramp_warns),
        cmocka_unit_test(approach_warns),
        cmocka_unit_test(collapse_per_pass),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
