/* The averaged tier on a sample with relaxation arms (a standard linear solid, whose
 * surface's depression is the law's state; src/solver/averaged_arms.c): its table of the
 * force's harmonics is taken on the state's periodic cycle. An arm of zero modulus or of
 * infinite relaxation time gives the elastic (relaxed or glassy) Hertz table; an arm far
 * faster than the contact gives the relaxed modulus's Hertz table, one far slower the
 * glassy modulus's on a surface held down by the cycle's mean push (the analytic limits
 * of an SLS); the harmonics and the loss per cycle the table books agree with a brute-
 * force integration of the arm over cycles until they repeat, and that loss is the
 * dashpot's; the tier's steady amplitude and phase over an SLS flat agree with the
 * every-cycle tier's scan within its stated error. */
#include <stdlib.h>
#include <string.h>

#include "tt_test.h"
#include "tt_scan_test.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/solver/averaged.h"
#include "tiptap/util/clock.h"
#include "tiptap/util/error.h"

enum { NLINE = 6 };
static const double K = 1e9, K1 = 1e9, R = 10e-9;

static tt_cantilever standard(void)
{
    tt_cantilever c;
    assert_int_equal(tt_cantilever_init(&c, 40, 300e3, 400, 20e-9, 300e3, TT_DRIVE_BASE), TT_OK);
    return c;
}

/* Hertz at modulus k, with one arm (modulus k1, relaxation time tau; k1 < 0: none). */
static tt_contact *sls(double k, double k1, double tau)
{
    tt_contact_params p = {TT_CONTACT_HERTZ, k, R, 0, 0.265e-9, NAN, 0, 0, k1 >= 0, {k1}, {tau}};
    tt_contact *ct;
    assert_int_equal(tt_contact_alloc(&ct, &p), TT_OK);
    return ct;
}

static tt_averaged *table_of(const tt_contact *ct, double *seconds)
{
    tt_cantilever c = standard();
    tt_averaged *a;
    double t0 = tt_clock(TT_CLOCK_THREAD);
    assert_int_equal(tt_averaged_alloc(&a, &c, ct, NAN, 1), TT_OK);
    if (seconds)
        *seconds = tt_clock(TT_CLOCK_THREAD) - t0;
    assert_int_equal(tt_averaged_build_misses(a), 0);
    return a;
}

/* (B, x) where the tip taps: amplitudes 8 to 24 nm, closest penetrations 0.2 to 3 nm. */
static const double Bs[3] = {8e-9, 16e-9, 24e-9}, xs[4] = {0.2e-9, 0.7e-9, 1.5e-9, 3e-9};

/* The largest difference of the first harmonic and mean between two tables (looked
 * up, direct: by quadrature), relative to k A0. */
static double table_gap(const tt_averaged *a, const tt_averaged *b, int direct)
{
    double worst = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            tt_averaged_force f, g;
            tt_averaged_force_at(a, Bs[i], xs[j], 0, direct, &f);
            tt_averaged_force_at(b, Bs[i], xs[j], 0, direct, &g);
            double e = fmax(fabs(f.gc[0] - g.gc[0]), fmax(fabs(f.gs[0] - g.gs[0]), fabs(f.mean - g.mean)));
            worst = fmax(worst, e);
        }
    return worst / (40 * 20e-9);
}

/* (a) An arm of zero modulus, or one that never relaxes: the relaxed and the glassy
 * Hertz tables within rounding; an arm of 1e-9 K close to elastic on the arms' own cycle
 * (to its quadrature's error). */
static void elastic_limits(void **state)
{
    (void)state;
    tt_contact *h = sls(K, -1, 0), *hg = sls(K + K1, -1, 0), *z = sls(K, 0, 1e-6);
    tt_contact *inf = sls(K, K1, INFINITY), *tiny = sls(K, 1e-9 * K, 1e-6);
    tt_averaged *ah = table_of(h, NULL), *ag = table_of(hg, NULL), *az = table_of(z, NULL);
    tt_averaged *ai = table_of(inf, NULL), *at = table_of(tiny, NULL);
    double ez = table_gap(ah, az, 0), ei = table_gap(ag, ai, 0), et = table_gap(ah, at, 1);
    print_message("zero modulus %.2g, infinite time %.2g, 1e-9 K %.2g of k A0\n", ez, ei, et);
    assert_true(ez < 1e-14 && ei < 1e-14);
    assert_true(et < 1e-6);
    tt_averaged_free(ah), tt_averaged_free(ag), tt_averaged_free(az), tt_averaged_free(ai);
    tt_averaged_free(at);
    tt_contact_free(h), tt_contact_free(hg), tt_contact_free(z), tt_contact_free(inf);
    tt_contact_free(tiny);
}

