/* The extreme scenes of examples/extreme (issue 5): at each scene's steady point
 * ([trace] separation, settled from the free oscillation at the scene's own setting),
 * (a) the result converges as each method's accuracy knob tightens, (b) the energy
 * balance holds at each method's default setting, (c) no observable is NaN or infinite,
 * and (d) settings that cannot be honoured are refused with a clear message.
 *
 * Every method is one line of methods[]: its knob, a ladder of three settings from coarse
 * to fine, its default, and what it promises. Each run starts from the same steady state
 * and runs NC cycles, so the differences between settings are integration error alone. */
#include <stdlib.h>

#include "tt_test.h"
#include "tiptap/physics/contact.h"
#include "tiptap/config/config.h"
#include "tiptap/util/error.h"
#include "tiptap/config/setup.h"

#define SCENE_DIR TT_SOURCE_DIR "/examples/extreme/"

/* cycles run from the steady state at each setting */
#define NC 2

/* ---- methods: one line each ---- */

typedef enum {
    KNOB_STEPS,    /* fixed steps per cycle; the ladder doubles */
    KNOB_TOLERANCE /* adaptive local error tolerance */
} knob_kind;

typedef struct {
    tt_method method;
    const char *name;
    knob_kind knob;
    double ladder[3];       /* coarse to fine */
    double deflt;           /* tt_solver_default's setting */
    double order;           /* KNOB_STEPS: the classical order, shown where the solution is smooth */
    double residual_bound;  /* |residual_rel| at the default setting, every scene */
    double accuracy_bound;  /* amplitude (of A0) and phase (rad) error after NC cycles at the default */
    int stiffness_limited;  /* explicit fixed steps: too few on a stiff contact must be refused */
    double bad[3];          /* knob values tt_sim_alloc must refuse (NAN ends the list early) */
} method_row;

static const method_row methods[] = {
    /* measured at the default: residual up to 2.0e-5 (Q = 1e4), error up to 2.0e-6 */
    {TT_METHOD_DOPRI5, "dopri5", KNOB_TOLERANCE, {1e-6, 1e-8, 1e-10}, 1e-8, 5, 1e-4, 1e-5, 0,
     {0, 1, -1e-8}},
    /* measured at the default: residual up to 1.4e-4 (Q = 1 with Q_i = 0.03), error up to
     * 3e-4 (the 1 TPa contact, whose ladder is scaled up) */
    {TT_METHOD_RK4, "rk4", KNOB_STEPS, {256, 512, 1024}, 512, 4, 1e-3, 3e-3, 1, {4, 0, -512}},
    /* implicit, adaptive on the same tolerance as dopri5 */
    {TT_METHOD_RADAU, "radau", KNOB_TOLERANCE, {1e-6, 1e-8, 1e-10}, 1e-8, 5, 1e-4, 1e-5, 0,
     {0, 1, -1e-8}},
};
#define NMETHODS (sizeof methods / sizeof methods[0])

/* ---- scenes ---- */

typedef struct scene_case scene_case;

typedef struct {
    const scene_case *sc;
    tt_scene *scene;
    tt_setup *su;
    const tt_contact *ct;
    double qi;       /* the material's interaction quality factor */
    double z;        /* the steady point's rest separation, m */
    tt_cycle steady; /* its last cycle at the scene's own setting */
    long settle_cycles;
    double d, v;     /* the state at that cycle's end */
    int contact;
} run_ctx;

struct scene_case {
    const char *file;
    double steps_scale; /* KNOB_STEPS ladders are multiplied by this */
    int coarse_steps;   /* stiffness-limited methods must refuse this many steps (0: none) */
    const char *coarse_says; /* ... with this in the message besides the contact stiffness */
    void (*extra)(const run_ctx *);
};

