/* One scan line on the averaged preview tier (docs/dynamics.md, Tiers, Averaged): each
 * lock-in block is one step of the averaged slow flow (tiptap/solver/averaged.h) with
 * the sample at the block's mean position, and its periods reach the lock-in as
 * components, so the lock-in, the feedback, the piezo and the pixels' sums are the
 * other tiers' code. Where the slow flow fails (an impact, a ringing loop's swing) the
 * blocks are integrated cycle by cycle and the slow flow re-enters from the integrated
 * state once it follows it again. The surface is looked up once a block (at its first
 * cycle), linear between blocks. Where the slow flow runs with the tip collapsed onto
 * the sample or leaves the table, the pixel is marked (tt_scan_averaged_collapsed). Noise
 * (docs/dynamics.md, "Noise on the averaged tier"): the thermal force as an impulse on
 * each step of the slow flow and at each integrated cycle's end, the detector's on the
 * block's components, the z piezo's on the sample's position per cycle, all drawn from
 * (seed, line, cycle). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scan_private.h"
#include "tiptap/solver/noise.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

typedef struct {
    tt_averaged_state st;
    char *mark; /* [direction][pixel]: 1 collapsed, 2 outside the table */
    double *s;  /* the sample's position in each cycle of a block */
    double *y;  /* an integrated cycle's deflection samples */
    double *rn; /* per lock-in component, its row's norm over a period (detector_noise) */
    int on;     /* the blocks are integrated (the slow flow failed) */
    int trusted; /* the slow flow took over from an integration it matched, and has
                  * moved fast since */
    long integrated;
} avg_line;

/* The averaged tier books the loss as a whole (its force's first harmonic): the
 * channels per mechanism are NaN on it. */
static void no_losses(pixel_acc *a)
{
    for (int i = 0; i < 3; i++)
        a->sum[TT_CH_LOSS_INDEX + i] = NAN;
}

/* The per-cycle channels of cycles k0 .. k0 + n - 1 into their pixels' sums: za0 and
 * dz the height command's first value and step; the topography and the dilation linear
 * from the surface at the block's start a to its end b. */
static void cycle_sums(const line_ctx *L, long k0, int n, double za0, double dz, const surf_pt *sa,
                       const surf_pt *sb, const tt_averaged_out *o)
{
    const double t0 = sa->topo, dt = (sb->topo - sa->topo) / n, d0 = sa->dil,
                 dd = (sb->dil - sa->dil) / n;
    const tt_raster *R = &L->S->raster;
    pixel_acc *pix = L->pix + (size_t)L->dir * (size_t)R->pixels;
    long p0 = tt_raster_pixel(R, L->dir, L->nc, k0), p1 = tt_raster_pixel(R, L->dir, L->nc, k0 + n - 1);
    if (p0 == p1) {
        pixel_acc *a = &pix[p0];
        double tri = 0.5 * n * (n - 1);
        a->sum[0] += n * za0 + dz * tri;
        a->sum[3] += n * o->peak;
        a->sum[4] += n * o->indent;
        a->sum[5] += n * o->ets;
        a->sum[6] += n * t0 + dt * tri;
        a->sum[TT_CH_DILATION_INDEX] += n * d0 + dd * tri;
        a->n += n;
        no_losses(a);
        return;
    }
    for (int j = 0; j < n; j++) {
        pixel_acc *a = &pix[tt_raster_pixel(R, L->dir, L->nc, k0 + j)];
        a->sum[0] += za0 + dz * j;
        a->sum[3] += o->peak;
        a->sum[4] += o->indent;
        a->sum[5] += o->ets;
        a->sum[6] += t0 + dt * j;
        a->sum[TT_CH_DILATION_INDEX] += d0 + dd * j;
        a->n++;
        no_losses(a);
    }
}

/* The sample's position (rest separation) over each of the block's n cycles, its
 * mean returned: the z piezo's actual height advanced through them (with its noise at
 * the cycle's middle, the every-cycle tier's draws), the surface linear from a to b. */
