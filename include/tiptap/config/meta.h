/* tiptap: a run's parameters as key/value metadata for the files it writes (GSF header
 * keys, .gwy metadata, HDF5 attributes) and for the Python package's results.
 *
 * tt_meta_scene lists first the given pairs (the program's version, lines finished),
 * then every key of the effective scene but its approach and trace sections (which a
 * scan does not use), as "section.key" or "material.NAME.key" (as --set spells it) = the
 * value with its unit, in the order tt_scene_write writes them.
 *
 * Ownership: the strings belong to the tt_meta; tt_meta_free frees them.
 */
#ifndef TIPTAP_META_H
#define TIPTAP_META_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/config/scene.h"

TT_BEGIN_DECLS

typedef struct {
    char **keys, **values;
    size_t n, cap;
} tt_meta;

int tt_meta_scene(tt_meta *m, const tt_scene *scene, const char *const *first_keys,
                  const char *const *first_values, size_t nfirst);
/* Append one pair (copied). */
int tt_meta_add(tt_meta *m, const char *key, const char *value);
void tt_meta_free(tt_meta *m);

TT_END_DECLS
#endif