static void assert_finite_cycle(const tt_cycle *c, const char *what)
{
    const double v[] = {c->amplitude, c->phase, c->mean, c->peak_force, c->max_indentation,
                        c->contact_fraction, c->e_drive, c->e_damp, c->e_ts, c->e_sample,
                        c->residual, c->residual_rel, c->y_min, c->y_max};
    const char *names[] = {"amplitude", "phase", "mean", "peak_force", "max_indentation",
                           "contact_fraction", "e_drive", "e_damp", "e_ts", "e_sample",
                           "residual", "residual_rel", "y_min", "y_max"};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        /* untracked extremes are +-INFINITY by contract; any NaN fails */
        if (!isfinite(v[i]) && !(i >= 12 && isinf(v[i]) && (v[12] == INFINITY) && (v[13] == -INFINITY)))
            fail_msg("%s: %s is %g", what, names[i], v[i]);
    /* event times are NaN exactly when no such event happened in the cycle */
    if (c->events == 0 && (!isnan(c->t_contact) || !isnan(c->t_release)))
        fail_msg("%s: event times without events", what);
    if (c->events > 0 && isnan(c->t_contact) && isnan(c->t_release))
        fail_msg("%s: %ld events without a time", what, c->events);
}

static tt_solver solver_of(const method_row *m, double knob)
{
    tt_solver s;
    tt_solver_default(&s);
    s.method = m->method;
    if (m->knob == KNOB_STEPS)
        s.steps_per_cycle = (int)knob;
    else
        s.tolerance = knob;
    return s;
}

/* NC cycles from the steady state with a solver: TT_OK or the failing status. */
static int run_from_steady(const run_ctx *r, const tt_solver *s, tt_cycle *out, long *events)
{
    tt_sim *sim;
    int rc = tt_sim_alloc(&sim, tt_setup_cantilever(r->su), s);
    if (rc)
        return rc;
    tt_sim_set_contact(sim, r->ct, r->qi);
    tt_sim_set_sample(sim, r->z, 0);
    tt_sim_set_state(sim, r->d, r->v, r->contact);
    /* dopri5 runs as in a scan, without tracking the extremes, so that it takes its
     * free-flight steps out of contact (tracking turns them off) */
    tt_sim_track_extremes(sim, s->method != TT_METHOD_DOPRI5);
    if (events)
        *events = 0;
    for (int i = 0; i < NC && rc == TT_OK; i++)
        if ((rc = tt_sim_cycle(sim, out)) == TT_OK && events)
            *events += out->events;
    tt_sim_free(sim);
    return rc;
}

/* error of a run against the reference: amplitude relative to A0, phase in rad */
static double error_of(const run_ctx *r, const tt_cycle *c, const tt_cycle *ref)
{
    return fmax(fabs(c->amplitude - ref->amplitude) / tt_setup_cantilever(r->su)->A0,
                fabs(c->phase - ref->phase));
}

static double order3(double a, double b, double c) { return log2(fabs(a - b) / fabs(b - c)); }

