/* Surfaces: shapes, rough statistics, material maps, PNG maps, and their errors. */
#include <png.h>
#include <stdlib.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/instrument/tip.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/surface.h"

static const char *mats = "[material a]\nyoungs_modulus = 1 GPa\nmap_value = 0\n"
                          "[material b]\nyoungs_modulus = 50 GPa\nmap_value = #ff0000\n";

static tt_surface *make(const char *text, int expect_ok)
{
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, mats, "m.ini"), TT_OK);
    int rc = tt_scene_load_string(s, text, "s.ini");
    tt_surface *S = NULL;
    if (rc == TT_OK)
        rc = tt_config_surface_alloc(&S, s, 1e-6, 1e-6);
    tt_scene_free(s);
    if (expect_ok && rc)
        fail_msg("%s", tt_error_message());
    if (!expect_ok && !rc)
        fail_msg("accepted: %s", text);
    return S;
}

static void shapes(void **st)
{
    (void)st;
    tt_surface *S = make("[surface]\ntype = steps\nstep_height = 2 nm\nstep_width = 300 nm\n", 1);
    assert_close(tt_surface_height(S, 100e-9, 0), 0, 0);
    assert_close(tt_surface_height(S, 350e-9, 0), 2e-9, 1e-20);
    assert_close(tt_surface_height(S, 650e-9, 0), 4e-9, 1e-20);
    assert_false(tt_surface_flat(S));
    tt_surface_free(S);
    S = make("[surface]\ntype = grating\nperiod = 400 nm\nduty = 25 %\nheight = 20 nm\nedge_width = 10 nm\n", 1);
    assert_close(tt_surface_height(S, 5e-9, 0), 10e-9, 1e-18);  /* half-way up the edge */
    assert_close(tt_surface_height(S, 50e-9, 0), 20e-9, 0);     /* on the line */
    assert_close(tt_surface_height(S, 300e-9, 0), 0, 0);        /* in the gap */
    assert_close(tt_surface_height(S, 450e-9, 0), 20e-9, 0);    /* next period */
    tt_surface_free(S);
    S = make("[surface]\ntype = particles\nparticle_radius = 30 nm\nparticle_count = 5\nseed = 3\n", 1);
    /* the highest point of the image is a sphere's apex, 2 r above the flat */
    double best = 0;
    for (int j = 0; j < 400; j++)
        for (int i = 0; i < 400; i++)
            best = fmax(best, tt_surface_height(S, i * 2.5e-9, j * 2.5e-9));
    assert_close(best, 60e-9, 0.1e-9);
    tt_surface_free(S);
}

static void rough_statistics(void **st)
{
    (void)st;
    tt_surface *S = make("[surface]\ntype = rough\nrms = 2 nm\ncorrelation_length = 40 nm\nseed = 7\n", 1);
    int n = 256;
    double s2 = 0, m = 0, c = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double h = tt_surface_height(S, (i + 0.5) * 1e-6 / n, (j + 0.5) * 1e-6 / n);
            m += h;
            s2 += h * h;
            /* correlation at a lag of one correlation length along x */
            c += h * tt_surface_height(S, (i + 0.5) * 1e-6 / n + 40e-9, (j + 0.5) * 1e-6 / n);
        }
    m /= n * n;
    double var = s2 / (n * n) - m * m;
    assert_close(sqrt(var), 2e-9, 0.02e-9);
    /* Gaussian autocorrelation: exp(-1) at one correlation length, within sampling noise */
    assert_close(c / (n * n) / var, exp(-1), 0.1);
    tt_surface *T = make("[surface]\ntype = rough\nrms = 2 nm\ncorrelation_length = 40 nm\nseed = 7\n", 1);
    assert_close(tt_surface_height(T, 1e-7, 2e-7), tt_surface_height(S, 1e-7, 2e-7), 0); /* seeded */
    tt_surface_free(S);
    tt_surface_free(T);
}