static double block_sample(const line_ctx *L, line_state *st, const surf_pt *a, const surf_pt *b,
                           int n, double *s)
{
    const tt_noise_ou *zn = &L->S->zn;
    const double P = L->P, dz = (st->z_to - st->z_from) / P, z0 = st->z_from + dz * (double)(st->k % L->P);
    double mean = 0;
    for (int j = 0; j < n; j++) {
        double z = z0 + dz * (j + 0.5);
        if (L->piezo) {
            double pa = st->z_act;
            st->z_act = tt_piezo_advance(&st->pz, z0 + dz * (j + 1), L->S->cantilever.T);
            z = 0.5 * (pa + st->z_act);
        }
        s[j] = L->s_ref - (a->h + (b->h - a->h) * (j + 0.5) / n) + z;
        if (zn->sd > 0) {
            double za = st->zn;
            st->zn = tt_noise_ou_next(zn, L->kz, (uint64_t)(st->cycles + j) + 1, st->zn);
            s[j] += 0.5 * (za + st->zn);
        }
        mean += s[j];
    }
    return mean / n;
}

/* One step of the slow flow over h from the line's cycle `cycle` on, with the thermal
 * force's impulse there when the noise is on (sig: its density, 0 off). */
static void flow_step(const line_ctx *L, avg_line *t, const tt_averaged *tab, double s, double h,
                      double sig, long cycle, tt_averaged_out *o)
{
    if (!(sig > 0)) {
        tt_averaged_step(tab, &t->st, s, h, o);
        return;
    }
    double g[2];
    tt_noise_pair(L->ke, (uint64_t)cycle, g);
    const double kick[2] = {sig * sqrt(h) * g[0], sig * sqrt(h) * g[1]};
    tt_averaged_step_noisy(tab, &t->st, s, h, kick, o);
}

/* The slow flow through the block: one step, or where it changed the state by more
 * than SUB_TOL of the free amplitude (an edge, a transient), one step a cycle from
 * the block's start again; each cycle's components into the block's periods. cycle:
 * the line's count at the block's start (the noise's index). A step that changed it by
 * more than fail (the block is then integrated instead: block) returns at once. */
#define SUB_TOL 1e-3
static double block_flow(const line_ctx *L, avg_line *t, const tt_averaged *tab, long k0, int n,
                         const double *s, double smean, long cycle, double fail, tt_averaged_out *o)
{
    worker *W = L->W;
    const int nc = tt_lockin_components(W->lockin);
    const double T = L->S->cantilever.T;
    const double sig = tt_averaged_thermal_density(&L->S->cantilever, L->S->noise.temperature);
    tt_averaged_state start = t->st;
    flow_step(L, t, tab, smean, n * T, sig, cycle, o);
    const double change = o->change;
    if (change > fail)
        return change;
    if (o->change > SUB_TOL && n > 1) {
        t->st = start;
        tt_averaged_out c, sum;
        memset(&sum, 0, sizeof sum);
        for (int j = 0; j < n; j++) {
            flow_step(L, t, tab, s[j], T, sig, cycle + j, &c);
            for (int q = 0; q < nc; q++)
                W->y[(size_t)((k0 + j) % L->P) * (size_t)nc + (size_t)q] = c.comp[q];
            sum.peak += c.peak / n;
            sum.indent += c.indent / n;
            sum.ets += c.ets / n;
            sum.collapsed |= c.collapsed;
            sum.outside |= c.outside;
        }
        *o = sum;
        return change;
    }
    for (int j = 0; j < n; j++)
        for (int q = 0; q < nc; q++)
            W->y[(size_t)((k0 + j) % L->P) * (size_t)nc + (size_t)q] = o->comp[q];
    return change;
}

/* Per lock-in component, the norm of its row over one period's N samples divided by
 * the root of the periods a block, sqrt(sum R^2 / P): detector_noise's scale, the same
 * for every block, so taken once a line (rn: nc values). */
static void detector_norms(const tt_scan *S, const worker *W, double *rn)
{
    const int nc = tt_lockin_components(W->lockin), N = S->lockin.samples_per_period,
              P = S->lockin.periods_per_block;
    const double *R = tt_lockin_component_matrix(W->lockin);
    for (int q = 0; q < nc; q++) {
        double r2 = 0;
        for (int i = 0; i < N; i++)
            r2 += R[(size_t)q * (size_t)N + (size_t)i] * R[(size_t)q * (size_t)N + (size_t)i];
        rn[q] = sqrt(r2 / P);
    }
}

/* The detector's white noise on the block's components (the lock-in's mean of its
 * periods, so drawn once a block): per component the samples' rms times the norm of
 * the lock-in's row over the block's N P samples (detector_norms), spread over the n
 * periods written; cycle: the line's count at the block's start (the draws' index). */
