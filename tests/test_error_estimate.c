/* The run's error estimate (tt_scan_estimate_error) against the error measured against
 * an every-cycle reference at a tight tolerance: on a uniform sample, over height and
 * material edges, and at low Q it must never be below the measured error and within a
 * factor of ten of it. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/scan.h"

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material soft]\nyoungs_modulus = 0.5 GPa\nadhesion_energy = 30 mJ/m^2\n"
    "interaction_quality_factor = 10\n"
    "[material stiff]\nyoungs_modulus = 3 GPa\nadhesion_energy = 40 mJ/m^2\n"
    "[scan]\nsize = 1 um\npixels = 16\nlines = 1\nline_rate = 40 Hz\nsettle_cycles = 2000\n"
    "channels = height, error, phase\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

/* The estimate lies between the measured error and ten times it. */
static void check(const char *what, double est, double meas)
{
    print_message("%-22s estimate %.3g measured %.3g ratio %.2f\n", what, est, meas, est / meas);
    assert_true(est >= meas);
    assert_true(est <= 10 * meas);
}

static void estimate_brackets_error(const char *extra)
{
    char text[1024];
    tt_scene *sc, *rsc;
    tt_scan *run = tt_run_scan(base, extra, &sc);
    snprintf(text, sizeof text, "%s\n[solver]\ntolerance = 1e-11\n", extra);
    tt_scan *ref = tt_run_scan(base, text, &rsc);
    tt_scan_error e;
    assert_int_equal(tt_scan_estimate_error(run, &e), TT_OK);
    double hm, hr, am, ar, pm, pr;
    tt_scan_diff(run, ref, 0, &hm, &hr);
    tt_scan_diff(run, ref, 1, &am, &ar);
    tt_scan_diff(run, ref, 2, &pm, &pr);
    check("height rms (m)", e.height_rms, hr);
    check("height max (m)", e.height_max, hm);
    check("phase rms (deg)", e.phase_rms, pr);
    check("phase max (deg)", e.phase_max, pm);
    check("amplitude rms (rel)", e.amplitude_rms, ar / 20e-9);
    tt_scan_free(run);
    tt_scan_free(ref);
    tt_scene_free(sc);
    tt_scene_free(rsc);
}

static void uniform_sample(void **st)
{
    (void)st;
    estimate_brackets_error("[surface]\nmap = uniform\n");
}

static void height_and_material_edges(void **st)
{
    (void)st;
    estimate_brackets_error("[surface]\ntype = steps\nstep_height = 1 nm\nstep_width = 300 nm\n"
                            "map = stripes\nmap_materials = soft, stiff\nmap_period = 500 nm\n");
}

static void low_q(void **st)
{
    (void)st;
    estimate_brackets_error("[cantilever]\nquality_factor = 10\n"
                            "[surface]\ntype = steps\nstep_height = 1 nm\nstep_width = 300 nm\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(uniform_sample),
        cmocka_unit_test(height_and_material_edges),
        cmocka_unit_test(low_q),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
