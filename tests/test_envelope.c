/* The envelope tier ([solver] tier = envelope) against the every-cycle tier: on a
 * uniform sample, over height and material edges, on the bistable scene and where the
 * tip grazes a sticky sample (touching in some cycles, not in others) its images
 * agree with the every-cycle tier's within the envelope run's own error estimate (the
 * companion line), at Q 1e4, 10 and 1 too; and its images are the same on one thread
 * as on two. Noise: tests/test_envelope_noise.c. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/scan.h"

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
    "free_amplitude = 20 nm\n"
    "[material soft]\nyoungs_modulus = 0.5 GPa\nadhesion_energy = 30 mJ/m^2\n"
    "interaction_quality_factor = 10\n"
    "[material stiff]\nyoungs_modulus = 3 GPa\nadhesion_energy = 40 mJ/m^2\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 1\nline_rate = 8 Hz\nsettle_cycles = 2000\n"
    "channels = height, error, phase, peak_force\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

static tt_scan *scan_with(const char *b, const char *extra, const char *solver, tt_scene **sc)
{
    char text[2048];
    snprintf(text, sizeof text, "%s\n[solver]\n%s\n", extra, solver);
    return tt_run_scan(b, text, sc);
}

/* The envelope run against the every-cycle run at the same tolerance: their difference
 * is within the envelope run's own error estimate (the companion line); and the
 * envelope tier skipped at least the given share of the cycles. */
static void agrees(const char *b, const char *extra, double skipped_at_least)
{
    tt_scene *s1, *s2, *s3;
    tt_scan *env = scan_with(b, extra, "tier = envelope", &s1);
    tt_scan *every = scan_with(b, extra, "tier = every", &s2);
    tt_scan *ref = scan_with(b, extra, "tolerance = 1e-11", &s3);
    tt_scan_error e;
    assert_int_equal(tt_scan_estimate_error(env, &e), TT_OK);
    double frac = 1 - (double)tt_scan_cycles_integrated(env) / (double)tt_scan_cycles(env);
    print_message("cycles %ld, integrated %ld (%.1f %% skipped)\n", tt_scan_cycles(env),
                  tt_scan_cycles_integrated(env), 100 * frac);
    assert_int_equal(tt_scan_cycles(env), tt_scan_cycles(every));
    assert_true(frac >= skipped_at_least);
    const double est[3][2] = {{e.height_max, e.height_rms},
                              {e.amplitude_max * 20e-9, e.amplitude_rms * 20e-9},
                              {e.phase_max, e.phase_rms}};
    const char *name[3] = {"height (m)", "amplitude (m)", "phase (deg)"};
    for (int c = 0; c < 3; c++) {
        double dm, dr, rm, rr;
        tt_scan_diff(env, every, c, &dm, &dr);
        tt_scan_diff(every, ref, c, &rm, &rr);
        print_message("%-14s envelope - every: max %.3g rms %.3g; estimate max %.3g rms %.3g; "
                      "every - reference: max %.3g rms %.3g\n",
                      name[c], dm, dr, est[c][0], est[c][1], rm, rr);
        /* height and phase within the estimate alone; the amplitude's estimate on a
         * uniform sample is rounding (1e-17 m), so the every-cycle run's error is its
         * floor */
        double floor_max = c == 1 ? rm : 0, floor_rms = c == 1 ? rr : 0;
        assert_true(dm <= est[c][0] + floor_max);
        assert_true(dr <= est[c][1] + floor_rms);
    }
    tt_scan_free(env);
    tt_scan_free(every);
    tt_scan_free(ref);
    tt_scene_free(s1);
    tt_scene_free(s2);
    tt_scene_free(s3);
}

static void uniform_sample(void **st)
{
    (void)st;
    agrees(base, "[surface]\nmap = uniform\n", 0.5);
}

static void height_and_material_edges(void **st)
{
    (void)st;
    agrees(base,
           "[surface]\ntype = steps\nstep_height = 1 nm\nstep_width = 300 nm\n"
           "map = stripes\nmap_materials = soft, stiff\nmap_period = 500 nm\n",
           0.3);
}

