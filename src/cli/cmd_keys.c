/* tiptap keys: print the scene schema (sections, keys, units, defaults, ranges). */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "commands.h"

int cmd_keys(int argc, char **argv)
{
    static const struct option opts[] = {{"help", no_argument, NULL, 'h'}, {NULL, 0, NULL, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        if (c == 'h') {
            printf("Usage: tiptap keys\nLists every scene section and key: kind, default, meaning.\n");
            return CLI_OK;
        }
        return CLI_USAGE;
    }
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    for (size_t i = 0; i < n; i++) {
        printf("[%s%s]  %s\n", sec[i].name, sec[i].named ? " NAME" : "", sec[i].doc);
        for (size_t k = 0; k < sec[i].nkeys; k++) {
            const tt_scene_key *key = &sec[i].keys[k];
            const char *kind = key->kind == TT_KEY_ENUM     ? key->choices
                               : key->kind == TT_KEY_INT    ? "integer"
                               : key->kind == TT_KEY_BOOL   ? "yes|no"
                               : key->kind == TT_KEY_STRING ? "text"
                                                            : tt_units_describe(key->dims);
            printf("  %-28s default %-12s %s; %s\n", key->key, key->def ? key->def : "(none)", kind,
                   key->doc);
        }
    }
    return CLI_OK;
}
