/* The run's parameters as metadata of the files a scan writes (GSF header keys, .gwy
 * metadata, HDF5 attributes): every key of the effective scene that the scan uses
 * (see include/tiptap/config/meta.h). */
#include "tiptap/config/meta.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

void tt_meta_free(tt_meta *m)
{
    for (size_t i = 0; i < m->n; i++) {
        free(m->keys[i]);
        free(m->values[i]);
    }
    free(m->keys);
    free(m->values);
    memset(m, 0, sizeof *m);
}

int tt_meta_add(tt_meta *m, const char *key, const char *value)
{
    if (m->n == m->cap) {
        size_t cap = m->cap ? 2 * m->cap : 64;
        char **k = realloc(m->keys, cap * sizeof *k);
        if (k)
            m->keys = k;
        char **v = realloc(m->values, cap * sizeof *v);
        if (v)
            m->values = v;
        if (!k || !v)
            return tt_error_nomem("the outputs' metadata");
        m->cap = cap;
    }
    char *k = tt_strdup(key), *v = tt_strdup(value);
    if (!k || !v) {
        free(k);
        free(v);
        return tt_error_nomem("the outputs' metadata");
    }
    m->keys[m->n] = k;
    m->values[m->n] = v;
    m->n++;
    return TT_OK;
}

/* "[material glass]" + "adhesion_energy = 20 mJ/m^2" -> "material.glass.adhesion_energy",
 * the value as the scene writes it (with its unit); the approach and trace sections,
 * which a scan does not use, are left out. */
int tt_meta_scene(tt_meta *m, const tt_scene *scene, const char *const *first_keys,
                  const char *const *first_values, size_t nfirst)
{
    memset(m, 0, sizeof *m);
    char *text = tt_scene_write_string(scene, NULL);
    int rc = text ? TT_OK : TT_ENOMEM;
    for (size_t i = 0; rc == TT_OK && i < nfirst; i++)
        rc = tt_meta_add(m, first_keys[i], first_values[i]);
    char section[256] = "", key[512];
    int skip = 1;
    for (char *line = text, *next; rc == TT_OK && line && *line; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = 0;
        char *eq = strstr(line, " = ");
        if (line[0] == '[' && strchr(line, ']')) {
            snprintf(section, sizeof section, "%.*s", (int)(strchr(line, ']') - line - 1), line + 1);
            skip = !strcmp(section, "approach") || !strcmp(section, "trace");
        } else if (!skip && eq && line[0] != ';' && line[0] != '#') {
            *eq = 0;
            /* the --set spelling: material.NAME.key, the name as it is (tt_scene_set
             * takes the last dot as the key's) */
            char *sp = strchr(section, ' ');
            if (sp)
                *sp = '.';
            snprintf(key, sizeof key, "%s.%s", section, line);
            rc = tt_meta_add(m, key, eq + 3);
        }
    }
    free(text);
    if (rc)
        tt_meta_free(m);
    return rc;
}
