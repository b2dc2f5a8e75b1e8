/* The averaged preview tier ([solver] tier = averaged; tiptap/solver/averaged.h): its
 * slow flow reaches the free oscillator's analytic steady state and relaxes at its
 * rate; its table of the force's harmonics agrees with direct quadrature and, for
 * Hertz contact, with the closed-form loss of interaction damping (none without it);
 * on the standard cantilever its images agree with the every-cycle tier's on a
 * uniform sample, and its material contrast over stripes within 0.02 nm and 2 deg;
 * an oscillation that collapses is reported; below Q 30 the scan runs on the envelope tier; the
 * images do not depend on threads. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/solver/averaged.h"
#include "tiptap/util/error.h"

static tt_cantilever standard(double fd)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, fd, TT_DRIVE_BASE), TT_OK);
    return c;
}

static tt_contact *hertz(void)
{
    tt_contact_params p = {TT_CONTACT_HERTZ, 10e9, 10e-9, 0, 0.265e-9, NAN, 0, 0, 0, {0}, {0}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    return ct;
}

/* Far from the sample, from rest: after one amplitude time constant 2 Q / w0 the
 * amplitude at resonance is A0 (1 - 1/e) (the slow flow of a linear oscillator is
 * exact), and at last the steady state of the transfer function, on and off
 * resonance. */
static void free_oscillator(void **state)
{
    (void)state;
    tt_contact *ct = hertz();
    const double fds[2] = {300e3, 300.4e3};
    for (int i = 0; i < 2; i++) {
        tt_cantilever c = standard(fds[i]);
        tt_averaged *a;
        assert_int_equal(tt_averaged_alloc(&a, &c, ct, NAN, 1), TT_OK);
        tt_averaged_state st = {0, 0, 0, 0};
        tt_averaged_out o;
        const double tau = 2 * c.Q / c.w0, h = 4 * c.T;
        long n = lround(tau / h);
        for (long k = 0; k < n; k++)
            tt_averaged_step(a, &st, 1e-6, h, &o);
        if (i == 0)
            assert_close(hypot(st.X, st.Y) / c.A0, 1 - exp(-(double)n * h / tau), 1e-4);
        for (long k = 0; k < 40 * n; k++)
            tt_averaged_step(a, &st, 1e-6, h, &o);
        double amp, lag;
        tt_cantilever_response(&c, c.wd, &amp, &lag);
        assert_close(hypot(st.X, st.Y), amp, 1e-6 * c.A0);
        assert_close(atan2(st.Y, st.X), lag, 1e-6);
        assert_close(o.ets, 0, 1e-30);
        tt_averaged_free(a);
    }
    tt_contact_free(ct);
}

/* Hertz contact: conservative without interaction damping (no first-harmonic loss);
 * with it, the loss per cycle is c_i B^2 w (t - sin t cos t) over the contact's half
 * angle t, cos t = 1 - x / B. The table agrees with quadrature at cell middles. */
static void table(void **state)
{
    (void)state;
    tt_contact *ct = hertz();
    tt_cantilever c = standard(300e3);
    tt_averaged *a, *d;
    assert_int_equal(tt_averaged_alloc(&a, &c, ct, NAN, 3), TT_OK);
    assert_int_equal(tt_averaged_alloc(&d, &c, ct, 2, 1), TT_OK);
    double e = tt_averaged_table_error(a);
    print_message("table error %.3g of k A0\n", e);
    assert_true(e < 1e-4);
    const double ci = c.m * c.w0 / 2;
    for (int i = 0; i < 5; i++) {
        double B = 16e-9 + 0.7e-9 * i, x = 0.3e-9 + 0.77e-9 * i;
        tt_averaged_force f, g;
        tt_averaged_force_at(a, B, x, 0, 0, &f);
        assert_close(f.gs[0], 0, 1e-7 * c.k * c.A0);
        assert_true(f.gc[0] < 0 && f.mean < 0 && f.peak > 0);
        tt_averaged_force_at(d, B, x, 0, 0, &g);
        double t = acos(1 - x / B);
        double loss = ci * B * B * c.wd * (t - sin(t) * cos(t));
        assert_close(M_PI * B * g.gs[0], loss, 1e-3 * loss);
    }
    tt_averaged_free(a);
    tt_averaged_free(d);
    tt_contact_free(ct);
}

static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
    "free_amplitude = 20 nm\n"
    "[material matrix]\nyoungs_modulus = 2 GPa\npoisson_ratio = 0.35\n"
    "adhesion_energy = 40 mJ/m^2\ninteratomic_distance = 0.265 nm\n"
    "interaction_quality_factor = 2\n"
    "[material disk]\nyoungs_modulus = 30 GPa\npoisson_ratio = 0.3\n"
    "adhesion_energy = 40 mJ/m^2\ninteratomic_distance = 0.265 nm\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 1\nline_rate = 8 Hz\n"
    "channels = height, error, phase\n"
    "[feedback]\nsetpoint = 80 %\n";

static tt_scan *scan_with(const char *extra, const char *tier, tt_scene **sc)
{
    return tt_run_scan_on(base, extra, tier, sc);
}

/* The mean of channel c (height in nm, phase in deg) over the pixels of trace and
 * retrace in the middle of each stripe of one material (second: the map's second). */
