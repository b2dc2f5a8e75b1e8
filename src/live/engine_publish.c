/* Publishing a line of the live console's engine (src/live/engine_private.h): its pixels,
 * its scope record decimated for a screen, the loop's judgement from it, and the run's warnings. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine_private.h"
#include "live_private.h"
#include "tiptap/instrument/scan_oscillation.h"
#include "tiptap/io/decimate.h"
#include "tiptap/util/error.h"

/* A scope record of scan s, decimated for a screen, into the view (under mu). */
void tt_live_publish_scope(tt_live_engine *e, const tt_scan *s, const tt_scan_scope *sc, long line, int tier)
{
    static const int q[TT_LIVE_NS] = {TT_SCOPE_POSITION, TT_SCOPE_Z, TT_SCOPE_ERROR,
                                      TT_SCOPE_AMPLITUDE, TT_SCOPE_PHASE, TT_SCOPE_SURFACE};
    for (int r = 0; r < 2; r++) {
        long n = tt_scan_scope_points(sc, r);
        tt_decimate *d = NULL;
        e->v.scope_n[r] = 0;
        if (n <= 0 || tt_decimate_alloc(&d, TT_LIVE_NS, (double)n, TT_LIVE_SCOPE_BUDGET))
            continue;
        const double *src[TT_LIVE_NS];
        for (int k = 0; k < TT_LIVE_NS; k++)
            src[k] = tt_scan_scope_series(sc, r, q[k]);
        const double *t = tt_scan_scope_series(sc, r, TT_SCOPE_TIME);
        for (long i = 0; i < n; i++) {
            double v[TT_LIVE_NS];
            for (int k = 0; k < TT_LIVE_NS; k++)
                v[k] = src[k] ? src[k][i] : NAN;
            tt_decimate_push(d, v);
        }
        tt_decimate_finish(d);
        size_t m = tt_decimate_count(d);
        for (int k = 0; k < TT_LIVE_NS; k++) {
            double *a = realloc(e->series[r][k], (m ? m : 1) * sizeof(double));
            if (!a)
                break;
            memcpy(a, tt_decimate_line(d, (size_t)k), m * sizeof(double));
            e->series[r][k] = a;
            e->v.scope[r][k] = a;
        }
        e->v.scope_n[r] = m;
        e->v.scope_t0[r] = t ? t[0] : 0;
        e->v.scope_t1[r] = t ? t[n - 1] : 0;
        tt_decimate_free(d);
    }
    e->v.scope_line = line;
    e->v.scope_tier = tier;
    e->v.scope_rate = tt_scan_scope_rate(sc);
    /* the line's own gains: a line under way when a change came arrives after it */
    tt_loop loop;
    tt_scan_loop(s, &loop);
    e->v.scope_kp = loop.kp;
    e->v.scope_ki = loop.ki;
    e->v.scope_version = e->v.version;
}

/* Line `line`'s pixels from scan s (buf: a line's room) into the published rows, as
 * tier's (under mu). */
void tt_live_publish_row(tt_live_engine *e, const tt_scan *s, double *buf, long line, int tier)
{
    long px = e->v.pixels;
    unsigned long ver = ++e->v.version;
    for (int c = 0; c < TT_LIVE_NCH; c++)
        for (int r = 0; r < 2; r++)
            if (e->rows[c][r] && tt_scan_line_values(s, e->ch_index[c], r, line, buf) == TT_OK)
                memcpy(e->rows[c][r] + line * px, buf, (size_t)px * sizeof(double));
    e->row_version[line] = ver;
    e->row_tier[line] = (unsigned char)tier;
    e->v.status_version = ver;
}

/* The oscillation warning and the gain suggestion, from the line's record on the scan's
 * own tier (instrument/scan_oscillation.h): z and the error at the loop's rate, not the
 * pixel means, which hide a ring of a period a pixel (under mu). */
