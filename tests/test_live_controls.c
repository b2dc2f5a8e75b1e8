/* The live console's controls: a message is checked as a scene file is, applied whole or
 * not at all, and the scene it leaves is the files' scene with the console's values. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/live/controls.h"
#include "tiptap/util/error.h"

#define SRC TT_SOURCE_DIR
static char *files[] = {SRC "/scans/quick.ini", SRC "/surfaces/grating.ini"};

static tt_live_controls *make(void)
{
    tt_live_controls *c = NULL;
    if (tt_live_controls_alloc(&c, files, 2, NULL, 0, SRC "/surfaces") != TT_OK)
        fail_msg("%s", tt_error_message());
    return c;
}

static double ki_of(const tt_live_controls *c)
{
    tt_scene *s;
    tt_scan_params p;
    assert_int_equal(tt_live_controls_scene(c, &s, &p), TT_OK);
    double ki = p.feedback.ki;
    tt_config_scan_free(&p);
    tt_scene_free(s);
    return ki;
}

static int apply(tt_live_controls *c, const char *msg, tt_live_change *ch)
{
    return tt_live_controls_apply(c, msg, strlen(msg), ch);
}

static void a_gain_is_set_in_the_scene(void **st)
{
    (void)st;
    tt_live_controls *c = make();
    tt_live_change ch;
    assert_int_equal(apply(c, "set feedback.integral_gain = 6 kHz", &ch), TT_OK);
    assert_close(ki_of(c), 6000, 0);
    assert_int_equal(ch.changed, 1);
    assert_int_equal(ch.restart, 0); /* a gain applies from the next line */
    char buf[64];
    size_t n;
    const tt_live_control *t = tt_live_control_table(&n);
    for (size_t i = 0; i < n; i++)
        if (strcmp(t[i].name, "feedback.integral_gain") == 0)
            assert_string_equal(tt_live_controls_value(c, i, buf, sizeof buf), "6000");
    tt_live_controls_free(c);
}

/* The configuration layer's own refusals, in its words, and nothing changes. */
static void refused_values_change_nothing(void **st)
{
    (void)st;
    static const struct {
        const char *msg, *want;
    } bad[] = {
        {"set feedback.integral_gain = 6", "console: [feedback] integral_gain:"},
        {"set feedback.integral_gain = -5 kHz", "console: [feedback] integral_gain:"},
        {"set feedback.integral_gain = nan Hz", "console: [feedback] integral_gain:"},
        {"set scan.pixels = 1", "console: [scan] pixels:"},
        {"set feedback.setpoint = 30 nm", "setpoint"},        /* above the free amplitude */
        {"set solver.tier = fast", "console: [solver] tier:"},
        {"set tip.radius = 5 nm", "no such control"},          /* not a console knob */
        {"set sample = nowhere", "not a bundled sample"},
        {"set noise = maybe", "expected on or off"},
        {"set feedback.integral_gain", "expected set NAME = VALUE"},
        {"hello", "expected set NAME = VALUE or restart"},
        {"", "an empty message"},
        /* the second line fails: the first, good on its own, is not applied either */
        {"set feedback.integral_gain = 9 kHz\nset scan.pixels = abc", "console: [scan] pixels:"},
        /* no way to smuggle another section in through a value */
        {"set feedback.integral_gain = 9 kHz\r\n[tip]", "expected set NAME = VALUE or restart"},
    };
    tt_live_controls *c = make();
    double ki0 = ki_of(c);
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        tt_live_change ch;
        if (apply(c, bad[i].msg, &ch) != TT_EINVAL)
            fail_msg("accepted: '%s'", bad[i].msg);
        if (!strstr(ch.why, bad[i].want) || strchr(ch.why, '\n'))
            fail_msg("'%s': reply '%s' lacks '%s'", bad[i].msg, ch.why, bad[i].want);
        assert_close(ki_of(c), ki0, 0);
    }
    tt_live_change ch;
    const char nul[] = "set feedback.integral_gain = 9\0 kHz";
    assert_int_equal(tt_live_controls_apply(c, nul, sizeof nul - 1, &ch), TT_EINVAL);
    assert_close(ki_of(c), ki0, 0);
    tt_live_controls_free(c);
}

/* Knobs that change the raster restart the frame; the sample replaces the bundled file
 * given, and noise on gives a good instrument's noise to a scene without any. */
static void sample_and_noise(void **st)
{
    (void)st;
    tt_live_controls *c = make();
    tt_live_change ch;
    assert_string_equal(tt_live_controls_sample(c, (size_t)tt_live_controls_sample_index(c)), "grating");
    assert_int_equal(apply(c, "set sample = steps\nset scan.pixels = 32", &ch), TT_OK);
    assert_int_equal(ch.restart, 1);
    tt_scene *s;
    tt_scan_params p;
    assert_int_equal(tt_live_controls_scene(c, &s, &p), TT_OK);
    assert_int_equal(p.surface.type, TT_SURFACE_STEPS);
    assert_int_equal(p.raster.pixels, 32);
    assert_close(p.noise.temperature, 0, 0);
    tt_config_scan_free(&p);
    tt_scene_free(s);
    assert_int_equal(apply(c, "set noise = on", &ch), TT_OK);
    assert_int_equal(tt_live_controls_scene(c, &s, &p), TT_OK);
    assert_close(p.noise.temperature, 300, 0);
    assert_close(p.noise.detector, 100e-15, 1e-27);
    tt_config_scan_free(&p);
    tt_scene_free(s);
    tt_live_controls_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_gain_is_set_in_the_scene),
        cmocka_unit_test(refused_values_change_nothing),
        cmocka_unit_test(sample_and_noise),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
