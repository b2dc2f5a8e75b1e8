/* Every bundled surface under every tip shape: each file in surfaces/ (listed from the
 * folder, so a new one is covered) scanned on a small raster with a point, a sphere and
 * a cone tip must run, make a dilation wherever the topography is not flat, and give
 * finite numbers in every image. The tip's reach takes the dilation's look-ups past the
 * scan area, where a rough surface's grid had been read before its array (issue 19). */
#include <dirent.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/util/error.h"

/* 12 x 12 pixels of 25 nm: fine enough for the particles' 15 nm spheres, a few tens of
 * drive cycles a pixel; a small tip radius widens the dilation's margin the most in
 * nodes, a large one in metres, so both are run. */
static const char *const overrides[] = {
    "scan.size=300 nm", "scan.pixels=12", "scan.lines=12", "scan.line_rate=800 Hz",
    "scan.settle_cycles=200",
    "scan.channels=height, error, phase, peak_force, indentation, dissipation, topography",
};

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The names of the .ini files in surfaces/, sorted; the caller frees each and the array. */
static char **surface_files(size_t *n)
{
    DIR *d = opendir(TT_SOURCE_DIR "/surfaces");
    assert_non_null(d);
    char **names = NULL;
    *n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".ini") != 0)
            continue;
        names = realloc(names, (*n + 1) * sizeof *names);
        assert_non_null(names);
        names[(*n)++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, *n, sizeof *names, by_name);
    return names;
}

static void scan_one(const char *file, const char *shape, const char *radius)
{
    char path[4096], set[200];
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load(sc, TT_SOURCE_DIR "/scans/quick.ini"), TT_OK);
    snprintf(path, sizeof path, "%s/surfaces/%s", TT_SOURCE_DIR, file);
    if (tt_scene_load(sc, path) != TT_OK)
        fail_msg("%s: %s", file, tt_error_message());
    for (size_t i = 0; i < sizeof overrides / sizeof *overrides; i++)
        assert_int_equal(tt_scene_set(sc, overrides[i]), TT_OK);
    snprintf(set, sizeof set, "tip.shape=%s", shape);
    assert_int_equal(tt_scene_set(sc, set), TT_OK);
    snprintf(set, sizeof set, "tip.radius=%s", radius);
    assert_int_equal(tt_scene_set(sc, set), TT_OK);
    tt_scan *s = NULL;
    if (tt_config_scan_alloc(&s, sc) != TT_OK)
        fail_msg("%s, %s tip: %s", file, shape, tt_error_message());
    int flat = tt_scan_dilation(s) == NULL;
    if (strcmp(shape, "point") != 0 && flat) {
        /* no dilation: only for a flat topography */
        tt_surface *S = NULL;
        assert_int_equal(tt_config_surface_alloc(&S, sc, 300e-9, 300e-9), TT_OK);
        assert_true(tt_surface_flat(S));
        tt_surface_free(S);
    }
    if (tt_scan_run(s, 2, NULL, NULL) != TT_OK)
        fail_msg("%s, %s tip: %s", file, shape, tt_error_message());
    long n = tt_scan_xres(s) * tt_scan_yres(s), bad = 0, checked = 0;
    for (int c = 0; c < TT_CH_COUNT; c++)
        for (int r = 0; r < 2; r++) {
            const double *img = tt_scan_image(s, c, r);
            for (long i = 0; img && i < n; i++, checked++)
                bad += !isfinite(img[i]);
        }
    print_message("%-18s %-6s R = %-5s: %ld values, %ld not finite%s\n", file, shape, radius,
                  checked, bad, flat ? "" : ", dilated");
    assert_int_equal(checked, 2 * 7 * n);
    assert_int_equal(bad, 0);
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void every_surface_with_every_tip(void **st)
{
    (void)st;
    size_t n;
    char **files = surface_files(&n);
    assert_true(n >= 8); /* the bundled samples at the time of writing */
    for (size_t i = 0; i < n; i++) {
        scan_one(files[i], "point", "10 nm");
        scan_one(files[i], "sphere", "10 nm");
        scan_one(files[i], "cone", "10 nm");
        scan_one(files[i], "sphere", "2 nm");
        scan_one(files[i], "cone", "40 nm");
        free(files[i]);
    }
    free(files);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_surface_with_every_tip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
