/* Force volume (tiptap/run/force_volume.h): over a two-material surface the adhesion
 * map is each material's Maugis-Dugdale least load on either side of the edge, and the
 * stiffness map the slope a quasi-static curve of that material's law gives, computed
 * here by hand from the law; the maps are the same bytes on one thread and two with the
 * thermal force on, pixel 0 is tiptap force's curve, and a run cut short keeps the lines
 * it finished, in its files too. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tt_blend_test.h"
#include "tt_test.h"
#include "tiptap/config/scene.h"
#include "tiptap/io/gsf.h"
#include "tiptap/physics/contact.h"
#include "tiptap/run/force.h"
#include "tiptap/run/force_volume.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

/* The blend's two materials (surfaces/polymer-blend.ini) in stripes across x: 8 pixels
 * over one 400 nm period, the disk material on the first half. */
static const char *blend =
    TT_TEST_BLEND_MATERIALS
    "[surface]\ntype = flat\nmap = stripes\nmap_materials = matrix, disk\nmap_period = 400 nm\n"
    "map_duty = 0.5\n"
    "[scan]\nsize = 400 nm\npixels = 8\nlines = 2\n"
    "[cantilever]\nspring_constant = 0.5 N/m\nresonance_frequency = 20 kHz\nquality_factor = 50\n"
    "free_amplitude = 10 nm\n"
    "[force]\nfrom = 12 nm\nto = -6 nm\nspeed = 1 um/s\n";

static const double K = 0.5, FROM = 12e-9, TO = -6e-9;

static tt_scene *scene(const char *more)
{
    tt_scene *s = tt_scene_alloc();
    if (tt_scene_load_string(s, blend, "blend") || (more && tt_scene_load_string(s, more, "more")))
        fail_msg("%s", tt_error_message());
    return s;
}

static tt_force_volume *run(const tt_scene *s, int threads, const char *folder, int want)
{
    tt_force_volume *v = NULL;
    const tt_force_volume_job job = {threads, folder, 0, NULL, NULL};
    int rc = tt_run_force_volume(s, &job, &v, NULL);
    if (rc != want)
        fail_msg("status %d: %s", rc, tt_error_message());
    assert_non_null(v);
    return v;
}

/* The contact branch's penetration where the lever's static balance holds at rest
 * separation z: z = -P(delta) / k - delta, with P >= 0 (its left side falls with delta
 * there), by bisection from lo (where P = 0) to 100 nm. */
