/* tiptap sweep --plot: the finished table drawn with tt_figure (see sweep.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sweep.h"
#include "tiptap/io/plot.h"
#include "tiptap/util/error.h"

/* Field col of a CSV row as a number (text fields give NaN). */
static double field(const char *row, int col)
{
    for (int c = 0; c < col; c++) {
        int quoted = 0;
        while (*row && (quoted || *row != ',') && *row != '\n')
            quoted ^= *row++ == '"';
        if (*row != ',')
            return NAN;
        row++;
    }
    char *end;
    double v = strtod(row, &end);
    return end == row ? NAN : v;
}

/* Points that did not settle within [approach] max_cycles (the CSV's settled = 0),
 * gathered per panel and drawn over the lines as marks: their values are where the run
 * stopped, not a steady state. */
typedef struct {
    double *x[3], *y[3];
    size_t n[3], cap[3];
} unsettled;

static int mark(unsettled *u, int p, double x, double y)
{
    if (u->n[p] == u->cap[p]) {
        size_t cap = u->cap[p] ? 2 * u->cap[p] : 64;
        double *nx = realloc(u->x[p], cap * sizeof *nx);
        if (nx)
            u->x[p] = nx;
        double *ny = realloc(u->y[p], cap * sizeof *ny);
        if (ny)
            u->y[p] = ny;
        if (!nx || !ny)
            return tt_error(TT_ENOMEM, "out of memory");
        u->cap[p] = cap;
    }
    u->x[p][u->n[p]] = x;
    u->y[p][u->n[p]++] = y;
    return TT_OK;
}

/* The marks drawn (the legend names them once), and freed. */
static void draw_unsettled(tt_figure *f, unsettled *u)
{
    int first = 1;
    for (int p = 0; p < 3; p++) {
        if (u->n[p])
            tt_figure_line(f, p, u->x[p], u->y[p], u->n[p],
                           first ? "not settled within max_cycles" : NULL, 7 | TT_PLOT_POINTS);
        first &= !u->n[p];
        free(u->x[p]);
        free(u->y[p]);
    }
}

/* Series of a combination: its levels of every key but x and the contrast key. */
static size_t series_of(const tt_sweep *g, size_t i, size_t x, long contrast, size_t *count)
{
    size_t s = 0, n = 1;
    for (size_t k = 0; k < tt_sweep_keys(g); k++)
        if (k != x && (long)k != contrast) {
            s = s * tt_sweep_levels(g, k) + tt_sweep_level(g, i, k);
            n *= tt_sweep_levels(g, k);
        }
    *count = n;
    return s;
}

static void series_label(const tt_sweep *g, size_t i, size_t x, long contrast, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < tt_sweep_keys(g) && used < len; k++) {
        if (k == x)
            continue;
        const char *key = tt_sweep_key(g, k), *dot = strrchr(key, '.');
        int w = (long)k == contrast
                    ? snprintf(buf + used, len - used, "%s%s - %s", used ? ", " : "", tt_sweep_text(g, i, k),
                               tt_sweep_text(g, 0, k))
                    : snprintf(buf + used, len - used, "%s%s = %s", used ? ", " : "", dot ? dot + 1 : key,
                               tt_sweep_text(g, i, k));
        if (w < 0)
            break;
        used += (size_t)w;
    }
}

/* The key steady and setpoint points are drawn against: the last one other than the
 * contrast key; the number of keys when there is none. */
static size_t x_key(const tt_sweep *g, long contrast)
{
    size_t nk = tt_sweep_keys(g);
    for (size_t k = nk; k-- > 0;)
        if ((long)k != contrast)
            return k;
    return nk;
}

int sweep_plot_check(const sweep_job *job, long contrast)
{
    if (job->kind == TT_SWEEP_SCAN)
        return tt_error(TT_EINVAL, "--plot: not for scans (each folder has its images)");
    if (job->kind != TT_SWEEP_APPROACH && x_key(job->grid, contrast) == tt_sweep_keys(job->grid))
        return tt_error(TT_EINVAL, "--plot: needs a varied key besides the contrast key");
    return TT_OK;
}

/* A series' colour: one per contrast level after the first within each series, or one
 * per series without a contrast key (the first form gave them all the first colour). */
static unsigned series_style(size_t s, size_t c, size_t nc, long contrast)
{
    return (unsigned)(contrast >= 0 ? s * (nc - 1) + c : s) % 8 + 1;
}

/* Steady and setpoint points: three panels against the x key, one line per series
 * (and per contrast level, as differences to the first). */
