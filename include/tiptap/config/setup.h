/* tiptap: a scene made ready to run: cantilever, solver, the materials' force laws
 * and the simulation state, built once from a scene.
 *
 * Force laws are built lazily, only for the materials a run uses (a uniform sample
 * builds one table; a material without adhesion builds none at all).
 *
 * Ownership: tt_setup_alloc borrows the scene (it must outlive the setup and may be
 * changed through tt_setup_apply); everything else belongs to the setup and is freed
 * by tt_setup_free.
 */
#ifndef TIPTAP_SETUP_H
#define TIPTAP_SETUP_H

#include <stddef.h>

#include "tiptap/physics/cantilever.h"
#include "tiptap/physics/contact.h"
#include "tiptap/solver/integrator.h"
#include "tiptap/config/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    tt_scene *scene;
    tt_cantilever cantilever;
    tt_solver solver;
    tt_sim *sim;
    size_t nmaterials;
    const char **names;     /* material names in scene order */
    tt_contact **contacts;  /* built on first use; NULL until then */
    double *Qi;             /* interaction quality factors (NAN: none) */
    long current;           /* material under the tip, -1 for none */
} tt_setup;

int tt_setup_alloc(tt_setup **out, tt_scene *scene);
void tt_setup_free(tt_setup *st);

/* Index of a material by name; name NULL means the first. TT_EINVAL naming the
 * section and key (key_section, key) that asked for it when unknown. */
int tt_setup_find_material(const tt_setup *st, const char *name, const char *key_section,
                           const char *key, size_t *index);

/* Build material i's force law if needed and put it under the tip. */
int tt_setup_use_material(tt_setup *st, size_t i);

/* Set a number-valued key ("cantilever.spring_constant",
 * "material.glass.adhesion_energy") to an SI value and rebuild what depends on it
 * (used for ramps, seed figures 5 to 8). */
int tt_setup_apply(tt_setup *st, const char *key, double value);

/* Parse a ramp key and value text as the schema reads that key. */
int tt_setup_parse_key_value(const tt_setup *st, const char *key, const char *text, double *value);

#ifdef __cplusplus
}
#endif
#endif
