/* tiptap: the scene's [trace] section read into tt_trace_params.
 *
 * Ownership: the material and ramp texts in the parameters point into the scene,
 * which must outlive them.
 */
#ifndef TIPTAP_READ_TRACE_H
#define TIPTAP_READ_TRACE_H

#include "tiptap/export.h"
#include "tiptap/config/scene.h"
#include "tiptap/instrument/trace.h"

TT_BEGIN_DECLS

/* Fill p from [trace]: separation_end defaults to separation; ramp_from and ramp_to
 * are parsed as values of the ramped key, in SI. TT_EINVAL with "file: [trace] key:
 * what is wrong" (a ramp without both ends, a value the ramped key cannot take). */
int tt_config_trace(const tt_scene *s, tt_trace_params *p);

TT_END_DECLS
#endif
