/* The advice of a scan's error-estimate warning (tt_run_scan_warn_error): for a noisy
 * scan of two modes the estimate is the runs' real spread, which no tolerance narrows
 * (mode 2 rings for Q_2 fd / (pi f_2) drive cycles after each tap: docs/dynamics.md, "A
 * noisy scan of two modes"), so the warning says so and names what helps; one mode, or
 * two without noise, keep the advice to tighten the tolerance. */
#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/run/run.h"
#include "tiptap/util/error.h"
#include "tiptap/util/warning.h"

typedef struct {
    int n;
    char message[2048];
} heard;

static void hear(const char *category, const char *message, void *data)
{
    heard *h = data;
    if (strcmp(category, TT_WARN_ESTIMATE) == 0) {
        h->n++;
        snprintf(h->message, sizeof h->message, "%s", message);
    }
}

/* The standard cantilever, scanned every cycle, with extra keys; the warning an estimate
 * of 0.8 deg rms (4.1 deg largest) in phase raises. */
static heard warn(const char *extra)
{
    char text[2048];
    snprintf(text, sizeof text,
             "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\n"
             "quality_factor = 400\nfree_amplitude = 20 nm\n"
             "[scan]\nsize = 100 nm\npixels = 4\nlines = 2\nline_rate = 10 Hz\n"
             "[solver]\ntier = every\n%s", extra);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "scene"), TT_OK);
    tt_scan *scan = NULL;
    if (tt_config_scan_alloc(&scan, s) != TT_OK)
        fail_msg("%s", tt_error_message());
    tt_run_scan_cost cost = {0};
    tt_scan_error e = {0};
    e.phase_max = 4.1;
    e.phase_rms = 0.8;
    heard h = {0};
    tt_warning_sink old = tt_warning_push(hear, &h);
    tt_run_scan_warn_error(scan, &cost, &e);
    tt_warning_pop(old);
    tt_scan_free(scan);
    tt_scene_free(s);
    print_message("%s\n", h.message);
    return h;
}

static void two_modes_with_noise(void **st)
{
    (void)st;
    heard h = warn("[cantilever]\nmodes = 2\n[noise]\ntemperature = 300 K\n");
    assert_int_equal(h.n, 1);
    assert_non_null(strstr(h.message, "4.1 deg in phase"));
    assert_non_null(strstr(h.message, "with noise and 2 modes this is the runs' real spread"));
    /* Q_2 fd / (pi f_2): 2507 x 300 kHz / (pi 1.88 MHz) = 127 cycles */
    assert_non_null(strstr(h.message, "mode 2, Q 2507 at 1.88 MHz, rings for 127 drive cycles"));
    assert_non_null(strstr(h.message, "a tighter [solver] tolerance does not help"));
    assert_non_null(strstr(h.message, "lower line rate"));
    assert_non_null(strstr(h.message, "[cantilever] modes = 1"));
    assert_null(strstr(h.message, "tighten [solver] tolerance"));
    /* detector noise alone is noise too */
    h = warn("[cantilever]\nmodes = 2\n[noise]\ndetector = 50 fm/sqrt(Hz)\n");
    assert_non_null(strstr(h.message, "a tighter [solver] tolerance does not help"));
}

static void one_mode_or_no_noise(void **st)
{
    (void)st;
    const char *old_text = "the run's own error estimate is 4.1 deg in phase (above 1e-3 of the free "
                           "amplitude or 0.1 deg): tighten [solver] tolerance (now 1e-08)";
    heard h = warn("[noise]\ntemperature = 300 K\n");
    assert_int_equal(h.n, 1);
    assert_string_equal(h.message, old_text);
    h = warn("[cantilever]\nmodes = 2\n");
    assert_string_equal(h.message, old_text);
}

TT_TEST_MAIN(cmocka_unit_test(two_modes_with_noise), cmocka_unit_test(one_mode_or_no_noise))
