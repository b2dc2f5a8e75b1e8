/* A scan line's full-rate record as files (scope.csv, scope.png) and the warning of an
 * oscillating loop judged from it (tiptap/instrument/scan_oscillation.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "tiptap/io/decimate.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/instrument/scan_oscillation.h"
#include "tiptap/run/run.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

/* The plot keeps at most this many points a direction (each bucket's extremes, so that
 * a ring stays visible): 4000 pixels wide show no more. */
#define SCOPE_BUDGET 8000

/* The followed height differs from the surface only under a shaped tip, a tilt or a
 * drift: written then alone, so that a point tip's scope.csv keeps its columns. */
static int followed_differs(const tt_scan_scope *sc)
{
    for (int r = 0; r < 2; r++)
        for (long i = 0; i < tt_scan_scope_points(sc, r); i++)
            if (tt_scan_scope_series(sc, r, TT_SCOPE_FOLLOWED)[i] !=
                tt_scan_scope_series(sc, r, TT_SCOPE_SURFACE)[i])
                return 1;
    return 0;
}

static int write_csv(const tt_scan_scope *sc, const char *path)
{
    tt_outfile *of;
    int rc = tt_outfile_open(&of, path);
    if (rc)
        return rc;
    FILE *f = tt_outfile_stream(of);
    const int nq = followed_differs(sc) ? TT_SCOPE_COUNT : TT_SCOPE_FOLLOWED;
    fprintf(f, "direction");
    for (int q = 0; q < nq; q++) {
        const char *u = tt_scan_scope_unit(q);
        fprintf(f, ",%s%s%s", tt_scan_scope_name(q), *u ? "_" : "", u);
    }
    fputc('\n', f);
    /* a row at a time, each number as "%.9g" (tt_format_g9: the same bytes, without
     * printf's exact conversion, most of this file's time) */
    char row[16 + 33 * TT_SCOPE_COUNT];
    for (int r = 0; r < 2; r++)
        for (long i = 0; i < tt_scan_scope_points(sc, r); i++) {
            size_t n = (size_t)snprintf(row, sizeof row, "%s", r ? "retrace" : "trace");
            for (int q = 0; q < nq; q++) {
                row[n++] = ',';
                n += (size_t)tt_format_g9(row + n, tt_scan_scope_series(sc, r, q)[i]);
            }
            row[n++] = '\n';
            fwrite(row, 1, n, f);
        }
    return tt_outfile_close(of, 1);
}

/* One direction's series in the plot's units, decimated: time (ms), z, surface, error,
 * amplitude (nm), phase (deg). */
static int series(const tt_scan_scope *sc, int r, tt_decimate **out)
{
    static const int q[6] = {TT_SCOPE_TIME, TT_SCOPE_Z, TT_SCOPE_SURFACE, TT_SCOPE_ERROR,
                             TT_SCOPE_AMPLITUDE, TT_SCOPE_PHASE};
    static const double scale[6] = {1e3, 1e9, 1e9, 1e9, 1e9, 1};
    long n = tt_scan_scope_points(sc, r);
    int rc = tt_decimate_alloc(out, 6, (double)n, SCOPE_BUDGET);
    for (long i = 0; i < n && !rc; i++) {
        double v[6];
        for (int k = 0; k < 6; k++)
            v[k] = tt_scan_scope_series(sc, r, q[k])[i] * scale[k];
        rc = tt_decimate_push(*out, v);
    }
    return rc ? rc : tt_decimate_finish(*out);
}

/* The zoom's window: around the longest ring the check found, else around the error's
 * largest swing; 6 ms at least. */
static void zoom_window(const tt_scan_scope *sc, const tt_oscillation *o, double *t0, double *t1)
{
    double tc = NAN, half = 3e-3;
    if (o->periods > 0 && isfinite(o->frequency)) {
        tc = 0.5 * (o->t_start + o->t_end);
        half = fmax(half, 0.5 * (o->t_end - o->t_start) + 2 / o->frequency);
    } else {
        double big = -1;
        for (int r = 0; r < 2; r++)
            for (long i = 0; i < tt_scan_scope_points(sc, r); i++) {
                double e = fabs(tt_scan_scope_series(sc, r, TT_SCOPE_ERROR)[i]);
                if (e > big) {
                    big = e;
                    tc = tt_scan_scope_series(sc, r, TT_SCOPE_TIME)[i];
                }
            }
    }
    *t0 = tc - half;
    *t1 = tc + half;
}

/* The zoom panel: z - surface and the error over [t0, t1], both directions. */
static int zoom(tt_figure *f, int panel, const tt_scan_scope *sc, double t0, double t1)
{
    int rc = TT_OK;
    for (int r = 0; r < 2 && !rc; r++) {
        long n = tt_scan_scope_points(sc, r), m = 0;
        const double *t = tt_scan_scope_series(sc, r, TT_SCOPE_TIME);
        double *x = malloc((size_t)(n > 0 ? n : 1) * 3 * sizeof *x);
        if (!x)
            return tt_error_nomem("the scope's zoom");
        double *dz = x + n, *e = x + 2 * n;
        for (long i = 0; i < n; i++)
            if (t[i] >= t0 && t[i] <= t1) {
                x[m] = t[i] * 1e3;
                dz[m] = (tt_scan_scope_series(sc, r, TT_SCOPE_Z)[i] -
                         tt_scan_scope_series(sc, r, TT_SCOPE_SURFACE)[i]) * 1e9;
                e[m++] = tt_scan_scope_series(sc, r, TT_SCOPE_ERROR)[i] * 1e9;
            }
        if (m) {
            rc = tt_figure_line(f, panel, x, dz, (size_t)m, r ? "z - surface, retrace" : "z - surface, trace",
                                r ? 2 : 1);
            if (!rc)
                rc = tt_figure_line(f, panel, x, e, (size_t)m, r ? "error, retrace" : "error, trace",
                                    (r ? 2 : 1) | TT_PLOT_DASHED);
        }
        free(x);
    }
    return rc;
}

