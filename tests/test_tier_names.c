/* The tiers' names are one table (solver/tier.c): each name parses back to its tier, and
 * the scene's [solver] tier offers exactly those names, in the table's order. */
#include "tt_test.h"
#include "tiptap/config/scene.h"
#include "tiptap/solver/integrator.h"

#include <string.h>

static void each_name_parses_to_its_tier(void **st)
{
    (void)st;
    assert_int_equal(tt_tier_count(), TT_TIER_COUNT);
    assert_string_equal(tt_tier_name(TT_TIER_EVERY), "every");
    assert_string_equal(tt_tier_name(TT_TIER_ENVELOPE), "envelope");
    assert_string_equal(tt_tier_name(TT_TIER_AVERAGED), "averaged");
    assert_string_equal(tt_tier_name((tt_tier)TT_TIER_COUNT), "?");
    for (int i = 0; i < tt_tier_count(); i++) {
        tt_tier t = (tt_tier)-1;
        assert_int_equal(tt_tier_parse(tt_tier_name((tt_tier)i), &t), 0);
        assert_int_equal((int)t, i);
    }
    tt_tier t = TT_TIER_ENVELOPE;
    assert_int_equal(tt_tier_parse("every cycle", &t), -1);
    assert_int_equal(tt_tier_parse(NULL, &t), -1);
    assert_int_equal((int)t, TT_TIER_ENVELOPE);
}

static void the_scene_key_offers_the_tables_names(void **st)
{
    (void)st;
    char want[128] = "";
    for (int i = 0; i < tt_tier_count(); i++) {
        strcat(want, i ? "|" : "");
        strcat(want, tt_tier_name((tt_tier)i));
    }
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    const char *choices = NULL;
    for (size_t i = 0; i < n; i++)
        for (size_t k = 0; strcmp(sec[i].name, "solver") == 0 && k < sec[i].nkeys; k++)
            if (strcmp(sec[i].keys[k].key, "tier") == 0)
                choices = sec[i].keys[k].choices;
    assert_non_null(choices);
    assert_string_equal(choices, want);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(each_name_parses_to_its_tier),
        cmocka_unit_test(the_scene_key_offers_the_tables_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
