/* The envelope tier through a ringing loop (the lesson's ki 10 kHz on the 20 nm
 * grating): the loop's oscillation moves the sample past the model's fixed 20 pm bound
 * in a cycle, and the bound grows where the checks pass well within their allowance
 * (scan_envelope.c's check). The model then runs most of the cycles, and the images and
 * the greatest indentation stay those of every cycle: the noise is 1e9 times colder
 * than the lesson's, so the difference is the tier's own, not two draws'. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tt_ringing_scene.h"
#include "tiptap/instrument/scan_envelope_stops.h"

static const char *base = TT_RINGING_SCENE;

static double greatest_indentation(const tt_scan *s)
{
    tt_contact_extent e;
    tt_scan_contact_extent(s, 0, &e);
    return e.indentation;
}

static void ringing_loop_on_the_model(void **st)
{
    (void)st;
    tt_scene *sa, *sb;
    tt_scan_envelope_stops_reset();
    tt_scan *env = tt_run_scan_on(base, "", "envelope", &sa);
    long n[TT_ENV_STOPS];
    tt_scan_envelope_stops(n);
    tt_scan *every = tt_run_scan_on(base, "", "every", &sb);
    const double frac = (double)tt_scan_cycles_integrated(env) / (double)tt_scan_cycles(env);
    double hmax, hrms, pmax, prms;
    tt_scan_diff(env, every, 0 /* height */, &hmax, &hrms);
    tt_scan_diff(env, every, 2 /* phase */, &pmax, &prms);
    const double ie = greatest_indentation(env), iv = greatest_indentation(every);
    print_message("integrated %.1f %% (model %ld, checks passed %ld, end_sample %ld); height "
                  "%.3g / %.3g nm, phase %.3g / %.3g deg; greatest indentation %.4g against "
                  "%.4g nm\n",
                  100 * frac, n[TT_ENV_MODEL], n[TT_ENV_CHECK_PASS], n[TT_ENV_END_SAMPLE],
                  hmax * 1e9, hrms * 1e9, pmax, prms, ie * 1e9, iv * 1e9);
    /* with the fixed bound nearly every cycle was integrated (97.8 % in the lesson) */
    assert_true(frac < 0.5);
    /* the ring itself, 79 nm at 295 Hz, against a tier error of tens of pm (4.5 pm max with the bound fixed) */
    assert_true(hrms < 0.05e-9);
    assert_true(hmax < 0.2e-9);
    assert_true(pmax < 0.5);
    /* the peaks come from the checked and integrated cycles' course, within 3 % */
    assert_true(iv > 0 && fabs(ie - iv) < 0.03 * iv);
    tt_scan_free(env);
    tt_scan_free(every);
    tt_scene_free(sa);
    tt_scene_free(sb);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(ringing_loop_on_the_model)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