static void material_maps(void **st)
{
    (void)st;
    tt_surface *S = make("[surface]\nmap = stripes\nmap_period = 200 nm\nmap_duty = 25 %\n", 1);
    assert_false(tt_surface_uniform(S));
    assert_int_equal(tt_surface_material(S, 10e-9, 0), 1);
    assert_int_equal(tt_surface_material(S, 100e-9, 0), 0);
    tt_surface_free(S);
    S = make("[surface]\nmap = disks\nmap_materials = b, a\nmap_period = 200 nm\nmap_radius = 50 nm\n", 1);
    assert_int_equal(tt_surface_material(S, 100e-9, 100e-9), 0); /* disk centre: a */
    assert_int_equal(tt_surface_material(S, 10e-9, 10e-9), 1);   /* background: b */
    tt_surface_free(S);
    S = make("[surface]\nmap = checkerboard\nmap_period = 200 nm\n", 1);
    assert_int_equal(tt_surface_material(S, 50e-9, 50e-9), 0);
    assert_int_equal(tt_surface_material(S, 150e-9, 50e-9), 1);
    assert_int_equal(tt_surface_material(S, 150e-9, 150e-9), 0);
    tt_surface_free(S);
    S = make("[surface]\n", 1);
    assert_true(tt_surface_uniform(S));
    assert_true(tt_surface_flat(S));
    tt_surface_free(S);
}

/* Write a small PNG: 16-bit grey if deep, else 8-bit RGB or grey. */
static void write_png(const char *path, int w, int h, int fmt, const void *data)
{
    png_image im;
    memset(&im, 0, sizeof im);
    im.version = PNG_IMAGE_VERSION;
    im.width = (png_uint_32)w;
    im.height = (png_uint_32)h;
    im.format = (png_uint_32)fmt;
    assert_true(png_image_write_to_file(&im, path, 0, data, 0, NULL));
}

static void png_maps(void **st)
{
    (void)st;
    char dir[] = "/tmp/tt_png_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char p8[256], p16[256], prgb[256], bad[256], text[1024];
    snprintf(p8, sizeof p8, "%s/h8.png", dir);
    snprintf(p16, sizeof p16, "%s/h16.png", dir);
    snprintf(prgb, sizeof prgb, "%s/m.png", dir);
    snprintf(bad, sizeof bad, "%s/bad.png", dir);
    unsigned char g8[4] = {0, 255, 51, 102};       /* 2 x 2 */
    unsigned short g16[4] = {0, 65535, 13107, 26214};
    unsigned char rgb[12] = {0, 0, 0, 255, 0, 0, 255, 0, 0, 0, 0, 0};
    write_png(p8, 2, 2, PNG_FORMAT_GRAY, g8);
    write_png(p16, 2, 2, PNG_FORMAT_LINEAR_Y, g16);
    write_png(prgb, 2, 2, PNG_FORMAT_RGB, rgb);
    FILE *f = fopen(bad, "wb");
    fputs("this is not a png file at all", f);
    fclose(f);
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s\npng_height_range = 10 nm\n", k ? p16 : p8);
        tt_surface *S = make(text, 1);
        /* pixel centres: (x, y) = ((i + 1/2), (j + 1/2)) * 500 nm */
        assert_close(tt_surface_height(S, 250e-9, 250e-9), 0, 1e-15);
        assert_close(tt_surface_height(S, 750e-9, 250e-9), 10e-9, 1e-15);
        assert_close(tt_surface_height(S, 250e-9, 750e-9), 2e-9, 1e-15);
        assert_close(tt_surface_height(S, 750e-9, 750e-9), 4e-9, 1e-15);
        tt_surface_free(S);
    }
    snprintf(text, sizeof text, "[surface]\nmap = png\nmap_png = %s\n", prgb);
    tt_surface *S = make(text, 1);
    assert_int_equal(tt_surface_material(S, 100e-9, 100e-9), 0);
    assert_int_equal(tt_surface_material(S, 900e-9, 100e-9), 1);
    assert_int_equal(tt_surface_material(S, 100e-9, 900e-9), 1);
    tt_surface_free(S);
    /* errors name the file, the section and the key */
    snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s/missing.png\n", dir);
    make(text, 0);
    assert_non_null(strstr(tt_error_message(), "s.ini: [surface] png:"));
    snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s\n", bad);
    make(text, 0);
    assert_non_null(strstr(tt_error_message(), "[surface] png:"));
    assert_non_null(strstr(tt_error_message(), bad));
    unsigned char rgb2[12] = {0, 0, 0, 0, 255, 0, 0, 0, 0, 0, 0, 0};
    write_png(prgb, 2, 2, PNG_FORMAT_RGB, rgb2);
    snprintf(text, sizeof text, "[surface]\nmap = png\nmap_png = %s\n", prgb);
    make(text, 0);
    assert_non_null(strstr(tt_error_message(), "#00ff00"));
    unlink(p8);
    unlink(p16);
    unlink(prgb);
    unlink(bad);
    rmdir(dir);
}