static void detector_noise(const line_ctx *L, const avg_line *t, long k0, int n, long cycle)
{
    const double sd = L->S->sd;
    if (!(sd > 0))
        return;
    worker *W = L->W;
    const int nc = tt_lockin_components(W->lockin);
    for (int q = 0; q < nc; q++) {
        const double v = sd * t->rn[q] * tt_noise_gauss(L->kd, (uint64_t)cycle * (uint64_t)nc + (uint64_t)q);
        for (int j = 0; j < n; j++)
            W->y[(size_t)((k0 + j) % L->P) * (size_t)nc + (size_t)q] += v * L->P / n;
    }
}

/* Where the slow flow fails (docs/dynamics.md, Averaged, "Where the slow flow fails"):
 * a block whose slow step moves X or Y by more than ENTER_TOL of A0, or that
 * tt_averaged_step resolved as an impact (its halvings report a change of IMPACT), is
 * integrated instead, cycle by cycle on the worker's sim from the slow state, and so
 * are the blocks after it until the slow flow, run from an integrated block's start,
 * lands within EXIT_TOL of A0 of where the integration did. The slow flow so checked is
 * trusted while it keeps moving fast (the loop pulling the tip off a wall), until a
 * block moves less than ENTER_TOL; an impact is integrated whatever the trust. */
#define ENTER_TOL 0.03
#define EXIT_TOL 0.005
#define IMPACT 0.1
/* An integrated block whose last two cycles' fundamentals differ by more than JUMP_TOL
 * of A0 is taken as not periodic (a tip bouncing on the sample: its phase turns by
 * radians a cycle) and its slow flow is not tried: where the lesson's seven settings
 * left the integration (five lines each) they differed by 0.23 A0 at most (ki 100 Hz,
 * the amplitude falling at a wall; 0.05 at most at the others), and by over 0.3 on 63
 * % of the blocks that stayed at ki 30 kHz, 69 % at 40 Hz lines (a trial cost a sixth
 * to a quarter of an integrated cycle there, its step halved through the impact). */
#define JUMP_TOL 0.3

/* The integration's tolerance: LOOSE times the scan's (1e-6 of A0 a step at the
 * default; rk4 keeps its steps): at 1e3 times the lesson's ki 4 kHz erred 1.9 nm
 * against 0.31 nm at 1e2, the speed alike (docs/live.md). */
#define LOOSE 1e2
tt_solver tt_scan_averaged_solver(const tt_solver *s)
{
    tt_solver o = *s;
    o.tolerance = fmin(s->tolerance * LOOSE, 1e-3);
    return o;
}

/* Whether the lock-in keeps the fundamental alone: an integrated cycle's components are
 * then its own Fourier integrals (tt_cycle), and the sim takes no samples. */
static int fundamental_only(const line_ctx *L)
{
    return tt_lockin_components(L->W->lockin) == 3 && !(L->S->lockin.ratio2 > 0);
}

/* The sim at the slow state, at a cycle's start (the drive's phase 0): the tip at
 * m0 + X plus the base, its velocity w Y (the base at rest there); the law's own
 * states as the sim last left them. */
static void enter(const line_ctx *L, avg_line *t)
{
    tt_sim *sim = L->W->sim;
    const tt_cantilever *c = &L->S->cantilever;
    double x[TT_SIM_DIM_MAX];
    int contact;
    tt_sim_get_x(sim, x, &contact);
    x[0] = (c->drive == TT_DRIVE_BASE ? c->a_d : 0) + t->st.m0 + t->st.X;
    x[1] = c->wd * t->st.Y;
    tt_sim_set_x(sim, x, t->st.stuck);
    if (fundamental_only(L))
        tt_sim_set_sampling(sim, 0, NULL);
    t->on = 1;
}

/* An integrated cycle's components of its period (j: its place in the block): its
 * mean and fundamental, or its samples' transform. */
