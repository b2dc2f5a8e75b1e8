/* tiptap: PI amplitude feedback with a clamped z piezo.
 *
 * The controller holds the lock-in amplitude at the setpoint by moving the sample.
 * Its output is the height signal z (m): the sample is lowered by z, so over a bump of
 * height H a converged loop reads z = H. When the amplitude is below the setpoint the
 * tip is too close and z grows. Error e = amplitude - setpoint;
 *   z = -(kp * e + ki * integral(e dt)) + z0, clamped to [z_min, z_max],
 * with the integrator held while clamped (anti-windup), as an instrument does.
 * Gains are in physical units: kp in m/m (dimensionless), ki in 1/s.
 *
 * Ownership: plain struct, no allocation.
 */
#ifndef TIPTAP_FEEDBACK_H
#define TIPTAP_FEEDBACK_H

#ifdef __cplusplus
extern "C" {
#endif

/* What the scene sets: the setpoint in metres, the gains, and the z piezo's range,
 * centred on the surface's zero. */
typedef struct {
    double setpoint;   /* m */
    double kp;         /* dimensionless */
    double ki;         /* 1/s */
    double z_range;    /* m */
} tt_feedback_params;

typedef struct {
    double setpoint;   /* m */
    double kp;         /* dimensionless */
    double ki;         /* 1/s */
    double z_min, z_max;
    /* state */
    double integral;   /* integral of e dt, m s */
    double z0;         /* output offset, m */
    double z;          /* last output, m */
    int clamped;       /* last output was clamped */
} tt_feedback;

/* Start the loop from output z0 (clamped to the piezo's range, -z_range / 2 to
 * z_range / 2) with an empty integrator. */
void tt_feedback_init(tt_feedback *f, const tt_feedback_params *p, double z0);
/* New gains, setpoint and range for a running loop, its output unchanged: the
 * integrator's share of z, ki * integral, moves into the offset z0 and the integral
 * restarts from zero, so that a new ki does not make z jump (bumpless). */
void tt_feedback_retune(tt_feedback *f, const tt_feedback_params *p);
/* One update after dt seconds with the measured amplitude; returns the new z. */
double tt_feedback_update(tt_feedback *f, double amplitude, double dt);

#ifdef __cplusplus
}
#endif
#endif
