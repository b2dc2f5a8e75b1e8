/* Bistability (Garcia and San Paulo 1999; issue 5 item 4): on examples/extreme/bistable.ini
 * the attractive oscillation (phase above 90 deg, the tip hovering short of the surface)
 * and the repulsive one (phase below 90 deg, the tip tapping into it) coexist over a range
 * of rest separations, and an approach followed by a retract shows both: at the same
 * separation the two branches give phases on opposite sides of 90 deg, and the amplitude
 * jumps where each path changes branch.
 *
 * Cheap on purpose: 7 separations 0.2 nm apart from 5.1 to 3.9 nm and back, dopri5 at
 * 1e-6, settled to 1e-5; the committed fine run (bistable-approach.csv: 0.05 nm steps at
 * the default settings) checks that this coarse setting has converged. Steps of 0.2 nm
 * knock the approach onto the repulsive branch at about 4.4 nm (0.05 nm steps keep it
 * attractive down to 0.15 nm): which branch a separation shows depends on the history. */
#include <stdlib.h>

#include "tt_approach_test.h"

#define DIR TT_SOURCE_DIR "/examples/extreme/"
#define NPTS 7

static const double deg = 180 / M_PI;

/* The committed fine run's row at separation z (nm) on a branch: amplitude (nm), phase
 * (deg). Fails if absent. */
static void committed_row(double z, int retract, double *A, double *ph)
{
    FILE *f = fopen(DIR "bistable-approach.csv", "r");
    assert_non_null(f);
    char line[1024];
    int found = 0;
    assert_non_null(fgets(line, sizeof line, f)); /* header */
    while (!found && fgets(line, sizeof line, f)) {
        double zz, a, p;
        char branch[16];
        /* z_nm,amplitude_nm,phase_deg,mean,peak_force,indentation,contact,dissipated,branch */
        if (sscanf(line, "%lf,%lf,%lf,%*[^,],%*[^,],%*[^,],%*[^,],%*[^,],%15[a-z]", &zz, &a, &p,
                   branch) == 4 &&
            fabs(zz - z) < 1e-6 && (strcmp(branch, "retract") == 0) == retract) {
            *A = a;
            *ph = p;
            found = 1;
        }
    }
    fclose(f);
    if (!found)
        fail_msg("no %s row at %g nm in bistable-approach.csv", retract ? "retract" : "approach", z);
}

static void both_branches_and_the_jumps(void **st)
{
    (void)st;
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load(s, DIR "bistable.ini"), TT_OK);
    const char *sets[] = {"approach.from=5.1 nm", "approach.to=3.9 nm", "approach.points=7",
                          "approach.settle_tolerance=1e-5", "solver.tolerance=1e-6"};
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++)
        assert_int_equal(tt_scene_set(s, sets[i]), TT_OK);
    tt_approach_params p;
    tt_approach_point pt[2 * NPTS];
    int arc;
    size_t n = tt_run_approach(s, pt, 2 * NPTS, &arc, &p);
    assert_int_equal(arc, TT_OK);
    assert_true(p.retract);
    assert_int_equal(n, 2 * NPTS);
    for (size_t i = 0; i < n; i++) {
        assert_true(pt[i].settled);
        assert_true(isfinite(pt[i].cycle.amplitude) && isfinite(pt[i].cycle.phase));
    }
    /* ap[i], re[i]: approach and retract at the same separation z[i], 5.1 down to 3.9 nm */
    const tt_approach_point *ap = pt, *re[NPTS];
    for (int i = 0; i < NPTS; i++) {
        re[i] = &pt[2 * NPTS - 1 - i];
        assert_close(re[i]->z, ap[i].z, 1e-15);
        print_message("%.1f nm: approach %.4f nm %6.2f deg | retract %.4f nm %6.2f deg\n",
                      ap[i].z * 1e9, ap[i].cycle.amplitude * 1e9, ap[i].cycle.phase * deg,
                      re[i]->cycle.amplitude * 1e9, re[i]->cycle.phase * deg);
    }

    /* Each branch is what it says: attractive points never touch (amplitude short of the
     * separation), repulsive ones tap (amplitude past it, by the indentation). */
    for (size_t i = 0; i < n; i++) {
        const tt_cycle *c = &pt[i].cycle;
        if (c->phase > M_PI / 2) {
            assert_true(c->contact_fraction == 0);
            assert_true(c->amplitude < pt[i].z);
        } else {
            assert_true(c->contact_fraction > 0);
            assert_true(c->amplitude > pt[i].z);
        }
    }

    /* Hysteresis: at some separations the approach is attractive and the retract
     * repulsive, their amplitudes apart by the gap plus the indentation. */
    int both = 0;
    for (int i = 0; i < NPTS; i++)
        if (ap[i].cycle.phase > M_PI / 2 && re[i]->cycle.phase < M_PI / 2) {
            both++;
            assert_true(re[i]->cycle.amplitude - ap[i].cycle.amplitude > 0.02 * 5e-9);
        }
    assert_true(both >= 2);

    /* One jump along each path: the approach crosses 90 deg downwards once, and there the
     * amplitude rises although the separation falls; the retract crosses back upwards
     * once, and there the amplitude falls although the separation rises. */
    int down = 0, up = 0;
    for (int i = 0; i + 1 < NPTS; i++) {
        if (ap[i].cycle.phase > M_PI / 2 && ap[i + 1].cycle.phase < M_PI / 2) {
            down++;
            assert_true(ap[i + 1].cycle.amplitude > ap[i].cycle.amplitude);
        }
        assert_false(ap[i].cycle.phase < M_PI / 2 && ap[i + 1].cycle.phase > M_PI / 2);
        /* retract runs from z[i + 1] to z[i] */
        if (re[i + 1]->cycle.phase < M_PI / 2 && re[i]->cycle.phase > M_PI / 2) {
            up++;
            assert_true(re[i]->cycle.amplitude < re[i + 1]->cycle.amplitude);
        }
        assert_false(re[i + 1]->cycle.phase > M_PI / 2 && re[i]->cycle.phase < M_PI / 2);
    }
    assert_int_equal(down, 1);
    assert_int_equal(up, 1);
    /* far out only the attractive branch exists, close in only the repulsive one */
    assert_true(ap[0].cycle.phase > M_PI / 2 && re[0]->cycle.phase > M_PI / 2);
    assert_true(ap[NPTS - 1].cycle.phase < M_PI / 2 && re[NPTS - 1]->cycle.phase < M_PI / 2);

    /* The coarse setting has converged: on the same branch it agrees with the committed
     * fine run (measured: up to 4e-4 nm and 0.07 deg). */
    for (int i = 0; i < NPTS; i++) {
        const tt_approach_point *q[2] = {&ap[i], re[i]};
        for (int b = 0; b < 2; b++) {
            double A = NAN, ph = NAN;
            committed_row(q[b]->z * 1e9, b, &A, &ph);
            if ((ph > 90) != (q[b]->cycle.phase > M_PI / 2))
                continue; /* the fine run's 0.05 nm steps keep the approach attractive longer */
            assert_close(q[b]->cycle.amplitude * 1e9, A, 0.005);
            assert_close(q[b]->cycle.phase * deg, ph, 0.2);
        }
    }
    tt_scene_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(both_branches_and_the_jumps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
