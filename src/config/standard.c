/* The standard tapping scene (see include/tiptap/config/standard.h). */
#include "tiptap/config/standard.h"

const char *tt_standard_scene(void)
{
    return "; the standard tapping scene of tiptap's benchmark and accuracy study\n"
           "[cantilever]\n"
           "spring_constant = 40 N/m\n"
           "resonance_frequency = 300 kHz\n"
           "quality_factor = 400\n"
           "free_amplitude = 20 nm\n"
           "drive = base\n"
           "\n[tip]\n"
           "radius = 10 nm\n"
           "youngs_modulus = 169 GPa\n"
           "poisson_ratio = 0.27\n"
           "\n[material polymer]\n"
           "youngs_modulus = 2 GPa\n"
           "poisson_ratio = 0.35\n"
           "adhesion_energy = 40 mJ/m^2\n"
           "interatomic_distance = 0.265 nm\n"
           "interaction_quality_factor = 2\n"
           "\n[approach]\n"
           "from = 16 nm\n"
           "to = 16 nm\n"
           "points = 1\n"
           "\n[trace]\n"
           "separation = 16 nm\n";
}
