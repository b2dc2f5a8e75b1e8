/* The instrument's imperfections against their analytic forms: the z piezo's step
 * response (second order) and creep (logarithmic), a tilted sample's plane in the
 * height image, and drift's shift of the image in z and along x. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/piezo.h"
#include "tiptap/util/error.h"

/* Unit step response of z'' + 2 zeta w z' + w^2 z = w^2 u. */
static double step_response(double w, double zeta, double t)
{
    if (zeta < 1) {
        double wd = w * sqrt(1 - zeta * zeta);
        return 1 - exp(-zeta * w * t) * (cos(wd * t) + zeta / sqrt(1 - zeta * zeta) * sin(wd * t));
    }
    double q = w * sqrt(zeta * zeta - 1), s1 = -zeta * w + q, s2 = -zeta * w - q;
    return 1 - (s2 * exp(s1 * t) - s1 * exp(s2 * t)) / (s2 - s1);
}

static void piezo_step_response_is_second_order(void **st)
{
    (void)st;
    const double dz = 10e-9, T = 1 / 300e3; /* one drive period per advance, as in a scan */
    const double zetas[] = {0.05, 0.3, 2.0};
    for (int i = 0; i < 3; i++) {
        tt_piezo_params p = {5e3, zetas[i], 0, 0.01};
        tt_piezo pz;
        tt_piezo_init(&pz, &p, 1e-9, 1);
        tt_piezo_advance(&pz, 1e-9 + dz, 1e-12); /* the step */
        double worst = 0, peak = 0, t = 1e-12;
        for (int k = 0; k < 3000; k++) {
            double z = tt_piezo_advance(&pz, 1e-9 + dz, T) - 1e-9;
            t += T;
            worst = fmax(worst, fabs(z - dz * step_response(2 * M_PI * 5e3, zetas[i], t)));
            peak = fmax(peak, z);
        }
        double over = zetas[i] < 1 ? exp(-M_PI * zetas[i] / sqrt(1 - zetas[i] * zetas[i])) : 0;
        print_message("zeta %.2f: overshoot %.4f (analytic %.4f), response within %.2g of the step\n",
                      zetas[i], peak / dz - 1, over, worst / dz);
        assert_true(worst < 1e-6 * dz);
        assert_close(peak / dz - 1, over, 1e-3);
    }
}

static void creep_is_logarithmic(void **st)
{
    (void)st;
    const double gamma = 0.02, t0 = 0.01, dz = 100e-9, span = 100, dt = 1e-4;
    tt_piezo_params p = {0, 0.3, gamma, t0};
    tt_piezo pz;
    tt_piezo_init(&pz, &p, 0, span);
    tt_piezo_advance(&pz, dz, 1e-9);
    double worst = 0, t = 1e-9, at_span = 0;
    /* steps growing with time, as a scan's many small ones would take too long here */
    for (double h = dt; t < span; h = fmin(h * 1.01, 0.01)) {
        double z = tt_piezo_advance(&pz, dz, h);
        t += h;
        double want = dz + gamma * dz * log10(1 + t / t0);
        worst = fmax(worst, fabs(z - want));
        at_span = z - dz;
    }
    print_message("creep after %g s: %.4f nm (analytic %.4f nm); worst %.2g of gamma dz\n", t,
                  at_span * 1e9, gamma * dz * log10(1 + t / t0) * 1e9, worst / (gamma * dz));
    assert_true(worst < 1e-3 * gamma * dz);
    /* a move back undoes it: superposition of the two moves */
    tt_piezo_advance(&pz, 0, 1e-9);
    assert_close(tt_piezo_creep(&pz), gamma * dz * log10(1 + t / t0), 1e-3 * gamma * dz);
}

/* A fast cantilever (Q 100) on a flat, stiff sample, 32 pixels by 4 lines at 20 Hz. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 4\nline_rate = 20 Hz\nsettle_cycles = 3000\n"
    "channels = height, topography\n[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

/* Least-squares plane z = a + b x + c y over pixels from first on of the trace. */
static void plane_fit(const double *h, long nx, long ny, double px, double py, long first, double *b,
                      double *c)
{
    double S[3][4] = {{0}};
    for (long j = 0; j < ny; j++)
        for (long i = first; i < nx; i++) {
            double v[3] = {1, (double)i * px, (double)j * py}, z = h[j * nx + i];
            for (int r = 0; r < 3; r++) {
                for (int q = 0; q < 3; q++)
                    S[r][q] += v[r] * v[q];
                S[r][3] += v[r] * z;
            }
        }
    for (int r = 0; r < 3; r++) /* Gauss-Jordan on the 3 x 3 normal equations */
        for (int q = 0; q < 3; q++)
            if (q != r) {
                double f = S[q][r] / S[r][r];
                for (int k = 0; k < 4; k++)
                    S[q][k] -= f * S[r][k];
            }
    *b = S[1][3] / S[1][1];
    *c = S[2][3] / S[2][2];
}

