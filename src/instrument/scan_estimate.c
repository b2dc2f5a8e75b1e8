/* The images' error estimate: a companion line at a tighter setting where the image is
 * hardest, compared with the image (see tt_scan_estimate_error in
 * include/tiptap/instrument/scan.h). */
#include "scan_engine.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/clock.h"
#include "tiptap/util/error.h"
#include "tiptap/util/phase.h"

/* One companion line on a solver setting: height, amplitude and phase of trace and
 * retrace into buf (6 blocks of pixels: [channel][direction]), stopped after budget
 * cycles (0: none); *hit says it stopped there, *ran counts its cycles. */
static int companion_line(tt_scan *S, const tt_solver *solver, long line, long budget, long k0,
                          double *buf, int *hit, long *ran)
{
    worker W;
    line_out out = {{{0}}, 1};
    long px = S->raster.pixels;
    for (long i = 0; i < 6 * px; i++)
        buf[i] = NAN; /* pixels the budget left out stay NaN */
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < (S->raster.retrace ? 2 : 1); r++)
            out.img[r][c] = buf + (size_t)(2 * c + r) * (size_t)px;
    line_tally t = {0};
    int rc = tt_scan_worker_alloc(S, &W, solver);
    /* The tight line's model is held ten times tighter than the run's, as its steps are
     * (a hundred times: see tt_companion_solver), so that the difference of the two is
     * the run's error, the model's included; a hundred times tighter is below what the
     * grazing touches' model can follow (1e-9 of A0 over the blend's orbit), and the
     * tight line would integrate every grazing cycle at 1e-10 (16 G instructions, a
     * fifth of the README job's) */
    W.model_tol = fmax(W.model_tol, S->solver.tolerance);
    W.budget = budget;
    W.k0 = k0;
    if (!rc)
        rc = tt_scan_worker_line(S, &W, line, &out, NULL, &t);
    *hit = W.budget_hit;
    *ran = t.cycles;
    tt_scan_worker_free(&W);
    return rc;
}

/* A hundred times tighter (rk4: four times the steps, 16 times at its order of 2 on
 * contact), so that the difference of the two runs is the run's own error even where
 * the error does not fall with the tolerance: on the bistable scene the envelope
 * model's error control changes course between 1e-9 and 1e-10, and the amplitude moved
 * 3.5 times more from 1e-9 to 1e-10 than from 1e-8 to 1e-9. Not below 1e-14, where the
 * steps' rounding takes over. */
tt_solver tt_companion_solver(const tt_solver *s)
{
    tt_solver t = *s;
    t.tolerance = fmax(s->tolerance / 100, fmin(s->tolerance, 1e-14));
    t.steps_per_cycle = s->steps_per_cycle <= 2500000 ? 4 * s->steps_per_cycle : 10000000;
    return t;
}

/* The companion's cycles: a fifth of the scan's cost, counted as the cycles the scan
 * integrated. On the every-cycle tier each of the companion's costs what its tighter
 * setting asks (dopri5's steps grow as the tolerance to the -1/5, 2.5 times at a
 * hundredth; rk4 runs four times the steps); on the envelope tier a cycle the scan
 * integrated cost 17 to 21 us with its model's work (the README's main job, the
 * teaching scene), a companion cycle 4 to 17 us, so one counts as one. 0 (no bound)
 * where the scan integrated none (the averaged tier). */
static long companion_budget(const tt_scan *S, const tt_solver *tight)
{
    double per = S->solver.method == TT_METHOD_RK4
                     ? (double)tight->steps_per_cycle / (double)S->solver.steps_per_cycle
                     : pow(S->solver.tolerance / tight->tolerance, 0.2);
    if (!(per >= 1) || tt_scan_envelope_usable(S, &S->solver))
        per = 1;
    return S->integrated > 0 ? (long)(TT_ESTIMATE_SHARE * (double)S->integrated / per) : 0;
}

/* Where the image is hardest: the largest height step between neighbouring pixels of
 * the trace (of trace and retrace when the companion covers whole lines, reach >= the
 * pixels), its line and pixel. The profile line from its start where no line has a
 * step (a flat image, or no height channel). */
static long hardest_line(const tt_scan *S, long reach, double *step, long *at)
{
    const tt_raster *R = &S->raster;
    const int dirs = reach >= R->pixels && R->retrace ? 2 : 1;
    long best = S->profile_line;
    double top = 0;
    *at = 0;
    for (long l = 0; l < R->lines; l++) {
        if (!S->line_done[l])
            continue;
        for (int r = 0; r < dirs && tt_scan_image(S, 0, r); r++) { /* asked for */
            const double *h = tt_scan_image(S, 0, r);
            for (long i = 1; i < R->pixels; i++) {
                double d = fabs(h[tt_raster_index(R, l, i)] - h[tt_raster_index(R, l, i - 1)]);
                if (d > top) {
                    top = d;
                    best = l;
                    *at = i;
                }
            }
        }
    }
    *step = top;
    return best;
}

