/* Phases compared modulo a turn (see include/tiptap/util/phase.h). */
#include "tiptap/util/phase.h"

#include <math.h>

/* remainder() is exact, so this equals min(fmod(|a - b|, 360), 360 - fmod(|a - b|, 360))
 * to the bit. */
double tt_phase_diff_deg(double a, double b)
{
    return fabs(remainder(a - b, 360.0));
}
