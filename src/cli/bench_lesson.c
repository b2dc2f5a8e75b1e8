/* tiptap bench's lesson figure: the teaching scene of examples/feedback-tuning at each of
 * the lesson's settings, stepped a line at a time as the live console's engine steps it
 * (tt_scan_step on one thread), each line's real time per CPU second of that thread, and
 * its height and phase against the every-cycle tier's same lines. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "commands.h"
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan_envelope_stops.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/util/clock.h"
#include "tiptap/util/error.h"
#include "tiptap/util/phase.h"

/* scans/standard.ini, surfaces/grating.ini and examples/feedback-tuning/common.ini, in
 * that order (what `tiptap scan` and `tiptap live` are given for the lesson). */
const char *bench_lesson_scene(void)
{
    return "[cantilever]\n"
           "spring_constant = 40 N/m\n"
           "resonance_frequency = 300 kHz\n"
           "quality_factor = 400\n"
           "free_amplitude = 20 nm\n"
           "drive = base\n"
           "[tip]\n"
           "radius = 10 nm\n"
           "youngs_modulus = 169 GPa\n"
           "poisson_ratio = 0.27\n"
           "[feedback]\n"
           "setpoint = 80 %\n"
           "[material silicon]\n"
           "reduced_modulus = 100 GPa\n"
           "adhesion_energy = 20 mJ/m^2\n"
           "interatomic_distance = 0.3 nm\n"
           "[surface]\n"
           "type = grating\n"
           "period = 1 um\n"
           "duty = 50 %\n"
           "height = 20 nm\n"
           "edge_width = 0 nm\n"
           "[scan]\n"
           "size = 2.25 um\n"
           "pixels = 64\n"
           "lines = 32\n"
           "line_rate = 2 Hz\n"
           "fast_axis = x\n"
           "retrace = yes\n"
           "channels = height, error, amplitude, phase, peak_force, topography\n"
           "lines_mode = continuous\n"
           "[noise]\n"
           "seed = 1\n"
           "temperature = 300 K\n"
           "detector = 100 fm/sqrt(Hz)\n";
}

typedef struct {
    const char *label;
    const char *set[3];
} lesson_setting;

static const lesson_setting settings[] = {
    {"ki 100 Hz", {"feedback.integral_gain=100 Hz", NULL}},
    {"ki 1.18 kHz", {"feedback.integral_gain=1180 Hz", NULL}},
    {"ki 4 kHz", {"feedback.integral_gain=4 kHz", NULL}},
    {"ki 10 kHz", {"feedback.integral_gain=10 kHz", NULL}},
    {"ki 30 kHz", {"feedback.integral_gain=30 kHz", NULL}},
    {"P 5, ki 1.18 kHz", {"feedback.integral_gain=1180 Hz", "feedback.proportional_gain=5", NULL}},
    {"40 Hz lines, ki 1.18 kHz", {"feedback.integral_gain=1180 Hz", "scan.line_rate=40 Hz", NULL}},
};

/* The lesson's noise 1e9 times colder (its powers: thermal and detector), where the
 * two tiers' draws no longer part their images: a tier's own model error
 * (tests/test_envelope_ringing.c's way). */
static const char *const cold[] = {"noise.temperature=3e-7 K", "noise.detector=3.162e-18 m/sqrt(Hz)", NULL};

/* One setting on one tier: lines 0 .. n - 1 stepped; per line its real time per CPU
 * second (rt) and its height and phase, trace and retrace (img: [line][4][pixels]). */
typedef struct {
    double *rt;
    double *img;
    long pixels, integrated, cycles;
    double ring_f, ring_a; /* the loop's ring (ring_of), mean over the lines and directions */
} lesson_run;

/* The loop's ring in one direction of a line's scope: the tracking error z - followed
 * (its mean removed, Hann-windowed) at the peak of its spectrum between 200 Hz and 5 kHz
 * (1 Hz apart; a 0.25 s trace resolves 4 Hz, the window's peak is found finer), f in Hz,
 * and its amplitude there as a sinusoid's (m). In part tt_scan_oscillation's question
 * (the console's ring read-out, tiptap/instrument/scan_oscillation.h, which judges the
 * same record by its swings' spacing and z's peak to peak over the longest ring): kept,
 * as the spectrum's peak is another measure (over the whole line), the one the docs'
 * tables of earlier runs quote. */
