/* The live console's controls: a message is checked as a scene file is, applied whole or
 * not at all, and the scene it leaves is the files' scene with the console's values. */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/live/controls.h"
#include "tiptap/live/lesson.h"
#include "tiptap/util/error.h"
#include "live/live_private.h"

#define SRC TT_SOURCE_DIR
static char *files[] = {SRC "/scans/quick.ini", SRC "/surfaces/grating.ini"};

static tt_live_controls *make(void)
{
    tt_live_controls *c = NULL;
    if (tt_live_controls_alloc(&c, files, 2, NULL, 0, SRC "/surfaces", NULL) != TT_OK)
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
    return tt_live_controls_apply(c, msg, strlen(msg), ch, NULL, NULL);
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
    assert_int_equal(tt_live_controls_apply(c, nul, sizeof nul - 1, &ch, NULL, NULL), TT_EINVAL);
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

/* A machine of 1 GB for the memory checks. */
static double one_gb(void) { return 1e9; }

/* A scene whose scans, page images or scope records do not fit is refused before
 * anything is made, at start-up and as a change, naming the key; one that fits is
 * taken. quick.ini's 300 kHz drive at 0.0002 Hz: 1.9e8 scope points a direction. */
static void memory_is_checked_before_anything_is_made(void **st)
{
    (void)st;
    static const struct {
        const char *set, *key;
    } big[] = {
        {"scan.line_rate=0.0002Hz", "[scan] line_rate:"},
        {"scan.pixels=16384", "[scan] pixels:"},
    };
    for (size_t i = 0; i < sizeof big / sizeof big[0]; i++) {
        tt_live_controls *c = NULL;
        char *sets[] = {(char *)big[i].set, (char *)"scan.lines=16384", (char *)"scan.line_rate=0.0002Hz"};
        int nsets = i == 0 ? 1 : 3;
        if (i == 1)
            sets[2] = (char *)"scan.line_rate=1Hz";
        assert_int_equal(tt_live_controls_alloc(&c, files, 2, sets, nsets, SRC "/surfaces", one_gb),
                         TT_EINVAL);
        if (!strstr(tt_error_message(), big[i].key) || !strstr(tt_error_message(), "more than the 1.0 GB"))
            fail_msg("start-up with %s: '%s'", big[i].set, tt_error_message());
    }
    tt_live_controls *c = NULL;
    assert_int_equal(tt_live_controls_alloc(&c, files, 2, NULL, 0, SRC "/surfaces", one_gb), TT_OK);
    tt_live_change ch;
    double ki0 = ki_of(c);
    assert_int_equal(apply(c, "set feedback.integral_gain = 7 kHz\nset scan.line_rate = 0.0002 Hz", &ch),
                     TT_EINVAL);
    if (!strstr(ch.why, "console: [scan] line_rate:") || !strstr(ch.why, "memory"))
        fail_msg("a change to 0.0002 Hz: '%s'", ch.why);
    assert_int_equal(apply(c, "set scan.pixels = 16384\nset scan.lines = 16384\nset scan.line_rate = 1 Hz",
                           &ch), TT_EINVAL);
    if (!strstr(ch.why, "console: [scan] pixels:") || !strstr(ch.why, "memory"))
        fail_msg("a change to 16384 x 16384: '%s'", ch.why);
    assert_close(ki_of(c), ki0, 0);
    assert_int_equal(apply(c, "set scan.pixels = 256\nset scan.lines = 256", &ch), TT_OK);
    tt_live_controls_free(c);
}

static int refuse(void *user, tt_scene *scene, tt_scan_params *p, int restart)
{
    (void)restart;
    ++*(int *)user;
    tt_scene_free(scene);
    tt_config_scan_free(p);
    return tt_error(TT_EINVAL, "cannot build it");
}

static int accept_it(void *user, tt_scene *scene, tt_scan_params *p, int restart)
{
    *(int *)user = restart ? 2 : 1;
    tt_scene_free(scene);
    tt_config_scan_free(p);
    return TT_OK;
}

/* A change the taker (the engine) refuses leaves the controls as they were: the value
 * shown and the scene built are the ones in force. */
static void a_change_is_taken_whole_or_not_at_all(void **st)
{
    (void)st;
    tt_live_controls *c = make();
    tt_live_change ch;
    int calls = 0;
    double ki0 = ki_of(c);
    const char *msg = "set feedback.integral_gain = 7 kHz\nset sample = particles";
    assert_int_equal(tt_live_controls_apply(c, msg, strlen(msg), &ch, refuse, &calls), TT_EINVAL);
    assert_int_equal(calls, 1);
    assert_string_equal(ch.why, "cannot build it");
    assert_close(ki_of(c), ki0, 0);
    assert_string_equal(tt_live_controls_sample(c, (size_t)tt_live_controls_sample_index(c)), "grating");
    char buf[64], want[64];
    size_t n;
    const tt_live_control *t = tt_live_control_table(&n);
    snprintf(want, sizeof want, "%.6g", ki0);
    for (size_t i = 0; i < n; i++)
        if (strcmp(t[i].name, "feedback.integral_gain") == 0)
            assert_string_equal(tt_live_controls_value(c, i, buf, sizeof buf), want);
    assert_int_equal(tt_live_controls_apply(c, msg, strlen(msg), &ch, accept_it, &calls), TT_OK);
    assert_int_equal(calls, 2); /* the sample restarts the frame */
    assert_close(ki_of(c), 7000, 0);
    tt_live_controls_free(c);
}

/* Text from a page that is not UTF-8 is refused; a refusal that quotes the page's text
 * cuts it on a character's boundary. */
static void replies_are_utf8(void **st)
{
    (void)st;
    tt_live_controls *c = make();
    tt_live_change ch;
    assert_int_equal(apply(c, "set f\xff\xfeo = 1", &ch), TT_EINVAL);
    assert_true(tt_live_utf8_valid(ch.why, strlen(ch.why)));
    assert_non_null(strstr(ch.why, "not UTF-8"));
    char msg[200] = "set x";
    for (int i = 0; i < 40; i++)
        strcat(msg, "\xc3\xa9"); /* e acute: the cut at 60 bytes falls inside one */
    strcat(msg, " = 1");
    assert_int_equal(apply(c, msg, &ch), TT_EINVAL);
    if (!tt_live_utf8_valid(ch.why, strlen(ch.why)))
        fail_msg("not UTF-8: '%s'", ch.why);
    tt_live_controls_free(c);
    /* the one decoder: overlong forms, surrogates, stray and cut bytes are not characters */
    assert_int_equal(tt_live_utf8_char("\xc3\xa9", 2), 2);
    assert_int_equal(tt_live_utf8_char("\xf0\x9f\x94\xac", 4), 4);
    assert_int_equal(tt_live_utf8_char("\xc0\xaf", 2), 0);
    assert_int_equal(tt_live_utf8_char("\xed\xa0\x80", 3), 0);
    assert_int_equal(tt_live_utf8_char("\xf4\x90\x80\x80", 4), 0);
    assert_int_equal(tt_live_utf8_char("\xe2\x82", 2), 0);
    assert_int_equal(tt_live_utf8_fit("a\xe2\x82\xac", 3), 1);
    assert_int_equal(tt_live_utf8_fit("a\xe2\x82\xac", 4), 4);
    char out[8];
    tt_live_text(out, sizeof out, "ab\xff" "c\xe2\x82\xac\xe2\x82\xac");
    assert_string_equal(out, "ab?c\xe2\x82\xac"); /* the second euro does not fit: cut before it */
}

/* The Host and the Origin this server answers: 127.0.0.1, localhost and [::1] with its
 * port, or without one where the port is HTTP's default 80. */
static void hosts_and_origins(void **st)
{
    (void)st;
    assert_true(tt_live_authority_ok("127.0.0.1:8421", 0, 8421));
    assert_true(tt_live_authority_ok("localhost:8421", 0, 8421));
    assert_true(tt_live_authority_ok("LocalHost:8421", 0, 8421));
    assert_true(tt_live_authority_ok("[::1]:8421", 0, 8421));
    assert_true(tt_live_authority_ok("http://127.0.0.1:8421", 1, 8421));
    assert_true(tt_live_authority_ok("127.0.0.1", 0, 80));
    assert_true(tt_live_authority_ok("localhost", 0, 80));
    assert_true(tt_live_authority_ok("[::1]", 0, 80));
    assert_true(tt_live_authority_ok("http://127.0.0.1", 1, 80));
    assert_true(tt_live_authority_ok("http://localhost", 1, 80));
    assert_true(tt_live_authority_ok("http://[::1]:80", 1, 80));
    assert_false(tt_live_authority_ok("127.0.0.1", 0, 8421));
    assert_false(tt_live_authority_ok("127.0.0.1:80", 0, 8421));
    assert_false(tt_live_authority_ok("127.0.0.1:84210", 0, 8421));
    assert_false(tt_live_authority_ok("127.0.0.1:", 0, 80));
    assert_false(tt_live_authority_ok("evil.example:8421", 0, 8421));
    assert_false(tt_live_authority_ok("127.0.0.1.evil.example:8421", 0, 8421));
    assert_false(tt_live_authority_ok("localhost.:8421", 0, 8421));
    assert_false(tt_live_authority_ok("http://127.0.0.1:8421/", 1, 8421));
    assert_false(tt_live_authority_ok("https://127.0.0.1:8421", 1, 8421));
    assert_false(tt_live_authority_ok("null", 1, 8421));
    assert_false(tt_live_authority_ok("127.0.0.1:8421", 1, 8421));
}

/* A lesson's own sections, its locks held by the controls (not only the page), and its
 * bad keys named with the file and line. */
static void a_lesson_locks_and_hides(void **st)
{
    (void)st;
    char path[] = "/tmp/tt-lesson-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fprintf(f, "[lesson]\ntitle = T\ninstructions = one\n    two\nhide = noise, tier\nlock = scan_size, integral_gain\n"
               "[feedback]\nintegral_gain = 321 Hz\n");
    fclose(f);
    tt_live_lesson *l = NULL;
    assert_int_equal(tt_live_lesson_load(&l, path), TT_OK);
    assert_string_equal(l->instructions, "one\ntwo");
    tt_live_controls *c = NULL;
    if (tt_live_controls_alloc_lesson(&c, l, files, 2, NULL, 0, SRC "/surfaces", NULL) != TT_OK)
        fail_msg("%s", tt_error_message());
    assert_close(ki_of(c), 321, 0); /* the lesson's section, after the files */
    tt_live_change ch;
    assert_int_equal(apply(c, "set feedback.integral_gain = 6 kHz", &ch), TT_EINVAL);
    assert_non_null(strstr(ch.why, "feedback.integral_gain is locked by the lesson"));
    assert_int_equal(apply(c, "set solver.tier = averaged", &ch), TT_EINVAL);
    assert_non_null(strstr(ch.why, "solver.tier is hidden by the lesson"));
    assert_close(ki_of(c), 321, 0);
    assert_int_equal(apply(c, "set feedback.setpoint = 15 nm", &ch), TT_OK);
    tt_live_controls_free(c);
    f = fopen(path, "w");
    fprintf(f, "[lesson]\ntitle = T\nlock = scan_size, gains\n");
    fclose(f);
    assert_int_equal(tt_live_lesson_load(&l, path), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), ":3: [lesson] lock: 'gains' is not a control"));
    unlink(path);
}

