/* The warnings every surface of tiptap gives about a run, and tiptap scan's checks before
 * it runs (see include/tiptap/run/run.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "tiptap/config/config.h"
#include "tiptap/instrument/scan_oscillation.h"
#include "tiptap/instrument/scan_scope.h"
#include "tiptap/physics/contact.h"
#include "tiptap/run/run.h"
#include "tiptap/run/sweep.h"
#include "tiptap/util/error.h"
#include "tiptap/util/warning.h"

const char *tt_run_duration(double s, char *buf, size_t len)
{
    if (s < 90)
        snprintf(buf, len, "%.2g s", s);
    else if (s < 5400)
        snprintf(buf, len, "%.0f min", s / 60);
    else if (s < 2 * 86400)
        snprintf(buf, len, "%.1f h", s / 3600);
    else
        snprintf(buf, len, "%.3g days", s / 86400);
    return buf;
}

const char *tt_run_bytes(double b, char *buf, size_t len)
{
    if (b < 1e6)
        snprintf(buf, len, "%.0f kB", b / 1e3);
    else if (b < 1e9)
        snprintf(buf, len, "%.0f MB", b / 1e6);
    else
        snprintf(buf, len, "%.1f GB", b / 1e9);
    return buf;
}

double tt_run_memory_available(void)
{
    double avail = -1;
    FILE *f = fopen("/proc/meminfo", "r");
    if (f) {
        char line[256];
        unsigned long long kb;
        while (fgets(line, sizeof line, f))
            if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1)
                avail = (double)kb * 1024;
        fclose(f);
    }
    if (avail < 0) {
        long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
        avail = pages > 0 && size > 0 ? (double)pages * (double)size : INFINITY;
    }
    const int limits[] = {RLIMIT_AS, RLIMIT_DATA};
    for (size_t i = 0; i < sizeof limits / sizeof limits[0]; i++) {
        struct rlimit rl;
        if (getrlimit(limits[i], &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
            (double)rl.rlim_cur < avail)
            avail = (double)rl.rlim_cur;
    }
    return avail;
}

/* The cost of p on threads threads into *c; TT_ENOMEM past the memory available (a
 * 16384 x 16384 scan of 12 images holds 25 GB), rather than left to the OOM killer. */
static int scan_cost(const tt_scan_params *p, int threads, tt_run_scan_cost *c)
{
    tt_estimate e;
    tt_config_scan_estimate(p, &e);
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int n = threads > 0 ? threads : cores > 0 ? (int)cores : 1;
    if (n > p->raster.lines)
        n = (int)p->raster.lines;
    *c = (tt_run_scan_cost){p->raster.pixels, p->raster.lines, n, e.upper_bound, e.envelope,
                            tt_scan_averaged_tier(p), e.cycles, e.seconds, e.seconds_low,
                            e.integrated_low, e.integrated_high,
                            e.bytes + e.thread_bytes * n + e.scope_bytes,
                            tt_run_memory_available(), p->cantilever.f0, p->cantilever.fd};
    if (c->bytes <= c->available)
        return TT_OK;
    char need[32], have[32], img[32];
    /* the profile line's scope record holds every lock-in block of the line: at a very
     * slow line rate it, not the images, is what cannot be held (0.0002 Hz: 27 GB) */
    if (e.scope_bytes > 0.5 * c->bytes)
        return tt_error(TT_ENOMEM, "[scan] line_rate: %g Hz makes the profile line's scope record "
                                   "(every lock-in block of the line) need about %s of memory, "
                                   "more than the %s available; scan faster lines",
                        p->raster.line_rate, tt_run_bytes(e.scope_bytes, need, sizeof need),
                        tt_run_bytes(c->available, have, sizeof have));
    double image = (double)p->raster.pixels * (double)p->raster.lines * sizeof(double);
    double nimg = e.bytes / image - 1;
    return tt_error(TT_ENOMEM, "%ld x %ld pixels need about %s of memory (%.0f image%s of %s each), "
                               "more than the %s available; scan fewer pixels, lines or channels",
                    p->raster.pixels, p->raster.lines, tt_run_bytes(c->bytes, need, sizeof need), nimg,
                    nimg > 1.5 ? "s" : "", tt_run_bytes(image, img, sizeof img),
                    tt_run_bytes(c->available, have, sizeof have));
}

