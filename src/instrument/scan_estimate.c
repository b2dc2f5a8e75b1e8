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
 * retrace into buf (6 blocks of pixels: [channel][direction]), stopped at budget (0:
 * none) of its work (of its cycles where in_cycles is set); *hit says it stopped there,
 * *ran and *work count its cycles and work. */
static int companion_line(tt_scan *S, const tt_solver *solver, long line, long budget,
                          int in_cycles, long k0, double *buf, int *hit, long *ran, long *work)
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
    W.budget_cycles = in_cycles;
    W.k0 = k0;
    if (!rc)
        rc = tt_scan_worker_line(S, &W, line, &out, NULL, &t);
    *hit = W.budget_hit;
    *ran = t.cycles;
    *work = t.work;
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

/* What the tight setting's cycles cost against the scan's own, on average: 1.4 to 2.6
 * times after settling on the viscoelastic blend and the steps, with noise and without
 * (its model, held ten times tighter, integrates more of the cycles, each in 2.5 times
 * the steps), and 1.9 to 3 times, more on the bench's edge sample, in settling, where
 * most cycles are integrated. They place the stretches; the budget itself stops each
 * line at its work. */
#define TIGHT_COST 2.5
#define TIGHT_SETTLE 4

/* The predicted work of a companion line, [0] at the run's setting and [1] at the
 * tight one: settle of its settling (7 to 13 % of a line's work on the blends and the
 * steps), cycle a cycle after it. */
typedef struct {
    double settle[2], cycle[2];
} line_cost;

/* The companion's budget: a fifth of the scan's work (tt_scan_line_work), and in *c
 * what its lines will cost. The averaged tier's slow flow takes no steps: there the
 * budget is a fifth of the cycles the scan integrated, over the tight setting's cost
 * per cycle, each of the companion's cycles counting one (*in_cycles); 0 (no bound)
 * where it integrated none. */
static long companion_budget(const tt_scan *S, const tt_solver *tight, long settle, line_cost *c,
                             int *in_cycles)
{
    *in_cycles = tt_scan_averaged_usable(S, &S->solver);
    if (*in_cycles) {
        double per = S->solver.method == TT_METHOD_RK4
                         ? (double)tight->steps_per_cycle / (double)S->solver.steps_per_cycle
                         : pow(S->solver.tolerance / tight->tolerance, 0.2);
        if (!(per >= 1) || tt_scan_envelope_usable(S, &S->solver))
            per = 1;
        *c = (line_cost){{(double)settle, (double)settle}, {1, 1}};
        return S->integrated > 0 ? (long)(TT_ESTIMATE_SHARE * (double)S->integrated / per) : 0;
    }
    const double lines = S->lines_done > 0 ? (double)S->lines_done : 1;
    const double after = (double)S->cycles - lines * (double)settle;
    const double sw = (double)S->settle_work / lines;
    const double cw = after > 0 ? (double)(S->work - S->settle_work) / after : 1;
    *c = (line_cost){{sw, TIGHT_SETTLE * sw}, {cw, TIGHT_COST * cw}};
    return (long)(TT_ESTIMATE_SHARE * (double)S->work);
}

/* Where the image is hardest: the largest height step between neighbouring pixels of
 * the trace (of trace and retrace when the companion covers whole lines, reach >= the
 * pixels), its line and pixel. The profile line from its start where no line has a
 * step (a flat image, or no height channel). */
