/* What `tiptap keys` says a key's value looks like (tt_scene_key_describe): a key
 * without a unit is "a number, no unit" with an example of its own, which the key takes
 * (before, every one read "a plain number such as '400'", poisson_ratio and lambda
 * included, where 400 is refused or absurd); a key with a unit keeps its unit's words. */
#include "tt_test.h"
#include "tiptap/config/scene.h"
#include "tiptap/config/units.h"
#include "tiptap/util/error.h"

/* A scene with [material x], whose keys --set may change. */
static tt_scene *with_material(void)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, "[material x]\nyoungs_modulus = 1 GPa\n", "x"), TT_OK);
    return s;
}

/* Every 'quoted' example in text, set as the value of section.key: each accepted. */
static int examples_taken(const tt_scene_section *sec, const tt_scene_key *k, const char *text)
{
    int n = 0;
    for (const char *p = strchr(text, '\''); p; p = strchr(p, '\'')) {
        const char *q = strchr(p + 1, '\'');
        assert_non_null(q);
        char set[256];
        snprintf(set, sizeof set, "%s%s.%s=%.*s", sec->name, sec->named ? ".x" : "", k->key,
                 (int)(q - p - 1), p + 1);
        tt_scene *s = with_material();
        if (tt_scene_set(s, set) != TT_OK)
            fail_msg("%s: refused: %s", set, tt_error_message());
        tt_scene_free(s);
        n++;
        p = q + 1;
    }
    return n;
}

static void unitless_keys_have_their_own_examples(void **st)
{
    (void)st;
    size_t n, seen = 0;
    const tt_scene_section *sec = tt_scene_schema(&n);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < sec[i].nkeys; j++) {
            const tt_scene_key *k = &sec[i].keys[j];
            if (k->kind != TT_KEY_QUANTITY || !(k->dims & TT_DIM_NONE))
                continue;
            const char *d = tt_scene_key_describe(k);
            print_message("[%s] %s: %s\n", sec[i].name, k->key, d);
            if (!strstr(d, "no unit") && !strstr(d, "a fraction such as"))
                fail_msg("[%s] %s: '%s' does not say it takes no unit", sec[i].name, k->key, d);
            assert_null(strstr(d, "plain number"));
            assert_true(examples_taken(&sec[i], k, d) >= 1);
            seen++;
        }
    assert_true(seen >= 14);
    /* and the examples are checked: one out of range is refused */
    tt_scene *s = with_material();
    assert_int_not_equal(tt_scene_set(s, "material.x.poisson_ratio=400"), TT_OK);
    assert_int_equal(tt_scene_set(s, "material.x.poisson_ratio=0.49"), TT_OK);
    tt_scene_free(s);
}

static void poisson_ratio_and_lambda(void **st)
{
    (void)st;
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    int found = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < sec[i].nkeys; j++) {
            const tt_scene_key *k = &sec[i].keys[j];
            if (strcmp(k->key, "poisson_ratio") == 0) {
                assert_string_equal(tt_scene_key_describe(k), "a number, no unit, such as '0.3'");
                found++;
            } else if (strcmp(k->key, "lambda") == 0) {
                assert_string_equal(tt_scene_key_describe(k), "a number, no unit, such as '1'");
                found++;
            } else if (strcmp(k->key, "radius") == 0 && strcmp(sec[i].name, "tip") == 0) {
                assert_string_equal(tt_scene_key_describe(k), "a length such as '0.265 nm'");
                found++;
            }
        }
    assert_int_equal(found, 4);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(unitless_keys_have_their_own_examples),
        cmocka_unit_test(poisson_ratio_and_lambda),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
