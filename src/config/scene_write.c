/* The effective scene: every key of the scene written back as scene text, defaults
 * included (of [surface], only the chosen type's) and paths made absolute, so that the file reproduces the run from anywhere
 * (see include/tiptap/config/scene.h). */
#include "scene_private.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

static int wanted(const char *sections, const char *name)
{
    if (!sections)
        return 1;
    return scene_enum_has(sections, name);
}

/* Defaults that do not apply when another key of the same section is given: writing
 * them out would make the effective scene contradict itself. */
static const struct {
    const char *section, *key, *given;
} yields[] = {
    {"material", "youngs_modulus", "reduced_modulus"},
    {"material", "poisson_ratio", "reduced_modulus"},
};

static int default_yields(const tt_scene *s, const char *section, const char *name,
                          const char *key)
{
    for (size_t i = 0; i < sizeof yields / sizeof yields[0]; i++)
        if (strcmp(yields[i].section, section) == 0 && strcmp(yields[i].key, key) == 0 &&
            tt_scene_has(s, section, name, yields[i].given))
            return 1;
    return 0;
}

int tt_scene_write(const tt_scene *s, FILE *out, const char *sections)
{
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    fprintf(out, "; effective scene written by tiptap: every key the surface type reads, defaults included\n");
    for (size_t i = 0; i < n; i++) {
        if (!wanted(sections, sec[i].name))
            continue;
        size_t names = sec[i].named ? tt_scene_count_named(s, sec[i].name) : 1;
        for (size_t j = 0; j < names; j++) {
            const char *name = sec[i].named ? tt_scene_named(s, sec[i].name, j) : NULL;
            if (name)
                fprintf(out, "\n[%s %s]\n", sec[i].name, name);
            else
                fprintf(out, "\n[%s]\n", sec[i].name);
            for (size_t k = 0; k < sec[i].nkeys; k++) {
                const entry *e = scene_find_entry(s, sec[i].name, name, sec[i].keys[k].key);
                const char *v = e ? e->value : sec[i].keys[k].def;
                if (!e && default_yields(s, sec[i].name, name, sec[i].keys[k].key))
                    continue;
                /* another surface type's key is read by nothing: written, it is only
                 * noise, and given with a value it would be refused on reading back */
                if (strcmp(sec[i].name, "surface") == 0 &&
                    !scene_surface_key_applies(s, sec[i].keys[k].key))
                    continue;
                char path[4096], abs[4096];
                if (e && (sec[i].keys[k].flags & TT_KEY_PATH) &&
                    tt_scene_get_path(s, sec[i].name, name, sec[i].keys[k].key, path, sizeof path) ==
                        TT_OK) {
                    /* the written scene lives elsewhere: name files absolutely */
                    v = realpath(path, abs) ? abs : path;
                }
                if (v)
                    fprintf(out, "%s = %s\n", sec[i].keys[k].key, v);
            }
        }
    }
    return ferror(out) ? tt_error(TT_EIO, "could not write the scene") : TT_OK;
}

char *tt_scene_write_string(const tt_scene *s, const char *sections)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) {
        tt_error_nomem("the effective scene's text");
        return NULL;
    }
    int rc = tt_scene_write(s, f, sections);
    if (fclose(f) != 0 && rc == TT_OK)
        rc = tt_error_nomem("the effective scene's text");
    if (rc) {
        free(text);
        return NULL;
    }
    return text;
}