static void check_method(const run_ctx *r, const method_row *m, const tt_cycle *ref)
{
    const char *f = r->sc->file;
    double scale = m->knob == KNOB_STEPS ? r->sc->steps_scale : 1;
    tt_cycle c[3];
    double e[3];
    long events = 0;
    for (int i = 0; i < 3; i++) {
        tt_solver s = solver_of(m, m->ladder[i] * scale);
        long ev;
        if (run_from_steady(r, &s, &c[i], &ev) != TT_OK)
            fail_msg("%s: %s at %g: %s", f, m->name, m->ladder[i] * scale, tt_error_message());
        assert_finite_cycle(&c[i], m->name);
        e[i] = error_of(r, &c[i], ref);
        events += ev;
    }
    /* (a) convergence */
    if (m->knob == KNOB_STEPS) {
        double A0 = tt_setup_cantilever(r->su)->A0;
        double pA = order3(c[0].amplitude, c[1].amplitude, c[2].amplitude);
        double pP = order3(c[0].phase, c[1].phase, c[2].phase);
        double pref = log2(e[0] / e[2]) / 2;
        print_message("  %-7s %5.0f..%5.0f steps: order amplitude %5.2f, phase %5.2f, against the "
                      "reference %5.2f (errors %.1e %.1e %.1e)\n",
                      m->name, m->ladder[0] * scale, m->ladder[2] * scale, pA, pP, pref, e[0],
                      e[1], e[2]);
        if (events == 0) {
            /* No contact event in these cycles: the tip stays on one smooth branch (in the
             * van der Waals field or captured in contact), the solution is smooth, and the
             * differences between step counts fall at the method's order. Below 1e-12 they
             * are rounding, and there is no order to see. */
            if (fabs(c[1].amplitude - c[2].amplitude) > 1e-12 * A0) {
                assert_between(pA, m->order - 0.3, m->order + 0.3);
                assert_between(pP, m->order - 0.3, m->order + 0.3);
            } else {
                assert_true(e[2] < 1e-11);
            }
        } else {
            /* Through contact events the force law is not smooth: the Hertz-type onset
             * P ~ delta^(3/2) and the square-root fold leave the solution only a few times
             * differentiable at each event, so the first steps after one lose accuracy and
             * the observed order is not 4 (measured 1.9 to 3.5 against the reference, and
             * 5 to 7 where the coarsest rung is still far from the asymptotic regime: the
             * 1 TPa contact, the drive at half the resonance; the three-count estimates,
             * built from differences down to 1e-9, scatter from -0.2 to 6). What holds
             * robustly: the error falls, at an order of at least 1. */
            assert_true(pref >= 1);
        }
    } else {
        /* An adaptive method's error at one tolerance carries a step pattern's luck: on
         * event-laden cycles it can be 10 times off its trend at a single rung (measured
         * for dopri5 and radau alike on the drive at twice the resonance). So the trend is
         * fitted over a decade ladder, 1e-5 to 1e-11, not read from neighbours: the
         * least-squares slope of log error against log tolerance must be at least 0.5
         * (measured: dopri5 0.7 to 1.1; radau 0.55 to 0.9, its estimate being held to
         * tolerance^(2/3)), and the finest rung at least 100 times better than the
         * coarsest, unless the coarsest is already down near the reference's level. */
        double lt[7], le[7], sx = 0, sy = 0, sxx = 0, sxy = 0;
        int n = 0;
        for (int i = 0; i < 7; i++) {
            double tol = pow(10, -5 - i);
            tt_solver s = solver_of(m, tol);
            tt_cycle cy;
            if (run_from_steady(r, &s, &cy, NULL) != TT_OK)
                fail_msg("%s: %s at %g: %s", f, m->name, tol, tt_error_message());
            assert_finite_cycle(&cy, m->name);
            double err = error_of(r, &cy, ref);
            if (err > 1e-11) {
                lt[n] = log10(tol);
                le[n] = log10(err);
                sx += lt[n];
                sy += le[n];
                sxx += lt[n] * lt[n];
                sxy += lt[n] * le[n];
                n++;
            }
            if (i == 0)
                e[0] = err;
            if (i == 6)
                e[2] = err;
        }
        double slope = n >= 3 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : NAN;
        print_message("  %-7s tolerance 1e-5..1e-11: errors %.1e .. %.1e, slope %.2f over %d rungs\n",
                      m->name, e[0], e[2], slope, n);
        /* an error already below 1e-9 at 1e-5 leaves no trend to see (measured: the free
         * flight solves the 0.1 nm hover to 1e-9 at every rung) */
        if (n >= 3 && e[0] > 1e-9)
            assert_true(slope >= 0.5);
        if (e[0] > 1e-9)
            assert_true(e[2] < e[0] / 100);
    }

    /* (b) the energy balance and the accuracy at the default setting, and (c) */
    tt_solver s = solver_of(m, m->deflt);
    tt_cycle cd;
    if (run_from_steady(r, &s, &cd, NULL) != TT_OK)
        fail_msg("%s: %s at its default: %s", f, m->name, tt_error_message());
    assert_finite_cycle(&cd, m->name);
    print_message("  %-7s default: residual %.1e, error %.1e, %ld steps\n", m->name, cd.residual_rel,
                  error_of(r, &cd, ref), cd.steps);
    assert_true(cd.residual_rel < m->residual_bound);
    assert_true(error_of(r, &cd, ref) < m->accuracy_bound);

    /* (d) what cannot be honoured is refused */
    for (int i = 0; i < 3 && !isnan(m->bad[i]); i++) {
        tt_solver b = solver_of(m, m->bad[i]);
        tt_sim *sim = NULL;
        assert_int_equal(tt_sim_alloc(&sim, tt_setup_cantilever(r->su), &b), TT_EINVAL);
        assert_null(sim);
        assert_true(strlen(tt_error_message()) > 0);
    }
    if (m->stiffness_limited && r->sc->coarse_steps > 0) {
        tt_solver b = solver_of(m, r->sc->coarse_steps);
        tt_cycle cc;
        assert_int_equal(run_from_steady(r, &b, &cc, NULL), TT_ENUM);
        const char *msg = tt_error_message();
        print_message("  %-7s %d steps: %s\n", m->name, r->sc->coarse_steps, msg);
        assert_non_null(strstr(msg, "contact stiffness"));
        if (r->sc->coarse_says)
            assert_non_null(strstr(msg, r->sc->coarse_says));
        const char *need = strstr(msg, "needs at least ");
        assert_non_null(need);
        assert_true(strtol(need + strlen("needs at least "), NULL, 10) > r->sc->coarse_steps);
    }
}

