/* Closed-loop imaging: flat and stepped samples, material contrast predicted from the
 * approach curves, a feedback loop with far too much gain. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/config/setup.h"

/* A fast cantilever for tests: Q 100 settles in a few hundred cycles. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[material soft]\nyoungs_modulus = 0.5 GPa\nadhesion_energy = 30 mJ/m^2\n"
    "interaction_quality_factor = 20\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 2\nline_rate = 20 Hz\nsettle_cycles = 3000\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n";

static tt_scan *run_scan(const char *extra, tt_scene **sc) { return tt_run_scan(base, extra, sc); }

static double mean_range(const double *img, long row, long xres, long a, long b, double *sd)
{
    double m = 0, q = 0;
    for (long i = a; i < b; i++)
        m += img[row * xres + i];
    m /= (double)(b - a);
    for (long i = a; i < b; i++)
        q += (img[row * xres + i] - m) * (img[row * xres + i] - m);
    if (sd)
        *sd = sqrt(q / (double)(b - a));
    return m;
}

static void flat_uniform_sample_is_flat(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = run_scan("[surface]\nmap = uniform\n", &sc);
    const double *h = tt_scan_image(s, 0, 0), *a = tt_scan_image(s, 1, 0);
    double sd;
    mean_range(h, 1, 32, 0, 32, &sd);
    assert_true(sd < 1e-12); /* flat to a picometre */
    for (long i = 0; i < 64; i++)
        assert_close(a[i], 0, 1e-3 * 16e-9); /* the amplitude sits on the setpoint */
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void step_height_is_recovered(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *s = run_scan("[surface]\ntype = steps\nstep_height = 4 nm\nstep_width = 500 nm\n", &sc);
    for (int r = 0; r < 2; r++) {
        const double *h = tt_scan_image(s, 0, r);
        /* away from the edge: pixels 4..12 on the low terrace, 20..30 on the high one */
        double lo = mean_range(h, 0, 32, 4, 12, NULL), hi = mean_range(h, 0, 32, 20, 30, NULL);
        print_message("%s: step %.4f nm\n", r ? "retrace" : "trace", (hi - lo) * 1e9);
        assert_close(hi - lo, 4e-9, 0.01e-9);
    }
    tt_scan_free(s);
    tt_scene_free(sc);
}

/* The separation at which the steady amplitude of a material falls to the setpoint,
 * and the phase there, from an approach in 0.05 nm steps, interpolated. */
static void crossing(tt_scene *sc, size_t mat, double setpoint, double *z, double *phase)
{
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, sc), TT_OK);
    assert_int_equal(tt_setup_use_material(su, mat), TT_OK);
    tt_sim_reset_free(tt_setup_sim(su));
    double pz = NAN, pa = NAN, pp = NAN;
    for (double g = 19e-9; g > 10e-9; g -= 0.05e-9) {
        tt_sim_set_sample(tt_setup_sim(su), g, 0);
        tt_cycle c;
        int ok;
        long n;
        assert_int_equal(tt_sim_settle(tt_setup_sim(su), 20000, 1e-9, &c, &ok, &n), TT_OK);
        if (c.amplitude <= setpoint && isfinite(pa)) {
            double f = (pa - setpoint) / (pa - c.amplitude);
            *z = pz + f * (g - pz);
            *phase = pp + f * (c.phase - pp);
            tt_setup_free(su);
            return;
        }
        pz = g;
        pa = c.amplitude;
        pp = c.phase;
    }
    fail_msg("no crossing of the setpoint");
}

