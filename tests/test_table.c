/* Tables of results (util/table.h): columns of numbers and texts, new rows NaN and "",
 * arrays that stay contiguous as rows grow past the first allocations, metadata, and
 * columns refused once rows exist. */
#include "tt_test.h"
#include "tiptap/util/error.h"
#include "tiptap/util/table.h"

static void rows_grow_and_keep_their_values(void **st)
{
    (void)st;
    tt_table *t;
    assert_int_equal(tt_table_alloc(&t), TT_OK);
    assert_int_equal(tt_table_add(t, "z", "m", 0), TT_OK);
    assert_int_equal(tt_table_add(t, "branch", "", 1), TT_OK);
    assert_int_equal(tt_table_add(t, "phase", "deg", 0), TT_OK);
    enum { N = 1000 }; /* past several doublings of the first 64 */
    for (int i = 0; i < N; i++) {
        assert_int_equal(tt_table_row(t), TT_OK);
        tt_table_set(t, 0, i * 1e-9);
        if (i % 3 == 0)
            assert_int_equal(tt_table_set_text(t, 1, i % 2 ? "retract" : "approach"), TT_OK);
    }
    assert_int_equal(tt_table_rows(t), N);
    assert_int_equal(tt_table_columns(t), 3);
    const double *z = tt_table_numbers(t, 0), *ph = tt_table_numbers(t, 2);
    for (int i = 0; i < N; i++) {
        assert_true(z[i] == i * 1e-9);
        assert_true(isnan(ph[i])); /* never set */
        assert_string_equal(tt_table_text(t, 1, (size_t)i), i % 3 ? "" : i % 2 ? "retract" : "approach");
    }
    assert_null(tt_table_numbers(t, 1));
    assert_string_equal(tt_table_text(t, 0, 0), "");
    assert_string_equal(tt_table_unit(t, 2), "deg");
    assert_int_equal(tt_table_is_text(t, 1), 1);
    assert_int_equal(tt_table_find(t, "phase"), 2);
    assert_int_equal(tt_table_find(t, "nothing"), -1);
    /* a text into a number column, a column after the rows: refused */
    assert_int_equal(tt_table_set_text(t, 0, "x"), TT_EINVAL);
    assert_int_equal(tt_table_add(t, "late", "", 0), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "late"));
    tt_table_free(t);
}

static void metadata_in_order(void **st)
{
    (void)st;
    tt_table *t;
    assert_int_equal(tt_table_alloc(&t), TT_OK);
    assert_int_equal(tt_table_meta(t, "kind", "point"), TT_OK);
    assert_int_equal(tt_table_meta(t, "cycles", "100"), TT_OK);
    assert_int_equal(tt_table_metas(t), 2);
    assert_string_equal(tt_table_meta_key(t, 1), "cycles");
    assert_string_equal(tt_table_meta_value(t, 0), "point");
    assert_string_equal(tt_table_meta_key(t, 2), "");
    assert_int_equal(tt_table_rows(t), 0);
    tt_table_free(t);
    tt_table_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rows_grow_and_keep_their_values),
        cmocka_unit_test(metadata_in_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
