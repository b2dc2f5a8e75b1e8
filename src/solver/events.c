/* Contact events: jump-in and pull-off located on the step's dense output (Illinois
 * search), the step redone up to the event, and the contact state flipped there with its
 * energy jump. */
#include <float.h>
#include <string.h>

#include "stepper.h"
#include "tiptap/util/error.h"

/* Switches closer together than this (a millionth of a millionth of the cycle) are made
 * "within one instant": the root search resolves 1e-14 of a step, and no touch that
 * short moves the tip by anything a double can hold. */
static int same_instant(const tt_sim *S)
{
    return fabs(S->tau - S->switched_at) <= 1e-12 * S->c.T;
}

/* The rounding floor of the event function at the step's start: d - s is the difference
 * of two positions of up to tens of nanometres, good to a few of their ulp (about
 * 1e-23 m), and a sign inside that floor says nothing about the side of the threshold. */
static double event_floor(const tt_sim *S, double thr)
{
    double s = S->sys.s0 + S->sys.sdot * S->step_tau;
    return 16 * DBL_EPSILON * (fabs(S->y[Y_D]) + fabs(s) + fabs(thr));
}

/* A step that starts on the threshold (within the rounding floor) heading away from the
 * event side starts at the switch just made: its rounding would pass for roots at once
 * (a grazing touch 1.5e-14 m past a threshold without hysteresis, drawn by thermal
 * noise, was switched back and forth 3e-20 s at a time, ~1e10 times in one cycle). The
 * search for the way back starts where the tip turns. */
static double event_from_threshold(const tt_sim *S, double thr, double sgn)
{
    double v0 = tt_event_vel(S, 0), v1 = tt_event_vel(S, 1);
    if (!(v0 * v1 < 0))
        return 2; /* no turning point: the step stays on this side */
    double tm = tt_event_root(S, 1, 0, 0, 1, v0, v1);
    double gm = sgn * tt_event_delta(S, tm, thr);
    if (gm <= 0)
        return tm; /* an excursion within rounding: back at the turning point */
    double g1 = sgn * tt_event_delta(S, 1, thr);
    if (g1 > 0)
        return 2;
    return tt_event_root(S, 0, thr, tm, 1, tt_event_delta(S, tm, thr), tt_event_delta(S, 1, thr));
}

/* Where in the current step (fraction, > 1 = none) the contact state must flip:
 * out of contact when the penetration rises to jumpin, in contact when it falls to
 * jumpout. A turning point inside the step is checked too, so that a brief touch
 * between step ends is not missed. */
static double event_at(const tt_sim *S)
{
    if (!S->sys.contact)
        return 2;
    int in = S->contact_state;
    double thr = in ? S->sys.jumpout : S->sys.jumpin;
    if (!isfinite(thr))
        return 2;
    /* sign convention: event when sgn * g crosses from > 0 to <= 0 */
    double sgn = in ? 1.0 : -1.0;
    double g0 = sgn * tt_event_delta(S, 0, thr);
    if (g0 <= -S->sys.margin)
        return 0; /* already past by more than the margin: switch now */
    double g1 = sgn * tt_event_delta(S, 1, thr);
    if (g0 > 0 && g1 <= 0) {
        double th = tt_event_root(S, 0, thr, 0, 1, tt_event_delta(S, 0, thr), tt_event_delta(S, 1, thr));
        /* a root at once after a switch, from a start on the threshold heading away, is
         * the rounding of that start, not the way back */
        if (th * S->step_h <= 1e-12 * S->c.T && fabs(g0) <= event_floor(S, thr) &&
            sgn * tt_event_vel(S, 0) > 0)
            return event_from_threshold(S, thr, sgn);
        return th;
    }
    /* A turning point of the penetration inside the step: out of contact a maximum,
     * in contact a minimum. */
    double v0 = tt_event_vel(S, 0), v1 = tt_event_vel(S, 1);
    if (g0 > 0 && ((!in && v0 > 0 && v1 < 0) || (in && v0 < 0 && v1 > 0))) {
        double tm = tt_event_root(S, 1, 0, 0, 1, v0, v1);
        double gm = sgn * tt_event_delta(S, tm, thr);
        if (gm <= 0)
            return tt_event_root(S, 0, thr, 0, tm, tt_event_delta(S, 0, thr),
                                 tt_event_delta(S, tm, thr));
    }
    /* Here the step started within the margin past the threshold (g0 <= 0: no root in
     * it) and ended past it by more: the switch belongs at its start, or the whole step
     * would run on the branch the tip has left (a pull-off 0.04 nm late on the
     * standard polymer-blend's disk, with an energy jump the balance then missed): a
     * touch at a turning point on the threshold, in and out at one instant. Should the
     * tip be switched there a third time, the branches send it back and forth: that
     * step is taken whole and the switch made at its end. */
    if (g1 <= -S->sys.margin)
        return S->tau == S->switched_at && S->switches_there >= 2 ? 1 : 0;
    return 2;
}

double tt_event_find(const tt_sim *S)
{
    double th = event_at(S);
    /* A backstop against any other way of switching back and forth without time going
     * on: after 16 switches within one instant, one more at that instant is made only
     * at the end of a step that ends past the threshold. */
    if (th * S->step_h <= 1e-12 * S->c.T && S->switches_near >= 16 && same_instant(S)) {
        double thr = S->contact_state ? S->sys.jumpout : S->sys.jumpin;
        double sgn = S->contact_state ? 1.0 : -1.0;
        return sgn * tt_event_delta(S, 1, thr) <= 0 ? 1 : 2;
    }
    return th;
}

/* Redo the current step up to fraction th, take it, and flip the contact state. */
int tt_event_take(tt_sim *S, double th)
{
    double h = S->step_h;
    tt_observe(S, th);
    if (th > 0) {
        int rc = S->type->redo(S->step, S, th * h);
        if (rc)
            return rc;
        sim_copy(S, S->y, S->y1);
        S->tau = S->step_tau + S->step_h;
        S->steps++;
    }
    /* Energy jumps by U_old - U_new at the switch: the hysteresis loss (Burnham et al.;
     * docs/physics.md). */
    double U_old = S->sys.energy(S, S->tau, S->y, S->contact_state);
    S->contact_state = !S->contact_state;
    double U_new = S->sys.energy(S, S->tau, S->y, S->contact_state);
    S->e_jumps += U_old - U_new;
    S->switches_near = same_instant(S) ? S->switches_near + 1 : 1;
    S->switches_there = S->tau == S->switched_at ? S->switches_there + 1 : 1;
    S->switched_at = S->tau;
    if (S->contact_state && !isfinite(S->t_contact))
        S->t_contact = S->tau;
    if (!S->contact_state)
        S->t_release = S->tau;
    tt_sim_invalidate(S);
    S->events++;
    S->step_h = h; /* keep the step length the controller chose */
    return TT_OK;
}