int tt_run_scan_alloc(const tt_scene *s, int threads, tt_scan **out, tt_run_scan_cost *cost)
{
    tt_scan_params p;
    *out = NULL;
    int rc = tt_config_scan(s, &p);
    if (rc)
        return rc;
    /* the scan's own solver setting (an accuracy study of the same scene tries coarser
     * ones on purpose, so this is the run's check, not tt_config_scan's) */
    if (!(rc = tt_config_check_rk4(s, NULL, 0)) && !(rc = scan_cost(&p, threads, cost)))
        rc = tt_scene_locate(s, tt_scan_alloc(out, &p));
    tt_config_scan_free(&p);
    return rc;
}

int tt_run_warn_duration(double wall, int upper_bound, double f0, double fd)
{
    char t[32], why[200] = "";
    if (!(wall > 60))
        return 0;
    /* an adaptive step resolves the resonance: each drive cycle costs f0 / fd resonance
     * periods */
    if (f0 > 2 * fd)
        snprintf(why, sizeof why, "; the drive at %.4g kHz is %.0f times below the %.4g kHz "
                                  "resonance, so each drive cycle costs %.0f cycles of it",
                 fd * 1e-3, f0 / fd, f0 * 1e-3, f0 / fd);
    tt_warn(TT_WARN_RUN, "this run takes %s%s by estimate%s", upper_bound ? "up to " : "about ",
            tt_run_duration(wall, t, sizeof t), why);
    return 1;
}

int tt_run_scan_warn_inputs(const tt_scene *s, const tt_run_scan_cost *cost)
{
    int n = tt_run_warn_duration(cost->seconds / (cost->threads > 0 ? cost->threads : 1),
                                 cost->upper_bound, cost->f0, cost->fd);
    tt_scan_params p;
    if (tt_config_scan(s, &p))
        return n; /* tt_run_scan_alloc read it: not reached */
    /* a material that the surface map never puts under the tip is most likely a typo */
    size_t idx[8], unused = tt_config_scan_unused(&p, idx, 8);
    for (size_t i = 0; i < unused && i < 8; i++, n++)
        tt_warn(TT_WARN_INPUT, "[material %s] is not used: %s", p.materials[idx[i]].name,
                p.surface.map == TT_MAP_UNIFORM ? "a uniform map scans the first material only"
                : p.surface.map == TT_MAP_PNG   ? "it has no map_value, so no pixel of map_png names it"
                : p.surface.map == TT_MAP_LABELS ? "it has no whole-number map_value, so no label of map_image names it"
                                                : "[surface] map_materials names two others");
    if (unused > 8 && ++n)
        tt_warn(TT_WARN_INPUT, "and %zu more materials are not used", unused - 8);
    tt_config_scan_free(&p);
    return n;
}

