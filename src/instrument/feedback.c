/* PI amplitude feedback with a clamped z piezo (see include/tiptap/instrument/feedback.h). */
#include "tiptap/instrument/feedback.h"

void tt_feedback_init(tt_feedback *f, double setpoint, double kp, double ki, double z_min,
                      double z_max, double z0)
{
    f->setpoint = setpoint;
    f->kp = kp;
    f->ki = ki;
    f->z_min = z_min;
    f->z_max = z_max;
    f->integral = 0;
    f->z0 = z0;
    f->z = z0 < z_min ? z_min : z0 > z_max ? z_max : z0;
    f->clamped = 0;
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
