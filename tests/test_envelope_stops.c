/* The envelope tier's counts of why it integrates (tiptap/instrument/scan_envelope_stops.h)
 * account for the cycles it ran: every cycle of a line is the model's, a check's or one
 * integrated with the model off, the cycles the scan counts as integrated are checks or
 * such cycles, and the every-cycle tier, which has no controller, counts nothing. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_envelope_stops.h"
#include "tiptap/util/error.h"

/* A fast cantilever (Q 100) over 4 nm steps at 40 Hz, with thermal and detector noise
 * (the lesson's noise: the second-order model and its checks). */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 100\n"
    "free_amplitude = 20 nm\n"
    "[material stiff]\nyoungs_modulus = 100 GPa\n"
    "[scan]\nsize = 1 um\npixels = 16\nlines = 3\nline_rate = 40 Hz\nsettle_cycles = 1000\n"
    "lines_mode = continuous\n"
    "[surface]\ntype = steps\nstep_height = 4 nm\nstep_width = 300 nm\n"
    "[feedback]\nsetpoint = 80 %\nintegral_gain = 3000 Hz\n"
    "[noise]\nseed = 1\ntemperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n";

static void stepped(const char *extra, long n[TT_ENV_STOPS], long *cycles, long *integrated)
{
    tt_scene *sc;
    tt_scan *s = tt_make_scan(base, extra, &sc);
    tt_scan_envelope_stops_reset();
    for (long line = 0; line < tt_scan_lines(s); line++)
        if (tt_scan_step(s, line, NULL) != TT_OK)
            fail_msg("%s", tt_error_message());
    tt_scan_envelope_stops(n);
    *cycles = tt_scan_cycles(s);
    *integrated = tt_scan_cycles_integrated(s);
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void counts_account_for_the_cycles(void **st)
{
    (void)st;
    long n[TT_ENV_STOPS], cycles, integrated;
    stepped("[solver]\ntier = envelope\n", n, &cycles, &integrated);
    const long checks = n[TT_ENV_CHECK_PASS] + n[TT_ENV_CHECK_ERROR] + n[TT_ENV_CHECK_CONTACT] +
                        n[TT_ENV_CHECK_TOUCH] + n[TT_ENV_CHECK_CYCLE];
    print_message("cycles %ld, integrated %ld; model %ld, checks %ld (passed %ld), full %ld, "
                  "end_sample %ld, builds %ld\n",
                  cycles, integrated, n[TT_ENV_MODEL], checks, n[TT_ENV_CHECK_PASS], n[TT_ENV_FULL],
                  n[TT_ENV_END_SAMPLE], n[TT_ENV_BUILD]);
    /* the model ran most cycles, and each cycle that stands is one of three kinds (a
     * rolled-back stretch's cycles were counted once more) */
    assert_true(n[TT_ENV_MODEL] > cycles / 2);
    assert_true(n[TT_ENV_MODEL] + n[TT_ENV_CHECK_PASS] + n[TT_ENV_FULL] >= cycles);
    /* an integrated cycle of the run is a check or a cycle with the model off */
    assert_true(integrated > 0);
    assert_true(integrated <= checks + n[TT_ENV_FULL]);
    /* the reasons for a cycle with the model off are some of those cycles */
    const long why = n[TT_ENV_FULL_EDGE] + n[TT_ENV_FULL_CHANGE] + n[TT_ENV_FULL_REDO] +
                     n[TT_ENV_FULL_WAIT] + n[TT_ENV_FULL_GRAZE];
    assert_true(why > 0 && why <= n[TT_ENV_FULL]);
    assert_true(n[TT_ENV_BUILD] > 0);
    for (int i = 0; i < TT_ENV_STOPS; i++) {
        assert_true(n[i] >= 0);
        assert_string_not_equal(tt_scan_envelope_stop_name(i), "?");
    }
}

static void every_cycle_counts_nothing(void **st)
{
    (void)st;
    long n[TT_ENV_STOPS], cycles, integrated;
    stepped("[solver]\ntier = every\n", n, &cycles, &integrated);
    assert_int_equal(integrated, cycles);
    for (int i = 0; i < TT_ENV_STOPS; i++)
        assert_int_equal(n[i], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(counts_account_for_the_cycles),
        cmocka_unit_test(every_cycle_counts_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