int tt_run_scan_warn_result(const tt_scan *scan)
{
    int n = 0;
    /* a contact the force laws do not describe: once per material, from the greatest
     * indentation of the whole run */
    for (size_t i = 0; i < tt_scan_materials(scan); i++) {
        tt_contact_extent e;
        if (tt_scan_contact_extent(scan, i, &e))
            n += tt_contact_warn_validity(tt_scan_material_name(scan, i), e.radius, e.indentation,
                                          e.tip_radius, "a larger [tip] radius, a higher [feedback] "
                                          "setpoint or a smaller [cantilever] free_amplitude");
    }
    /* the averaged tier's model can be wrong where its slow flow ran on with the
     * oscillation collapsed (the impacts it sees are integrated, these blocks are not) */
    long line, px, collapsed = tt_scan_averaged_collapsed(scan, &line, &px);
    if (collapsed > 0 && ++n)
        tt_warn(TT_WARN_VALIDITY, "the oscillation collapsed in %ld pixel%s (first: line %ld, pixel "
                                  "%ld): the averaged tier followed them on its slow flow, not "
                                  "integrated, with the amplitude under a quarter of the free "
                                  "amplitude or the tip stuck, where its images can be wrong by "
                                  "nanometres and tens of degrees: compare with [solver] tier = envelope "
                                  "(docs/dynamics.md, Averaged, \"Where it is wrong\")",
                collapsed, collapsed > 1 ? "s" : "", line, px);
    if (tt_scan_clamped(scan) && ++n)
        tt_warn(TT_WARN_SETPOINT, "the z piezo reached the end of its range ([feedback] z_range)");
    return n;
}

int tt_run_scan_warn_oscillation(const tt_scan *scan, const tt_scan_scope *sc, const char *files)
{
    tt_loop loop;
    tt_oscillation o;
    tt_scan_loop(scan, &loop);
    if (tt_scan_scope_line(sc) < 0 || tt_scan_oscillation(sc, &loop, &o) || !o.rings)
        return 0;
    char where[128] = "";
    if (files)
        snprintf(where, sizeof where, " (%s)", files);
    tt_warn(TT_WARN_OSCILLATION,
            "the feedback loop oscillates: in line %ld's %s, z rings at %.0f Hz, %.3g nm peak to "
            "peak about the surface, for %.0f periods from t = %.4g s (error swings to %.3g nm, "
            "damping ratio %.2f); the pixels (%.3g ms each) average it away%s",
            tt_scan_scope_line(sc), o.retrace ? "retrace" : "trace", o.frequency,
            o.z_peak_to_peak * 1e9, o.periods, o.t_start, o.error_peak * 1e9, fmax(o.damping, 0),
            1e3 / (2 * tt_scan_line_rate(scan) *
                   (double)(tt_scan_fast_y(scan) ? tt_scan_yres(scan) : tt_scan_xres(scan))),
            where);
    return 1;
}

/* The estimate's parts past the limits into parts; 0 when none is. */
static int estimate_parts(char *parts, size_t len, double A0, double height_m, const char *what,
                          double amplitude_rel, double phase_deg)
{
    double h = height_m / A0;
    int bad_h = h > TT_RUN_WARN_AMPLITUDE_REL, bad_a = amplitude_rel > TT_RUN_WARN_AMPLITUDE_REL,
        bad_p = phase_deg > TT_RUN_WARN_PHASE_DEG;
    size_t n = 0;
    parts[0] = '\0';
    if (bad_h)
        n += (size_t)snprintf(parts + n, len - n, "%.2g nm in height (%.1e of the free "
                              "amplitude)", height_m * 1e9, h);
    if (bad_a && n < len)
        n += (size_t)snprintf(parts + n, len - n, "%s%.1e of the free amplitude in %s",
                              n ? ", " : "", amplitude_rel, what);
    if (bad_p && n < len)
        snprintf(parts + n, len - n, "%s%.2g deg in phase", n ? " and " : "", phase_deg);
    return bad_h || bad_a || bad_p;
}

int tt_run_warn_estimate(const tt_solver *s, double A0, double height_m, const char *what,
                         double amplitude_rel, double phase_deg)
{
    char parts[256], k[96];
    if (!estimate_parts(parts, sizeof parts, A0, height_m, what, amplitude_rel, phase_deg))
        return 0;
    /* the key that tightens the run: the method's accuracy knob */
    if (s->method == TT_METHOD_RK4)
        snprintf(k, sizeof k, "raise [solver] steps_per_cycle (now %d)", s->steps_per_cycle);
    else
        snprintf(k, sizeof k, "tighten [solver] tolerance (now %.3g)", s->tolerance);
    tt_warn(TT_WARN_ESTIMATE, "the run's own error estimate is %s (above 1e-3 of the free amplitude "
                              "or 0.1 deg): %s", parts, k);
    return 1;
}

