/* tiptap: the standard tapping scene used by the benchmark and the accuracy study:
 * 300 kHz, Q 400, 40 N/m, 20 nm free amplitude, silicon tip of 10 nm radius on a
 * glassy polymer with adhesion (2 GPa, 40 mJ/m^2, Maugis-Dugdale), tapping at 16 nm
 * rest separation (about 80 % of the free amplitude). */
#ifndef TIPTAP_STANDARD_H
#define TIPTAP_STANDARD_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* INI text of the standard scene (static storage). */
const char *tt_standard_scene(void);

TT_END_DECLS
#endif