/* Keys set to values a scene must refuse, and a fragment of the message. */
static const struct {
    const char *set, *says;
} refused[] = {
    {"solver.tolerance=0", "[solver] tolerance"},
    {"solver.tolerance=0.5", "[solver] tolerance"},
    {"solver.steps_per_cycle=4", "[solver] steps_per_cycle"},
    {"solver.method=euler", "[solver] method"},
    {"cantilever.quality_factor=0", "[cantilever] quality_factor"},
    {"cantilever.free_amplitude=-0.1 nm", "[cantilever] free_amplitude"},
    {"cantilever.drive_frequency=nan Hz", "[cantilever] drive_frequency"},
};

static void check_scene(void **state)
{
    const scene_case *sc = *state;
    run_ctx r;
    memset(&r, 0, sizeof r);
    r.sc = sc;
    char path[1024];
    snprintf(path, sizeof path, "%s%s", SCENE_DIR, sc->file);
    r.scene = tt_scene_alloc();
    if (tt_scene_load(r.scene, path) != TT_OK)
        fail_msg("%s", tt_error_message());
    size_t mat = 0;
    if (tt_setup_alloc(&r.su, r.scene) != TT_OK ||
        tt_setup_find_material(r.su, tt_scene_get_string(r.scene, "approach", NULL, "material"),
                               "approach", "material", &mat) != TT_OK ||
        tt_setup_use_material(r.su, mat) != TT_OK ||
        tt_scene_get_double(r.scene, "trace", NULL, "separation", &r.z) != TT_OK)
        fail_msg("%s: %s", sc->file, tt_error_message());
    r.ct = tt_setup_contact(r.su, mat);
    r.qi = tt_setup_material(r.su, mat)->Qi;

    /* the steady point, from the free oscillation, at the scene's own setting */
    tt_sim_reset_free(tt_setup_sim(r.su));
    tt_sim_set_sample(tt_setup_sim(r.su), r.z, 0);
    tt_sim_track_extremes(tt_setup_sim(r.su), 1);
    int settled;
    if (tt_sim_settle(tt_setup_sim(r.su), 100000, 1e-6, &r.steady, &settled, &r.settle_cycles) != TT_OK)
        fail_msg("%s: %s", sc->file, tt_error_message());
    assert_true(settled);
    assert_finite_cycle(&r.steady, sc->file);
    tt_sim_get_state(tt_setup_sim(r.su), &r.d, &r.v, &r.contact);
    print_message("%s at %g nm: %ld cycles to settle; amplitude %.5g nm, phase %.3f deg, contact "
                  "%.3f, %ld events, %ld steps, residual %.1e\n",
                  sc->file, r.z * 1e9, r.settle_cycles, r.steady.amplitude * 1e9,
                  r.steady.phase * 180 / M_PI, r.steady.contact_fraction, r.steady.events,
                  r.steady.steps, r.steady.residual_rel);
    /* (b) at the scene's own setting (the library default) */
    assert_true(r.steady.residual_rel < methods[0].residual_bound);

    tt_solver rs;
    tt_solver_default(&rs);
    rs.tolerance = 1e-12;
    tt_cycle ref;
    if (run_from_steady(&r, &rs, &ref, NULL) != TT_OK)
        fail_msg("%s: reference: %s", sc->file, tt_error_message());
    assert_finite_cycle(&ref, "reference");
    for (size_t i = 0; i < NMETHODS; i++)
        check_method(&r, &methods[i], &ref);
    sc->extra(&r);

    /* (d) invalid settings are refused by the scene, naming the key */
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        tt_scene *s = tt_scene_alloc();
        assert_int_equal(tt_scene_load(s, path), TT_OK);
        assert_int_equal(tt_scene_set(s, refused[i].set), TT_EINVAL);
        if (!strstr(tt_error_message(), refused[i].says))
            fail_msg("%s: '%s' refused with '%s'", sc->file, refused[i].set, tt_error_message());
        tt_scene_free(s);
    }
    tt_setup_free(r.su);
    tt_scene_free(r.scene);
}

