/* GSF files: exact layout (header, NUL padding to a multiple of 4, little-endian
 * float32, first row at the top) and a round trip; Gwyddion's thumbnailer reads them
 * where it is installed. */
#include <locale.h>
#include <stdlib.h>
#include <unistd.h>

#include "tt_gwyddion_test.h"
#include "tiptap/util/error.h"
#include "tiptap/io/gsf.h"

static void layout_is_exact(void **st)
{
    (void)st;
    const char *titles[] = {"h", "hh", "hhh", "hhhh"}; /* four header lengths mod 4 */
    for (int t = 0; t < 4; t++) {
        double d[6] = {1, 2, 3, 4, 5, NAN};
        tt_gsf_field g = {3, 2, 1e-6, 0.5e-6, 0, 0, "m", "m", titles[t], d, NULL, NULL, 0};
        char path[] = "/tmp/tt_gsf_XXXXXX";
        int fd = mkstemp(path);
        close(fd);
        assert_int_equal(tt_gsf_write(path, &g), TT_OK);
        FILE *f = fopen(path, "rb");
        static unsigned char buf[4096];
        size_t n = fread(buf, 1, sizeof buf, f);
        fclose(f);
        assert_memory_equal(buf, "Gwyddion Simple Field 1.0\n", 26);
        assert_non_null(strstr((char *)buf, "XRes = 3\n"));
        assert_non_null(strstr((char *)buf, "YRes = 2\n"));
        assert_non_null(strstr((char *)buf, "XReal = 1e-06\n"));
        size_t hdr = strlen((char *)buf);
        size_t start = (hdr / 4 + 1) * 4;
        for (size_t i = hdr; i < start; i++)
            assert_int_equal(buf[i], 0);
        assert_int_equal(n, start + 6 * 4);
        assert_int_equal(start % 4, 0);
        /* little endian float32: 1.0f = 00 00 80 3f; the first row comes first */
        unsigned char one[4] = {0x00, 0x00, 0x80, 0x3f};
        assert_memory_equal(buf + start, one, 4);
        size_t xr, yr;
        double xre, yre, *data;
        assert_int_equal(tt_gsf_read(path, &xr, &yr, &xre, &yre, &data), TT_OK);
        assert_int_equal(xr, 3);
        assert_int_equal(yr, 2);
        assert_close(yre, 0.5e-6, 1e-18);
        for (int i = 0; i < 5; i++)
            assert_close(data[i], d[i], 0);
        assert_true(isnan(data[5]));
        free(data);
        tt_assert_gwyddion_loads(path);
        unlink(path);
    }
}

static void numbers_in_the_c_locale(void **st)
{
    (void)st;
    if (!setlocale(LC_ALL, "de_DE.UTF-8") && !setlocale(LC_ALL, "fr_FR.UTF-8")) {
        print_message("no comma-decimal locale installed: skipped\n");
        return;
    }
    double d[1] = {1};
    tt_gsf_field g = {1, 1, 1.5e-6, 1.5e-6, 0, 0, "m", "m", "x", d, NULL, NULL, 0};
    char path[] = "/tmp/tt_gsf_XXXXXX";
    close(mkstemp(path));
    assert_int_equal(tt_gsf_write(path, &g), TT_OK);
    setlocale(LC_ALL, "C");
    FILE *f = fopen(path, "rb");
    char buf[512];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = 0;
    fclose(f);
    assert_non_null(strstr(buf, "XReal = 1.5e-06"));
    unlink(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(layout_is_exact),
        cmocka_unit_test(numbers_in_the_c_locale),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