static double balance(const tt_contact *law, double z, double lo)
{
    double hi = 100e-9;
    for (int i = 0; i < 200; i++) {
        double mid = 0.5 * (lo + hi);
        if (-tt_contact_load(law, mid, 1, NULL, NULL) / K - mid > z)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* What the volume's stiffness is, by hand: the quasi-static curve P(z) of the law on
 * an even grid of z, and -dP/dz by least squares through its points above half the
 * largest force (at z = to), as tiptap force fits the contact part. */
static double static_slope(const tt_contact *law)
{
    double lo = tt_contact_jumpin(law), hi = 100e-9;
    for (int i = 0; i < 200; i++) { /* P = 0 on the contact branch */
        double mid = 0.5 * (lo + hi);
        if (tt_contact_load(law, mid, 1, NULL, NULL) < 0)
            lo = mid;
        else
            hi = mid;
    }
    const double d0 = hi, pmax = tt_contact_load(law, balance(law, TO, d0), 1, NULL, NULL);
    double n = 0, sz = 0, szz = 0, sf = 0, szf = 0;
    for (int i = 0; i <= 4000; i++) {
        double z = TO + (FROM - TO) * i / 4000.0, d = balance(law, z, d0);
        double P = tt_contact_load(law, d, 1, NULL, NULL);
        if (!(P >= 0.5 * pmax))
            continue;
        n++, sz += z, szz += z * z, sf += P, szf += z * P;
    }
    return -(n * szf - sz * sf) / (n * szz - sz * sz);
}

static void maps_follow_each_material(void **state)
{
    (void)state;
    tt_scene *s = scene(NULL);
    tt_force_volume *v = run(s, 2, NULL, TT_OK);
    assert_int_equal(tt_force_volume_xres(v), 8);
    assert_int_equal(tt_force_volume_yres(v), 2);
    const double *mat = tt_force_volume_map(v, TT_FV_MATERIAL), *adh = tt_force_volume_map(v, TT_FV_ADHESION);
    const double *stiff = tt_force_volume_map(v, TT_FV_STIFFNESS);
    const char *names[2] = {"matrix", "disk"};
    double least[2], slope[2];
    for (int m = 0; m < 2; m++) {
        tt_contact *law;
        tt_contact_params cp;
        double Qi;
        if (tt_run_contact_alloc(s, names[m], NULL, &law, &cp, &Qi) != TT_OK)
            fail_msg("%s", tt_error_message());
        const tt_contact_summary *cs = tt_contact_summary_of(law);
        least[m] = -cs->pulloff_load * cs->force_scale;
        slope[m] = static_slope(law);
        tt_contact_free(law);
    }
    /* the edge between pixels 3 and 4: disk on the left half, matrix on the right */
    int seen[2] = {0, 0};
    for (long i = 0; i < 16; i++) {
        int m = (int)mat[i];
        assert_int_equal(m, i % 8 < 4 ? 1 : 0);
        seen[m]++;
        if (i % 8 == 3 || i % 8 == 4)
            print_message("pixel %ld (%s): adhesion %.6g nN (least load %.6g), stiffness %.7g N/m "
                          "(by hand %.7g)\n",
                          i, names[m], adh[i] * 1e9, least[m] * 1e9, stiff[i], slope[m]);
        assert_close(adh[i], least[m], 2e-3 * least[m]);
        /* 7e-6 off on the matrix (its interaction damping), 1e-7 on the disk */
        assert_close(stiff[i], slope[m], 1e-3 * slope[m]);
    }
    assert_int_equal(seen[0], 8);
    /* the two differ by far more than either's tolerance */
    assert_true(fabs(slope[1] - slope[0]) > 0.2 * slope[0]);
    assert_true(fabs(least[1] - least[0]) > 0.1 * least[0]);
    /* what each pixel reported is the map's */
    const tt_force_summary *p = tt_force_volume_pixel(v, 1, 6);
    assert_non_null(p);
    assert_true(p->adhesion == adh[14]);
    assert_true(p->indentation > 0 && p->indentation == tt_force_volume_map(v, TT_FV_INDENTATION)[14]);
    tt_force_volume_free(v);
    tt_scene_free(s);
}

static void same_bytes_on_any_thread_count(void **state)
{
    (void)state;
    tt_scene *s = scene("[noise]\ntemperature = 300 K\n[force]\nspeed = 4 um/s\n");
    tt_force_volume *a = run(s, 1, NULL, TT_OK), *b = run(s, 2, NULL, TT_OK);
    const size_t n = 16 * sizeof(double);
    for (int ch = 0; ch < TT_FV_COUNT; ch++)
        assert_memory_equal(tt_force_volume_map(a, ch), tt_force_volume_map(b, ch), n);
    /* and the noise is the pixel's own: two pixels of one material differ */
    const double *adh = tt_force_volume_map(a, TT_FV_ADHESION);
    assert_true(adh[5] != adh[6] && adh[13] != adh[5]);
    /* pixel 0's stream is tiptap force's own: its curve is that of the one curve on its
     * material (the disk), figure for figure */
    if (tt_scene_load_string(s, "[force]\nmaterial = disk\n", "one"))
        fail_msg("%s", tt_error_message());
    tt_table *t = NULL;
    tt_force_summary one;
    if (tt_run_force(s, &t, &one, NULL, NULL) != TT_OK)
        fail_msg("%s", tt_error_message());
    const tt_force_summary *p0 = tt_force_volume_pixel(a, 0, 0);
    assert_true(p0->adhesion == one.adhesion && p0->slope == one.slope && p0->jumpin_z == one.jumpin_z &&
                p0->pulloff_force == one.pulloff_force && p0->cycles == one.cycles);
    tt_table_free(t);
    tt_force_volume_free(a);
    tt_force_volume_free(b);
    tt_scene_free(s);
}

/* The first line's end asks to stop: the run says so, keeps that line (the other NAN)
 * and writes it. */
static void stop_after_line(void *user, long done, long total)
{
    (void)user, (void)total;
    if (done == 1)
        tt_cancel_request();
}

static void interrupted_keeps_lines(void **state)
{
    (void)state;
    char dir[] = "/tmp/tt_force_volume_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char out[300], path[400];
    snprintf(out, sizeof out, "%s/maps", dir);
    tt_scene *s = scene("[scan]\nlines = 3\n");
    tt_force_volume *v = NULL;
    const tt_force_volume_job job = {1, out, 0, stop_after_line, NULL};
    int written = 0;
    assert_int_equal(tt_run_force_volume(s, &job, &v, &written), TT_EINTR);
    tt_cancel_reset();
    assert_non_null(strstr(tt_error_message(), "1 of 3 lines"));
    assert_int_equal(tt_force_volume_lines_done(v), 1);
    assert_int_equal(written, 2 * TT_FV_COUNT + 2);
    snprintf(path, sizeof path, "%s/adhesion.gsf", out);
    size_t xres, yres;
    double xr, yr, *data;
    if (tt_gsf_read(path, &xres, &yres, &xr, &yr, &data))
        fail_msg("%s", tt_error_message());
    assert_int_equal(xres, 8);
    assert_int_equal(yres, 3);
    for (size_t i = 0; i < 24; i++) {
        assert_true(i < 8 ? data[i] > 1e-9 : isnan(data[i]));
        if (i < 8) /* GSF holds 32-bit floats */
            assert_close(data[i], tt_force_volume_map(v, TT_FV_ADHESION)[i], 1e-6 * data[i]);
    }
    free(data);
    tt_force_volume_free(v);
    tt_scene_free(s);
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

/* A bad key is refused before a line runs, and no folder is made. */
static void refusals(void **state)
{
    (void)state;
    tt_scene *s = scene("[force]\nfrom = -7 nm\n");
    tt_force_volume *v = NULL;
    const tt_force_volume_job job = {1, "/tmp/tt_force_volume_never", 0, NULL, NULL};
    assert_int_equal(tt_run_force_volume(s, &job, &v, NULL), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "[force] from"));
    assert_null(v);
    assert_int_not_equal(access("/tmp/tt_force_volume_never", F_OK), 0);
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(maps_follow_each_material),
        cmocka_unit_test(same_bytes_on_any_thread_count),
        cmocka_unit_test(interrupted_keeps_lines),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
