/* docs/scene-format.md documents every section and key of the schema. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/scene.h"

static void every_key_is_documented(void **st)
{
    (void)st;
    FILE *f = fopen(TT_SOURCE_DIR "/docs/scene-format.md", "r");
    assert_non_null(f);
    static char doc[1 << 20];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    doc[n] = '\0';
    fclose(f);
    size_t ns;
    const tt_scene_section *sec = tt_scene_schema(&ns);
    char buf[256];
    for (size_t i = 0; i < ns; i++) {
        snprintf(buf, sizeof buf, "### [%s", sec[i].name);
        if (!strstr(doc, buf))
            fail_msg("section [%s] is not documented", sec[i].name);
        for (size_t k = 0; k < sec[i].nkeys; k++) {
            snprintf(buf, sizeof buf, "| `%s` |", sec[i].keys[k].key);
            if (!strstr(doc, buf))
                fail_msg("[%s] %s is not documented (run: tiptap keys --markdown)", sec[i].name,
                         sec[i].keys[k].key);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(every_key_is_documented)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
