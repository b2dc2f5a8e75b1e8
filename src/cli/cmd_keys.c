/* tiptap keys: print the scene schema (sections, keys, units, defaults, ranges). */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "commands.h"

static void help(void)
{
    printf("Usage: tiptap keys [--markdown]\n"
           "Lists every scene section and key: kind, default, meaning.\n"
           "  --markdown  as the tables of docs/scene-format.md\n");
}

int cmd_keys(int argc, char **argv)
{
    static const struct option opts[] = {{"markdown", no_argument, NULL, 'm'}, {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"keys", 0, opts, "m", help};
    cli_args args = {0}; /* no --set: nothing to free */
    int c, markdown = 0;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0)
        markdown = 1; /* 'm', its only option */
    if (c == CLI_EXIT)
        return args.exit;
    if (cli_no_operands("keys", argc, argv, optind, "it lists the schema, not a scene"))
        return CLI_USAGE;
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    if (markdown) {
        for (size_t i = 0; i < n; i++) {
            printf("### [%s%s]\n\n%s.\n\n| key | value | default | meaning |\n|---|---|---|---|\n",
                   sec[i].name, sec[i].named ? " NAME" : "", sec[i].doc);
            for (size_t k = 0; k < sec[i].nkeys; k++) {
                const tt_scene_key *key = &sec[i].keys[k];
                const char *kind = key->kind == TT_KEY_ENUM     ? key->choices
                                   : key->kind == TT_KEY_INT    ? "integer"
                                   : key->kind == TT_KEY_BOOL   ? "yes/no"
                                   : key->kind == TT_KEY_STRING ? "text"
                                                                : tt_scene_key_describe(key);
                printf("| `%s` | ", key->key);
                for (const char *p = kind; *p; p++)
                    fputs(*p == '|' ? "\\|" : (char[]){*p, 0}, stdout);
                printf(" | %s | %s |\n", key->def ? key->def : "(none)", key->doc);
            }
            printf("\n");
        }
        return CLI_OK;
    }
    for (size_t i = 0; i < n; i++) {
        printf("[%s%s]  %s\n", sec[i].name, sec[i].named ? " NAME" : "", sec[i].doc);
        for (size_t k = 0; k < sec[i].nkeys; k++) {
            const tt_scene_key *key = &sec[i].keys[k];
            const char *kind = key->kind == TT_KEY_ENUM     ? key->choices
                               : key->kind == TT_KEY_INT    ? "integer"
                               : key->kind == TT_KEY_BOOL   ? "yes|no"
                               : key->kind == TT_KEY_STRING ? "text"
                                                            : tt_scene_key_describe(key);
            printf("  %-28s default %-12s %s; %s\n", key->key, key->def ? key->def : "(none)", kind,
                   key->doc);
        }
    }
    return CLI_OK;
}
