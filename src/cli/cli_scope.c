/* A scan line's full-rate record as files (scope.csv, scope.png) and the warning of an
 * oscillating loop judged from it (tiptap/instrument/scan_oscillation.h). */
#include <math.h>
#include <stdio.h>

#include "commands.h"
#include "tiptap/io/decimate.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/instrument/scan_oscillation.h"
#include "tiptap/util/error.h"

/* The plot keeps at most this many points a direction (each bucket's extremes, so that
 * a ring stays visible): 4000 pixels wide show no more. */
#define SCOPE_BUDGET 8000

static int write_csv(const tt_scan_scope *sc, const char *path)
{
    tt_outfile *of;
    int rc = tt_outfile_open(&of, path);
    if (rc)
        return rc;
    FILE *f = tt_outfile_stream(of);
    fprintf(f, "direction");
    for (int q = 0; q < TT_SCOPE_COUNT; q++) {
        const char *u = tt_scan_scope_unit(q);
        fprintf(f, ",%s%s%s", tt_scan_scope_name(q), *u ? "_" : "", u);
    }
    fputc('\n', f);
    for (int r = 0; r < 2; r++)
        for (long i = 0; i < tt_scan_scope_points(sc, r); i++) {
            fprintf(f, "%s", r ? "retrace" : "trace");
            for (int q = 0; q < TT_SCOPE_COUNT; q++)
                fprintf(f, ",%.9g", tt_scan_scope_series(sc, r, q)[i]);
            fputc('\n', f);
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

static int plot(const tt_scan_scope *sc, double setpoint, const char *path)
{
    char title[160];
    snprintf(title, sizeof title, "Scope: line %ld, trace then retrace, a point per lock-in block (%.3g kHz)",
             tt_scan_scope_line(sc), tt_scan_scope_rate(sc) * 1e-3);
    tt_figure *f = tt_figure_alloc(4, title);
    tt_decimate *d[2] = {NULL, NULL};
    int rc = f ? TT_OK : tt_error_nomem("the plot %s", path);
    for (int r = 0; r < 2 && !rc; r++)
        if (tt_scan_scope_points(sc, r) > 0)
            rc = series(sc, r, &d[r]);
    tt_figure_axes(f, 0, "instrument time (ms)", "z piezo (nm)");
    tt_figure_axes(f, 1, "instrument time (ms)", "error: amplitude - setpoint (nm)");
    tt_figure_axes(f, 2, "instrument time (ms)", "lock-in amplitude (nm)");
    tt_figure_axes(f, 3, "instrument time (ms)", "phase (deg)");
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
    if (!rc) {
        tt_figure_hline(f, 1, 0, NULL);
        tt_figure_hline(f, 2, setpoint * 1e9, "setpoint");
        rc = tt_figure_write_png(f, path, 1100, 1200);
    }
    tt_decimate_free(d[0]);
    tt_decimate_free(d[1]);
    tt_figure_free(f);
    return rc;
}

int cli_scope_write(const tt_scan_scope *sc, double setpoint, const char *dir, int *written)
{
    char path[4200];
    if (tt_scan_scope_line(sc) < 0)
        return TT_OK; /* the line did not finish (interrupted): nothing to write */
    snprintf(path, sizeof path, "%s/scope.csv", dir);
    int rc = write_csv(sc, path);
    if (rc)
        return rc;
    (*written)++;
    snprintf(path, sizeof path, "%s/scope.png", dir);
    if ((rc = plot(sc, setpoint, path)) == TT_OK)
        (*written)++;
    return rc;
}

void cli_scope_warn(const char *cmd, const tt_scan *scan, const tt_scan_scope *sc)
{
    tt_loop loop;
    tt_oscillation o;
    tt_scan_loop(scan, &loop);
    if (tt_scan_scope_line(sc) < 0 || tt_scan_oscillation(sc, &loop, &o) || !o.rings)
        return;
    fprintf(stderr, "tiptap %s: warning: the feedback loop oscillates: in line %ld's %s, z rings "
                    "at %.0f Hz, %.3g nm peak to peak about the surface, for %.0f periods from "
                    "t = %.4g s (error swings to %.3g nm, damping ratio %.2f); the pixels (%.3g ms "
                    "each) average it away (scope.csv, scope.png)\n",
            cmd, tt_scan_scope_line(sc), o.retrace ? "retrace" : "trace", o.frequency,
            o.z_peak_to_peak * 1e9, o.periods, o.t_start, o.error_peak * 1e9, fmax(o.damping, 0),
            1e3 / (2 * tt_scan_line_rate(scan) *
                   (double)(tt_scan_fast_y(scan) ? tt_scan_yres(scan) : tt_scan_xres(scan))));
    if (isfinite(o.ki_suggested))
        fprintf(stderr, "tiptap %s: note: integral_gain %.4g Hz has a phase margin of %.0f deg "
                        "on the loop's model fitted to the ring (plant gain %.2f, amplitude time "
                        "constant %.3g ms); %.0f Hz gives 60 deg (docs/imaging.md, The scope)\n",
                cmd, loop.ki, o.phase_margin + 0.0, o.plant_gain, o.amplitude_time * 1e3,
                o.ki_suggested);
}