/* A stretch of the trace the companion runs: its line, the pixel of its feature and its
 * first pixel. */
typedef struct {
    long line, at, first;
} stretch;

enum { MAX_STRETCHES = 8 };

/* The material where the tip touches at the trace's pixel px of a line (at its centre,
 * without drift). */
static int material_at(const tt_scan *S, long line, long px, long nc)
{
    double x, y;
    long k = (2 * px + 1) * nc / (2 * S->raster.pixels);
    tt_raster_position(&S->raster, line, 0, nc, k, &x, &y);
    if (S->dilation)
        tt_dilation_contact(S->dilation, x, y, &x, &y);
    return tt_surface_material(S->surface, x, y);
}

/* The first pixel of a stretch of reach pixels with its feature (at) a quarter into it. */
static long first_pixel(long at, long reach, long pixels)
{
    long first = at - reach / 4 > 0 ? at - reach / 4 : 0;
    return first + reach > pixels ? pixels - reach : first;
}

/* The stretches where the image's error is largest: the largest height step (st[0]),
 * and the first edge of each ordered pair of materials met along the trace (from the
 * soft sticky matrix onto a stiff disk the every-cycle tier at 1e-7 erred 0.19 pm where
 * the largest height step, on the disk, erred 0.04 pm: the bench's edge sample), each
 * as far as no stretch already holds it; at most MAX_STRETCHES. */
static int hardest_stretches(const tt_scan *S, long reach, long nc, stretch *st, double *step)
{
    const tt_raster *R = &S->raster;
    *step = 0;
    st[0] = (stretch){S->profile_line, 0, 0};
    if (S->lines_done > 0)
        st[0].line = hardest_line(S, reach, step, &st[0].at);
    int n = 1, seen[MAX_STRETCHES][2];
    for (long l = 0; l < R->lines && !S->uniform && reach < R->pixels; l++) {
        if (!S->line_done[l])
            continue;
        int prev = material_at(S, l, 0, nc);
        for (long i = 1; i < R->pixels; i++) {
            int m = material_at(S, l, i, nc), known = 0;
            if (m == prev)
                continue;
            for (int k = 1; k < n; k++)
                known |= seen[k][0] == prev && seen[k][1] == m;
            /* held by the height step's stretch, a pixel or more from its start */
            long f0 = first_pixel(st[0].at, reach, R->pixels);
            known |= l == st[0].line && i > f0 && i < f0 + reach;
            if (!known && n < MAX_STRETCHES) {
                seen[n][0] = prev;
                seen[n][1] = m;
                st[n++] = (stretch){l, i, 0};
            }
            prev = m;
        }
    }
    for (int k = 0; k < n; k++)
        st[k].first = reach < R->pixels ? first_pixel(st[k].at, reach, R->pixels) : 0;
    return n;
}

/* The pixels a stretch reaches on budget cycles, settle of them settling, less the one
 * it stops in. */
static long stretch_reach(long budget, long settle, long nc, long px)
{
    return (long)((double)(budget - settle) / (double)nc * (double)px) - 1;
}

/* The differences of a stretch's two lines (buf: the run's setting, then the tight
 * one's; [channel][direction] blocks of px) into max and sum, *n counting the pixels. */
static void compare(const tt_scan *S, const double *buf, long first, int dirs, int partial,
                    int rerun, double *max, double *sum, long *n)
{
    const long px = S->raster.pixels;
    const double scale[3] = {1, 1 / S->A0, 1};
    for (int r = 0; r < (partial ? 1 : dirs); r++)
        for (long i = r ? 0 : first; i < px; i++) {
            /* a line stopped by its budget: the trace's pixels before the one it stopped in */
            if (partial && (i + 1 >= px || isnan(buf[(size_t)(6 * px + 1 + i)]) ||
                            (rerun && isnan(buf[(size_t)(1 + i)]))))
                break;
            for (int c = 0; c < 3; c++) {
                double a = buf[(size_t)((2 * c + r) * px + i)], b = buf[(size_t)((6 + 2 * c + r) * px + i)];
                /* phases a turn apart are the same phase (where the oscillation nearly
                 * stops its phase may land anywhere), as the bench and accuracy compare */
                double d = (c == 2 ? tt_phase_diff_deg(a, b) : fabs(a - b)) * scale[c];
                if (!(d <= max[c]))
                    max[c] = d; /* a NaN (a pixel without data) stays visible */
                sum[c] += d * d;
            }
            (*n)++;
        }
}

