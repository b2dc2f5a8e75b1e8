/* Units: SI prefixes, compound units, refusal of missing and wrong units. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "tiptap/config/units.h"

static double parse_ok(const char *text, unsigned dims)
{
    double v = NAN;
    char why[256];
    assert_int_equal(tt_units_parse(text, dims, &v, NULL, why, sizeof why), 0);
    return v;
}

static void prefixes_scale_to_si(void **state)
{
    (void)state;
    assert_float_equal(parse_ok("52 kHz", TT_DIM_FREQUENCY), 52e3, 1e-9);
    assert_float_equal(parse_ok("0.58 N/m", TT_DIM_STIFFNESS), 0.58, 1e-15);
    assert_float_equal(parse_ok("100 mJ/m^2", TT_DIM_SURFACE_ENERGY), 0.1, 1e-15);
    assert_float_equal(parse_ok("0.265 nm", TT_DIM_LENGTH), 0.265e-9, 1e-24);
    assert_float_equal(parse_ok("70 GPa", TT_DIM_PRESSURE), 70e9, 1e-3);
    assert_float_equal(parse_ok("1 TPa", TT_DIM_PRESSURE), 1e12, 1);
    assert_float_equal(parse_ok("10 um/s", TT_DIM_VELOCITY), 1e-5, 1e-18);
    assert_float_equal(parse_ok("2 µm", TT_DIM_LENGTH), 2e-6, 1e-18);
    assert_float_equal(parse_ok("1.5e3 m", TT_DIM_LENGTH), 1500, 1e-12);
    assert_float_equal(parse_ok("-5 nm", TT_DIM_LENGTH), -5e-9, 1e-21);
    assert_float_equal(parse_ok("90 deg", TT_DIM_ANGLE), M_PI / 2, 1e-15);
    assert_float_equal(parse_ok("400", TT_DIM_NONE), 400, 0);
    assert_float_equal(parse_ok("1 mm", TT_DIM_LENGTH), 1e-3, 1e-18);
    assert_float_equal(parse_ok("3 m", TT_DIM_LENGTH), 3, 0);
}

static void setpoint_takes_length_or_percent(void **state)
{
    (void)state;
    double v;
    tt_dim d;
    char why[256];
    unsigned dims = TT_DIM_LENGTH | TT_DIM_FRACTION;
    assert_int_equal(tt_units_parse("80 %", dims, &v, &d, why, sizeof why), 0);
    assert_float_equal(v, 0.8, 1e-15);
    assert_int_equal(d, TT_DIM_FRACTION);
    assert_int_equal(tt_units_parse("16 nm", dims, &v, &d, why, sizeof why), 0);
    assert_int_equal(d, TT_DIM_LENGTH);
}

static void refuses_bad_units(void **state)
{
    (void)state;
    double v;
    char why[256];
    assert_int_not_equal(tt_units_parse("52", TT_DIM_FREQUENCY, &v, NULL, why, sizeof why), 0);
    assert_non_null(strstr(why, "missing unit"));
    assert_int_not_equal(tt_units_parse("52 nm", TT_DIM_FREQUENCY, &v, NULL, why, sizeof why), 0);
    assert_non_null(strstr(why, "wrong unit"));
    assert_int_not_equal(tt_units_parse("52 kHzz", TT_DIM_FREQUENCY, &v, NULL, why, sizeof why), 0);
    assert_non_null(strstr(why, "unknown unit"));
    assert_int_not_equal(tt_units_parse("nan Hz", TT_DIM_FREQUENCY, &v, NULL, why, sizeof why), 0);
    assert_int_not_equal(tt_units_parse("inf Hz", TT_DIM_FREQUENCY, &v, NULL, why, sizeof why), 0);
    assert_int_not_equal(tt_units_parse("abc", TT_DIM_NONE, &v, NULL, why, sizeof why), 0);
    assert_int_not_equal(tt_units_parse("400 Hz", TT_DIM_NONE, &v, NULL, why, sizeof why), 0);
    assert_int_not_equal(tt_units_parse("", TT_DIM_LENGTH, &v, NULL, why, sizeof why), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(prefixes_scale_to_si),
        cmocka_unit_test(setpoint_takes_length_or_percent),
        cmocka_unit_test(refuses_bad_units),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