static void integrated_components(const line_ctx *L, const avg_line *t, int j, const tt_cycle *cy)
{
    worker *W = L->W;
    double *c = W->y + (size_t)j * (size_t)tt_lockin_components(W->lockin);
    if (fundamental_only(L)) {
        c[0] = cy->mean;
        c[1] = cy->amplitude * cos(cy->phase);
        c[2] = cy->amplitude * sin(cy->phase);
        return;
    }
    const tt_sample *smp = W->samples;
    for (int q = 0; q < L->N; q++)
        t->y[q] = smp[q].d - smp[q].z;
    tt_lockin_transform(W->lockin, t->y, c);
}

/* The thermal force over the integrated cycle just ended as the slow flow takes it
 * (flow_step's impulse, its draw of the line's cycle): X and Y moved at the cycle's
 * end, where y = X + m0 and y' = w Y; the sim's own thermal force is off on this tier
 * (its knots a cycle bound the steps whatever the tolerance). */
static void thermal_kick(const line_ctx *L, long cycle)
{
    const tt_cantilever *c = &L->S->cantilever;
    const double sig = tt_averaged_thermal_density(c, L->S->noise.temperature);
    if (!(sig > 0))
        return;
    double g[2], x[TT_SIM_DIM_MAX];
    int contact;
    tt_noise_pair(L->ke, (uint64_t)cycle, g);
    tt_sim_get_x(L->W->sim, x, &contact);
    x[0] += sig * sqrt(c->T) * g[0];
    x[1] += c->wd * sig * sqrt(c->T) * g[1];
    tt_sim_set_x(L->W->sim, x, contact);
}

/* One block of n cycles integrated (the every-cycle tier's steps; the detector's noise
 * as on the slow flow's blocks), then the slow state projected from its last cycle's
 * fundamental and mean, and the test whether the slow flow may take over again. */
static int integrated_block(const line_ctx *L, line_state *st, avg_line *t, int n)
{
    const long k0 = st->k, cycle0 = st->cycles;
    const tt_averaged_state pre = t->st;
    double smean = 0, prev[2] = {0, 0}; /* prev: the cycle before the last's X, Y */
    size_t mat = 0;
    tt_cycle cy;
    for (int j = 0; j < n; j++) {
        cycle_in in;
        int rc = tt_scan_cycle_begin(L, st, &in);
        if (!rc)
            rc = tt_scan_integrate(L, st, &in, &cy);
        if (rc)
            return rc;
        thermal_kick(L, st->cycles);
        smean += 0.5 * (in.sa + in.sb) / n;
        mat = in.mat;
        integrated_components(L, t, in.j, &cy);
        if (j == n - 1)
            detector_noise(L, t, k0, n, cycle0);
        else {
            prev[0] = cy.amplitude * cos(cy.phase);
            prev[1] = cy.amplitude * sin(cy.phase);
        }
        t->integrated++;
        if ((rc = tt_scan_cycle_end(L, st, &in, cy.peak_force, cy.max_indentation, cy.e_ts)))
            return rc;
    }
    const double A0 = L->S->cantilever.A0;
    t->st.X = cy.amplitude * cos(cy.phase);
    t->st.Y = cy.amplitude * sin(cy.phase);
    t->st.m0 = cy.mean;
    t->st.stuck = 0;
    if (n > 1 && fmax(fabs(t->st.X - prev[0]), fabs(t->st.Y - prev[1])) > JUMP_TOL * A0)
        return TT_OK;
    tt_averaged_state pred = pre;
    tt_averaged_out o;
    tt_averaged_step(L->S->avg[mat], &pred, smean, n * L->S->cantilever.T, &o);
    const double dev = fmax(fabs(pred.X - t->st.X), fabs(pred.Y - t->st.Y)) / A0;
    if (dev <= EXIT_TOL) {
        t->on = 0;
        t->trusted = o.change > ENTER_TOL;
    }
    return TT_OK;
}