/* A lesson read from text (a file written and removed). */
static tt_live_lesson *lesson_of(const char *text)
{
    char path[] = "/tmp/tt-lesson-XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    fputs(text, f);
    fclose(f);
    tt_live_lesson *l = NULL;
    assert_int_equal(tt_live_lesson_load(&l, path), TT_OK);
    unlink(path);
    return l;
}

/* Each page's instrument has a copy of the controls: a change to one is not the other's,
 * and a copy keeps the lesson's locks (borrowed: freed with the original, after it). */
static void a_copy_is_its_own(void **st)
{
    (void)st;
    tt_live_lesson *l = lesson_of("[lesson]\ntitle = T\nlock = scan_size\n[feedback]\nsetpoint = 15 nm\n");
    tt_live_controls *c = NULL, *a = NULL, *b = NULL;
    if (tt_live_controls_alloc_lesson(&c, l, files, 2, NULL, 0, SRC "/surfaces", NULL) != TT_OK)
        fail_msg("%s", tt_error_message());
    tt_live_change ch;
    assert_int_equal(apply(c, "set feedback.integral_gain = 2 kHz\nset sample = edges", &ch), TT_OK);
    assert_int_equal(tt_live_controls_copy(&a, c), TT_OK);
    assert_int_equal(tt_live_controls_copy(&b, c), TT_OK);
    assert_close(ki_of(a), 2000, 0); /* a copy starts at the values in force */
    assert_int_equal(apply(a, "set feedback.integral_gain = 7 kHz", &ch), TT_OK);
    assert_close(ki_of(a), 7000, 0);
    assert_close(ki_of(b), 2000, 0);
    assert_close(ki_of(c), 2000, 0);
    assert_int_equal(apply(b, "set sample = grating", &ch), TT_OK);
    assert_string_equal(tt_live_controls_sample(a, (size_t)tt_live_controls_sample_index(a)), "edges");
    assert_string_equal(tt_live_controls_sample(b, (size_t)tt_live_controls_sample_index(b)), "grating");
    assert_ptr_equal(tt_live_controls_lesson(a), tt_live_controls_lesson(c));
    assert_int_equal(apply(a, "set scan.size = 1 um", &ch), TT_EINVAL);
    assert_non_null(strstr(ch.why, "scan.size is locked by the lesson"));
    tt_live_controls_free(a);
    tt_live_controls_free(b);
    tt_live_controls_free(c);
}

