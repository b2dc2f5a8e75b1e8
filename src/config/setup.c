/* A scene made ready to run (see include/tiptap/config/setup.h). */
#include "tiptap/config/setup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "tiptap/config/config.h"

struct tt_setup {
    tt_scene *scene;
    tt_cantilever cantilever;
    tt_solver solver;
    tt_sim *sim;
    size_t nmaterials;
    tt_material *materials; /* in scene order */
    tt_contact **contacts;  /* every material's, built up front */
    long current;           /* material under the tip, -1 for none */
};

/* Read every material again and rebuild the force laws of those which; which NULL:
 * all of them. */
static int build_materials(tt_setup *st, const char *which)
{
    tt_material *m;
    size_t n;
    int rc = tt_config_materials(st->scene, &m, &n);
    if (rc)
        return rc;
    if (st->materials && n != st->nmaterials) {
        free(m);
        return tt_error(TT_EINVAL, "internal: the materials changed in number");
    }
    if (!st->contacts && !(st->contacts = calloc(n, sizeof *st->contacts))) {
        free(m);
        return tt_error_nomem("the force laws of %zu materials", n);
    }
    free(st->materials);
    st->materials = m;
    st->nmaterials = n;
    for (size_t i = 0; i < n; i++) {
        if (which && strcmp(which, m[i].name) != 0)
            continue;
        tt_contact *c;
        if (tt_contact_alloc(&c, &m[i].contact))
            return tt_scene_fail(st->scene, "material", m[i].name, NULL, "%s", tt_error_message());
        tt_contact_free(st->contacts[i]);
        st->contacts[i] = c;
    }
    return TT_OK;
}
#include "tiptap/config/solver_scene.h"

int tt_setup_alloc(tt_setup **out, tt_scene *scene)
{
    *out = NULL;
    tt_setup *st = calloc(1, sizeof *st);
    if (!st)
        return tt_error_nomem("the run's setup of %s", tt_scene_origin(scene));
    st->scene = scene;
    st->current = -1;
    int rc;
    if ((rc = tt_config_cantilever(scene, &st->cantilever)) ||
        (rc = tt_solver_from_scene(&st->solver, scene)) || (rc = build_materials(st, NULL)) ||
        (rc = tt_sim_alloc(&st->sim, &st->cantilever, &st->solver))) {
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
    for (size_t i = 0; i < st->nmaterials && st->contacts; i++)
        tt_contact_free(st->contacts[i]);
    free(st->contacts);
    free(st->materials);
    tt_sim_free(st->sim);
    free(st);
}

tt_sim *tt_setup_sim(const tt_setup *st) { return st->sim; }
const tt_cantilever *tt_setup_cantilever(const tt_setup *st) { return &st->cantilever; }
const tt_solver *tt_setup_solver(const tt_setup *st) { return &st->solver; }
size_t tt_setup_materials(const tt_setup *st) { return st->nmaterials; }

const tt_material *tt_setup_material(const tt_setup *st, size_t i)
{
    return i < st->nmaterials ? &st->materials[i] : NULL;
}

const tt_contact *tt_setup_contact(const tt_setup *st, size_t i)
{
    return i < st->nmaterials ? st->contacts[i] : NULL;
}

int tt_setup_viscous(const tt_setup *st)
{
    for (size_t i = 0; i < st->nmaterials; i++)
        if (tt_material_viscous(tt_setup_material(st, i)))
            return 1;
    return 0;
}

int tt_setup_find_material(const tt_setup *st, const char *name, const char *key_section,
                           const char *key, size_t *index)
{
    if (!name) {
        *index = 0;
        return TT_OK;
    }
    for (size_t i = 0; i < st->nmaterials; i++)
        if (strcmp(st->materials[i].name, name) == 0) {
            *index = i;
            return TT_OK;
        }
    return tt_scene_fail(st->scene, key_section, NULL, key,
                         "no [material %s] section in the scene", name);
}

int tt_setup_use_material(tt_setup *st, size_t i)
{
    if (i >= st->nmaterials)
        return tt_error(TT_EINVAL, "material index %zu out of range", i);
    tt_sim_set_contact(st->sim, st->contacts[i], st->materials[i].Qi);
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
                    for (unsigned d = 1; d <= TT_DIM_VISCOSITY; d <<= 1)
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
        if ((rc = tt_config_cantilever(st->scene, &c)))
            return rc;
        if (fabs(c.T - st->cantilever.T) > 1e-15 * st->cantilever.T)
            return tt_error(TT_EINVAL, "%s: a ramp may not change the drive frequency", key);
        st->cantilever = c;
        tt_sim_set_cantilever(st->sim, &c);
        return TT_OK;
    }
    if (strcmp(section, "material") == 0 || strcmp(section, "tip") == 0) {
        if ((rc = build_materials(st, section[0] == 't' ? NULL : name)))
            return rc;
        /* the old force law is gone: the sim must hold the new one */
        if (st->current >= 0 &&
            (section[0] == 't' || strcmp(st->materials[st->current].name, name) == 0))
            tt_sim_set_contact(st->sim, st->contacts[st->current], st->materials[st->current].Qi);
        return TT_OK;
    }
    return tt_error(TT_EINVAL, "%s: only [cantilever], [tip] and [material] keys can be ramped", key);
}
