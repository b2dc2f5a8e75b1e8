/* Scene text is read exactly as written: no line or name is cut, an indented key is a
 * key, a section without keys exists, every refusal is one line with the line number
 * and control characters escaped; only regular files are scenes; --set values of any
 * length; the effective scene, long paths included, reads back to the same text. */
#include <stdlib.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/config/scene.h"
#include "tiptap/util/error.h"

static tt_scene *load_ok(const char *text)
{
    tt_scene *s = tt_scene_alloc();
    if (tt_scene_load_string(s, text, "t.ini") != TT_OK)
        fail_msg("refused: %s", tt_error_message());
    return s;
}

/* The refusal of text: its status is TT_EINVAL and its one-line message holds frag. */
static void refused(const char *text, const char *frag)
{
    tt_scene *s = tt_scene_alloc();
    tt_error_clear();
    if (tt_scene_load_string(s, text, "t.ini") != TT_EINVAL)
        fail_msg("accepted: %s", text);
    const char *m = tt_error_message();
    if (!strstr(m, frag))
        fail_msg("message '%s' lacks '%s'", m, frag);
    for (const char *p = m; *p; p++)
        if ((unsigned char)*p < 0x20)
            fail_msg("message holds control character 0x%02x: '%s'", *p, m);
    tt_scene_free(s);
}

static char *written(const tt_scene *s)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    assert_int_equal(tt_scene_write(s, f, NULL), TT_OK);
    fclose(f);
    return buf;
}

/* inih cut lines at 199 bytes and parsed the rest as a line of its own. */
static void long_lines_are_whole(void **st)
{
    (void)st;
    char text[2048], path[700];
    memset(path, 'p', sizeof path - 1);
    path[0] = '/';
    path[sizeof path - 1] = '\0';
    char comment[400];
    memset(comment, 'c', sizeof comment - 1);
    comment[sizeof comment - 1] = '\0';
    snprintf(text, sizeof text, "; %s = x\n[surface]\npng = %s\n", comment, path);
    tt_scene *s = load_ok(text);
    assert_string_equal(tt_scene_get_string(s, "surface", NULL, "png"), path);
    tt_scene_free(s);
}

/* inih cut section names at 50 bytes: these two materials became one. */
static void long_names_stay_apart(void **st)
{
    (void)st;
    tt_scene *s = load_ok("[material polystyrene_sample_from_batch_2024_spin_coated_A]\n"
                          "reduced_modulus = 1 GPa\n"
                          "[material polystyrene_sample_from_batch_2024_spin_coated_B]\n"
                          "reduced_modulus = 2 GPa\n");
    assert_int_equal(tt_scene_count_named(s, "material"), 2);
    assert_string_equal(tt_scene_named(s, "material", 1),
                        "polystyrene_sample_from_batch_2024_spin_coated_B");
    tt_scene_free(s);
}

/* inih read an indented line as the continuation of the previous value. */
static void indented_key_is_a_key(void **st)
{
    (void)st;
    tt_scene *s = load_ok("[cantilever]\nspring_constant = 1 N/m\n    quality_factor = 40\n");
    assert_string_equal(tt_scene_get_string(s, "cantilever", NULL, "spring_constant"), "1 N/m");
    assert_string_equal(tt_scene_get_string(s, "cantilever", NULL, "quality_factor"), "40");
    tt_scene_free(s);
}

/* A section of defaults only exists; inih reported only keys. */
static void empty_named_section_exists(void **st)
{
    (void)st;
    tt_scene *s = load_ok("[material glass]\n[material mica]\nreduced_modulus = 60 GPa\n");
    assert_int_equal(tt_scene_count_named(s, "material"), 2);
    assert_string_equal(tt_scene_named(s, "material", 0), "glass");
    assert_true(tt_scene_has_section(s, "material", "glass"));
    char *w = written(s);
    assert_non_null(strstr(w, "[material glass]\n"));
    free(w);
    tt_scene_free(s);
    refused("[cantilver]\n", "t.ini: [cantilver]: unknown section");
}

static void line_endings_and_bad_lines(void **st)
{
    (void)st;
    /* CR only, CRLF, LF */
    tt_scene *s = load_ok("[cantilever]\rspring_constant = 1 N/m\r\nquality_factor = 40\r");
    assert_string_equal(tt_scene_get_string(s, "cantilever", NULL, "quality_factor"), "40");
    tt_scene_free(s);
    /* inih reported the header's missing ']' against the next key */
    refused("; scene\n[cantilever\nspring_constant = 1 N/m\n",
            "t.ini: line 2: section header without its closing ']': '[cantilever'");
    refused("[cantilever] x\n", "t.ini: line 1: text after the section header");
    refused("[cantilever]\n\n= 3\n", "t.ini: line 3: a value without a key");
    /* a terminal escape is shown, not sent to the terminal */
    refused("[cantilever]\nspring_constant = 1 \x1b[31mN/m\n", "t.ini: line 2: control character \\x1b");
    refused("[material glass]\nmodel = \x1b]0;pwned\x07\n", "line 2: control character \\x1b");
}

