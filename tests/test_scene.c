/* Scene files: every documented error gives one line naming the file, the section and
 * the key; overrides and defaults behave as documented. */
#include <stdlib.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/util/error.h"
#include "tiptap/config/scene.h"

/* Load text as a scene file named origin; return the status, message in *msg. */
static int load(const char *text, const char **msg)
{
    tt_scene *s = tt_scene_alloc();
    tt_error_clear();
    int rc = tt_scene_load_string(s, text, "t.ini");
    *msg = tt_error_message();
    tt_scene_free(s);
    return rc;
}

static void expect_error(const char *text, const char *fragment1, const char *fragment2)
{
    const char *msg;
    int rc = load(text, &msg);
    if (rc != TT_EINVAL)
        fail_msg("accepted: %s", text);
    if (!strstr(msg, fragment1) || (fragment2 && !strstr(msg, fragment2)))
        fail_msg("message '%s' lacks '%s' / '%s'", msg, fragment1, fragment2 ? fragment2 : "");
    if (strchr(msg, '\n'))
        fail_msg("message is not one line: '%s'", msg);
}

static void typo_in_key_is_named(void **st)
{
    (void)st;
    expect_error("[cantilever]\nspring_constnat = 2 N/m\n", "t.ini: [cantilever] spring_constnat:",
                 "unknown key");
}

static void unknown_section_is_named(void **st)
{
    (void)st;
    expect_error("[cantilver]\nspring_constant = 2 N/m\n", "t.ini: [cantilver]", "unknown section");
}

static void missing_and_wrong_units(void **st)
{
    (void)st;
    expect_error("[cantilever]\nresonance_frequency = 52\n", "[cantilever] resonance_frequency:",
                 "missing unit");
    expect_error("[cantilever]\nresonance_frequency = 52 nm\n", "[cantilever] resonance_frequency:",
                 "wrong unit");
    expect_error("[material glass]\nadhesion_energy = 100 mJ\n", "[material glass] adhesion_energy:",
                 "J/m^2");
    expect_error("[cantilever]\nquality_factor = 400 Hz\n", "[cantilever] quality_factor:", "no unit");
}

static void out_of_range_and_nan(void **st)
{
    (void)st;
    expect_error("[cantilever]\nspring_constant = -2 N/m\n", "[cantilever] spring_constant:",
                 "above 0");
    expect_error("[cantilever]\nspring_constant = nan N/m\n", "[cantilever] spring_constant:",
                 "not a finite number");
    expect_error("[tip]\npoisson_ratio = 0.7\n", "[tip] poisson_ratio:", "at most 0.5");
    expect_error("[approach]\npoints = 0\n", "[approach] points:", "at least 1");
    expect_error("[approach]\npoints = many\n", "[approach] points:", "whole number");
    expect_error("[material a]\nmodel = hertzz\n", "[material a] model:", "maugis|hertz|dmt|jkr");
}

static void structure_errors(void **st)
{
    (void)st;
    expect_error("[material]\nyoungs_modulus = 1 GPa\n", "[material]", "needs a name");
    expect_error("[cantilever x]\nspring_constant = 1 N/m\n", "[cantilever x]", "takes no name");
    expect_error("[cantilever]\nspring_constant = 1 N/m\nspring_constant = 2 N/m\n",
                 "[cantilever] spring_constant:", "twice");
    expect_error("spring_constant = 1 N/m\n", "t.ini:", "outside any section");
    expect_error("[cantilever]\nthis line has no equals sign\n", "t.ini: line 2", NULL);
}

