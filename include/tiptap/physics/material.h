/* tiptap: a scene's materials as contact parameters ([tip] and [material NAME]).
 *
 * The reduced modulus of the pair is 1/K = 3/4 [(1 - nu_tip^2)/E_tip +
 * (1 - nu_sample^2)/E_sample] (seed section 2.2.1), unless the material gives
 * reduced_modulus directly; the radius is the tip's (a flat sample).
 * A scene without any [material] section has one material, "sample", with the
 * schema's defaults. Strings returned belong to the scene.
 */
#ifndef TIPTAP_MATERIAL_H
#define TIPTAP_MATERIAL_H

#include <stddef.h>

#include "tiptap/physics/contact.h"
#include "tiptap/config/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

size_t tt_material_count(const tt_scene *s);
const char *tt_material_name(const tt_scene *s, size_t i);

/* Contact parameters and the interaction quality factor (NAN when absent) of a named
 * material. Errors name the file, the section and the key. */
int tt_material_params(const tt_scene *s, const char *name, tt_contact_params *p, double *Qi);

#ifdef __cplusplus
}
#endif
#endif
