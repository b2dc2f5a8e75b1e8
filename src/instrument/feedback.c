/* PI amplitude feedback with a clamped z piezo (see include/tiptap/instrument/feedback.h). */
#include "tiptap/instrument/feedback.h"

void tt_feedback_init(tt_feedback *f, const tt_feedback_params *p, double z0)
{
    f->setpoint = p->setpoint;
    f->kp = p->kp;
    f->ki = p->ki;
    f->z_min = -0.5 * p->z_range;
    f->z_max = 0.5 * p->z_range;
    f->integral = 0;
    f->z0 = z0;
    f->z = z0 < f->z_min ? f->z_min : z0 > f->z_max ? f->z_max : z0;
    f->clamped = 0;
}

void tt_feedback_retune(tt_feedback *f, const tt_feedback_params *p)
{
    f->z0 -= f->ki * f->integral;
    f->integral = 0;
    f->setpoint = p->setpoint;
    f->kp = p->kp;
    f->ki = p->ki;
    f->z_min = -0.5 * p->z_range;
    f->z_max = 0.5 * p->z_range;
}

double tt_feedback_update(tt_feedback *f, double amplitude, double dt)
{
    double e = amplitude - f->setpoint;
    double integral = f->integral + e * dt;
    double z = f->z0 - (f->kp * e + f->ki * integral);
    f->clamped = 0;
    if (z > f->z_max || z < f->z_min) {
        /* at a stop: output the stop and hold the integral rather than wind it up
         * further into it (anti-windup), so that the loop recovers at once */
        f->clamped = 1;
        z = z > f->z_max ? f->z_max : f->z_min;
    } else {
        f->integral = integral;
    }
    f->z = z;
    return z;
}