/* ---- what each scene probes, checked where an exact statement exists ---- */

static void extra_none(const run_ctx *r) { (void)r; }

static void extra_dmt(const run_ctx *r)
{
    /* lambda = 1e-3: below the fold (0.938), no hysteresis; adhesion costs nothing */
    const tt_contact_summary *sum = tt_contact_summary_of(r->ct);
    assert_close(sum->lambda, 1e-3, 1e-15);
    assert_false(sum->hysteresis);
    assert_true(r->steady.events == 2);
    assert_close(r->steady.e_ts, 0, 1e-7 * r->steady.e_drive);
    /* DMT's pull-off load, -2 pi w R, to the table's accuracy */
    assert_close(sum->pulloff_load, -2, 1e-3);
}

static void extra_jkr(const run_ctx *r)
{
    /* lambda = 1e3: a fold; with no interaction damping each tap loses the loop's area */
    const tt_contact_summary *sum = tt_contact_summary_of(r->ct);
    assert_true(sum->hysteresis);
    assert_int_equal(r->steady.events, 2);
    assert_close(r->steady.e_ts, sum->loop_energy, 1e-6 * sum->loop_energy);
    assert_close(sum->pulloff_load, -1.5, 1e-3);
}

static void extra_hertz(const run_ctx *r)
{
    /* w = 0: Hertz exactly, one force law for both states, and with no interaction
     * damping not a single joule lost to the sample */
    assert_false(tt_contact_summary_of(r->ct)->adhesive);
    assert_int_equal(r->steady.events, 2);
    assert_true(r->steady.e_ts == 0);
    /* all the drive work goes to the cantilever's damping (up to the stored energy still
     * changing at the settling tolerance) */
    assert_close(r->steady.e_drive, r->steady.e_damp, 1e-4 * r->steady.e_drive);
}

static void extra_stiff(const run_ctx *r)
{
    /* the contact stiffness at the deepest point is thousands of times the cantilever's */
    double k;
    (void)tt_contact_load(r->ct, r->steady.max_indentation, 1, &k, NULL);
    print_message("  contact stiffness %.3g N/m, %.0f times the cantilever's\n", k,
                  k / tt_setup_cantilever(r->su)->k);
    assert_true(k > 1000 * tt_setup_cantilever(r->su)->k);
}

static void extra_liquid(const run_ctx *r)
{
    /* Q = 1: the oscillator forgets its past within a cycle or two */
    assert_true(r->settle_cycles < 20);
    assert_true(r->steady.e_ts > 0);
}