static void bad_input(void **st)
{
    (void)st;
    make("[surface]\nmap = stripes\nmap_materials = a, c\n", 0);
    assert_non_null(strstr(tt_error_message(), "s.ini: [surface] map_materials: no [material c]"));
    make("[surface]\nduty = 0 %\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] duty:"));
    make("[surface]\ntype = particles\nparticle_radius = 300 nm\nparticle_count = 50\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] particle_count:"));
    make("[surface]\nmap = islands\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] map: islands need type = particles"));
}

/* A key that only another type reads is refused, naming both types (issue 32); at its
 * default it passes, as the effective scene written back carries every key. */
static void other_types_keys(void **st)
{
    (void)st;
    make("[surface]\ntype = grating\nparticle_radius = 30 nm\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] particle_radius: a key of type = particles, "
                                               "not of this surface's type = grating"));
    make("[surface]\nmeasured_tip_shape = cone\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] measured_tip_shape: a key of type = measured, "
                                               "not of this surface's type = flat"));
    make("[surface]\ntype = steps\nseed = 4\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] seed: a key of type = particles or rough"));
    tt_surface_free(make("[surface]\ntype = grating\nparticle_radius = 2e-8 m\nlevel = none\nseed = 1\n", 1));
    tt_surface_free(make("[surface]\ntype = rough\nseed = 4\n", 1));
    /* a later file (or --set) that changes the type replaces the sample an earlier one
     * drew, its keys with it; a key given after the type is the user's for this type */
    for (int later = 0; later < 2; later++) {
        tt_scene *sc = tt_scene_alloc();
        assert_int_equal(tt_scene_load_string(sc, later ? "[surface]\ntype = flat\n"
                                                        : "[surface]\ntype = grating\nperiod = 300 nm\n", "a.ini"), TT_OK);
        assert_int_equal(tt_scene_load_string(sc, later ? "[surface]\nperiod = 300 nm\n"
                                                        : "[surface]\ntype = flat\n", "b.ini"), TT_OK);
        tt_surface *S = NULL;
        int rc = tt_config_surface_alloc(&S, sc, 1e-6, 1e-6);
        if (later)
            assert_non_null(strstr(tt_error_message(), "b.ini: [surface] period: a key of type = grating or lattice"));
        assert_int_equal(rc != TT_OK, later);
        tt_surface_free(S);
        tt_scene_free(sc);
    }
}

/* Lattices against hand-computed heights: pillars, holes and spikes on square and
 * hexagonal lattices; a grating's critical dimension and offset. */