/* One block of n cycles from cycle k0, the surface at its start a and end b. */
static int block(const line_ctx *L, line_state *st, avg_line *t, const surf_pt *a,
                 const surf_pt *b, int n)
{
    const tt_scan *S = L->S;
    worker *W = L->W;
    const long k0 = st->k;
    if (t->on)
        return integrated_block(L, st, t, n);
    const double za0 = st->z_from + (st->z_to - st->z_from) * (double)(k0 % L->P) / L->P;
    const line_state save = *st;
    const tt_averaged_state start = t->st;
    const double smean = block_sample(L, st, a, b, n, t->s);
    tt_averaged_out o;
    /* a block the slow flow fails outside the trust is integrated whatever its
     * sub-steps would give: they are not run */
    const double fail = L->phase > 0 && !t->trusted ? ENTER_TOL : INFINITY;
    const double change = block_flow(L, t, S->avg[a->mat], k0, n, t->s, smean, st->cycles, fail, &o);
    const int impact = change >= IMPACT && o.collapsed;
    if (change <= ENTER_TOL)
        t->trusted = 0;
    /* the settling's engage (a free tip dropped onto the setpoint) is left to the slow
     * flow, which settles as it did before: only the images' phases are integrated */
    if (L->phase > 0 && ((change > ENTER_TOL && !t->trusted) || impact)) {
        *st = save;
        t->st = start;
        enter(L, t);
        return integrated_block(L, st, t, n);
    }
    detector_noise(L, t, k0, n, st->cycles);
    if (L->phase > 0) {
        if (!(S->channels & (TT_CH_PEAK_FORCE | TT_CH_INDENTATION))) /* as untracked cycles */
            o.peak = o.indent = NAN;
        cycle_sums(L, k0, n, za0, (st->z_to - st->z_from) / L->P, a, b, &o);
        if (o.indent > W->indent[a->mat])
            W->indent[a->mat] = o.indent;
        if (o.collapsed || o.outside) {
            long px = tt_raster_pixel(&S->raster, L->dir, L->nc, k0 + n - 1);
            char *m = &t->mark[(size_t)L->dir * (size_t)S->raster.pixels + (size_t)px];
            *m |= (char)(o.collapsed ? 1 : 2);
        }
    }
    st->cycles += n;
    st->k = k0 + n;
    return tt_scan_block_end(L, st, (k0 + n - 1) / L->P);
}

/* The averaged tier's cycles of one phase (a scan_phase_fn; tier: the line's state). */
static int averaged_phase(const line_ctx *L, line_state *st, void *tier)
{
    avg_line *t = tier;
    surf_pt a = tt_scan_surface_at(L, 0);
    while (st->k < L->ncyc) {
        if ((st->k / L->P) % 64 == 0 && tt_cancel_requested())
            return TT_EINTR;
        long left = L->ncyc - st->k, in_block = L->P - st->k % L->P;
        int n = (int)(left < in_block ? left : in_block);
        surf_pt b = tt_scan_surface_at(L, st->k + n);
        int rc = block(L, st, t, &a, &b, n);
        if (rc)
            return rc;
        a = b;
    }
    return TT_OK;
}

int tt_scan_line_averaged(tt_scan *S, worker *W, long line, const line_out *out, long *cycles,
                          long *integrated, double *worst, int *clamped)
{
    avg_line t = {.on = 0};
    const long px = S->raster.pixels;
    t.mark = calloc((size_t)(2 * px), 1);
    t.s = malloc((size_t)S->lockin.periods_per_block * sizeof *t.s);
    t.y = malloc((size_t)S->lockin.samples_per_period * sizeof *t.y);
    t.rn = malloc((size_t)tt_lockin_components(W->lockin) * sizeof *t.rn);
    if (!t.mark || !t.s || !t.y || !t.rn) {
        free(t.mark);
        free(t.s);
        free(t.y);
        free(t.rn);
        return tt_error_nomem("the averaged tier's marks of a line ([scan] pixels = %ld)", px);
    }
    detector_norms(S, W, t.rn);
    if (S->continuous && W->engaged)
        t.st = W->avg;
    else
        tt_averaged_state_free(&S->cantilever, &t.st);
    int rc = tt_scan_line_run(S, W, line, out, averaged_phase, &t, cycles, worst, clamped);
    W->avg = t.st;
    long col = 0, outside = 0, first = -1;
    for (long i = 0; i < 2 * px; i++) {
        if (t.mark[i] & 1) {
            col++;
            if (first < 0)
                first = i % px;
        }
        outside += (t.mark[i] & 2) != 0;
    }
    free(t.mark);
    free(t.s);
    free(t.y);
    free(t.rn);
    *integrated += t.integrated;
    if (rc == TT_OK && (col || outside)) {
#pragma omp critical(tt_scan_averaged)
        {
            S->collapsed += col;
            S->outside += outside;
            if (col && (S->collapse_line < 0 || line < S->collapse_line)) {
                S->collapse_line = line;
                S->collapse_px = first;
            }
        }
    }
    return rc;
}