static void tilt_is_a_plane_background(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, "[instrument]\ntilt_x = 2 %\ntilt_y = -1 %\n", &sc);
    for (int r = 0; r < 2; r++) {
        double b, c;
        plane_fit(tt_scan_image(s, 0, r), 32, 4, 1e-6 / 32, 1e-6 / 4, 2, &b, &c);
        print_message("%s: plane fit slopes %.5f %%, %.5f %% (tilt 2 %%, -1 %%)\n",
                      r ? "retrace" : "trace", b * 100, c * 100);
        assert_close(b, 0.02, 0.02 * 0.01);
        assert_close(c, -0.01, 0.01 * 0.01);
    }
    /* the topography channel is the sample's own: flat */
    const double *t = tt_scan_image(s, 6, 0);
    for (int i = 0; i < 128; i++)
        assert_close(t[i], 0, 0);
    tt_scan_free(s);
    tt_scene_free(sc);
}

/* z drift: the sample rises drift_z t; line n starts n / line_rate later. */
static void z_drift_raises_later_lines(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = tt_run_scan(base, "[instrument]\ndrift_z = 100 nm/s\n", &sc);
    const double *h = tt_scan_image(s, 0, 0);
    double worst = 0;
    for (int j = 1; j < 4; j++)
        for (int i = 2; i < 32; i++)
            worst = fmax(worst, fabs(h[j * 32 + i] - h[i] - 100e-9 * j / 20));
    /* within a trace, pixel i is seen (i + 1/2) / 64 of a line period after the start */
    double in_line = h[31] - h[2], want = 100e-9 * 29.0 / 64 / 20;
    print_message("z drift: lines rise by 5 nm each within %.2g nm; trace rises %.4f nm (%.4f)\n",
                  worst * 1e9, in_line * 1e9, want * 1e9);
    assert_true(worst < 0.005e-9);
    assert_close(in_line, want, 0.02 * want);
    tt_scan_free(s);
    tt_scene_free(sc);
}

/* Lateral drift: a step at x = 500 nm seen in line n where x - drift_x t = 500 nm, with
 * t = n / line_rate + x / (2 line_rate size) on the trace: it moves by
 * drift_x n / line_rate / (1 - drift_x / (2 line_rate size)) from line to line (the
 * sample drifts along with the trace, too). The edge is found where the height crosses
 * half the step, interpolated between pixels. */
static double edge(const double *h, long row)
{
    for (long i = 1; i < 32; i++)
        if (h[row * 32 + i] >= 2e-9 && h[row * 32 + i - 1] < 2e-9)
            return ((double)i - 1 + (2e-9 - h[row * 32 + i - 1]) / (h[row * 32 + i] - h[row * 32 + i - 1]) +
                    0.5) * 1e-6 / 32;
    return NAN;
}

static void x_drift_shifts_later_lines(void **st)
{
    (void)st;
    tt_scene *sc;
    const char *steps = "[surface]\ntype = steps\nstep_height = 4 nm\nstep_width = 500 nm\n";
    char text[512];
    snprintf(text, sizeof text, "%s[instrument]\ndrift_x = 1.25 um/s\n", steps);
    tt_scan *s = tt_run_scan(base, text, &sc);
    const double *h = tt_scan_image(s, 0, 0), *t = tt_scan_image(s, 6, 0);
    for (int j = 1; j < 4; j++) {
        double shift = edge(h, j) - edge(h, 0), topo = edge(t, j) - edge(t, 0);
        double want = 1.25e-6 * j / 20 / (1 - 1.25e-6 / (2 * 20 * 1e-6));
        print_message("line %d: edge moved %.2f nm (height), %.2f nm (topography); expected %.2f nm\n",
                      j, shift * 1e9, topo * 1e9, want * 1e9);
        assert_close(shift, want, 0.1 * 1e-6 / 32);
    }
    tt_scan_free(s);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(piezo_step_response_is_second_order),
        cmocka_unit_test(creep_is_logarithmic),
        cmocka_unit_test(tilt_is_a_plane_background),
        cmocka_unit_test(z_drift_raises_later_lines),
        cmocka_unit_test(x_drift_shifts_later_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