static void defaults_overrides_and_named_sections(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s,
                                          "[cantilever]\nspring_constant = 0.58 N/m\n"
                                          "[material glass]\nadhesion_energy = 100 mJ/m^2\n"
                                          "[material mica]\nyoungs_modulus = 60 GPa\n",
                                          "a.ini"),
                     TT_OK);
    double v;
    assert_int_equal(tt_scene_get_double(s, "cantilever", NULL, "spring_constant", &v), TT_OK);
    assert_close(v, 0.58, 1e-15);
    /* a default from the schema */
    assert_int_equal(tt_scene_get_double(s, "cantilever", NULL, "quality_factor", &v), TT_OK);
    assert_close(v, 400, 0);
    assert_int_equal(tt_scene_count_named(s, "material"), 2);
    assert_string_equal(tt_scene_named(s, "material", 0), "glass");
    assert_string_equal(tt_scene_named(s, "material", 1), "mica");
    /* --set overrides, named sections through material.NAME.key */
    assert_int_equal(tt_scene_set(s, "material.glass.adhesion_energy=72 mJ/m^2"), TT_OK);
    assert_int_equal(tt_scene_get_double(s, "material", "glass", "adhesion_energy", &v), TT_OK);
    assert_close(v, 0.072, 1e-15);
    assert_int_equal(tt_scene_set(s, "cantilever.quality_factor = 40"), TT_OK);
    assert_int_equal(tt_scene_get_double(s, "cantilever", NULL, "quality_factor", &v), TT_OK);
    assert_close(v, 40, 0);
    /* a later file overrides an earlier one */
    assert_int_equal(tt_scene_load_string(s, "[cantilever]\nspring_constant = 2 N/m\n", "b.ini"),
                     TT_OK);
    assert_int_equal(tt_scene_get_double(s, "cantilever", NULL, "spring_constant", &v), TT_OK);
    assert_close(v, 2, 0);
    /* a bad --set names itself */
    assert_int_equal(tt_scene_set(s, "cantilever.spring_constant=abc"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "--set: [cantilever] spring_constant:"));
    assert_int_equal(tt_scene_set(s, "nodot=1"), TT_EINVAL);
    assert_int_equal(tt_scene_set(s, "cantilever.spring_constant"), TT_EINVAL);
    /* later failures found by a module name the file that set the key */
    assert_int_equal(tt_scene_fail(s, "material", "glass", "adhesion_energy", "too sticky"), TT_EINVAL);
    assert_string_equal(tt_error_message(), "--set: [material glass] adhesion_energy: too sticky");
    assert_int_equal(tt_scene_fail(s, "material", "mica", "youngs_modulus", "x"), TT_EINVAL);
    assert_string_equal(tt_error_message(), "a.ini: [material mica] youngs_modulus: x");
    tt_scene_free(s);
}

static void effective_scene_reads_back_the_same(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s,
                                          "[cantilever]\nspring_constant = 0.58 N/m\n"
                                          "[material glass]\nadhesion_energy = 100 mJ/m^2\n",
                                          "a.ini"),
                     TT_OK);
    char path[] = "/tmp/tt_scene_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "w");
    assert_int_equal(tt_scene_write(s, f, NULL), TT_OK);
    fclose(f);
    tt_scene *r = tt_scene_alloc();
    int rc = tt_scene_load(r, path);
    if (rc)
        fail_msg("re-reading the written scene: %s", tt_error_message());
    double a, b;
    assert_int_equal(tt_scene_get_double(r, "material", "glass", "adhesion_energy", &a), TT_OK);
    assert_close(a, 0.1, 1e-15);
    assert_int_equal(tt_scene_get_double(r, "cantilever", NULL, "spring_constant", &b), TT_OK);
    assert_close(b, 0.58, 1e-15);
    /* defaults are written out explicitly */
    assert_true(tt_scene_has(r, "cantilever", NULL, "quality_factor"));
    unlink(path);
    tt_scene_free(r);
    tt_scene_free(s);
}

/* A copy keeps values, origins and sections, and changing it leaves the original alone. */
static void copy_is_independent(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, "[cantilever]\nspring_constant = 0.58 N/m\n"
                                             "[material glass]\nadhesion_energy = 100 mJ/m^2\n",
                                          "a.ini"),
                     TT_OK);
    tt_scene *c = tt_scene_copy(s);
    assert_non_null(c);
    assert_string_equal(tt_scene_origin(c), "a.ini");
    assert_true(tt_scene_has_section(c, "material", "glass"));
    assert_false(tt_scene_has_section(c, "scan", NULL));
    assert_int_equal(tt_scene_set(c, "cantilever.spring_constant=2 N/m"), TT_OK);
    double a, b;
    assert_int_equal(tt_scene_get_double(s, "cantilever", NULL, "spring_constant", &a), TT_OK);
    assert_int_equal(tt_scene_get_double(c, "cantilever", NULL, "spring_constant", &b), TT_OK);
    assert_close(a, 0.58, 1e-15);
    assert_close(b, 2, 0);
    assert_int_equal(tt_scene_fail(c, "material", "glass", "adhesion_energy", "x"), TT_EINVAL);
    assert_string_equal(tt_error_message(), "a.ini: [material glass] adhesion_energy: x");
    tt_scene_free(c);
    tt_scene_free(s);
}

static void missing_file_is_named(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load(s, "/nonexistent/scene.ini"), TT_EIO);
    assert_non_null(strstr(tt_error_message(), "/nonexistent/scene.ini"));
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(typo_in_key_is_named),
        cmocka_unit_test(unknown_section_is_named),
        cmocka_unit_test(missing_and_wrong_units),
        cmocka_unit_test(out_of_range_and_nan),
        cmocka_unit_test(structure_errors),
        cmocka_unit_test(defaults_overrides_and_named_sections),
        cmocka_unit_test(effective_scene_reads_back_the_same),
        cmocka_unit_test(copy_is_independent),
        cmocka_unit_test(missing_file_is_named),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
