/* The envelope tier on a sample with relaxation arms (a standard linear solid, whose
 * surface's depression is a state after the tip's (d, d')): over stripes of an elastic
 * matrix and the SLS, so that the sim's dimension changes at each material edge and the
 * scan thread's plan with it (scan_worker.c), its images agree with the every-cycle
 * tier's within the envelope run's own error estimate, and so does the viscous loss the
 * lagging surface books; an arm of zero modulus gives the elastic envelope run's images
 * within that estimate. Noise on such a sample: tests/test_envelope_noise.c. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/scan.h"

/* examples/viscoelastic-blend/arms.ini's materials (a glassy 1 GPa relaxed to 500 MPa by
 * one arm of 1 us, under the drive period: the next tap meets the surface part-way
 * back) as stripes, the Hertz law alone (the arms' condition). */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
    "free_amplitude = 20 nm\n"
    "[material matrix]\nyoungs_modulus = 1 GPa\npoisson_ratio = 0.4\n"
    "[material domain]\nyoungs_modulus = 500 MPa\npoisson_ratio = 0.4\n"
    "[surface]\ntype = flat\nmap = stripes\nmap_materials = matrix, domain\nmap_period = 500 nm\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 1\nline_rate = 8 Hz\nsettle_cycles = 2000\n"
    "channels = height, error, phase, dissipation_viscous\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

/* The channels' indices (their bits in TT_CH_*): height, error, phase; the viscous loss. */
static const int ch[3] = {0, 1, 2};
enum { VISCOUS = 25 };

static const char *arm = "[material domain]\narm1_modulus = 500 MPa\narm1_relaxation_time = 1 us\n";

static tt_scan *scan_with(const char *extra, const char *solver, tt_scene **sc)
{
    char text[2048];
    snprintf(text, sizeof text, "%s\n[solver]\n%s\n", extra, solver);
    return tt_run_scan(base, text, sc);
}

/* The envelope run's error estimate per channel (height, error as the amplitude's,
 * phase): max, rms. */
static void estimate(tt_scan *env, double est[3][2])
{
    tt_scan_error e;
    assert_int_equal(tt_scan_estimate_error(env, &e), TT_OK);
    const double a0 = 20e-9;
    est[0][0] = e.height_max;
    est[0][1] = e.height_rms;
    est[1][0] = e.amplitude_max * a0;
    est[1][1] = e.amplitude_rms * a0;
    est[2][0] = e.phase_max;
    est[2][1] = e.phase_rms;
}

/* The channel's largest magnitude over trace and retrace. */
static double largest(const tt_scan *s, int c)
{
    long n = tt_scan_xres(s) * tt_scan_yres(s);
    double m = 0;
    for (int r = 0; r < 2; r++)
        for (long i = 0; i < n; i++)
            m = fmax(m, fabs(tt_scan_image(s, c, r)[i]));
    return m;
}

/* Channels height, error and phase of a against b within est (a's estimate) plus b's own
 * integration error (b against ref, every cycle at a tolerance of 1e-11). */
static void within_estimate(const char *what, const tt_scan *a, const tt_scan *b,
                            const tt_scan *ref, const double est[3][2])
{
    const char *name[3] = {"height (m)", "error (m)", "phase (deg)"};
    for (int c = 0; c < 3; c++) {
        double dm, dr, rm, rr;
        tt_scan_diff(a, b, ch[c], &dm, &dr);
        tt_scan_diff(b, ref, ch[c], &rm, &rr);
        print_message("%-12s %s: max %.3g rms %.3g; estimate max %.3g rms %.3g; "
                      "against the reference: max %.3g rms %.3g\n",
                      name[c], what, dm, dr, est[c][0], est[c][1], rm, rr);
        assert_true(dm <= est[c][0] + rm);
        assert_true(dr <= est[c][1] + rr);
    }
}

/* Three scans and their scenes freed. */
static void free_runs(tt_scan *s[3], tt_scene *sc[3])
{
    for (int i = 0; i < 3; i++) {
        tt_scan_free(s[i]);
        tt_scene_free(sc[i]);
    }
}

/* The SLS stripes: envelope against every cycle at the same tolerance, each channel
 * within the envelope run's estimate (the every-cycle run's own error against a
 * tolerance of 1e-11 its floor, as tests/test_envelope.c allows the amplitude); the
 * viscous loss, which only the arm's state gives, within 1e-3 of its largest (its
 * error is the surface's, whose model is the plan's third input); the model ran most
 * cycles. */
static void arms_agree(void **st)
{
    (void)st;
    tt_scene *sc[3];
    tt_scan *r[3] = {scan_with(arm, "tier = envelope", &sc[0]), scan_with(arm, "tier = every", &sc[1]),
                     scan_with(arm, "tolerance = 1e-11", &sc[2])};
    double est[3][2];
    estimate(r[0], est);
    double frac = 1 - (double)tt_scan_cycles_integrated(r[0]) / (double)tt_scan_cycles(r[0]);
    print_message("cycles %ld, integrated %ld (%.1f %% skipped)\n", tt_scan_cycles(r[0]),
                  tt_scan_cycles_integrated(r[0]), 100 * frac);
    assert_int_equal(tt_scan_cycles(r[0]), tt_scan_cycles(r[1]));
    assert_true(frac >= 0.8);
    within_estimate("envelope - every", r[0], r[1], r[2], est);
    double vm, vr, big = largest(r[1], VISCOUS);
    tt_scan_diff(r[0], r[1], VISCOUS, &vm, &vr);
    print_message("viscous loss envelope - every: max %.3g rms %.3g of %.3g J\n", vm, vr, big);
    assert_true(big > 0);
    assert_true(vm <= 1e-3 * big);
    free_runs(r, sc);
}

/* An arm of zero modulus and a relaxation time past the run is the relaxed elastic law
 * (tests/test_contact_sls.c): its envelope run, on the plan of dimension 3, gives the
 * elastic envelope run's images within the former's error estimate and the two runs'
 * own integration error (every cycle against a tolerance of 1e-11), and books no
 * viscous loss. */
static void zero_arm_is_elastic(void **st)
{
    (void)st;
    tt_scene *sc[3];
    tt_scan *r[3] = {scan_with("[material domain]\narm1_modulus = 0 Pa\narm1_relaxation_time = 1000 s\n",
                               "tier = envelope", &sc[0]),
                     scan_with("", "tier = envelope", &sc[1]), scan_with("", "tolerance = 1e-11", &sc[2])};
    double est[3][2];
    estimate(r[0], est);
    within_estimate("zero arm - elastic", r[0], r[1], r[2], est);
    assert_true(largest(r[0], VISCOUS) == 0);
    free_runs(r, sc);
}

TT_TEST_MAIN(cmocka_unit_test(arms_agree),
             cmocka_unit_test(zero_arm_is_elastic))
