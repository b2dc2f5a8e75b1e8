/* The error estimate's budget, counted in work (integrator steps, accepted and rejected,
 * and one a cycle: tt_sim_work, tt_scan_error.work): the sim counts every step of every
 * cycle it integrated; a companion in stretches spends at most a fifth of the scan's
 * work, the same on one thread as on two; with thermal noise it runs whole lines (part
 * of a line reads low there), first the one where the error signal strays furthest, as
 * many as a fifth holds, and on a scan too short for one that line over the share,
 * saying so. */
#include <math.h>
#include <stdlib.h>

#include "tt_test.h"
#include "tt_laws.h"
#include "tt_scan_test.h"
#include "tt_sim_test.h"

/* tt_sim_work: the steps and rejected steps of every cycle, on an adaptive method that
 * rejects some (dopri5 through contact at a tight tolerance) and on rk4's fixed steps. */
static void sim_work_counts_every_step(void **st)
{
    (void)st;
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc_normalised(&ct, TT_CONTACT_DMT, 0, 0.3), TT_OK);
    tt_cantilever c;
    tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE);
    const tt_method methods[2] = {TT_METHOD_DOPRI5, TT_METHOD_RK4};
    for (int m = 0; m < 2; m++) {
        tt_sim *sim = tt_test_sim_on(&c, methods[m], 1e-10, 2000);
        tt_sim_set_contact(sim, ct, 2);
        tt_sim_set_sample(sim, 15e-9, 0);
        assert_int_equal(tt_sim_work(sim), 0);
        long sum = 0, rejected = 0;
        for (int i = 0; i < 30; i++) {
            tt_cycle cy;
            assert_int_equal(tt_sim_cycle(sim, &cy), TT_OK);
            sum += cy.steps + cy.rejected;
            rejected += cy.rejected;
        }
        print_message("%s: work %ld, %ld of it rejected\n", m ? "rk4" : "dopri5", tt_sim_work(sim),
                      rejected);
        assert_int_equal(tt_sim_work(sim), sum);
        assert_true(m ? sum >= 30 * 2000 : rejected > 0); /* rk4: and a step split at an event */
        tt_sim_free(sim);
    }
    tt_contact_free(ct);
}

/* A scan of steps long enough for stretches (6 lines of 32 pixels; the every-cycle
 * tier, whose settling costs a line's share: its fifth holds stretches). */
static const char *steps =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
    "free_amplitude = 20 nm\n"
    "[surface]\ntype = steps\nstep_height = 2 nm\nstep_width = 250 nm\n"
    "[scan]\nsize = 1 um\npixels = 32\nlines = 6\nline_rate = 8 Hz\n"
    "[feedback]\nsetpoint = 80 %\n[solver]\ntolerance = 3e-8\ntier = every\n";

static tt_scan_error estimate(tt_scan *s)
{
    tt_scan_error e;
    assert_int_equal(tt_scan_estimate_error(s, &e), TT_OK);
    return e;
}

static void stretches_within_a_fifth_of_the_work(void **st)
{
    (void)st;
    tt_scene *sa, *sb;
    tt_scan *a = tt_run_scan(steps, "", &sa);
    tt_scan *b = tt_make_scan(steps, "", &sb);
    assert_int_equal(tt_scan_run(b, 1, NULL, NULL), TT_OK);
    tt_scan_error ea = estimate(a), eb = estimate(b);
    print_message("work %ld of the scan's %ld (budget %ld), %ld stretches, %ld of %ld pixels, "
                  "over %d; height %.3g m\n", ea.work, ea.scan_work, ea.budget, ea.stretches,
                  ea.pixels, ea.pixels_line, ea.over, ea.height_max);
    assert_false(ea.over);
    assert_true(ea.stretches >= 1 && ea.pixels < ea.pixels_line);
    /* each line stops at the first cycle past its budget: at most a cycle's steps over */
    assert_true(ea.budget == (long)(TT_ESTIMATE_SHARE * (double)ea.scan_work));
    assert_true(ea.work > 0 && ea.work <= ea.budget + 2 * ea.stretches * 1000);
    assert_int_equal(ea.lines, 0);
    /* the work, and so the budget and the estimate, are the machine's and threads' alike */
    assert_int_equal(ea.scan_work, eb.scan_work);
    assert_int_equal(ea.work, eb.work);
    assert_true(ea.height_max == eb.height_max && ea.phase_max == eb.phase_max);
    tt_scan_free(a);
    tt_scan_free(b);
    tt_scene_free(sa);
    tt_scene_free(sb);
}

/* The viscoelastic blend at 300 K on the envelope tier, 16 pixels a line at 8 Hz. */
static const char *noisy = TT_TEST_BLEND
    "[scan]\nsize = 1 um\npixels = 16\nline_rate = 8 Hz\nprofile_line = 0\n"
    "[feedback]\nsetpoint = 80 %\n[solver]\ntolerance = 3e-8\n"
    "[noise]\nseed = 5\ntemperature = 300 K\n";

static void noise_runs_whole_lines(void **st)
{
    (void)st;
    static const char *lines[2] = {"[scan]\nlines = 2\n", "[scan]\nlines = 40\n"};
    for (int k = 0; k < 2; k++) {
        tt_scene *sc;
        tt_scan *s = tt_run_scan(noisy, lines[k], &sc);
        tt_scan_error e = estimate(s);
        print_message("%d lines: %ld lines whole, %ld pixels of %ld a line, work %ld of the scan's %ld, "
                      "over %d\n", k ? 40 : 2, e.lines, e.pixels, e.pixels_line, e.work,
                      e.scan_work, e.over);
        assert_true(e.lines >= 1);
        assert_int_equal(e.pixels, e.lines * e.pixels_line); /* every pixel of each */
        /* the first is the line where the error signal strays furthest */
        double top = 0;
        long at = -1;
        for (int r = 0; r < 2; r++) {
            const double *err = tt_scan_image(s, 1, r);
            assert_non_null(err);
            for (long i = 0; i < tt_scan_yres(s) * tt_scan_xres(s); i++)
                if (fabs(err[i]) > top) {
                    top = fabs(err[i]);
                    at = i / tt_scan_xres(s); /* the fast axis along x: a row a line */
                }
        }
        assert_true(e.signal == top && e.line == at);
        if (k == 0) { /* two lines hold no whole line in a fifth: one, over, and says so */
            assert_true(e.over && e.lines == 1 && e.work > e.budget);
        } else { /* forty hold more than one, within the fifth as predicted */
            assert_false(e.over);
            assert_true(e.lines > 1 && e.work <= e.budget);
        }
        tt_scan_free(s);
        tt_scene_free(sc);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sim_work_counts_every_step),
        cmocka_unit_test(stretches_within_a_fifth_of_the_work),
        cmocka_unit_test(noise_runs_whole_lines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