static double stripe_mean(const tt_scan *s, int c, int second)
{
    const long nx = tt_scan_xres(s);
    double sum = 0;
    long n = 0;
    for (int r = 0; r < 2; r++)
        for (long px = 0; px < nx; px++) {
            double f = fmod((px + 0.5) / nx * 1e-6, 500e-9) / 500e-9; /* place in a period */
            if ((second && f > 0.1 && f < 0.4) || (!second && f > 0.6 && f < 0.9)) {
                sum += tt_scan_image(s, c, r)[px];
                n++;
            }
        }
    return sum / (double)n * (c == 0 ? 1e9 : 1);
}

/* The standard scene's uniform matrix: steady height within 5 pm and phase within
 * 0.2 deg of the every-cycle tier (measured 0.4 pm, 0.073 deg); material stripes of
 * the matrix and a stiff disk: the contrast (disk - matrix) within 0.02 nm and 2 deg
 * (measured 0.0017 nm and 0.073 deg). */
static void against_every(void **state)
{
    (void)state;
    tt_scene *s1, *s2, *s3, *s4;
    tt_scan *a = scan_with("", "averaged", &s1), *e = scan_with("", "every", &s2);
    double hm, hr, pm, pr;
    tt_scan_diff(a, e, 0, &hm, &hr);
    tt_scan_diff(a, e, 2, &pm, &pr);
    print_message("uniform: height %.3g m, phase %.3g deg (max)\n", hm, pm);
    assert_true(hm < 5e-12);
    assert_true(pm < 0.2);
    assert_int_equal(tt_scan_cycles_integrated(a), 0);
    assert_int_equal(tt_scan_averaged_collapsed(a, NULL, NULL), 0);
    const char *stripes = "[surface]\nmap = stripes\nmap_materials = matrix, disk\n"
                          "map_period = 500 nm\nmap_duty = 50 %\n";
    tt_scan *sa = scan_with(stripes, "averaged", &s3), *se = scan_with(stripes, "every", &s4);
    double ch[2][2];
    for (int c = 0; c < 2; c++) {
        const tt_scan *s = c ? se : sa;
        ch[c][0] = stripe_mean(s, 0, 1) - stripe_mean(s, 0, 0);
        ch[c][1] = stripe_mean(s, 2, 1) - stripe_mean(s, 2, 0);
    }
    print_message("contrast: height %.4f / %.4f nm, phase %.3f / %.3f deg (averaged / every)\n",
                  ch[0][0], ch[1][0], ch[0][1], ch[1][1]);
    assert_true(fabs(ch[1][0]) > 0.1 && fabs(ch[1][1]) > 10); /* a contrast to judge */
    assert_close(ch[0][0], ch[1][0], 0.02);
    assert_close(ch[0][1], ch[1][1], 2);
    tt_scan *list[] = {a, e, sa, se};
    tt_scene *scenes[] = {s1, s2, s3, s4};
    for (int i = 0; i < 4; i++) {
        tt_scan_free(list[i]);
        tt_scene_free(scenes[i]);
    }
}

/* A setpoint of 10 % presses the oscillation below a quarter of the free amplitude:
 * the averaged tier says so, naming the first pixel. */
static void collapse_reported(void **state)
{
    (void)state;
    tt_scene *sc;
    tt_scan *s = scan_with("[feedback]\nsetpoint = 10 %\n", "averaged", &sc);
    long line = -2, px = -2, n = tt_scan_averaged_collapsed(s, &line, &px);
    print_message("collapsed pixels %ld (first: line %ld, pixel %ld)\n", n, line, px);
    assert_true(n > 0);
    assert_int_equal(line, 0);
    assert_between(px, 0, 31);
    tt_scan_free(s);
    tt_scene_free(sc);
}

/* Below Q 30 averaging does not hold: the scan runs on the envelope tier's terms, the
 * images identical to the envelope tier's (which at Q 10 skips cycles). */
static void low_q_falls_back(void **state)
{
    (void)state;
    tt_scene *s1, *s2;
    const char *q = "[cantilever]\nquality_factor = 10\n[scan]\nline_rate = 40 Hz\n";
    tt_scan *a = scan_with(q, "averaged", &s1), *e = scan_with(q, "envelope", &s2);
    assert_int_equal(tt_scan_cycles_integrated(a), tt_scan_cycles_integrated(e));
    assert_true(tt_scan_cycles_integrated(a) < tt_scan_cycles(a));
    tt_scan_assert_identical(a, e, 3);
    tt_scan_free(a);
    tt_scan_free(e);
    tt_scene_free(s1);
    tt_scene_free(s2);
}

/* Two lines on one thread and on two: the same images. */
static void threads_agree(void **state)
{
    (void)state;
    tt_scan_assert_threads_agree(base,
                                 "[scan]\nlines = 2\n[surface]\ntype = steps\n"
                                 "step_height = 1 nm\nstep_width = 300 nm\n"
                                 "[solver]\ntier = averaged\n",
                                 3, 0);
}

TT_TEST_MAIN(cmocka_unit_test(free_oscillator),
             cmocka_unit_test(table),
             cmocka_unit_test(against_every),
             cmocka_unit_test(collapse_reported),
             cmocka_unit_test(low_q_falls_back),
             cmocka_unit_test(threads_agree))
