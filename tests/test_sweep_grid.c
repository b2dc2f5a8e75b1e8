/* Parameter grids (tiptap/config/sweep.h): lists, linear and log ranges in SI units,
 * the first key varying slowest, each combination's scene holding its values, and bad
 * specifications refused naming the key. */
#include <math.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/sweep.h"
#include "tiptap/util/error.h"

static tt_scene *blend(void)
{
    tt_scene *s = tt_scene_alloc();
    assert_non_null(s);
    assert_int_equal(tt_scene_load_string(s, "[material soft]\nyoungs_modulus = 100 MPa\n"
                                             "[material hard]\nyoungs_modulus = 3 GPa\n", "blend"), TT_OK);
    return s;
}

static void grid_order_and_values(void **st)
{
    (void)st;
    tt_scene *s = blend();
    tt_sweep *g;
    assert_int_equal(tt_sweep_alloc(&g, s), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=10nm:30nm:5"), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "approach.material = soft, hard"), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "material.hard.adhesion_energy=log:1mJ/m^2:100mJ/m^2:3"), TT_OK);
    assert_int_equal(tt_sweep_count(g), 5 * 2 * 3);
    assert_string_equal(tt_sweep_unit(g, 0), "m");
    assert_string_equal(tt_sweep_unit(g, 1), "");
    assert_string_equal(tt_sweep_unit(g, 2), "J/m^2");
    /* combination 7 = levels (1, 0, 1): nested loops, the first key outermost */
    assert_int_equal(tt_sweep_level(g, 7, 0), 1);
    assert_int_equal(tt_sweep_level(g, 7, 1), 0);
    assert_int_equal(tt_sweep_level(g, 7, 2), 1);
    assert_true(fabs(tt_sweep_value(g, 7, 0) - 15e-9) < 1e-20);
    assert_true(isnan(tt_sweep_value(g, 7, 1)));
    assert_true(fabs(tt_sweep_value(g, 7, 2) - 10e-3) < 1e-15);
    assert_true(fabs(tt_sweep_value(g, 29, 0) - 30e-9) < 1e-22); /* the range ends at TO */
    tt_scene *c;
    assert_int_equal(tt_sweep_scene(g, 7, &c), TT_OK);
    double a0, w;
    assert_int_equal(tt_scene_get_double(c, "cantilever", NULL, "free_amplitude", &a0), TT_OK);
    assert_int_equal(tt_scene_get_double(c, "material", "hard", "adhesion_energy", &w), TT_OK);
    assert_true(fabs(a0 - 15e-9) < 1e-20 && fabs(w - 10e-3) < 1e-15);
    assert_string_equal(tt_scene_get_string(c, "approach", NULL, "material"), "soft");
    tt_scene_free(c);
    /* the base scene is untouched */
    assert_false(tt_scene_has(s, "cantilever", NULL, "free_amplitude"));
    tt_sweep_free(g);
    tt_scene_free(s);
}

static void percentages_stay_fractions(void **st)
{
    (void)st;
    tt_scene *s = blend();
    tt_sweep *g;
    assert_int_equal(tt_sweep_alloc(&g, s), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "feedback.setpoint=10%:90%:3"), TT_OK);
    assert_string_equal(tt_sweep_unit(g, 0), "1");
    assert_true(fabs(tt_sweep_value(g, 1, 0) - 0.5) < 1e-15);
    tt_scene *c;
    assert_int_equal(tt_sweep_scene(g, 1, &c), TT_OK);
    double sp;
    tt_dim dim;
    assert_int_equal(tt_scene_get_quantity(c, "feedback", NULL, "setpoint", &sp, &dim), TT_OK);
    assert_true(dim == TT_DIM_FRACTION && fabs(sp - 0.5) < 1e-15);
    tt_scene_free(c);
    tt_sweep_free(g);
    tt_scene_free(s);
}

static void bad_specifications(void **st)
{
    (void)st;
    tt_scene *s = blend();
    tt_sweep *g;
    assert_int_equal(tt_sweep_alloc(&g, s), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "cantilever.stiffness=1N/m"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "cantilever.stiffness: unknown key"));
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=10kHz,20kHz"), TT_EINVAL);
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=10nm:20nm:0"), TT_EINVAL);
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=log:0nm:20nm:3"), TT_EINVAL);
    assert_int_equal(tt_sweep_vary(g, "approach.material=a:b:3"), TT_EINVAL);
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude"), TT_EINVAL);
    assert_int_equal(tt_sweep_keys(g), 0);
    /* a value the scene refuses names the combination and the key */
    assert_int_equal(tt_sweep_vary(g, "cantilever.quality_factor=400,-1"), TT_OK);
    tt_scene *c = NULL;
    assert_int_equal(tt_sweep_scene(g, 1, &c), TT_EINVAL);
    assert_null(c);
    assert_non_null(strstr(tt_error_message(), "combination 2 (cantilever.quality_factor=-1)"));
    assert_non_null(strstr(tt_error_message(), "quality_factor"));
    tt_sweep_free(g);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(grid_order_and_values),
        cmocka_unit_test(percentages_stay_fractions),
        cmocka_unit_test(bad_specifications),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