static void lattices_and_offsets(void **st)
{
    (void)st;
    tt_surface *S = make("[surface]\ntype = lattice\nperiod = 200 nm\nfeature_radius = 50 nm\n"
                         "edge_width = 10 nm\nheight = 20 nm\n", 1);
    assert_close(tt_surface_height(S, 100e-9, 100e-9), 20e-9, 1e-21);   /* a centre */
    assert_close(tt_surface_height(S, 155e-9, 100e-9), 10e-9, 1e-18);   /* mid-wall */
    assert_close(tt_surface_height(S, 100e-9, 39e-9), 0, 0);            /* past it */
    assert_close(tt_surface_height(S, 300e-9, 500e-9), 20e-9, 1e-21);   /* another cell */
    tt_surface_free(S);
    S = make("[surface]\ntype = lattice\nfeature = hole\nperiod = 200 nm\nfeature_radius = 50 nm\n"
             "height = 20 nm\noffset_x = 30 nm\noffset_y = -20 nm\n", 1);
    assert_close(tt_surface_height(S, 130e-9, 80e-9), 0, 0);            /* a hole's floor */
    assert_close(tt_surface_height(S, 100e-9, 100e-9), 0, 0);           /* 36 nm from it */
    assert_close(tt_surface_height(S, 185e-9, 80e-9), 20e-9, 0);        /* 55 nm: the plane */
    tt_surface_free(S);
    /* hexagonal: rows 173.2 nm apart, the second shifted by half a period */
    S = make("[surface]\ntype = lattice\nlattice = hexagonal\nperiod = 200 nm\nfeature_radius = 50 nm\n"
             "height = 20 nm\n", 1);
    const double b = 200e-9 * sqrt(3) / 2;
    assert_close(tt_surface_height(S, 100e-9, 0.5 * b), 20e-9, 0);
    assert_close(tt_surface_height(S, 200e-9, 1.5 * b + 49e-9), 20e-9, 0);
    assert_close(tt_surface_height(S, 100e-9, 1.5 * b), 0, 0);
    assert_close(tt_surface_height(S, 300e-9, 2.5 * b), 20e-9, 0);
    tt_surface_free(S);
    /* spikes: the cone tip's profile upside down, R = 10 nm, 25 deg, 50 nm high */
    S = make("[surface]\ntype = lattice\nfeature = spike\nperiod = 200 nm\nheight = 50 nm\n"
             "spike_radius = 10 nm\nspike_half_angle = 25 deg\n", 1);
    const double R = 10e-9, th = 25 * M_PI / 180, H = 50e-9;
    for (double rho = 0; rho < 60e-9; rho += 1e-9) {
        double t = rho <= R * cos(th) ? R - sqrt(R * R - rho * rho) : R * (1 - sin(th)) + (rho - R * cos(th)) / tan(th);
        assert_close(tt_surface_height(S, 100e-9 + rho, 100e-9), fmax(H - t, 0), 1e-17);
    }
    tt_surface_free(S);
    /* a grating by its critical dimension, shifted: lines 60 nm wide from x = 50 nm */
    S = make("[surface]\ntype = grating\nperiod = 200 nm\nline_width = 60 nm\noffset_x = 50 nm\n", 1);
    assert_close(tt_surface_height(S, 49e-9, 0), 0, 0);
    assert_close(tt_surface_height(S, 51e-9, 0), 20e-9, 0);
    assert_close(tt_surface_height(S, 109e-9, 0), 20e-9, 0);
    assert_close(tt_surface_height(S, 111e-9, 0), 0, 0);
    /* the exact dilation follows the shift: a sphere's image is the unshifted one's, moved */
    tt_surface *U = make("[surface]\ntype = grating\nperiod = 200 nm\nline_width = 60 nm\n", 1);
    tt_tip_shape tip = {TT_TIP_SPHERE, 30e-9, 0};
    tt_dilation *D, *E;
    assert_int_equal(tt_dilation_alloc(&D, S, &tip, 0, 0, 1e-6, 1e-6, 1e-9), TT_OK);
    assert_int_equal(tt_dilation_alloc(&E, U, &tip, 0, 0, 1e-6, 1e-6, 1e-9), TT_OK);
    assert_int_equal(tt_dilation_nodes(D), 0);
    for (double x = 100e-9; x < 500e-9; x += 0.7e-9)
        assert_close(tt_dilation_height(D, x, 0), tt_dilation_height(E, x - 50e-9, 0), 1e-20);
    tt_dilation_free(D);
    tt_dilation_free(E);
    tt_surface_free(U);
    tt_surface_free(S);
    make("[surface]\ntype = grating\nline_width = 60 nm\nduty = 30 %\n", 0);
    assert_non_null(strstr(tt_error_message(), "line_width and duty both give the line's width"));
    make("[surface]\ntype = grating\nperiod = 200 nm\nline_width = 200 nm\n", 0);
    assert_non_null(strstr(tt_error_message(), "fills the 200 nm period"));
    make("[surface]\ntype = lattice\nperiod = 200 nm\nfeature_radius = 95 nm\nedge_width = 5 nm\n", 0);
    assert_non_null(strstr(tt_error_message(), "touch at the 200 nm period"));
    make("[surface]\ntype = lattice\nfeature = spike\nperiod = 100 nm\nheight = 500 nm\n", 0);
    assert_non_null(strstr(tt_error_message(), "more than twice the 100 nm period"));
    make("[surface]\ntype = grating\nfeature = hole\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] feature: a key of type = lattice"));
    make("[surface]\ntype = steps\noffset_y = 5 nm\n", 0);
    assert_non_null(strstr(tt_error_message(), "[surface] offset_y: a key of type = lattice"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shapes),     cmocka_unit_test(rough_statistics), cmocka_unit_test(material_maps),
        cmocka_unit_test(png_maps),   cmocka_unit_test(bad_input), cmocka_unit_test(other_types_keys), cmocka_unit_test(lattices_and_offsets),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
