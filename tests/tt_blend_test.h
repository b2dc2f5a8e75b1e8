/* The polymer blend's two materials (surfaces/polymer-blend.ini) under the standard tip,
 * as scene text for the force tests. */
#ifndef TT_BLEND_TEST_H
#define TT_BLEND_TEST_H

#define TT_TEST_BLEND_MATERIALS                                                                              \
    "[tip]\nradius = 10 nm\n"                                                                                \
    "[material matrix]\nyoungs_modulus = 100 MPa\npoisson_ratio = 0.49\nadhesion_energy = 60 mJ/m^2\n"       \
    "interatomic_distance = 0.3 nm\ninteraction_quality_factor = 10\n"                                       \
    "[material disk]\nyoungs_modulus = 3 GPa\npoisson_ratio = 0.35\nadhesion_energy = 40 mJ/m^2\n"           \
    "interatomic_distance = 0.3 nm\n"

#endif
