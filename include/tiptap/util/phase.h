/* tiptap: phases compared modulo a turn. */
#ifndef TIPTAP_UTIL_PHASE_H
#define TIPTAP_UTIL_PHASE_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* The distance of two phases in degrees, in [0, 180]: phases a turn apart are the same
 * phase (an oscillation nearly stopped, or a phase near +-180 deg, may land on either
 * side of the cut). */
double tt_phase_diff_deg(double a, double b);

TT_END_DECLS
#endif