/* The frozen surface of a slow arm: its state q constant where the cycle's push in
 * contact (chi(delta) - q over the contact) balances its recovery out of it (K / K_g q
 * over the rest), chi(delta) = delta sqrt(delta / R); the glassy law on that surface's
 * harmonics by the midpoint rule. */
static void frozen(double B, double x, double *gc, double *mean)
{
    const int N = 40000;
    const double Kg = K + K1;
    double lo = 0, hi = x * sqrt(x / R);
    for (int it = 0; it < 60; it++) {
        double q = 0.5 * (lo + hi), f = 0;
        for (int i = 0; i < N; i++) {
            double th = -M_PI + (i + 0.5) * 2 * M_PI / N, d = x - B + B * cos(th);
            double chi = d > 0 ? d * sqrt(d / R) : 0;
            f += chi > K1 / Kg * q ? chi - q : -K / Kg * q;
        }
        *(f > 0 ? &lo : &hi) = q;
    }
    double q = 0.5 * (lo + hi), sc = 0, sm = 0;
    for (int i = 0; i < N; i++) {
        double th = -M_PI + (i + 0.5) * 2 * M_PI / N, d = x - B + B * cos(th);
        double chi = d > 0 ? d * sqrt(d / R) : 0, P = fmax(R * Kg * (chi - K1 / Kg * q), 0);
        sc -= P * cos(th);
        sm -= P;
    }
    *gc = sc * 2 / N;
    *mean = sm / N;
}

/* (b) An arm 1e-5 periods long relaxes within the contact: the relaxed modulus's Hertz
 * table, and no loss; one 1e4 periods long stays where the cycle holds it: the glassy
 * modulus on the frozen surface. */
static void sls_limits(void **state)
{
    (void)state;
    const double T = 1 / 300e3;
    tt_contact *h = sls(K, -1, 0), *fast = sls(K, K1, 1e-5 * T), *slow = sls(K, K1, 1e4 * T);
    tt_averaged *ah = table_of(h, NULL), *af = table_of(fast, NULL), *as = table_of(slow, NULL);
    double ef = table_gap(ah, af, 1), es = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            tt_averaged_force f;
            double gc, mean;
            tt_averaged_force_at(as, Bs[i], xs[j], 0, 1, &f);
            frozen(Bs[i], xs[j], &gc, &mean);
            es = fmax(es, fmax(fabs(f.gc[0] - gc) / fabs(gc), fabs(f.mean - mean) / fabs(mean)));
        }
    print_message("fast arm %.2g of k A0 from relaxed Hertz; slow arm %.2g (relative) from the "
                  "frozen surface\n", ef, es);
    assert_true(ef < 2e-5);
    assert_true(es < 2e-3);
    tt_averaged_free(ah), tt_averaged_free(af), tt_averaged_free(as);
    tt_contact_free(h), tt_contact_free(fast), tt_contact_free(slow);
}

/* The periodic cycle by brute force: the law's state stepped by RK4 in the cycle's
 * angle (10000 steps a cycle, the contact as the penetration against the surface at
 * each stage) until a cycle repeats within 1e-10; the force's first harmonic, mean and
 * the dashpots' loss (the law's power) over that cycle. */
static void brute(const tt_contact *ct, double B, double x, double out[4])
{
    const tt_contact_law *law = tt_contact_law_of(ct);
    const int N = 10000;
    const double w = 2 * M_PI * 300e3, h = 2 * M_PI / N;
    double q = 0;
    for (int cyc = 0; cyc < 2000; cyc++) {
        double q0 = q, s[4] = {0};
        for (int i = 0; i < N; i++) {
            double th = -M_PI + i * h, k[4], qs = q, p, P0 = 0, L0 = 0;
            for (int st = 0; st < 4; st++) {
                double t = th + (st == 0 ? 0 : st == 3 ? h : 0.5 * h);
                double d = x - B + B * cos(t), dd = -B * w * sin(t);
                int in = d > law->surface(ct, &qs);
                law->rate(ct, d, dd, in, &qs, &k[st], &p);
                k[st] /= w;
                if (st == 0) {
                    P0 = law->force(ct, 0, d, dd, in, &qs).conservative;
                    L0 = p / w;
                }
                qs = q + (st == 2 ? h : 0.5 * h) * k[st];
            }
            s[0] -= P0 * cos(th) * h / M_PI;
            s[1] -= P0 * sin(th) * h / M_PI;
            s[2] -= P0 * h / (2 * M_PI);
            s[3] += L0 * h;
            q += h / 6 * (k[0] + 2 * k[1] + 2 * k[2] + k[3]);
        }
        memcpy(out, s, sizeof s);
        if (fabs(q - q0) <= 1e-10 * fabs(q))
            return;
    }
    fail_msg("the brute-force cycle did not repeat");
}

