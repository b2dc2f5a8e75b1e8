/* A scene made ready to run (see include/tiptap/config/setup.h). */
#include "tiptap/config/setup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "tiptap/physics/material.h"
#include "tiptap/config/solver_scene.h"

int tt_setup_alloc(tt_setup **out, tt_scene *scene)
{
    *out = NULL;
    tt_setup *st = calloc(1, sizeof *st);
    if (!st)
        return tt_error(TT_ENOMEM, "out of memory");
    st->scene = scene;
    st->current = -1;
    int rc;
    if ((rc = tt_cantilever_from_scene(&st->cantilever, scene)) ||
        (rc = tt_solver_from_scene(&st->solver, scene))) {
        free(st);
        return rc;
    }
    st->nmaterials = tt_material_count(scene);
    st->names = calloc(st->nmaterials, sizeof *st->names);
    st->contacts = calloc(st->nmaterials, sizeof *st->contacts);
    st->Qi = calloc(st->nmaterials, sizeof *st->Qi);
    if (!st->names || !st->contacts || !st->Qi) {
        tt_setup_free(st);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    for (size_t i = 0; i < st->nmaterials; i++) {
        st->names[i] = tt_material_name(scene, i);
        st->Qi[i] = NAN;
    }
    if ((rc = tt_sim_alloc(&st->sim, &st->cantilever, &st->solver))) {
        tt_setup_free(st);
        return rc;
    }
    *out = st;
    return TT_OK;
}

void tt_setup_free(tt_setup *st)
{
    if (!st)
        return;
    for (size_t i = 0; i < st->nmaterials; i++)
        tt_contact_free(st->contacts ? st->contacts[i] : NULL);
    free(st->contacts);
    free(st->names);
    free(st->Qi);
    tt_sim_free(st->sim);
    free(st);
}

int tt_setup_find_material(const tt_setup *st, const char *name, const char *key_section,
                           const char *key, size_t *index)
{
    if (!name) {
        *index = 0;
        return TT_OK;
    }
    for (size_t i = 0; i < st->nmaterials; i++)
        if (strcmp(st->names[i], name) == 0) {
            *index = i;
            return TT_OK;
        }
    return tt_scene_fail(st->scene, key_section, NULL, key,
                         "no [material %s] section in the scene", name);
}

static int build_material(tt_setup *st, size_t i)
{
    tt_contact_params p;
    double Qi;
    int rc = tt_material_params(st->scene, st->names[i], &p, &Qi);
    if (rc)
        return rc;
    tt_contact *c;
    if ((rc = tt_contact_alloc(&c, &p)))
        return tt_scene_fail(st->scene, "material", st->names[i], NULL, "%s", tt_error_message());
    tt_contact_free(st->contacts[i]);
    st->contacts[i] = c;
    st->Qi[i] = Qi;
    return TT_OK;
}

int tt_setup_use_material(tt_setup *st, size_t i)
{
    if (i >= st->nmaterials)
        return tt_error(TT_EINVAL, "material index %zu out of range", i);
    if (!st->contacts[i]) {
        int rc = build_material(st, i);
        if (rc)
            return rc;
    }
    tt_sim_set_contact(st->sim, st->contacts[i], st->Qi[i]);
    st->current = (long)i;
    return TT_OK;
}

/* Split "section.key" or "section.name.key". */
static int split_key(const char *key, char *section, char *name, char *k, size_t len)
{
    const char *d1 = strchr(key, '.');
    if (!d1)
        return -1;
    const char *d2 = strrchr(key, '.');
    snprintf(section, len, "%.*s", (int)(d1 - key), key);
    if (d2 != d1)
        snprintf(name, len, "%.*s", (int)(d2 - d1 - 1), d1 + 1);
    else
        name[0] = '\0';
    snprintf(k, len, "%s", d2 + 1);
    return 0;
}

int tt_setup_parse_key_value(const tt_setup *st, const char *key, const char *text, double *value)
{
    char section[128], name[128], k[128];
    if (split_key(key, section, name, k, sizeof section) != 0)
        return tt_error(TT_EINVAL, "'%s': expected section.key or material.NAME.key", key);
    return tt_scene_parse_value(st->scene, section, k, text, value);
}

int tt_setup_apply(tt_setup *st, const char *key, double value)
{
    char section[128], name[128], k[128], assign[512];
    if (split_key(key, section, name, k, sizeof section) != 0)
        return tt_error(TT_EINVAL, "'%s': expected section.key or material.NAME.key", key);
    /* Through the scene, so that validation and units are the loader's: the value is
     * written in SI with the key's unit symbol. */
    size_t n;
    const tt_scene_section *sec = tt_scene_schema(&n);
    const char *unit = "";
    for (size_t i = 0; i < n; i++)
        if (strcmp(sec[i].name, section) == 0)
            for (size_t j = 0; j < sec[i].nkeys; j++)
                if (strcmp(sec[i].keys[j].key, k) == 0 && sec[i].keys[j].kind == TT_KEY_QUANTITY)
                    for (unsigned d = 1; d <= TT_DIM_FRACTION; d <<= 1)
                        if ((sec[i].keys[j].dims & d) && d != TT_DIM_NONE) {
                            unit = d == TT_DIM_FRACTION ? "" : tt_units_symbol((tt_dim)d);
                            break;
                        }
    snprintf(assign, sizeof assign, "%s=%.17g %s", key, value, unit);
    int rc = tt_scene_set(st->scene, assign);
    if (rc)
        return rc;
    if (strcmp(section, "cantilever") == 0) {
        tt_cantilever c;
        if ((rc = tt_cantilever_from_scene(&c, st->scene)))
            return rc;
        if (fabs(c.T - st->cantilever.T) > 1e-15 * st->cantilever.T)
            return tt_error(TT_EINVAL, "%s: a ramp may not change the drive frequency", key);
        st->cantilever = c;
        tt_sim_set_cantilever(st->sim, &c);
        return TT_OK;
    }
    if (strcmp(section, "material") == 0 || strcmp(section, "tip") == 0) {
        for (size_t i = 0; i < st->nmaterials; i++)
            if (st->contacts[i] && (section[0] == 't' || strcmp(st->names[i], name) == 0)) {
                if ((rc = build_material(st, i)))
                    return rc;
                /* the old force law is gone: the sim must hold the new one */
                if ((long)i == st->current)
                    tt_sim_set_contact(st->sim, st->contacts[i], st->Qi[i]);
            }
        return TT_OK;
    }
    return tt_error(TT_EINVAL, "%s: only [cantilever], [tip] and [material] keys can be ramped", key);
}