static const char *value_of(const tt_live_controls *c, const char *name, char *buf, size_t len)
{
    size_t n;
    const tt_live_control *t = tt_live_control_table(&n);
    for (size_t i = 0; i < n; i++)
        if (strcmp(t[i].name, name) == 0)
            return tt_live_controls_value(c, i, buf, len);
    fail_msg("no control %s", name);
    return NULL;
}

/* The force bench's ramp: shown in its knobs' units, checked by tiptap force's rules (a
 * ramp of more than 1e9 drive periods passes the schema, not tt_config_force), a refusal
 * changing nothing; a lesson hiding both knobs hides the bench, not the tune. */
static void the_ramp_is_checked_as_tiptap_force_checks_it(void **st)
{
    (void)st;
    tt_live_controls *c = make();
    tt_live_change ch;
    char buf[64];
    assert_string_equal(value_of(c, "force.speed", buf, sizeof buf), "1");
    assert_int_equal(apply(c, "set force.range = 30 nm", &ch), TT_OK);
    assert_string_equal(value_of(c, "force.range", buf, sizeof buf), "30");
    assert_int_equal(ch.restart, 0);
    tt_scene *s;
    tt_force_params fp;
    assert_int_equal(tt_live_controls_scene(c, &s, NULL), TT_OK);
    assert_int_equal(tt_config_force(s, &fp), TT_OK);
    assert_close(fp.from - fp.to, 30e-9, 1e-15);
    tt_scene_free(s);
    assert_int_equal(apply(c, "set force.speed = 0 um/s", &ch), TT_EINVAL);
    assert_non_null(strstr(ch.why, "[force] speed"));
    assert_int_equal(apply(c, "set force.speed = 1 pm/s", &ch), TT_EINVAL);
    assert_non_null(strstr(ch.why, "[force] speed"));
    assert_string_equal(value_of(c, "force.speed", buf, sizeof buf), "1");
    assert_int_equal(tt_live_controls_panel_hidden(c, "force"), 0);
    tt_live_controls_free(c);
    tt_live_lesson *l = lesson_of("[lesson]\ntitle = T\nhide = speed, range\n[noise]\nseed = 3\n");
    if (tt_live_controls_alloc_lesson(&c, l, files, 2, NULL, 0, SRC "/surfaces", NULL) != TT_OK)
        fail_msg("%s", tt_error_message());
    assert_int_equal(tt_live_controls_panel_hidden(c, "force"), 1);
    assert_int_equal(tt_live_controls_panel_hidden(c, "tune"), 0);
    tt_live_controls_free(c);
}

