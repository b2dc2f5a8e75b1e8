/* tiptap: a scene made ready to run one cantilever: its constants, its solver, every
 * material's force law and the simulation, built once from a scene.
 *
 * Every material's force law is built when the setup is made, used or not, so that a
 * bad material is refused before anything runs (a material without adhesion builds no
 * table at all).
 *
 * Ownership: tt_setup_alloc borrows the scene (it must outlive the setup and may be
 * changed through tt_setup_apply); everything else belongs to the setup and is freed
 * by tt_setup_free. Pointers the accessors return live as long as the setup.
 */
#ifndef TIPTAP_SETUP_H
#define TIPTAP_SETUP_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/scene.h"
#include "tiptap/physics/cantilever.h"
#include "tiptap/physics/contact.h"
#include "tiptap/physics/material.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

typedef struct tt_setup tt_setup;

int tt_setup_alloc(tt_setup **out, tt_scene *scene);
void tt_setup_free(tt_setup *st);

/* The simulation (its force law: the material last put under the tip). */
tt_sim *tt_setup_sim(const tt_setup *st);
const tt_cantilever *tt_setup_cantilever(const tt_setup *st);
const tt_solver *tt_setup_solver(const tt_setup *st);
/* The materials in scene order, and material i's force law. */
size_t tt_setup_materials(const tt_setup *st);
const tt_material *tt_setup_material(const tt_setup *st, size_t i);
const tt_contact *tt_setup_contact(const tt_setup *st, size_t i);
/* 1 when some material of the scene is viscous (tt_material_viscous). */
int tt_setup_viscous(const tt_setup *st);

/* Index of a material by name; name NULL means the first. TT_EINVAL naming the
 * section and key (key_section, key) that asked for it when unknown. */
int tt_setup_find_material(const tt_setup *st, const char *name, const char *key_section,
                           const char *key, size_t *index);

/* Put material i's force law under the tip. */
int tt_setup_use_material(tt_setup *st, size_t i);

/* Set a number-valued key ("cantilever.spring_constant",
 * "material.glass.adhesion_energy") to an SI value and rebuild what depends on it
 * (used for ramps, Burnham et al.'s figures 5 to 8). */
int tt_setup_apply(tt_setup *st, const char *key, double value);

/* Parse a ramp key and value text as the schema reads that key. */
int tt_setup_parse_key_value(const tt_setup *st, const char *key, const char *text, double *value);

TT_END_DECLS
#endif