void tt_live_judge_loop(tt_live_engine *e)
{
    tt_loop loop;
    tt_oscillation o;
    tt_scan_loop(e->run.scan, &loop);
    if (tt_scan_oscillation(e->scope, &loop, &o) != TT_OK)
        return;
    e->v.oscillating = o.rings;
    e->v.ring_hz = o.rings ? o.frequency : 0;
    e->v.ring_nm = o.rings ? o.z_peak_to_peak : 0;
    e->v.ring_damping = o.rings && isfinite(o.damping) ? o.damping : 0;
    e->v.suggest_ki = o.rings && isfinite(o.ki_suggested) && o.ki_suggested > 0 ? o.ki_suggested : 0;
    /* what the page needs to say whether the loop lags and whether the image shows the
     * ring: the error's rms over the record, and the height pixels' spread */
    double sum = 0;
    long n = 0;
    for (int r = 0; r < 2; r++) {
        const double *er = tt_scan_scope_series(e->scope, r, TT_SCOPE_ERROR);
        long m = tt_scan_scope_points(e->scope, r);
        for (long i = 0; er && i < m; i++)
            if (isfinite(er[i])) {
                sum += er[i] * er[i];
                n++;
            }
    }
    double lo = INFINITY, hi = -INFINITY;
    const double *h = e->rows[TT_LIVE_HEIGHT][0];
    for (long i = 0; h && i < e->v.pixels; i++) {
        double z = h[e->v.line * e->v.pixels + i];
        if (isfinite(z)) {
            lo = z < lo ? z : lo;
            hi = z > hi ? z : hi;
        }
    }
    /* how far z strays from the true surface (its mean offset taken off), against the
     * surface's own peak to peak on the line: a loop that lags leaves z behind */
    double dz = 0, dz2 = 0, slo = INFINITY, shi = -INFINITY;
    long nz = 0;
    for (int r = 0; r < 2; r++) {
        const double *z = tt_scan_scope_series(e->scope, r, TT_SCOPE_Z);
        const double *su = tt_scan_scope_series(e->scope, r, TT_SCOPE_SURFACE);
        long m = tt_scan_scope_points(e->scope, r);
        for (long i = 0; z && su && i < m; i++)
            if (isfinite(z[i]) && isfinite(su[i])) {
                double d = z[i] - su[i];
                dz += d;
                dz2 += d * d;
                nz++;
                slo = su[i] < slo ? su[i] : slo;
                shi = su[i] > shi ? su[i] : shi;
            }
    }
    e->v.track_rms = nz ? sqrt(fmax(0, dz2 / (double)nz - (dz / (double)nz) * (dz / (double)nz))) : NAN;
    e->v.surface_range = shi >= slo ? shi - slo : NAN;
    /* the rule (docs/live.md): z strays by more than 0.35 of a surface's relief of 1 nm or
     * more (teaching grating at 8 Hz: 0.48 at ki 100 Hz, 0.44 at 300 Hz, 0.31 at 1 kHz) */
    e->v.lagging = e->v.surface_range >= 1e-9 && e->v.track_rms > 0.35 * e->v.surface_range;
    e->v.error_rms = n ? sqrt(sum / (double)n) : NAN;
    e->v.setpoint = e->params.feedback.setpoint;
    e->v.height_range = hi >= lo ? hi - lo : NAN;
    e->v.judged_line = e->v.line;
    e->v.judged++;
}

/* A warning raised on the engine's thread (the run layer's, as tiptap scan raises them):
 * kept for the page, a repeat moved to the end with its new frame, and printed on the
 * server's stderr as the program prints every warning. */
void tt_live_publish_warning(const char *category, const char *message, void *data)
{
    tt_live_engine *e = data;
    fprintf(stderr, "tiptap: warning: %s\n", message);
    pthread_mutex_lock(&e->mu);
    tt_live_view *v = &e->v;
    int i = 0;
    while (i < v->nwarnings && strcmp(v->warning[i], message) != 0)
        i++;
    if (i == TT_LIVE_WARNINGS)
        i = 0; /* full: the oldest goes */
    if (i < v->nwarnings) {
        v->nwarnings--;
        for (int k = i; k < v->nwarnings; k++) {
            memcpy(v->warning[k], v->warning[k + 1], sizeof v->warning[k]);
            memcpy(v->warning_category[k], v->warning_category[k + 1], sizeof v->warning_category[k]);
            v->warning_frame[k] = v->warning_frame[k + 1];
        }
    }
    i = v->nwarnings++;
    tt_live_text(v->warning[i], sizeof v->warning[i], message);
    tt_live_text(v->warning_category[i], sizeof v->warning_category[i], category);
    v->warning_frame[i] = v->frame;
    v->status_version = ++v->version;
    pthread_mutex_unlock(&e->mu);
}