/* The setpoint in % of the free amplitude, as the scene writes it (80 %): a value in nm
 * shown as its share, a share kept when the free amplitude changes, bounds in %. */
static void the_setpoint_is_a_share_of_the_free_amplitude(void **st)
{
    (void)st;
    tt_live_controls *c = make();
    tt_live_change ch;
    char buf[64];
    size_t n;
    const tt_live_control *t = tt_live_control_table(&n);
    for (size_t i = 0; i < n; i++)
        if (strcmp(t[i].name, "feedback.setpoint") == 0)
            assert_string_equal(t[i].unit, "%"); /* the page sends a bare 75 as 75 % */
    assert_string_equal(value_of(c, "feedback.setpoint", buf, sizeof buf), "80");
    assert_int_equal(apply(c, "set feedback.setpoint = 15 nm", &ch), TT_OK);
    assert_string_equal(value_of(c, "feedback.setpoint", buf, sizeof buf), "75");
    assert_int_equal(apply(c, "set feedback.setpoint = 60 %\nset cantilever.free_amplitude = 25 nm", &ch), TT_OK);
    assert_string_equal(value_of(c, "feedback.setpoint", buf, sizeof buf), "60");
    tt_scene *s;
    tt_scan_params p;
    assert_int_equal(tt_live_controls_scene(c, &s, &p), TT_OK);
    assert_close(p.feedback.setpoint, 15e-9, 1e-20);
    tt_config_scan_free(&p);
    tt_scene_free(s);
    static const char *const refused[][2] = {
        {"set feedback.setpoint = 0 %", "0 % is out of range; expected above 0 %"},
        {"set feedback.setpoint = 120 %", "between 0 and 100 %"},
    };
    for (size_t i = 0; i < 2; i++) {
        assert_int_equal(apply(c, refused[i][0], &ch), TT_EINVAL);
        if (!strstr(ch.why, refused[i][1]))
            fail_msg("'%s': reply '%s' lacks '%s'", refused[i][0], ch.why, refused[i][1]);
    }
    assert_string_equal(value_of(c, "feedback.setpoint", buf, sizeof buf), "60");
    tt_live_controls_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_gain_is_set_in_the_scene),
        cmocka_unit_test(refused_values_change_nothing),
        cmocka_unit_test(sample_and_noise),
        cmocka_unit_test(memory_is_checked_before_anything_is_made),
        cmocka_unit_test(a_change_is_taken_whole_or_not_at_all),
        cmocka_unit_test(replies_are_utf8),
        cmocka_unit_test(hosts_and_origins),
        cmocka_unit_test(a_lesson_locks_and_hides),
        cmocka_unit_test(a_copy_is_its_own),
        cmocka_unit_test(the_ramp_is_checked_as_tiptap_force_checks_it),
        cmocka_unit_test(the_setpoint_is_a_share_of_the_free_amplitude),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