/* examples/extreme/bistable.ini's cantilever and sample, imaged on the repulsive
 * branch over steps. */
static void bistable(void **st)
{
    (void)st;
    static const char *b =
        "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\n"
        "quality_factor = 400\nfree_amplitude = 5 nm\n"
        "[tip]\nradius = 10 nm\n"
        "[material silicon]\nyoungs_modulus = 100 GPa\npoisson_ratio = 0.27\n"
        "adhesion_energy = 40 mJ/m^2\n"
        "[scan]\nsize = 1 um\npixels = 32\nlines = 1\nline_rate = 8 Hz\nsettle_cycles = 2000\n"
        "channels = height, error, phase\n"
        "[feedback]\nsetpoint = 60 %\nintegral_gain = 3000 Hz\n";
    agrees(b, "[surface]\ntype = steps\nstep_height = 0.5 nm\nstep_width = 300 nm\n", 0.3);
}

/* The polymer blend's soft, sticky matrix (surfaces/polymer-blend.ini) at 80 %: the tip
 * touches in some cycles and not in others, and the tier follows each branch
 * (tiptap/solver/graze.h): before, it integrated every one of these cycles. */
static void grazing_touches(void **st)
{
    (void)st;
    static const char *b =
        "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\n"
        "quality_factor = 400\nfree_amplitude = 20 nm\n"
        "[material matrix]\nyoungs_modulus = 100 MPa\npoisson_ratio = 0.49\n"
        "adhesion_energy = 60 mJ/m^2\ninteratomic_distance = 0.3 nm\n"
        "interaction_quality_factor = 10\n"
        "[scan]\nsize = 1 um\npixels = 32\nlines = 1\nline_rate = 8 Hz\nsettle_cycles = 2000\n"
        "channels = height, error, phase, peak_force\n"
        "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";
    agrees(b, "[surface]\nmap = uniform\n", 0.9);
}

/* examples/extreme's Q 10 and Q 1 (liquid-q1.ini): the map contracts within a few
 * cycles and the model follows it (every cycle was integrated below Q 30 before). */
static void low_q(void **st)
{
    (void)st;
    agrees(base,
           "[cantilever]\nquality_factor = 10\n[scan]\nline_rate = 40 Hz\n"
           "[surface]\ntype = steps\nstep_height = 1 nm\nstep_width = 300 nm\n",
           0.4);
    agrees(base,
           "[cantilever]\nquality_factor = 1\n[scan]\nline_rate = 40 Hz\n"
           "[feedback]\nintegral_gain = 300 Hz\n"
           "[surface]\ntype = steps\nstep_height = 1 nm\nstep_width = 300 nm\n",
           0.15);
}

/* examples/extreme/vacuum-q1e4.ini's quality factor: the envelope's transients last the
 * whole line, and a stretch's checks bound its drift (scan_envelope.c); before, every
 * cycle was integrated above Q 3000. */
static void high_q(void **st)
{
    (void)st;
    agrees(base,
           "[cantilever]\nquality_factor = 1e4\n[feedback]\nintegral_gain = 30 Hz\n"
           "[scan]\nsettle_cycles = 20000\n"
           "[surface]\ntype = steps\nstep_height = 0.5 nm\nstep_width = 300 nm\n",
           0.5);
}

/* Two lines on one thread and on two: the same images. */
static void threads_agree(void **st)
{
    (void)st;
    tt_scan_assert_threads_agree(base,
                                 "[scan]\nlines = 2\nline_rate = 20 Hz\n"
                                 "[surface]\ntype = steps\nstep_height = 1 nm\n"
                                 "step_width = 300 nm\n[solver]\ntier = envelope\n",
                                 3, 1);
}

TT_TEST_MAIN(cmocka_unit_test(uniform_sample),
             cmocka_unit_test(height_and_material_edges),
             cmocka_unit_test(bistable),
             cmocka_unit_test(grazing_touches),
             cmocka_unit_test(high_q),
             cmocka_unit_test(low_q),
             cmocka_unit_test(threads_agree))