static int plot(const tt_scan_scope *sc, const tt_oscillation *o, double setpoint, const char *path)
{
    char title[160], zl[160];
    snprintf(title, sizeof title, "Scope: line %ld, trace then retrace, a point per lock-in block (%.3g kHz)",
             tt_scan_scope_line(sc), tt_scan_scope_rate(sc) * 1e-3);
    tt_figure *f = tt_figure_alloc(5, title);
    tt_decimate *d[2] = {NULL, NULL};
    int rc = f ? TT_OK : tt_error_nomem("the plot %s", path);
    for (int r = 0; r < 2 && !rc; r++)
        if (tt_scan_scope_points(sc, r) > 0)
            rc = series(sc, r, &d[r]);
    tt_figure_axes(f, 0, "instrument time (ms)", "z piezo (nm)");
    tt_figure_axes(f, 1, "instrument time (ms)", "error: amplitude - setpoint (nm)");
    tt_figure_axes(f, 2, "instrument time (ms)", "lock-in amplitude (nm)");
    tt_figure_axes(f, 3, "instrument time (ms)", "phase (deg)");
    double t0, t1;
    zoom_window(sc, o, &t0, &t1);
    snprintf(zl, sizeof zl, "instrument time (ms): zoom on %s", o->rings ? "the ring the loop's check found"
                                                          : o->periods > 0 ? "the longest ring, too short to warn"
                                                                           : "the largest error");
    tt_figure_axes(f, 4, zl, "z - surface; error (nm)");
    for (int r = 0; r < 2 && !rc; r++) {
        if (!d[r])
            continue;
        size_t n = tt_decimate_count(d[r]);
        const double *t = tt_decimate_line(d[r], 0);
        const char *name = r ? "retrace" : "trace";
        unsigned color = r ? 2 : 1;
        tt_figure_line(f, 0, t, tt_decimate_line(d[r], 1), n, name, color);
        tt_figure_line(f, 0, t, tt_decimate_line(d[r], 2), n, r ? NULL : "true surface",
                       3 | TT_PLOT_DASHED);
        for (int p = 1; p < 4; p++)
            tt_figure_line(f, p, t, tt_decimate_line(d[r], p + 2), n, name, color);
    }
    if (!rc)
        rc = zoom(f, 4, sc, t0, t1);
    if (!rc) {
        tt_figure_hline(f, 1, 0, NULL);
        tt_figure_hline(f, 2, setpoint * 1e9, "setpoint");
        tt_figure_hline(f, 4, 0, NULL);
        rc = tt_figure_write_png(f, path, 1100, 1450);
    }
    tt_decimate_free(d[0]);
    tt_decimate_free(d[1]);
    tt_figure_free(f);
    return rc;
}

int cli_scope_prepare(cli_scope_out *so, const tt_scan *scan, const tt_scan_scope *sc, const char *dir,
                      int *n)
{
    *n = 0;
    if (tt_scan_scope_line(sc) < 0)
        return TT_OK; /* the line did not finish (interrupted): nothing to write */
    tt_loop loop;
    tt_scan_loop(scan, &loop);
    so->sc = sc;
    so->setpoint = loop.setpoint;
    int rc = tt_scan_oscillation(sc, &loop, &so->o);
    if (rc)
        return rc;
    snprintf(so->csv, sizeof so->csv, "%s/scope.csv", dir);
    snprintf(so->png, sizeof so->png, "%s/scope.png", dir);
    *n = 2;
    return TT_OK;
}

int cli_scope_file(const cli_scope_out *so, int j, int *written)
{
    int rc = j == 0 ? plot(so->sc, &so->o, so->setpoint, so->png) : write_csv(so->sc, so->csv);
    *written += rc == TT_OK;
    return rc;
}

void cli_scope_warn(const char *cmd, const tt_scan *scan, const tt_scan_scope *sc)
{
    if (tt_run_scan_warn_oscillation(scan, sc, "scope.csv, scope.png"))
        cli_scope_note(cmd, scan, sc);
}

void cli_scope_note(const char *cmd, const tt_scan *scan, const tt_scan_scope *sc)
{
    tt_loop loop;
    tt_oscillation o;
    tt_scan_loop(scan, &loop);
    if (tt_scan_oscillation(sc, &loop, &o))
        return;
    if (isfinite(o.ki_suggested))
        fprintf(stderr, "tiptap %s: note: integral_gain %.0f Hz has a phase margin of %.0f deg "
                        "on the loop's model fitted to the ring (plant gain %.2f, amplitude time "
                        "constant %.3g ms); %.0f Hz gives 60 deg (docs/imaging.md, The scope)\n",
                cmd, loop.ki, o.phase_margin + 0.0, o.plant_gain, o.amplitude_time * 1e3,
                o.ki_suggested);
}