/* Only regular files are scenes: a folder read as an empty scene, /dev/zero never ended. */
static void only_regular_files(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load(s, TT_SOURCE_DIR "/tests"), TT_EINVAL);
    assert_string_equal(tt_error_message(), TT_SOURCE_DIR "/tests: is a folder, not a scene file");
    assert_int_equal(tt_scene_load(s, "/dev/zero"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "/dev/zero: not a regular file"));
    tt_scene_free(s);
}

static void set_values_whole_and_one_line(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    char set[1200] = "surface.png=/";
    size_t n = strlen(set);
    memset(set + n, 'q', 1000);
    set[n + 1000] = '\0';
    assert_int_equal(tt_scene_set(s, set), TT_OK);
    assert_string_equal(tt_scene_get_string(s, "surface", NULL, "png"), set + strlen("surface.png="));
    /* a line break would split the key in scene.ini */
    assert_int_equal(tt_scene_set(s, "surface.png=a.png\n[cantilever]\nquality_factor = 1"),
                     TT_EINVAL);
    assert_null(strchr(tt_error_message(), '\n'));
    assert_non_null(strstr(tt_error_message(), "control character"));
    assert_int_equal(tt_scene_set(s, "surface.png=a.png ; b"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "starts a comment"));
    /* "material..key" made a material named "" */
    assert_int_equal(tt_scene_set(s, "material..reduced_modulus=1 GPa"), TT_EINVAL);
    assert_string_equal(tt_error_message(), "--set material..reduced_modulus=1 GPa: empty name; "
                                            "expected section.key=value or section.name.key=value");
    assert_int_equal(tt_scene_count_named(s, "material"), 0);
    assert_int_equal(tt_scene_set(s, ".x=1"), TT_EINVAL);
    tt_scene_free(s);
}

/* What scan writes into scene.ini (absolute paths from deep folders, long names) reads
 * back to the same text. */
static void effective_scene_with_long_paths_reads_back(void **st)
{
    (void)st;
    char set[900] = "surface.png=/";
    size_t n = strlen(set);
    for (size_t i = 0; i < 80; i++)
        memcpy(set + n + 10 * i, "deep/fold/", 10);
    strcpy(set + n + 800, "map.png");
    tt_scene *s = load_ok("[surface]\nmap = png\n[material a_rather_long_material_name_for_a_sample]\n");
    assert_int_equal(tt_scene_set(s, set), TT_OK);
    char *w1 = written(s);
    tt_scene *r = load_ok(w1);
    char *w2 = written(r);
    assert_string_equal(w1, w2);
    free(w1);
    free(w2);
    tt_scene_free(r);
    tt_scene_free(s);
}

/* Loading many materials is near-linear (it was quadratic: 50,000 took over a minute);
 * here every name is kept apart and found. */
static void many_materials(void **st)
{
    (void)st;
    size_t count = 50000, len = 0;
    char *text = malloc(count * 64);
    assert_non_null(text);
    for (size_t i = 0; i < count; i++)
        len += (size_t)sprintf(text + len, "[material m%zu]\nreduced_modulus = %zu GPa\n", i, i + 1);
    tt_scene *s = load_ok(text);
    assert_int_equal(tt_scene_count_named(s, "material"), count);
    assert_string_equal(tt_scene_named(s, "material", count - 1), "m49999");
    assert_string_equal(tt_scene_get_string(s, "material", "m31415", "reduced_modulus"), "31416 GPa");
    tt_scene *c = tt_scene_copy(s);
    assert_non_null(c);
    assert_string_equal(tt_scene_named(c, "material", 31415), "m31415");
    tt_scene_free(c);
    tt_scene_free(s);
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(long_lines_are_whole),
        cmocka_unit_test(long_names_stay_apart),
        cmocka_unit_test(indented_key_is_a_key),
        cmocka_unit_test(empty_named_section_exists),
        cmocka_unit_test(line_endings_and_bad_lines),
        cmocka_unit_test(only_regular_files),
        cmocka_unit_test(set_values_whole_and_one_line),
        cmocka_unit_test(effective_scene_with_long_paths_reads_back),
        cmocka_unit_test(many_materials),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