static void extra_vacuum(const run_ctx *r)
{
    /* Q = 1e4: the memory is Q / pi cycles, and on this sample the tip settles on the
     * attractive branch without touching it (confirmed with rk4 at 1024 steps) */
    assert_true(r->settle_cycles > tt_setup_cantilever(r->su)->Q / M_PI);
    assert_int_equal(r->steady.events, 0);
    assert_true(r->steady.phase > M_PI / 2);
}

static void extra_captured(const run_ctx *r)
{
    /* held in contact all cycle long: the tip barely moves, so the deflection is the base
     * motion turned over, amplitude a_d = A0 / Q at a phase of 180 deg */
    const tt_cantilever *c = tt_setup_cantilever(r->su);
    assert_close(r->steady.contact_fraction, 1, 1e-12);
    assert_int_equal(r->steady.events, 0);
    assert_close(r->steady.amplitude, c->a_d, 0.01 * c->a_d);
    assert_close(r->steady.phase * 180 / M_PI, 180, 0.01);
}

static void extra_small(const run_ctx *r)
{
    /* At 0.1 nm the response in the van der Waals field is linear: the static equilibrium
     * y_e of k y = -P(y - z) and the force gradient g there give, for the base drive
     * a_d cos(w t), amplitude |m w^2 - g| a_d / |k + g - m w^2 + i c w| and lag
     * atan2(c w, k + g - m w^2). The nonlinearity, (A / gap)^2 ~ 3e-4, sets the match. */
    const tt_cantilever *c = tt_setup_cantilever(r->su);
    assert_int_equal(r->steady.events, 0);
    double y = 0, g = 0;
    for (int i = 0; i < 50; i++)
        y = -tt_contact_load(r->ct, y - r->z, 0, &g, NULL) / c->k;
    double w = c->wd, re = c->k + g - c->m * w * w, im = c->c * w;
    double A = fabs(c->m * w * w - g) * c->a_d / hypot(re, im), lag = atan2(im, re);
    print_message("  linear theory: amplitude %.6g nm, phase %.4f deg (gradient %.4g N/m)\n",
                  A * 1e9, lag * 180 / M_PI, g);
    assert_close(r->steady.amplitude, A, 2e-3 * A);
    assert_close(r->steady.phase, lag, 2e-3);
}

static void extra_setpoint(const run_ctx *r)
{
    double ratio = r->steady.amplitude / tt_setup_cantilever(r->su)->A0;
    assert_between(ratio, 0.08, 0.12);
    assert_true(r->steady.contact_fraction > 0);
}

static const scene_case scenes[] = {
    {"lambda-dmt.ini", 1, 0, NULL, extra_dmt},
    {"lambda-jkr.ini", 1, 0, NULL, extra_jkr},
    {"no-adhesion.ini", 1, 0, NULL, extra_hertz},
    {"stiff-contact.ini", 2, 64, NULL, extra_stiff},
    /* Q_i = 0.03: the interaction damping, not the stiffness, limits the step */
    {"liquid-q1.ini", 1, 64, "and its damping", extra_liquid},
    {"vacuum-q1e4.ini", 1, 0, NULL, extra_vacuum},
    {"captured.ini", 1, 64, NULL, extra_captured},
    {"small-amplitude.ini", 1, 0, NULL, extra_small},
    {"setpoint-10.ini", 1, 0, NULL, extra_setpoint},
    {"drive-half.ini", 1, 0, NULL, extra_none},
    {"drive-double.ini", 1, 0, NULL, extra_none},
    {"bistable.ini", 1, 0, NULL, extra_none},
};
#define NSCENES (sizeof scenes / sizeof scenes[0])

int main(void)
{
    struct CMUnitTest tests[NSCENES];
    for (size_t i = 0; i < NSCENES; i++) {
        tests[i].name = scenes[i].file;
        tests[i].test_func = check_scene;
        tests[i].setup_func = NULL;
        tests[i].teardown_func = NULL;
        tests[i].initial_state = (void *)&scenes[i];
    }
    return cmocka_run_group_tests(tests, NULL, NULL);
}