static void material_contrast_follows_the_approach_curves(void **st)
{
    (void)st;
    tt_scene *sc;
    /* stiff on the left half, soft on the right */
    tt_scan *s = run_scan("[surface]\nmap = stripes\nmap_materials = soft, stiff\nmap_period = 1 um\n"
                          "map_duty = 50 %\n",
                          &sc);
    double zs, ps, zf, pf;
    crossing(sc, 0, 16e-9, &zs, &ps); /* stiff */
    crossing(sc, 1, 16e-9, &zf, &pf); /* soft */
    const double *h = tt_scan_image(s, 0, 0), *ph = tt_scan_image(s, 2, 0);
    /* stripe of the second named material ("stiff") for x < 1 um * 50 %: pixels 0..15 */
    double hs = mean_range(h, 1, 32, 4, 13, NULL), hf = mean_range(h, 1, 32, 20, 29, NULL);
    double phs = mean_range(ph, 1, 32, 4, 13, NULL), phf = mean_range(ph, 1, 32, 20, 29, NULL);
    print_message("height difference: image %.4f nm, predicted %.4f nm\n", (hf - hs) * 1e9,
                  (zf - zs) * 1e9);
    print_message("phase difference: image %.3f deg, predicted %.3f deg\n", phf - phs,
                  (pf - ps) * 180 / M_PI);
    assert_true(fabs(zf - zs) > 0.1e-9); /* a real contrast, not a zero */
    assert_close(hf - hs, zf - zs, 0.03e-9 + 0.03 * fabs(zf - zs));
    assert_close(phf - phs, (pf - ps) * 180 / M_PI, 0.1 + 0.03 * fabs(pf - ps) * 180 / M_PI);
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void far_too_much_gain_oscillates(void **st)
{
    (void)st;
    tt_scene *sc;
    tt_scan *good = run_scan("[surface]\nmap = uniform\n", &sc);
    tt_scene_free(sc);
    tt_scan *bad = run_scan("[surface]\nmap = uniform\n[feedback]\nintegral_gain = 300 kHz\n", &sc);
    double sdg, sdb;
    mean_range(tt_scan_image(good, 0, 0), 1, 32, 0, 32, &sdg);
    mean_range(tt_scan_image(bad, 0, 0), 1, 32, 0, 32, &sdb);
    double sa;
    mean_range(tt_scan_image(bad, 1, 0), 1, 32, 0, 32, &sa);
    print_message("height rms on a flat sample: %.3g nm at 3 kHz, %.3g nm at 300 kHz (amplitude error rms %.3g nm)\n",
                  sdg * 1e9, sdb * 1e9, sa * 1e9);
    assert_true(sdb > 0.05e-9);
    assert_true(sdb > 1000 * sdg);
    tt_scan_free(good);
    tt_scan_free(bad);
    tt_scene_free(sc);
}

static void bad_scan_input_is_refused(void **st)
{
    (void)st;
    static const struct {
        const char *text, *frag;
    } cases[] = {
        {"[scan]\npixels = 1\n", "[scan] pixels:"},
        {"[scan]\nline_rate = -1 Hz\n", "[scan] line_rate:"},
        {"[scan]\nchannels = height, phse\n", "unknown channel 'phse'"},
        {"[feedback]\nsetpoint = 25 nm\n", "[feedback] setpoint:"},
        {"[surface]\nmap = stripes\nmap_materials = soft, glass\n", "no [material glass]"},
        {"[surface]\ntype = png\npng = /nonexistent.png\n", "[surface] png:"},
        {"[surface]\nmap = disks\nmap_radius = 200 nm\nmap_period = 300 nm\n", "[surface] map_radius:"},
        {"[surface]\nduty = 150 %\n", "[surface] duty:"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        tt_expect_scan_refused(base, cases[i].text, cases[i].frag);
}

/* Every material is checked before a scan runs, whether a pixel uses it or the raster
 * reaches it only late in a line; the scan builds every force law when it is made. */
static void every_material_is_checked_up_front(void **st)
{
    (void)st;
    tt_expect_scan_refused(base, "[material unused]\nadhesion_energy = 40 mJ/m^2\nlambda = 1e5\n",
                           "bad.ini: [material unused] lambda:");
    tt_expect_scan_refused(base,
                           "[material late]\nadhesion_energy = 40 mJ/m^2\ninteratomic_distance = 1e-6 nm\n"
                           "[surface]\nmap = stripes\nmap_materials = late, soft\nmap_period = 1 um\n"
                           "map_duty = 90 %\n",
                           "bad.ini: [material late] interatomic_distance:");
    /* typed parameters: a force law that cannot be made fails tt_scan_alloc, used or not */
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    tt_scan_params p;
    assert_int_equal(tt_config_scan(sc, &p), TT_OK);
    assert_int_equal(p.surface.map, TT_MAP_UNIFORM);
    assert_int_equal(p.nmaterials, 2);
    const tt_material *own = p.materials;
    tt_material m[2] = {own[0], own[1]};
    m[1].contact.K = -1;
    p.materials = m;
    tt_scan *s = NULL;
    assert_int_equal(tt_scan_alloc(&s, &p), TT_EINVAL);
    assert_null(s);
    assert_non_null(strstr(tt_error_message(), "[material soft]: contact:"));
    p.materials = own;
    tt_config_scan_free(&p);
    tt_scene_free(sc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(flat_uniform_sample_is_flat),
        cmocka_unit_test(step_height_is_recovered),
        cmocka_unit_test(material_contrast_follows_the_approach_curves),
        cmocka_unit_test(far_too_much_gain_oscillates),
        cmocka_unit_test(bad_scan_input_is_refused),
        cmocka_unit_test(every_material_is_checked_up_front),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
