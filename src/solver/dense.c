/* The event functions' zeros on the current step's dense output: the one root finder
 * that contact events, the observations and the free flight's hand-over share. */
#include "stepper.h"
#include "util/root.h"

/* What tt_event_root() seeks the zero of: which = 0 the penetration minus thr, 1 the
 * relative velocity, on the step's dense output. */
typedef struct {
    const tt_sim *S;
    int which;
    double thr;
} event_fn;

static double event_value(double th, void *data)
{
    const event_fn *e = data;
    return e->which ? tt_event_vel(e->S, th) : tt_event_delta(e->S, th, e->thr);
}

/* The root on [a, b] (fa, fb of opposite signs) to 1e-14 of the step; the end of the
 * final bracket on b's side, so that the switch happens just past the root. */
double tt_event_root(const tt_sim *S, int which, double thr, double a, double b, double fa,
                     double fb)
{
    event_fn e = {S, which, thr};
    tt_root_bracket br = {a, b, fa, fb};
    double m;
    return tt_root_illinois(event_value, &e, &br, 1e-14, 0, 100, &m) ? m : br.b;
}

