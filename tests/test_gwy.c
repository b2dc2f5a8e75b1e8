/* Gwyddion native files: written channels read back with their names, sizes, units,
 * values and metadata; Gwyddion itself loads the file where it is installed. */
#include <stdlib.h>

#include "tt_gwyddion_test.h"
#include "tiptap/io/gwy.h"
#include "tiptap/util/error.h"

static void round_trip(void **st)
{
    (void)st;
    enum { NX = 5, NY = 3 };
    double h[NX * NY], p[NX * NY];
    for (int i = 0; i < NX * NY; i++) {
        h[i] = 1e-9 * i - 3e-9;
        p[i] = 90 + 0.25 * i;
    }
    h[7] = NAN;
    tt_gwy_channel ch[2] = {{"height (trace)", NX, NY, 2e-6, 1.2e-6, 0, 0, "m", "m", h},
                            {"phase (retrace)", NX, NY, 2e-6, 1.2e-6, 0, 0, "m", "deg", p}};
    const char *keys[] = {"feedback.setpoint", "scan.line_rate"};
    const char *vals[] = {"80 %", "4 Hz"};
    char path[] = "/tmp/tt_gwy_XXXXXX";
    close(mkstemp(path));
    assert_int_equal(tt_gwy_write(path, ch, 2, keys, vals, 2), TT_OK);
    tt_gwy_file *f;
    assert_int_equal(tt_gwy_read(path, &f), TT_OK);
    assert_int_equal(f->nch, 2);
    assert_string_equal(f->ch[0].title, "height (trace)");
    assert_string_equal(f->ch[1].title, "phase (retrace)");
    assert_string_equal(f->ch[0].zunits, "m");
    assert_string_equal(f->ch[1].zunits, "deg");
    assert_string_equal(f->ch[1].xyunits, "m");
    for (int c = 0; c < 2; c++) {
        assert_int_equal(f->ch[c].xres, NX);
        assert_int_equal(f->ch[c].yres, NY);
        assert_true(f->ch[c].xreal == 2e-6 && f->ch[c].yreal == 1.2e-6);
    }
    for (int i = 0; i < NX * NY; i++) {
        if (i == 7)
            assert_true(isnan(f->ch[0].data[i]));
        else
            assert_true(f->ch[0].data[i] == h[i]); /* doubles, stored exactly */
        assert_true(f->ch[1].data[i] == p[i]);
    }
    assert_int_equal(f->nmeta, 2);
    assert_string_equal(f->keys[0], "feedback.setpoint");
    assert_string_equal(f->values[0], "80 %");
    assert_string_equal(f->values[1], "4 Hz");
    tt_gwy_file_free(f);
    tt_assert_gwyddion_loads(path);
    remove(path);
}

/* A damaged file is refused with its name, not read past its end. */
static void truncated_file_refused(void **st)
{
    (void)st;
    double d[4] = {1, 2, 3, 4};
    tt_gwy_channel ch = {"x", 2, 2, 1e-6, 1e-6, 0, 0, "m", "m", d};
    char path[] = "/tmp/tt_gwy_cut_XXXXXX";
    close(mkstemp(path));
    assert_int_equal(tt_gwy_write(path, &ch, 1, NULL, NULL, 0), TT_OK);
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    unsigned char b[4096];
    size_t n = fread(b, 1, sizeof b, fp);
    fclose(fp);
    assert_true(n > 0 && n < sizeof b); /* the whole file */
    for (size_t cut = 0; cut < n; cut++) {
        fp = fopen(path, "wb");
        assert_non_null(fp);
        fwrite(b, 1, cut, fp);
        fclose(fp);
        tt_gwy_file *f = NULL;
        assert_int_equal(tt_gwy_read(path, &f), TT_EIO);
        assert_null(f);
    }
    remove(path);
}

/* The titles TopoStats and AFMReader select channels by: TopoStats' default "Height" is
 * the height trace; a retrace is told apart, a long name is cut, never overrun. */
static void titles(void **st)
{
    (void)st;
    char t[32];
    assert_string_equal(tt_gwy_title(t, sizeof t, "height", 0), "Height");
    assert_string_equal(tt_gwy_title(t, sizeof t, "height", 1), "Height (retrace)");
    assert_string_equal(tt_gwy_title(t, sizeof t, "peak_force", 0), "Peak force");
    assert_string_equal(tt_gwy_title(t, sizeof t, "harmonic2_phase", 1), "Harmonic2 phase (retrace)");
    char small[7] = "xxxxxx";
    assert_string_equal(tt_gwy_title(small, sizeof small, "height", 1), "Height");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(round_trip),
        cmocka_unit_test(truncated_file_refused),
        cmocka_unit_test(titles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