/* The companion's plan (tt_scan_estimate_plan): its stretches, and per stretch the two
 * lines' profiles in buf (12 blocks of px each: the run's setting, then the tight
 * one's), each job's status, cycles and thread CPU. */
struct tt_scan_estimate {
    tt_scan *S;
    tt_solver tight;
    int dirs, rerun, over, ns;
    long budget;
    double step, cpu; /* cpu: the plan's own (the averaged tier's tables) */
    stretch st[MAX_STRETCHES];
    double *buf;
    int rc[MAX_STRETCHES][2], hit[MAX_STRETCHES][2];
    long cyc[MAX_STRETCHES][2];
    double job_cpu[MAX_STRETCHES][2];
    char why[MAX_STRETCHES][2][512]; /* a worker thread's message is its own */
};

/* The budget, the stretches and whether the run's setting runs beside the tight one. */
static void plan_stretches(tt_scan_estimate *E)
{
    tt_scan *S = E->S;
    const tt_raster *R = &S->raster;
    const long px = R->pixels;
    /* Lines that do not carry on from one another are each a function of the line alone
     * (the noise keyed by line, the envelope model forgotten): the image's own line is
     * what the run's setting gives, and only the tight line runs. Continuous lines start
     * where the last one ended, so the run's setting runs again beside it, from the
     * same engage, on half the budget each. */
    int whole_rerun = S->continuous || tt_scan_averaged_usable(S, &S->solver);
    for (int c = 0; c < 3; c++) /* and where the scan holds no channel it compares */
        for (int r = 0; r < E->dirs; r++)
            whole_rerun |= !S->img[r][c]; /* (tt_scan_kept_channels) */
    int rerun = whole_rerun;
    const long nc = tt_raster_cycles_per_direction(R, S->cantilever.T);
    const long settle = (S->settle_cycles + S->lockin.periods_per_block - 1) /
                        S->lockin.periods_per_block * S->lockin.periods_per_block;
    long budget = companion_budget(S, &E->tight);
    /* A stretch inside the line engages there, not where the image's line reached it
     * from the line's start (its noise counted from another cycle, its feedback fresh):
     * the run's setting runs the same stretch beside it, each on half the budget. The
     * trace's pixels the budget reaches, less the one it stops in: */
    if (budget > 0 && stretch_reach(budget, settle, nc, px) < px)
        rerun = 1;
    if (rerun)
        budget /= 2;
    long reach = budget > 0 ? stretch_reach(budget, settle, nc, px) : 2 * px;
    int ns = hardest_stretches(S, reach, nc, E->st, &E->step);
    /* each stretch its share of the budget, settling included */
    if (budget > 0 && ns > 1) {
        budget /= ns;
        reach = stretch_reach(budget, settle, nc, px);
        ns = hardest_stretches(S, reach, nc, E->st, &E->step);
    }
    if (budget > 0 && reach < 2) {
        /* a scan of a line or two: the fifth does not reach past each stretch's
         * settling, and the whole hardest line runs (e->cycles says what it cost) */
        budget = 0;
        reach = 2 * px;
        E->over = 1; /* and says so */
        /* a whole line engages where the image's did: independent lines compare with
         * the image's own, not a rerun (half the cost: a 4-line noisy envelope scan of
         * the steps ran 156,000 companion cycles, 3.5 of 4.7 s CPU) */
        rerun = whole_rerun;
        ns = hardest_stretches(S, reach, nc, E->st, &E->step);
    }
    E->ns = ns;
    E->rerun = rerun;
    E->budget = budget;
}

int tt_scan_estimate_plan(tt_scan *S, tt_scan_estimate **out)
{
    *out = NULL;
    const double c0 = tt_clock(TT_CLOCK_PROCESS);
    tt_scan_estimate *E = calloc(1, sizeof *E);
    const long px = S->raster.pixels;
    double *buf = calloc((size_t)(12 * px * MAX_STRETCHES), sizeof *buf);
    if (!E || !buf) {
        free(E);
        free(buf);
        return tt_error_nomem("the companion line's profile");
    }
    *E = (tt_scan_estimate){.S = S, .dirs = S->raster.retrace ? 2 : 1, .buf = buf,
                            .tight = tt_companion_solver(&S->solver)};
    /* the averaged tier's error is its model's, which no tolerance moves: its companion
     * is the envelope tier at the run's tolerance (as accurate as every cycle) */
    if (tt_scan_averaged_usable(S, &S->solver)) {
        E->tight = S->solver;
        E->tight.tier = TT_TIER_ENVELOPE;
        int rc = tt_scan_averaged_tables(S);
        if (rc) {
            tt_scan_estimate_free(E);
            return rc;
        }
    }
    plan_stretches(E);
    /* without a rerun the run's setting is the image's own line */
    for (int s = 0; s < E->ns && !E->rerun; s++)
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < E->dirs; r++)
                for (long i = 0; i < px; i++)
                    buf[(size_t)(12 * s + 2 * c + r) * (size_t)px + (size_t)i] =
                        S->img[r][c][tt_raster_index(&S->raster, E->st[s].line, i)];
    E->cpu = tt_clock(TT_CLOCK_PROCESS) - c0;
    *out = E;
    return TT_OK;
}

