/* The averaged tier through a ringing loop (the lesson's ki 10 kHz on the 20 nm
 * grating, the noise 1e9 times colder than the lesson's): where its slow flow fails
 * (the loop's swing, the tip's landings) the tier integrates the cycles and re-enters
 * the slow flow after them (scan_averaged.c), so the loop rings at every cycle's
 * frequency and amplitude, as the scope's oscillation judge (scan_oscillation.h, the
 * console's ring read-out) measures them: 284.7 Hz and 39.5 nm against every cycle's
 * 295.1 Hz and 39.4 nm; the slow flow alone rang at 439.2 Hz and 18.5 nm. */
#include <stdlib.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tt_ringing_scene.h"
#include "tiptap/instrument/scan_oscillation.h"
#include "tiptap/instrument/scan_scope.h"

static const char *base = TT_RINGING_SCENE;

/* Line 1 (the second, carried on from line 0) on a tier: its ring and the share of its
 * cycles integrated. */
static void line_ring(const char *tier, double *f, double *a, double *integrated)
{
    tt_scene *sc;
    char extra[64];
    snprintf(extra, sizeof extra, "[solver]\ntier = %s\n", tier);
    tt_scan *s = tt_make_scan(base, extra, &sc);
    tt_scan_scope *scope;
    assert_int_equal(tt_scan_scope_alloc(&scope), TT_OK);
    assert_int_equal(tt_scan_step(s, 0, NULL), TT_OK);
    assert_int_equal(tt_scan_step(s, 1, scope), TT_OK);
    /* the ring as the scope's oscillation judge measures it (its swings' spacing, and
     * z's peak to peak about the surface followed over the longest ring) */
    tt_loop loop;
    tt_oscillation o;
    tt_scan_loop(s, &loop);
    assert_int_equal(tt_scan_oscillation(scope, &loop, &o), TT_OK);
    assert_true(o.rings);
    *f = o.frequency;
    *a = 0.5 * o.z_peak_to_peak;
    *integrated = (double)tt_scan_cycles_integrated(s) / (double)tt_scan_cycles(s);
    tt_scan_scope_free(scope);
    tt_scan_free(s);
    tt_scene_free(sc);
}

static void ring_as_every_cycle(void **st)
{
    (void)st;
    double fa, aa, ia, fe, ae, ie;
    line_ring("averaged", &fa, &aa, &ia);
    line_ring("every", &fe, &ae, &ie);
    print_message("ring: averaged %.1f Hz, %.2f nm (%.1f %% of the cycles integrated); every "
                  "cycle %.1f Hz, %.2f nm\n",
                  fa, aa * 1e9, 100 * ia, fe, ae * 1e9);
    /* a ring to judge: tens of nanometres at a few hundred hertz */
    assert_true(ae > 20e-9 && fe > 150 && fe < 600);
    assert_true(fabs(fa - fe) < 0.05 * fe);
    assert_true(fabs(aa - ae) < 0.05 * ae);
    /* and most cycles still on the slow flow */
    assert_true(ia < 0.5);
}

/* Independent lines through the same ring on one thread and on two: the integrated
 * cycles start from each line's own slow state and sim, so height, error and phase are
 * the same bit for bit (1876 of 66000 cycles integrated, tiptap scan of the scene). */
static void threads_agree(void **st)
{
    (void)st;
    tt_scan_assert_threads_agree(base,
                                 "[solver]\ntier = averaged\n[scan]\nlines_mode = independent\n"
                                 "channels = height, error, phase\n",
                                 3, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(ring_as_every_cycle), cmocka_unit_test(threads_agree)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
