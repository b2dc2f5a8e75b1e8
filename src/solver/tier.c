/* The tiers' names: the one table the scene's [solver] tier, the outputs and the
 * console read (see include/tiptap/solver/integrator.h). */
#include "tiptap/solver/integrator.h"

#include <string.h>

/* in enum order */
static const char *const tier_names[TT_TIER_COUNT] = {"every", "envelope", "averaged"};

const char *tt_tier_name(tt_tier t)
{
    return (int)t >= 0 && t < TT_TIER_COUNT ? tier_names[t] : "?";
}

int tt_tier_parse(const char *name, tt_tier *t)
{
    for (int i = 0; name && i < TT_TIER_COUNT; i++)
        if (strcmp(name, tier_names[i]) == 0) {
            *t = (tt_tier)i;
            return 0;
        }
    return -1;
}

int tt_tier_count(void) { return TT_TIER_COUNT; }