int tt_scan_estimate_jobs(const tt_scan_estimate *E)
{
    return E->ns * (E->rerun ? 2 : 1);
}

/* Job j: the tight lines first (each stretch's, the costlier), then the run's setting's
 * beside them; any thread, each j once. */
int tt_scan_estimate_job(tt_scan_estimate *E, int j)
{
    const int s = j % E->ns, k = j < E->ns;
    tt_scan *S = E->S;
    const long px = S->raster.pixels;
    const double c0 = tt_clock(TT_CLOCK_THREAD);
    /* the stretch's first cycle: the first whole cycle of its first pixel */
    const long nc = tt_raster_cycles_per_direction(&S->raster, S->cantilever.T);
    const long k0 = (E->st[s].first * nc + px - 1) / px;
    int rc = companion_line(S, k ? &E->tight : &S->solver, E->st[s].line, E->budget, k0,
                            E->buf + (size_t)((12 * s + 6 * k) * px), &E->hit[s][k], &E->cyc[s][k]);
    snprintf(E->why[s][k], sizeof E->why[s][k], "%s", rc ? tt_error_message() : "");
    E->rc[s][k] = rc;
    E->job_cpu[s][k] = tt_clock(TT_CLOCK_THREAD) - c0;
    return rc;
}

void tt_scan_estimate_free(tt_scan_estimate *E)
{
    if (E)
        free(E->buf);
    free(E);
}

int tt_scan_estimate_finish(tt_scan_estimate *E, tt_scan_error *e)
{
    memset(e, 0, sizeof *e);
    tt_scan *S = E->S;
    double max[3] = {0}, sum[3] = {0}, cpu = E->cpu;
    long n = 0, ran = 0;
    /* the first failure in the stretches' order, the run's setting's before the tight */
    for (int s = 0; s < E->ns; s++)
        for (int k = 0; k < 2; k++)
            if (E->rc[s][k]) {
                int rc = tt_error(E->rc[s][k], "the companion line at tolerance %g: %s",
                                  k ? E->tight.tolerance : S->solver.tolerance, E->why[s][k]);
                tt_scan_estimate_free(E);
                return rc;
            }
    for (int s = 0; s < E->ns; s++) {
        compare(S, E->buf + (size_t)(12 * s) * (size_t)S->raster.pixels, E->st[s].first, E->dirs,
                E->hit[s][0] || E->hit[s][1], E->rerun, max, sum, &n);
        ran += E->cyc[s][0] + E->cyc[s][1];
        cpu += E->job_cpu[s][0] + E->job_cpu[s][1];
    }
    if (n == 0) {
        tt_scan_estimate_free(E);
        return tt_error(TT_EINVAL, "the companion line compared no pixel");
    }
    /* the difference stands for the run's error to within a tenth; twice it covers that
     * and the other lines, which the companion did not run */
    e->height_max = 2 * max[0];
    e->height_rms = 2 * sqrt(sum[0] / (double)n);
    e->amplitude_max = 2 * max[1];
    e->amplitude_rms = 2 * sqrt(sum[1] / (double)n);
    e->phase_max = 2 * max[2];
    e->phase_rms = 2 * sqrt(sum[2] / (double)n);
    e->line = E->st[0].line;
    e->tolerance = E->tight.tolerance;
    e->pixels = n;
    e->pixels_line = E->dirs * S->raster.pixels;
    e->step = E->step;
    e->first = E->st[0].first;
    e->stretches = E->ns;
    e->over = E->over;
    e->cycles = ran;
    e->seconds = cpu;
    tt_scan_estimate_free(E);
    return TT_OK;
}

int tt_scan_estimate_error(tt_scan *S, tt_scan_error *e)
{
    tt_scan_estimate *E;
    int rc = tt_scan_estimate_plan(S, &E);
    if (rc)
        return rc;
    const int n = tt_scan_estimate_jobs(E);
#pragma omp parallel for num_threads(2) schedule(dynamic, 1) if (n > 1)
    for (int j = 0; j < n; j++)
        tt_scan_estimate_job(E, j);
    return tt_scan_estimate_finish(E, e);
}