static int ring_of(const tt_scan_scope *sc, int dir, double *f, double *a)
{
    const long n = tt_scan_scope_points(sc, dir);
    const double *z = tt_scan_scope_series(sc, dir, TT_SCOPE_Z),
                 *h = tt_scan_scope_series(sc, dir, TT_SCOPE_FOLLOWED);
    double *e = n > 16 && z && h ? malloc((size_t)n * sizeof *e) : NULL;
    if (!e)
        return n > 16 && z && h ? tt_error_nomem("the bench's ring record") : TT_OK;
    double mean = 0, wsum = 0;
    for (long i = 0; i < n; i++)
        mean += (z[i] - h[i]) / (double)n;
    for (long i = 0; i < n; i++) {
        double w = 0.5 - 0.5 * cos(2 * M_PI * (double)i / (double)(n - 1));
        e[i] = w * (z[i] - h[i] - mean);
        wsum += w;
    }
    const double rate = tt_scan_scope_rate(sc);
    double best = -1, bf = 0;
    for (double fr = 200; fr <= 5000; fr += 1) {
        /* the sum by rotation: one complex product a point */
        const double c = cos(2 * M_PI * fr / rate), s = sin(2 * M_PI * fr / rate);
        double re = 0, im = 0, pc = 1, ps = 0;
        for (long i = 0; i < n; i++) {
            re += e[i] * pc;
            im += e[i] * ps;
            double t = pc * c - ps * s;
            ps = ps * c + pc * s;
            pc = t;
        }
        double p = re * re + im * im;
        if (p > best) {
            best = p;
            bf = fr;
        }
    }
    free(e);
    *f = bf;
    *a = 2 * sqrt(best) / wsum;
    return TT_OK;
}

static int lesson_scan(const tt_scene *base, const lesson_setting *ls, const char *tier,
                       const char *const *more, long n, int ring, lesson_run *out)
{
    memset(out, 0, sizeof *out);
    tt_scene *c = tt_scene_copy(base);
    if (!c)
        return tt_error_nomem("the bench's lesson scene");
    char tset[64];
    snprintf(tset, sizeof tset, "solver.tier=%s", tier);
    int rc = tt_scene_set(c, tset);
    for (size_t i = 0; ls->set[i] && !rc; i++)
        rc = tt_scene_set(c, ls->set[i]);
    for (size_t i = 0; more && more[i] && !rc; i++)
        rc = tt_scene_set(c, more[i]);
    tt_scan_params p;
    memset(&p, 0, sizeof p);
    if (!rc)
        rc = tt_config_scan(c, &p);
    tt_scene_free(c);
    if (rc)
        return rc;
    const tt_material *own = p.materials;
    p.raster.lines = n;
    p.profile_line = -1;
    tt_scan *s = NULL;
    rc = tt_scan_alloc(&s, &p);
    const long px = p.raster.pixels;
    out->pixels = px;
    out->rt = calloc((size_t)n, sizeof *out->rt);
    out->img = calloc((size_t)n * 4 * (size_t)px, sizeof *out->img);
    if (!rc && (!out->rt || !out->img))
        rc = tt_error_nomem("the bench's lesson lines");
    const double inst = 1.0 / p.raster.line_rate; /* a line's trace and retrace */
    tt_scan_scope *sc = NULL;
    if (!rc && ring)
        rc = tt_scan_scope_alloc(&sc);
    int rings = 0;
    for (long l = 0; l < n && !rc; l++) {
        double c0 = tt_clock(TT_CLOCK_THREAD);
        rc = tt_scan_step(s, l, sc);
        double cpu = tt_clock(TT_CLOCK_THREAD) - c0;
        out->rt[l] = inst / fmax(cpu, 1e-9);
        for (int d = 0; d < 2 && sc && !rc && (l > 0 || n == 1); d++) {
            double f = 0, a = 0;
            rc = ring_of(sc, d, &f, &a);
            out->ring_f += f;
            out->ring_a += a;
            rings++;
        }
        for (int k = 0; k < 4 && !rc; k++) /* height, phase; trace, retrace */
            rc = tt_scan_line_values(s, k / 2 ? 2 : 0, k % 2, l,
                                     out->img + ((size_t)l * 4 + (size_t)k) * (size_t)px);
    }
    tt_scan_scope_free(sc);
    if (rings) {
        out->ring_f /= rings;
        out->ring_a /= rings;
    }
    if (!rc) {
        out->cycles = tt_scan_cycles(s);
        out->integrated = tt_scan_cycles_integrated(s);
    }
    tt_scan_free(s);
    p.materials = own;
    tt_config_scan_free(&p);
    return rc;
}