/* (d) Against brute force at arms.ini's arm (1 us, 0.3 periods) and a slower one (10
 * us): the first harmonic and mean within 1e-5 of the largest, and the loss per cycle
 * the table books (pi B gs) the dashpot's within 1e-5. */
static void against_brute(void **state)
{
    (void)state;
    const double taus[2] = {1e-6, 10e-6};
    for (int t = 0; t < 2; t++) {
        tt_contact *ct = sls(K, K1, taus[t]);
        double secs;
        tt_averaged *a = table_of(ct, &secs);
        double eh = 0, el = 0;
        for (int i = 0; i < 3; i += 2)
            for (int j = 1; j < 4; j += 2) {
                double r[4];
                tt_averaged_force f;
                brute(ct, Bs[i], xs[j], r);
                tt_averaged_force_at(a, Bs[i], xs[j], 0, 1, &f);
                double big = fmax(fabs(r[0]), fabs(r[2]));
                eh = fmax(eh, fmax(fabs(f.gc[0] - r[0]), fmax(fabs(f.gs[0] - r[1]), fabs(f.mean - r[2]))) / big);
                el = fmax(el, fabs(M_PI * Bs[i] * f.gs[0] - r[3]) / r[3]);
                assert_true(r[3] > 0);
            }
        print_message("tau %.0f us: table built in %.3f s; harmonics %.2g, loss %.2g from "
                      "brute force\n", taus[t] * 1e6, secs, eh, el);
        assert_true(eh < 1e-5);
        assert_true(el < 1e-5);
        tt_averaged_free(a);
        tt_contact_free(ct);
    }
}

/* examples/viscoelastic-blend/arms.ini's disk (a glassy 1 GPa relaxed to 500 MPa by one
 * arm of 1 us, the surface recovering over 2 us, under a period) as a uniform flat. */
static const char *base =
    "[cantilever]\nspring_constant = 40 N/m\nresonance_frequency = 300 kHz\nquality_factor = 400\n"
    "free_amplitude = 20 nm\n"
    "[material p]\nyoungs_modulus = 500 MPa\npoisson_ratio = 0.4\n"
    "[surface]\ntype = flat\n"
    "[scan]\nsize = 1 um\npixels = 16\nlines = 1\nline_rate = 8 Hz\n"
    "channels = height, error, phase\n"
    "[feedback]\nsetpoint = 80 %\n";

/* (c) The averaged tier's steady height and phase over the SLS against the every-cycle
 * tier's scan, within the averaged tier's stated error on a uniform sample (the elastic
 * test's 5 pm and 0.2 deg, tests/test_averaged.c); the arm ignored (the law without its
 * state: the glassy modulus, what the table of a force of the tip's state alone gave)
 * lies far outside it. */
static void against_every(void **state)
{
    (void)state;
    const char *arm = "[material p]\narm1_modulus = 500 MPa\narm1_relaxation_time = 1 us\n";
    const char *glassy = "[material p]\nyoungs_modulus = 1 GPa\n";
    tt_scene *s1, *s2, *s3;
    tt_scan *a = tt_run_scan_on(base, arm, "averaged", &s1), *e = tt_run_scan_on(base, arm, "every", &s2);
    tt_scan *g = tt_run_scan_on(base, glassy, "averaged", &s3);
    double hm, hr, pm, pr, gh, gp;
    tt_scan_diff(a, e, 0, &hm, &hr);
    tt_scan_diff(a, e, 2, &pm, &pr);
    tt_scan_diff(g, e, 0, &gh, &hr);
    tt_scan_diff(g, e, 2, &gp, &pr);
    print_message("SLS: height %.3g m, phase %.3g deg (max) from every cycle; the arm ignored "
                  "%.3g m, %.3g deg\n", hm, pm, gh, gp);
    assert_true(hm < 5e-12);
    assert_true(pm < 0.2);
    assert_true(gh > 5e-12 || gp > 0.2);
    assert_int_equal(tt_scan_cycles_integrated(a), 0);
    assert_int_equal(tt_scan_averaged_collapsed(a, NULL, NULL), 0);
    tt_scan_free(a), tt_scan_free(e), tt_scan_free(g);
    tt_scene_free(s1), tt_scene_free(s2), tt_scene_free(s3);
}

TT_TEST_MAIN(cmocka_unit_test(elastic_limits), cmocka_unit_test(sls_limits),
             cmocka_unit_test(against_brute), cmocka_unit_test(against_every))