/* A noisy scan of more than one mode: its runs differ by the estimate at any tolerance,
 * since mode 2 rings for Q_2 fd / (pi f_2) drive cycles after each tap and the noise
 * finds a different orbit at each (docs/dynamics.md, "A noisy scan of two modes"). */
static int warn_estimate_modes(const tt_cantilever *c, double A0, double height_m, const tt_scan_error *e)
{
    char parts[256];
    if (!estimate_parts(parts, sizeof parts, A0, height_m, "amplitude", e->amplitude_max, e->phase_max))
        return 0;
    double ring = c->mode_Q[1] * c->fd / (M_PI * c->mode_f[1]);
    tt_warn(TT_WARN_ESTIMATE, "the run's own error estimate is %s (above 1e-3 of the free amplitude "
                              "or 0.1 deg): with noise and %d modes this is the runs' real spread, "
                              "not an integration error (mode 2, Q %.4g at %.4g MHz, rings for %.0f "
                              "drive cycles after each tap; docs/dynamics.md, \"A noisy scan of two "
                              "modes\"), so a tighter [solver] tolerance does not help: scan at a "
                              "lower line rate (more cycles a pixel), with [cantilever] modes = 1, "
                              "or read the estimate as the noise's spread",
            parts, c->modes, c->mode_Q[1], c->mode_f[1] / 1e6, ring);
    return 1;
}

int tt_run_scan_warn_error(const tt_scan *scan, const tt_run_scan_cost *cost,
                           const tt_scan_error *e)
{
    if (cost->averaged)
        return 0;
    tt_scan_noise nz;
    tt_scan_get_noise(scan, &nz);
    const tt_cantilever *c = tt_scan_cantilever(scan);
    if (c->modes > 1 && (nz.temperature > 0 || nz.detector > 0 || nz.z_piezo > 0))
        return warn_estimate_modes(c, tt_scan_free_amplitude(scan), e->height_max, e);
    return tt_run_warn_estimate(tt_scan_solver(scan), tt_scan_free_amplitude(scan), e->height_max,
                                "amplitude", e->amplitude_max, e->phase_max);
}

/* The column named name, or -1. */
static long column(const tt_table *t, const char *name)
{
    for (size_t c = 0; c < tt_table_columns(t); c++)
        if (strcmp(tt_table_name(t, c), name) == 0)
            return (long)c;
    return -1;
}

int tt_run_warn_unreached(const tt_table *t)
{
    long found = t ? column(t, "found") : -1, combo = t ? column(t, "combination") : -1;
    if (found < 0 || combo < 0 || !tt_table_is_text(t, (size_t)found))
        return 0;
    /* so that no one takes the closest points for points at the setpoint */
    size_t rows = tt_table_rows(t), n = 0, len = 0;
    char list[256] = "";
    const double *c = tt_table_numbers(t, (size_t)combo);
    for (size_t r = 0; r < rows; r++) {
        const char *f = tt_table_text(t, (size_t)found, r);
        if (!f || strcmp(f, TT_SWEEP_UNREACHABLE) != 0)
            continue;
        if (n++ < 10 && len < sizeof list)
            len += (size_t)snprintf(list + len, sizeof list - len, "%s%.0f", n > 1 ? ", " : "", c[r]);
    }
    if (!n)
        return 0;
    tt_warn(TT_WARN_SETPOINT, "the setpoint was not reached in %zu of %zu combinations (found=%s; "
                              "each row holds the closest point): %s%s",
            n, rows, TT_SWEEP_UNREACHABLE, list, n > 10 ? ", ..." : "");
    return 1;
}