static void lesson_free(lesson_run *r)
{
    free(r->rt);
    free(r->img);
    memset(r, 0, sizeof *r);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of lines first .. n - 1. */
static double median_rt(const lesson_run *r, long first, long n)
{
    double v[64];
    long m = 0;
    for (long l = first; l < n && m < 64; l++)
        v[m++] = r->rt[l];
    qsort(v, (size_t)m, sizeof *v, cmp_double);
    return m % 2 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
}

/* The largest and rms differences of height (k 0, 1) or phase (k 2, 3, modulo 360 deg)
 * over lines first .. n - 1. */
static void lesson_error(const lesson_run *a, const lesson_run *b, int phase, long first, long n,
                         double *max, double *rms)
{
    double m = 0, ss = 0;
    long cnt = 0;
    for (long l = first; l < n; l++)
        for (int k = 2 * phase; k < 2 * phase + 2; k++)
            for (long i = 0; i < a->pixels; i++) {
                size_t at = ((size_t)l * 4 + (size_t)k) * (size_t)a->pixels + (size_t)i;
                double d = phase ? tt_phase_diff_deg(a->img[at], b->img[at]) /* wraps */
                                 : fabs(a->img[at] - b->img[at]);
                m = fmax(m, d);
                ss += d * d;
                cnt++;
            }
    *max = m;
    *rms = cnt ? sqrt(ss / (double)cnt) : 0;
}

/* "max/rms" of height (nm) and phase (deg) between two runs over lines first .. n - 1. */
static void lesson_errors(const lesson_run *a, const lesson_run *b, long first, long n, char h[32],
                          char ph[32])
{
    double hm, hr, pm, pr;
    lesson_error(a, b, 0, first, n, &hm, &hr);
    lesson_error(a, b, 1, first, n, &pm, &pr);
    snprintf(h, 32, "%.3g/%.2g", hm * 1e9, hr * 1e9);
    snprintf(ph, 32, "%.3g/%.2g", pm, pr);
}

/* With cold: the tier's own error, both tiers run again with the noise 1e9 times colder. */
static int lesson_cold(const tt_scene *base, const lesson_setting *ls, const char *tier, long lines,
                       long first, char h[32], char ph[32], char ring[48])
{
    lesson_run fast, every = {0};
    int rc = lesson_scan(base, ls, tier, cold, lines, 1, &fast);
    if (!rc)
        rc = lesson_scan(base, ls, "every", cold, lines, 1, &every);
    if (!rc) {
        lesson_errors(&fast, &every, first, lines, h, ph);
        snprintf(ring, 48, "%.0f/%.0f %.3g/%.3g", every.ring_f, fast.ring_f, every.ring_a * 1e9,
                 fast.ring_a * 1e9);
    }
    lesson_free(&fast);
    lesson_free(&every);
    return rc;
}

int bench_lesson_figure(long lines, int quick, int only, const char *own_tier)
{
    tt_scene *base = tt_scene_alloc();
    int rc = base ? tt_scene_load_string(base, bench_lesson_scene(), "lesson scene (bench)")
                  : tt_error_nomem("the bench's lesson scene");
    const char *tier = own_tier ? own_tier : bench_default_tier();
    const long first = lines > 1 ? 1 : 0; /* line 0 engages and settles */
    printf("# lesson: the teaching scene (scans/standard.ini + surfaces/grating.ini + "
           "examples/feedback-tuning/common.ini: 64 pixels, 2 Hz, noise on), lines 0 to %ld "
           "stepped one at a time on one thread as tiptap live's engine steps them; "
           "figures over lines %ld to %ld\n",
           lines - 1, first, lines - 1);
    printf("%-26s %-10s %10s %10s %9s %13s %13s %10s", "setting", "tier", "rt/cpu_s", "integr_%",
           "every_rt", "height_nm", "phase_deg", "every_int");
    printf(own_tier ? " %13s %13s %21s\n" : "\n", "cold_h_nm", "cold_ph_deg", "cold_ring_Hz_nm");
    printf("%-26s %-10s %10s %10s %9s %13s %13s %10s", "", "", "(median)", "", "(median)",
           "max/rms", "max/rms", "%");
    printf(own_tier ? " %13s %13s %21s\n" : "\n", "max/rms", "max/rms", "every/tier");
    enum { NS = sizeof settings / sizeof settings[0] };
    const size_t ns = NS;
    long why[NS][TT_ENV_STOPS] = {{0}};
    for (size_t i = 0; i < ns && !rc; i++) {
        if (only ? (int)i != only - 1 : quick && i != ns - 1)
            continue;
        lesson_run fast, every = {0};
        tt_scan_envelope_stops_reset();
        rc = lesson_scan(base, &settings[i], tier, NULL, lines, 0, &fast);
        tt_scan_envelope_stops(why[i]);
        if (!rc)
            rc = lesson_scan(base, &settings[i], "every", NULL, lines, 0, &every);
        char h[32], ph[32], ch[32] = "", cph[32] = "", cr[48] = "";
        if (!rc && own_tier)
            rc = lesson_cold(base, &settings[i], tier, lines, first, ch, cph, cr);
        if (!rc) {
            lesson_errors(&fast, &every, first, lines, h, ph);
            printf("%-26s %-10s %10.2f %10.1f %9.3f %13s %13s %10.1f", settings[i].label, tier,
                   median_rt(&fast, first, lines),
                   100.0 * (double)fast.integrated / (double)fast.cycles, median_rt(&every, first, lines), h,
                   ph, 100.0 * (double)every.integrated / (double)every.cycles);
            printf(own_tier ? " %13s %13s %21s\n" : "\n", ch, cph, cr);
            fflush(stdout);
        }
        lesson_free(&fast);
        lesson_free(&every);
    }
    printf("# rt/cpu_s: a line's instrument time (trace and retrace) over its thread's CPU time; "
           "every_rt: the every-cycle tier's, same lines, same run; errors: the %s tier's "
           "images against the every-cycle tier's (each draws its own noise)%s\n",
           own_tier ? "lesson's" : "default",
           own_tier ? "; cold: both run again with the noise's powers 1e9 times lower, the tier's own "
                      "model error; cold_ring: the loop's ring on both, the peak of the spectrum of "
                      "z - followed in the scope (200 Hz to 5 kHz, Hann window) and its amplitude "
                      "there as a sinusoid's, mean over the lines and directions" : "");
    if (own_tier && strcmp(tier, "envelope") != 0) {
        tt_scene_free(base);
        return rc;
    }
    /* why the envelope tier integrated what it did, per line (all lines, settling too) */
    printf("# lesson, why the envelope tier integrates: its controller's counts per line "
           "(tiptap/instrument/scan_envelope_stops.h)\n%-26s", "setting");
    for (int k = 0; k < TT_ENV_STOPS; k++)
        printf(" %s", tt_scan_envelope_stop_name(k));
    printf("\n");
    for (size_t i = 0; i < ns && !rc; i++) {
        if (only ? (int)i != only - 1 : quick && i != ns - 1)
            continue;
        printf("%-26s", settings[i].label);
        for (int k = 0; k < TT_ENV_STOPS; k++)
            printf(" %ld", why[i][k] / lines);
        printf("\n");
    }
    tt_scene_free(base);
    return rc;
}