static long hardest_line(const tt_scan *S, long reach, const char *taken, double *step, long *at)
{
    const tt_raster *R = &S->raster;
    const int dirs = reach >= R->pixels && R->retrace ? 2 : 1;
    long best = S->profile_line;
    double top = 0;
    *at = 0;
    for (long l = 0; l < R->lines; l++) {
        if (!S->line_done[l] || (taken && taken[l]))
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
 * the start of its line, and the first edge of each ordered pair of materials met along
 * the trace (from the soft sticky matrix onto a stiff disk the every-cycle tier at 1e-7
 * erred 0.19 pm where the largest height step, on the disk, erred 0.04 pm: the bench's
 * edge sample), each as far as no stretch already holds it; at most MAX_STRETCHES. */
static int hardest_stretches(const tt_scan *S, long reach, long nc, stretch *st, double *step)
{
    const tt_raster *R = &S->raster;
    *step = 0;
    st[0] = (stretch){S->profile_line, 0, 0};
    if (S->lines_done > 0)
        st[0].line = hardest_line(S, reach, NULL, step, &st[0].at);
    int n = 1, seen[MAX_STRETCHES][2];
    /* and the line's start, where it engaged: the settling's error is the image's
     * largest on a line or two (the README's main job, 2 lines: 0.277 pm, against 0.03
     * pm at its disks' edges); independent lines compare it with the image's own */
    if (reach < R->pixels && !S->continuous && first_pixel(st[0].at, reach, R->pixels) > 0) {
        seen[n][0] = seen[n][1] = -1;
        st[n++] = (stretch){st[0].line, 0, 0};
    }
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

/* The cycles past settling a stretch holds on b of work, the run's setting running
 * beside the tight line (rr) or not. */
static double stretch_cycles(const line_cost *c, double b, int rr)
{
    return (b - c->settle[1] - (rr ? c->settle[0] : 0)) / (c->cycle[1] + (rr ? c->cycle[0] : 0));
}

/* The trace's pixels it reaches, less the one it stops in. */
static long reach_on(const line_cost *c, long b, int rr, long settle, long nc, long px)
{
    return stretch_reach(settle + (long)stretch_cycles(c, (double)b, rr), settle, nc, px);
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

/* The cycles a line settles: whole lock-in blocks. */
static long settle_cycles(const tt_scan *S)
{
    const long P = S->lockin.periods_per_block;
    return (S->settle_cycles + P - 1) / P * P;
}

/* The companion's plan (tt_scan_estimate_plan): its stretches, and per stretch the two
 * lines' profiles in buf (12 blocks of px each: the run's setting, then the tight
 * one's), whether the run's setting runs beside the tight one, each job's budget,
 * status, cycles, work and thread CPU ([stretch][0: the run's setting, 1: tight]). */
struct tt_scan_estimate {
    tt_scan *S;
    tt_solver tight;
    int dirs, over, ns, in_cycles, noisy; /* noisy: whole lines (plan_noisy) */
    long budget_all; /* the fifth of the scan's work (0: counted in cycles, or none) */
    double step, cpu; /* cpu: the plan's own (the averaged tier's tables) */
    double signal;    /* with noise: the first line's largest error signal, m */
    stretch st[MAX_STRETCHES];
    int rerun[MAX_STRETCHES];
    long budget[MAX_STRETCHES][2];
    double *buf;
    int rc[MAX_STRETCHES][2], hit[MAX_STRETCHES][2];
    long cyc[MAX_STRETCHES][2], work[MAX_STRETCHES][2];
    double job_cpu[MAX_STRETCHES][2];
    char why[MAX_STRETCHES][2][512]; /* a worker thread's message is its own */
};

/* A line's largest excursion of the error signal (the lock-in amplitude from the
 * setpoint), trace and retrace; -1 where the scan holds no error channel. */
static double line_signal(const tt_scan *S, long l)
{
    const tt_raster *R = &S->raster;
    double top = -1;
    for (int r = 0; r < (R->retrace ? 2 : 1) && S->img[r][1]; r++)
        for (long i = 0; i < R->pixels; i++) {
            double a = fabs(S->img[r][1][tt_raster_index(R, l, i)]);
            top = a > top ? a : top;
        }
    return top;
}

/* The n hardest lines with noise, whole (n within 1 and MAX_STRETCHES): those where
 * the error signal strays furthest, else (no error channel) the largest height steps'.
 * With noise the height steps do not tell where the loop erred: on eight noisy scans of
 * the blend and the steps the line of the largest step erred 0.18 to 1 times the worst
 * line's largest height error (0.62 on average), the line of the largest error signal
 * 0.48 to 1 times (0.88); the phase 0.10 and 0.19 at the least. */
static int hardest_lines(tt_scan_estimate *E, long n)
{
    tt_scan *S = E->S;
    const long lines = S->raster.lines;
    n = n < 1 ? 1 : n > MAX_STRETCHES ? MAX_STRETCHES : n;
    if (n > S->lines_done)
        n = S->lines_done > 0 ? S->lines_done : 1;
    char *taken = calloc((size_t)lines, 1);
    double *sig = malloc((size_t)lines * sizeof *sig);
    for (long l = 0; l < lines && sig; l++)
        sig[l] = S->line_done[l] ? line_signal(S, l) : -1;
    E->step = E->signal = 0;
    for (int k = 0; k < n; k++) {
        double step = 0, best = -1;
        long at;
        E->st[k] = (stretch){S->profile_line, 0, 0};
        for (long l = 0; l < lines && taken && sig; l++)
            if (!taken[l] && sig[l] > best) {
                best = sig[l];
                E->st[k].line = l;
            }
        if (best < 0 && S->lines_done > 0 && taken)
            E->st[k].line = hardest_line(S, 2 * S->raster.pixels, taken, &step, &at);
        if (k == 0) {
            E->step = step;
            E->signal = best > 0 ? best : 0;
        }
        if (taken)
            taken[E->st[k].line] = 1;
    }
    free(taken);
    free(sig);
    return (int)n;
}

/* Each stretch's jobs and budgets: the run's setting beside the tight line where the
 * stretch does not start where the image's line did (rerun, or a stretch inside the
 * line), their share of the stretch's budget b as their predicted costs (c). */
static void stretch_budgets(tt_scan_estimate *E, int rerun, int whole_rerun, long b,
                            const line_cost *c)
{
    for (int s = 0; s < E->ns; s++) {
        E->rerun[s] = rerun && (whole_rerun || E->st[s].first > 0);
        const double tight = b > 0 ? c->settle[1] + stretch_cycles(c, (double)b, 1) * c->cycle[1] : 0;
        E->budget[s][1] = E->rerun[s] ? (long)tight : b;
        E->budget[s][0] = E->rerun[s] ? (long)((double)b - tight) : 0;
    }
}

/* Lines that do not carry on from one another are each a function of the line alone
 * (the noise keyed by line, the envelope model forgotten): the image's own line is what
 * the run's setting gives, and only the tight line runs. Continuous lines start where
 * the last one ended, so the run's setting runs again beside it, from the same engage;
 * 1: the run's setting runs whole lines again. */
static int rerun_whole(const tt_scan_estimate *E)
{
    const tt_scan *S = E->S;
    int rerun = S->continuous || tt_scan_averaged_usable(S, &S->solver);
    for (int c = 0; c < 3; c++) /* and where the scan holds no channel it compares */
        for (int r = 0; r < E->dirs; r++)
            rerun |= !S->img[r][c]; /* (tt_scan_kept_channels) */
    return rerun;
}

/* The whole hardest line, over the share (and saying so): a whole line engages where the
 * image's did, so independent lines compare with the image's own, not a rerun (half the
 * cost: a 4-line noisy envelope scan of the steps ran 156,000 companion cycles, 3.5 of
 * 4.7 s CPU). */
static void plan_whole(tt_scan_estimate *E, int whole_rerun)
{
    const tt_scan *S = E->S;
    const long nc = tt_raster_cycles_per_direction(&S->raster, S->cantilever.T);
    E->over = 1;
    E->ns = hardest_stretches(S, 2 * S->raster.pixels, nc, E->st, &E->step);
    stretch_budgets(E, whole_rerun, whole_rerun, 0, NULL);
}

/* With noise that moves the state, on the envelope tier, lines from their start: a
 * stretch engaged inside the line reads low there (the blend at 300 K, 8 lines of 32
 * pixels: 5.4e-13 m against 3.05e-12 m measured; its model's store is fresh), and the
 * largest errors of lines alike differ up to fourfold with their noise (the 16 noisy
 * lines of the blend: 0.47 to 2.1 pm), so the fifth runs as many of the hardest lines
 * whole as it holds (at most MAX_STRETCHES), or the hardest over the fifth. Part of a
 * line from its start reads low too (the blend's 8 noisy lines: the trace's first 64
 * pixels 1.3 pm against 9.75 pm measured; the whole line 5.4 pm): the errors gather
 * along the line. */
static void plan_noisy(tt_scan_estimate *E, long budget, const line_cost *c, int whole_rerun)
{
    const tt_scan *S = E->S;
    const long nc = tt_raster_cycles_per_direction(&S->raster, S->cantilever.T);
    const double whole = c->settle[1] + (double)(2 * nc) * c->cycle[1] +
                         (whole_rerun ? c->settle[0] + (double)(2 * nc) * c->cycle[0] : 0);
    const long n = budget > 0 ? (long)((double)budget / whole) : 1;
    E->over = n < 1; /* the hardest line whole, over the fifth, and saying so */
    /* unbounded: a line its budget cut reads its trace alone */
    E->ns = hardest_lines(E, n);
    stretch_budgets(E, whole_rerun, whole_rerun, 0, NULL);
}

/* The budget, the stretches and whether the run's setting runs beside the tight one. */
static void plan_stretches(tt_scan_estimate *E)
{
    tt_scan *S = E->S;
    const tt_raster *R = &S->raster;
    const long px = R->pixels;
    const int whole_rerun = rerun_whole(E);
    int rerun = whole_rerun;
    const long nc = tt_raster_cycles_per_direction(R, S->cantilever.T);
    const long settle = settle_cycles(S);
    line_cost c;
    long budget = companion_budget(S, &E->tight, settle, &c, &E->in_cycles);
    E->budget_all = E->in_cycles ? 0 : budget;
    E->noisy = !E->in_cycles && tt_scan_second_order(S) && tt_scan_envelope_usable(S, &S->solver);
    if (E->noisy) {
        plan_noisy(E, budget, &c, whole_rerun);
        return;
    }
    /* A stretch inside the line engages there, not where the image's line reached it
     * from the line's start (its noise counted from another cycle, its feedback fresh):
     * the run's setting runs the same stretch beside it. The trace's pixels the budget
     * reaches, less the one it stops in: */
    if (budget > 0 && reach_on(&c, budget, whole_rerun, settle, nc, px) < px)
        rerun = 1;
    long reach = budget > 0 ? reach_on(&c, budget, rerun, settle, nc, px) : 2 * px;
    int ns = hardest_stretches(S, reach, nc, E->st, &E->step);
    /* each stretch its share of the budget, settling included */
    if (budget > 0 && ns > 1) {
        budget /= ns;
        reach = reach_on(&c, budget, rerun, settle, nc, px);
        ns = hardest_stretches(S, reach, nc, E->st, &E->step);
    }
    if (budget > 0 && reach < 2) {
        /* a scan of a line or two: the fifth does not reach past each stretch's
         * settling, and the whole hardest line runs (e->work says what it cost) */
        plan_whole(E, whole_rerun);
        return;
    }
    E->ns = ns;
    stretch_budgets(E, rerun, whole_rerun, budget, &c);
}

/* Without a rerun the run's setting is the image's own line. */
static void image_lines(tt_scan_estimate *E)
{
    const tt_scan *S = E->S;
    const long px = S->raster.pixels;
    for (int s = 0; s < E->ns; s++)
        for (int c = 0; c < 3 && !E->rerun[s]; c++)
            for (int r = 0; r < E->dirs; r++)
                for (long i = 0; i < px; i++)
                    E->buf[(size_t)(12 * s + 2 * c + r) * (size_t)px + (size_t)i] =
                        S->img[r][c][tt_raster_index(&S->raster, E->st[s].line, i)];
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
    image_lines(E);
    E->cpu = tt_clock(TT_CLOCK_PROCESS) - c0;
    *out = E;
    return TT_OK;
}

int tt_scan_estimate_jobs(const tt_scan_estimate *E)
{
    int n = E->ns;
    for (int s = 0; s < E->ns; s++)
        n += E->rerun[s];
    return n;
}

/* The i-th stretch the run's setting runs beside the tight line. */
static int rerun_stretch(const tt_scan_estimate *E, int i)
{
    for (int s = 0; s < E->ns; s++)
        if (E->rerun[s] && i-- == 0)
            return s;
    return 0;
}

/* Job j: the tight lines first (each stretch's, the costlier), then the run's setting's
 * beside those that need it; any thread, each j once. */
int tt_scan_estimate_job(tt_scan_estimate *E, int j)
{
    const int k = j < E->ns, s = k ? j : rerun_stretch(E, j - E->ns);
    tt_scan *S = E->S;
    const long px = S->raster.pixels;
    const double c0 = tt_clock(TT_CLOCK_THREAD);
    /* the stretch's first cycle: the first whole cycle of its first pixel */
    const long nc = tt_raster_cycles_per_direction(&S->raster, S->cantilever.T);
    const long k0 = (E->st[s].first * nc + px - 1) / px;
    int rc = companion_line(S, k ? &E->tight : &S->solver, E->st[s].line, E->budget[s][k],
                            E->in_cycles, k0, E->buf + (size_t)((12 * s + 6 * k) * px),
                            &E->hit[s][k], &E->cyc[s][k], &E->work[s][k]);
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

/* The first failure of the jobs in the stretches' order, the run's setting's before the
 * tight (TT_OK: none). */
static int job_failure(const tt_scan_estimate *E)
{
    for (int s = 0; s < E->ns; s++)
        for (int k = 0; k < 2; k++)
            if (E->rc[s][k])
                return tt_error(E->rc[s][k], "the companion line at tolerance %g: %s",
                                k ? E->tight.tolerance : E->S->solver.tolerance, E->why[s][k]);
    return TT_OK;
}

/* The stretches' differences into max and sum, what they ran into ran, work and cpu;
 * the pixels compared. */
static long compare_all(const tt_scan_estimate *E, double *max, double *sum, long *ran, long *work,
                        double *cpu)
{
    long n = 0;
    for (int s = 0; s < E->ns; s++) {
        compare(E->S, E->buf + (size_t)(12 * s) * (size_t)E->S->raster.pixels, E->st[s].first,
                E->dirs, E->hit[s][0] || E->hit[s][1], E->rerun[s], max, sum, &n);
        *ran += E->cyc[s][0] + E->cyc[s][1];
        *work += E->work[s][0] + E->work[s][1];
        *cpu += E->job_cpu[s][0] + E->job_cpu[s][1];
    }
    return n;
}

int tt_scan_estimate_finish(tt_scan_estimate *E, tt_scan_error *e)
{
    memset(e, 0, sizeof *e);
    tt_scan *S = E->S;
    double max[3] = {0}, sum[3] = {0}, cpu = E->cpu;
    long ran = 0, work = 0;
    int rc = job_failure(E);
    long n = rc ? 0 : compare_all(E, max, sum, &ran, &work, &cpu);
    if (!rc && n == 0 && !E->over) {
        /* every stretch stopped before its first pixel, its settling at the tight setting
         * dearer than predicted: the whole hardest line runs here, over the share */
        plan_whole(E, rerun_whole(E));
        image_lines(E);
        for (int j = 0; j < tt_scan_estimate_jobs(E) && !rc; j++)
            rc = tt_scan_estimate_job(E, j);
        rc = rc ? job_failure(E) : TT_OK;
        n = rc ? 0 : compare_all(E, max, sum, &ran, &work, &cpu);
    }
    if (rc || n == 0) {
        tt_scan_estimate_free(E);
        return rc ? rc : tt_error(TT_EINVAL, "the companion line compared no pixel");
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
    e->signal = E->signal;
    e->first = E->st[0].first;
    e->stretches = E->ns;
    e->over = E->over;
    e->cycles = ran;
    e->work = work;
    e->budget = E->budget_all;
    e->scan_work = S->work;
    e->lines = E->noisy ? E->ns : 0;
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
