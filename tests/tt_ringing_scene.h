/* The lesson's ringing loop for the tests: ki 10 kHz on the 20 nm grating, a 1 um line
 * of 16 pixels at 10 Hz, two continuous lines, the noise 1e9 times colder than the
 * lesson's (test_envelope_ringing.c, test_averaged_ring.c). */
#ifndef TT_RINGING_SCENE_H
#define TT_RINGING_SCENE_H

#define TT_RINGING_SCENE                                                                          \
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n" \
    "free_amplitude = 20 nm\ndrive = base\n"                                                        \
    "[tip]\nradius = 10 nm\nyoungs_modulus = 169 GPa\npoisson_ratio = 0.27\n"                      \
    "[material silicon]\nreduced_modulus = 100 GPa\nadhesion_energy = 20 mJ/m^2\n"                 \
    "interatomic_distance = 0.3 nm\n"                                                              \
    "[surface]\ntype = grating\nperiod = 1 um\nduty = 50 %\nheight = 20 nm\nedge_width = 0 nm\n"  \
    "[scan]\nsize = 1 um\npixels = 16\nlines = 2\nline_rate = 10 Hz\nretrace = yes\n"              \
    "channels = height, phase, peak_force\nlines_mode = continuous\n"                             \
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 10 kHz\n"                                        \
    "[noise]\nseed = 1\ntemperature = 3e-7 K\n"

#endif