static int plot_points(const sweep_job *job, const sweep_results *r, tt_figure *f, long contrast)
{
    const tt_sweep *g = job->grid;
    size_t nk = tt_sweep_keys(g), x = x_key(g, contrast); /* x < nk: sweep_plot_check */
    int base = 1 + (int)nk + (job->kind == TT_SWEEP_SETPOINT), ycol = job->kind == TT_SWEEP_SETPOINT ? base : base + 1;
    int cols[3] = {ycol, base + 2, base + 7}, settled = base + 12;
    unsettled u;
    memset(&u, 0, sizeof u);
    size_t nx = tt_sweep_levels(g, x), ns, nc = contrast >= 0 ? tt_sweep_levels(g, (size_t)contrast) : 1;
    series_of(g, 0, x, contrast, &ns);
    double *xs = malloc(nx * sizeof *xs), *ys = malloc(nx * sizeof *ys);
    size_t *idx = malloc(nx * sizeof *idx);
    int rc = (xs && ys && idx) ? TT_OK : tt_error(TT_ENOMEM, "out of memory");
    for (size_t s = 0; s < ns && !rc; s++)
        for (size_t c = contrast >= 0 ? 1 : 0; c < nc && !rc; c++) {
            size_t m = 0, ref[4096], nref = 0;
            for (size_t i = 0; i < r->n; i++) {
                size_t dummy;
                if (series_of(g, i, x, contrast, &dummy) != s || !r->text[i])
                    continue;
                size_t lc = contrast >= 0 ? tt_sweep_level(g, i, (size_t)contrast) : 0;
                if (lc == 0 && contrast >= 0 && nref < 4096)
                    ref[nref++] = i;
                if (lc == c && m < nx)
                    idx[m++] = i;
            }
            char label[512];
            if (m)
                series_label(g, idx[0], x, contrast, label, sizeof label);
            for (int p = 0; p < 3 && m; p++) {
                for (size_t j = 0; j < m && !rc; j++) {
                    xs[j] = tt_sweep_value(g, idx[j], x);
                    ys[j] = field(r->text[idx[j]], cols[p]);
                    int ok = field(r->text[idx[j]], settled) == 1;
                    if (contrast >= 0) {
                        /* the reference: same levels but the contrast key's first */
                        double y0 = NAN;
                        for (size_t q = 0; q < nref; q++)
                            if (tt_sweep_level(g, ref[q], x) == tt_sweep_level(g, idx[j], x)) {
                                y0 = field(r->text[ref[q]], cols[p]);
                                ok &= field(r->text[ref[q]], settled) == 1;
                            }
                        /* apparent height: where the setpoint needs a larger rest
                         * separation the feedback retracts the sample, as over a bump */
                        ys[j] -= y0;
                    }
                    if (!ok)
                        rc = mark(&u, p, xs[j], ys[j]);
                }
                tt_figure_line(f, p, xs, ys, m, p == 0 ? label : NULL, series_style(s, c, nc, contrast));
            }
        }
    const char *xl = tt_sweep_key(g, x);
    char xlabel[256];
    snprintf(xlabel, sizeof xlabel, "%s (%s)", xl, tt_sweep_unit(g, x));
    int d = contrast >= 0;
    tt_figure_axes(f, 0, xlabel, job->kind == TT_SWEEP_SETPOINT ? (d ? "apparent height difference (nm)" : "rest separation z (nm)")
                                                             : (d ? "amplitude difference (nm)" : "amplitude (nm)"));
    tt_figure_axes(f, 1, xlabel, d ? "phase difference (deg)" : "phase lag (deg)");
    tt_figure_axes(f, 2, xlabel, d ? "dissipation difference (aJ)" : "tip-sample loss per cycle (aJ)");
    if (d) {
        tt_figure_hline(f, 0, 0, NULL);
        tt_figure_hline(f, 1, 0, NULL);
    } else
        tt_figure_hline(f, 1, 90, NULL);
    draw_unsettled(f, &u);
    free(xs);
    free(ys);
    free(idx);
    return rc;
}

/* Approach curves: amplitude, phase and peak force against z, one line a combination
 * (colour: the first key's value, dashes: the second's). */
static int plot_curves(const sweep_job *job, const sweep_results *r, tt_figure *f)
{
    const tt_sweep *g = job->grid;
    int base = 1 + (int)tt_sweep_keys(g), cols[3] = {base + 1, base + 2, base + 4}, settled = base + 12;
    int rc = TT_OK;
    unsettled u;
    memset(&u, 0, sizeof u);
    for (size_t i = 0; i < r->n && !rc; i++) {
        const char *t = r->text[i];
        size_t m = 0;
        for (const char *p = t; p && *p; p = strchr(p, '\n'), p = p ? p + 1 : p)
            m++;
        double *xs = malloc((m + 1) * sizeof *xs), *ys = malloc((m + 1) * sizeof *ys);
        if (!xs || !ys)
            rc = tt_error(TT_ENOMEM, "out of memory");
        char label[512];
        tt_sweep_label(g, i, label, sizeof label);
        unsigned style = (unsigned)(tt_sweep_keys(g) ? tt_sweep_level(g, i, 0) % 8 + 1 : 1);
        if (tt_sweep_keys(g) > 1 && tt_sweep_level(g, i, 1) % 2)
            style |= TT_PLOT_DASHED;
        for (int p = 0; p < 3 && !rc; p++) {
            size_t j = 0;
            for (const char *q = t; q && *q && j < m && !rc; q = strchr(q, '\n'), q = q ? q + 1 : q) {
                xs[j] = field(q, base);
                ys[j] = field(q, cols[p]);
                if (field(q, settled) != 1)
                    rc = mark(&u, p, xs[j], ys[j]);
                j++;
            }
            tt_figure_line(f, p, xs, ys, j, p == 0 ? label : NULL, style);
        }
        free(xs);
        free(ys);
    }
    tt_figure_axes(f, 0, "rest separation z (nm)", "amplitude (nm)");
    tt_figure_axes(f, 1, "rest separation z (nm)", "phase lag (deg)");
    tt_figure_hline(f, 1, 90, NULL);
    tt_figure_axes(f, 2, "rest separation z (nm)", "peak force (nN)");
    draw_unsettled(f, &u);
    return rc;
}

int sweep_plot(const sweep_job *job, const sweep_results *r, const char *path, long contrast)
{
    int rc = sweep_plot_check(job, contrast);
    if (rc)
        return rc;
    tt_figure *f = tt_figure_alloc(3, job->kind == TT_SWEEP_APPROACH ? "Approach curves" : "Steady points");
    if (!f)
        return tt_error(TT_ENOMEM, "out of memory");
    rc = job->kind == TT_SWEEP_APPROACH ? plot_curves(job, r, f) : plot_points(job, r, f, contrast);
    if (!rc)
        rc = tt_figure_write_png(f, path, 900, 1100);
    tt_figure_free(f);
    return rc;
}
