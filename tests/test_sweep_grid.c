/* Parameter grids (tiptap/config/sweep.h): lists, linear and log ranges in SI units,
 * the first key varying slowest, each combination's scene holding its values, and bad
 * specifications refused naming the key; grids beyond TT_SWEEP_MAX_COMBINATIONS
 * refused from their forms alone with the count, however far beyond 64 bits; ranges
 * that would repeat or drop values refused, and ranges whose span overflows giving
 * finite values. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
    /* N is digits only, as the grid's count reads it: a sign would count one value */
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=10nm:20nm:+3"), TT_EINVAL);
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=10nm:20nm:3x"), TT_EINVAL);
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

/* The count is the product of the per-key counts, exact up to 64 bits and from the
 * logarithm beyond; nothing is parsed or stored, so the refusal costs the same for
 * 1e21 or 10^400 combinations. */
static void astronomical_grids_refused(void **st)
{
    (void)st;
    const char *three[] = {"approach.from=1nm:2nm:10000000", "cantilever.free_amplitude=1nm:2nm:10000000",
                           "approach.points=1:1000:10000000"};
    assert_int_equal(tt_sweep_check_size(three, 3), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "1e+21 (about 2^70) combinations"));
    assert_non_null(strstr(tt_error_message(), "--vary approach.from=1nm:2nm:10000000 --vary cantilever"));
    /* 10^400 values in one range: beyond every integer and double */
    char huge[512] = "approach.from=1nm:2nm:";
    memset(huge + strlen(huge), '9', 400);
    const char *one[] = {huge};
    assert_int_equal(tt_sweep_check_size(one, 1), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "about 10^400 combinations"));
    assert_null(strchr(tt_error_message(), '\n'));
    /* 2^64 exactly: wraps to 0 in 64-bit arithmetic */
    const char *wrap[] = {"approach.from=1nm:2nm:4294967296", "approach.points=1:9:4294967296"};
    assert_int_equal(tt_sweep_check_size(wrap, 2), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "1.8e+19 (about 2^64) combinations"));
    /* just over and just at the maximum, with a list */
    const char *list[] = {"approach.from=1nm:2nm:1000000", "approach.material=a,b,c,d,e,f,g,h,i,j,k"};
    assert_int_equal(tt_sweep_check_size(list, 2), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), ": 11000000 combinations"));
    const char *at[] = {"approach.from=1nm:2nm:1000", "cantilever.free_amplitude=1nm:2nm:10000"};
    assert_int_equal(tt_sweep_check_size(at, 2), TT_OK);
    const char *above[] = {"approach.from=1nm:2nm:1000", "cantilever.free_amplitude=1nm:2nm:10001"};
    assert_int_equal(tt_sweep_check_size(above, 2), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), ": 10001000 combinations, more than the 10000000"));
    /* tt_sweep_vary refuses the key that would pass the maximum before storing it */
    tt_scene *s = blend();
    tt_sweep *g;
    assert_int_equal(tt_sweep_alloc(&g, s), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "approach.from=1nm:2nm:1000"), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=1nm:2nm:100000000000000000000"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "the grid would have 1e+23 (about 2^76) combinations"));
    assert_int_equal(tt_sweep_keys(g), 1);
    assert_int_equal(tt_sweep_count(g), 1000);
    tt_sweep_free(g);
    tt_scene_free(s);
}

/* A range gives N distinct values with both ends, or is refused naming it. */
static void ranges_distinct_with_both_ends(void **st)
{
    (void)st;
    tt_scene *s = blend();
    tt_sweep *g;
    assert_int_equal(tt_sweep_alloc(&g, s), TT_OK);
    /* 5 whole numbers from 2 to 4 would give 2,3,3,4,4 */
    assert_int_equal(tt_sweep_vary(g, "approach.points=2:4:5"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "approach.points=2:4:5: 5 whole numbers from 2 to 4 would repeat"));
    assert_non_null(strstr(tt_error_message(), "N at most 3"));
    /* N = 1 would drop TO */
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=10nm:30nm:1"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "TO would be dropped"));
    assert_int_equal(tt_sweep_vary(g, "feedback.setpoint=log:10%:90%:1"), TT_EINVAL);
    assert_int_equal(tt_sweep_vary(g, "approach.from=1nm:1nm:3"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "FROM equals TO"));
    /* distinct numbers, alike once written at 15 digits */
    assert_int_equal(tt_sweep_vary(g, "approach.from=1nm:1.0000000000000004nm:3"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "values 1 and 2 are both '1e-09 m'"));
    assert_int_equal(tt_sweep_vary(g, "approach.points=1:99999999999999999999:3"), TT_EINVAL);
    /* finite as written, infinite in SI (found by fuzz_vary) */
    assert_int_equal(tt_sweep_vary(g, "material.hard.youngs_modulus=1e308GPa,2GPa"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "'1e308GPa' is beyond the largest number in SI units"));
    assert_int_equal(tt_sweep_vary(g, "material.hard.youngs_modulus=1GPa:1e308GPa:3"), TT_EINVAL);
    assert_int_equal(tt_sweep_keys(g), 0);
    /* one value is fine when the ends agree; whole numbers exact and descending */
    assert_int_equal(tt_sweep_vary(g, "cantilever.free_amplitude=10nm:10nm: 1 "), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "approach.points=9007199254740992:9007199254740000:3"), TT_OK);
    assert_string_equal(tt_sweep_text(g, 0, 1), "9007199254740992");
    assert_string_equal(tt_sweep_text(g, 1, 1), "9007199254740496");
    assert_string_equal(tt_sweep_text(g, 2, 1), "9007199254740000");
    /* as many whole numbers as there are: every one */
    assert_int_equal(tt_sweep_vary(g, "scan.lines=7:3:5"), TT_OK);
    for (size_t i = 0; i < 5; i++)
        assert_true(tt_sweep_value(g, i, 2) == 7.0 - (double)i);
    /* the span -1.7e308 to 1.7e308 overflows a double: still finite values, 0 between */
    assert_int_equal(tt_sweep_vary(g, "approach.from=-1.7e308m:1.7e308m:3"), TT_OK);
    assert_true(tt_sweep_value(g, 0, 3) == -1.7e308);
    assert_true(tt_sweep_value(g, 1, 3) == 0);
    assert_true(tt_sweep_value(g, 2, 3) == 1.7e308);
    assert_string_equal(tt_sweep_text(g, 1, 3), "0 m");
    assert_int_equal(tt_sweep_count(g), 1 * 3 * 5 * 3);
    tt_sweep_free(g);
    tt_scene_free(s);
}

/* A control character in a specification is refused, shown escaped on one line. */
static void control_characters_refused(void **st)
{
    (void)st;
    tt_scene *s = blend();
    tt_sweep *g;
    assert_int_equal(tt_sweep_alloc(&g, s), TT_OK);
    assert_int_equal(tt_sweep_vary(g, "approach.material=a,b\nc"), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "approach.material=a,b\\x0ac: control character \\x0a"));
    assert_null(strchr(tt_error_message(), '\n'));
    tt_sweep_free(g);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(grid_order_and_values),
        cmocka_unit_test(percentages_stay_fractions),
        cmocka_unit_test(bad_specifications),
        cmocka_unit_test(astronomical_grids_refused),
        cmocka_unit_test(ranges_distinct_with_both_ends),
        cmocka_unit_test(control_characters_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
