/* The configuration layer's estimates of what a run will cost before it starts
 * (see include/tiptap/config/config.h). */
#include "tiptap/config/config.h"
#include "tiptap/instrument/scan_scope.h"

#include <math.h>
#include <string.h>

/* Wall time of one resonance period with dopri5 at tolerance 1e-8 on one core,
 * lock-in sampling included (tiptap bench: about 70,000 cycles/s of the standard scene,
 * 24 steps a cycle; a scan's sampling adds some). An order of magnitude, not a promise. */
#define PERIOD_SECONDS 2e-5
/* rk4: one fixed step (tiptap bench: 512 steps a cycle at about 8,400 cycles/s). */
#define RK4_STEP_SECONDS 2.5e-7

double tt_config_cycle_seconds(const tt_cantilever *c, const tt_solver *s)
{
    if (s->method == TT_METHOD_RK4)
        return RK4_STEP_SECONDS * (double)s->steps_per_cycle;
    /* An adaptive step resolves the resonance: a drive far below it spans f0 / fd
     * periods of the free oscillation, each needing its steps. A step's error goes as
     * its length to the fifth power, so the step count as tolerance^(-1/5). */
    double periods = c->f0 > c->fd ? c->f0 / c->fd : 1;
    double tol = s->tolerance > 0 ? s->tolerance : 1e-8;
    double per = PERIOD_SECONDS * pow(1e-8 / tol, 0.2);
    if (s->method == TT_METHOD_RADAU)
        per *= 2.5; /* tiptap bench: radau at 1e-8 runs at about 0.4 of dopri5's rate */
    return per * periods;
}

/* The envelope tier integrates only some of the cycles, how many depends on the scene:
 * of scans/quick.ini's cycles on the bundled surfaces (4 lines each, tiptap scan's
 * cycles_integrated), 1.9 % on polymer, 15 % on steps and grating, 77 % on
 * polymer-blend and 81 % on rough. A model cycle costs a few per cent of an integrated
 * one, left out. */
#define ENVELOPE_FRACTION_LOW 0.02
#define ENVELOPE_FRACTION_HIGH 0.8

/* The averaged tier integrates no cycle: a block of the slow flow, the lock-in and the
 * feedback cost about 70 ns a cycle on one core (a 256-pixel line at 1 Hz on the
 * standard scene, 303,000 cycles: 21 ms), each material's table 20 ms, one with
 * relaxation arms (their periodic cycle solved at each node) 0.5 s. */
#define AVERAGED_CYCLE_SECONDS 7e-8
#define AVERAGED_TABLE_SECONDS 0.02
#define AVERAGED_ARMS_TABLE_SECONDS 0.5

static void finish(tt_estimate *e, const tt_cantilever *c, const tt_solver *s)
{
    e->cycle_seconds = tt_config_cycle_seconds(c, s);
    e->seconds = e->seconds_low = e->cycles * e->cycle_seconds;
}

void tt_config_scan_estimate(const tt_scan_params *p, tt_estimate *e)
{
    memset(e, 0, sizeof *e);
    const tt_raster *r = &p->raster;
    double P = p->lockin.periods_per_block > 0 ? p->lockin.periods_per_block : 1;
    double nc = fmax((double)r->pixels, round(p->cantilever.fd / (2 * r->line_rate)));
    double settle = ceil((double)p->settle_cycles / P) * P;
    double dirs = r->retrace ? 2 : 1;
    e->cycles = (double)r->lines * (settle + dirs * ceil(nc / P) * P);
    finish(e, &p->cantilever, &p->solver);
    if (tt_scan_averaged_tier(p)) {
        e->cycle_seconds = AVERAGED_CYCLE_SECONDS;
        e->seconds = e->seconds_low = e->cycles * AVERAGED_CYCLE_SECONDS;
        for (size_t i = 0; i < p->nmaterials; i++)
            e->seconds = e->seconds_low += p->materials[i].contact.arms > 0
                                               ? AVERAGED_ARMS_TABLE_SECONDS
                                               : AVERAGED_TABLE_SECONDS;
    } else if ((e->envelope = tt_scan_envelope_tier(p))) {
        e->integrated_low = ENVELOPE_FRACTION_LOW;
        e->integrated_high = ENVELOPE_FRACTION_HIGH;
        e->seconds_low = e->seconds * ENVELOPE_FRACTION_LOW;
        e->seconds *= ENVELOPE_FRACTION_HIGH;
    }
    /* Every image as doubles, one more for the previews and files being written, and
     * each thread's pixel sums (about 40 doubles a pixel, both directions) and envelope
     * plans (one per state dimension: a material with relaxation arms adds one). */
    int nch = 0;
    for (int ch = 0; ch < TT_CH_COUNT; ch++) /* the estimate's kept ones too */
        nch += ((p->channels | tt_scan_kept_channels(p)) >> ch) & 1u;
    double image = (double)r->pixels * (double)r->lines * sizeof(double);
    e->bytes = image * (nch * dirs + 1);
    e->thread_bytes = (double)r->pixels * 2 * 40 * sizeof(double) + tt_scan_envelope_plans_bytes(p);
    /* a point a lock-in block of every quantity, trace and retrace (0.0002 Hz on the
     * standard scene: 1.9e8 points a direction, 27 GB) */
    e->scope_bytes = ceil(nc / P) * TT_SCOPE_COUNT * 2 * sizeof(double);
}

/* One row of the trace's CSV, nine numbers formatted and written: 1.0 us of CPU time
 * (20,000 cycles of the standard scene at 100 samples a cycle: 2.25 s, against 0.30 s
 * at 4). At the default 100 samples a cycle the rows cost more than the integration. */
#define TRACE_ROW_SECONDS 1e-6

void tt_config_trace_estimate(const tt_cantilever *c, const tt_solver *s, const tt_trace_params *p,
                              tt_estimate *e)
{
    memset(e, 0, sizeof *e);
    e->cycles = (double)p->settle_cycles + (double)p->cycles;
    finish(e, c, s);
    e->seconds += (double)p->cycles * (double)p->samples_per_cycle * TRACE_ROW_SECONDS;
    e->seconds_low = e->seconds;
}

void tt_config_approach_estimate(const tt_cantilever *c, const tt_solver *s,
                                 const tt_approach_params *p, tt_estimate *e)
{
    memset(e, 0, sizeof *e);
    double branches = p->retract ? 2 : 1;
    if (p->mode == TT_APPROACH_RAMP) {
        e->cycles = ceil(fabs(p->to - p->from) / (p->speed * c->T)) * branches +
                    (double)p->max_cycles;
    } else if (p->steady == TT_STEADY_SETTLE) {
        e->cycles = (double)p->points * branches * (double)p->max_cycles;
        e->upper_bound = 1;
    } else {
        /* shooting: a transient of about Q / 2 pi ln(1 / tolerance) cycles, then a few
         * Newton iterations of a few cycles each (src/solver/shooting.c) */
        double tol = p->settle_tolerance > 0 ? fmin(p->settle_tolerance, 0.1) : 0.1;
        double per = fmin((double)p->max_cycles, 0.5 * c->Q / M_PI * log(1 / tol) + 50);
        e->cycles = (double)p->points * branches * per;
    }
    finish(e, c, s);
}
