/* Particle surfaces: the cell grid stays bounded at any radius and placement is
 * near-linear in the count (issue 12, item 14). */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/instrument/surface.h"

static tt_surface *particles(const char *radius, long count)
{
    char text[256];
    snprintf(text, sizeof text,
             "[material a]\n[surface]\ntype = particles\nparticle_radius = %s\nparticle_count = %ld\n"
             "seed = 5\n", radius, count);
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(s, text, "p.ini"), TT_OK);
    tt_surface *S = NULL;
    int rc = tt_config_surface_alloc(&S, s, 1e-6, 1e-6);
    tt_scene_free(s);
    if (rc)
        fail_msg("%s particles of radius %s: %s", count > 0 ? "placing" : "no", radius,
                 tt_error_message());
    return S;
}

/* (size / 2 r)^2 cells overflowed an int at 1e-30 m and asked for 5.1 GB at 14 pm. */
static void tiny_radius_bounded_grid(void **st)
{
    (void)st;
    const char *radii[] = {"1e-30 m", "14 pm", "1e-21 nm"};
    for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++) {
        tt_surface *S = particles(radii[i], 12);
        /* spheres far below any sampling: the flat, nowhere above 2 r */
        for (int k = 0; k < 100; k++)
            assert_true(tt_surface_height(S, k * 1e-8, k * 0.7e-8) <= 2 * 14e-12);
        tt_surface_free(S);
    }
}

/* 100,000 spheres of 0.5 nm over 1 um: they cover N pi r^2 / A = 7.85 % of the area, the
 * highest points are 2 r, and placing them is near-linear (it had been quadratic:
 * over 100 s). */
static void many_particles_cover_their_area(void **st)
{
    (void)st;
    tt_surface *S = particles("0.5 nm", 100000);
    long in = 0, n = 1000;
    double top = 0;
    for (long j = 0; j < n; j++)
        for (long i = 0; i < n; i++) {
            double h = tt_surface_height(S, (i + 0.5) * 1e-9, (j + 0.5) * 1e-9);
            in += h > 0;
            top = fmax(top, h);
        }
    double want = 100000 * M_PI * 0.25e-18 / 1e-12;
    assert_close((double)in / (double)(n * n), want, 0.004);
    assert_true(top <= 1e-9 && top > 0.9e-9);
    tt_surface_free(S);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(tiny_radius_bounded_grid),
        cmocka_unit_test(many_particles_cover_their_area),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
