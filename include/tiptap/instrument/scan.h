/* tiptap: closed-loop imaging (Burnham et al. section 3.2.4; docs/architecture.md).
 *
 * A scan moves the sample under the tapping tip line by line. Each drive cycle the
 * tip sits over the surface point the raster has reached (height and material
 * looked up there), the lock-in demodulates the deflection over whole periods, and
 * the PI feedback moves the sample to hold the amplitude at the setpoint. Per pixel
 * it records the channels asked for, trace and retrace.
 *
 * By default lines are independent: each starts from a settled state at its first
 * pixel (the feedback engaged there for [scan] settle_cycles cycles), so lines can run
 * in parallel and the images do not depend on the number of threads. What this costs
 * is the continuity of a real raster: a line does not inherit the previous line's
 * retrace state (the same place, one line away). With continuous set, lines run as an
 * instrument runs them, one after the other on one thread: only the first line
 * settles, and each next line starts where the last retrace ended (the cantilever,
 * the lock-in's filters, the feedback's integrator and z carried over), so an
 * unstable loop rings differently on every line.
 *
 * Every material's force law is built when the scan is made, used by a pixel or not,
 * so a material that cannot be built is refused before any line runs.
 *
 * Ownership: tt_scan_alloc copies what it needs from the parameters (the materials
 * included); the scan owns its surface, force laws, images and per-thread workspaces,
 * freed by tt_scan_free.
 */
#ifndef TIPTAP_SCAN_H
#define TIPTAP_SCAN_H

#include <stddef.h>
#include <stdint.h>

#include "tiptap/export.h"
#include "tiptap/instrument/feedback.h"
#include "tiptap/instrument/lockin.h"
#include "tiptap/instrument/piezo.h"
#include "tiptap/instrument/scanner.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/instrument/tip.h"
#include "tiptap/physics/cantilever.h"
#include "tiptap/physics/material.h"
#include "tiptap/solver/integrator.h"

TT_BEGIN_DECLS

/* Channels (bit flags). */
enum {
    TT_CH_HEIGHT = 1 << 0,      /* feedback height, m */
    TT_CH_ERROR = 1 << 1,       /* the error signal: lock-in amplitude - setpoint, m */
    TT_CH_PHASE = 1 << 2,       /* lock-in phase lag, deg */
    TT_CH_PEAK_FORCE = 1 << 3,  /* greatest tip-sample force per cycle, N */
    TT_CH_INDENTATION = 1 << 4, /* greatest penetration per cycle, m */
    TT_CH_DISSIPATION = 1 << 5, /* tip-sample energy lost per cycle, J */
    TT_CH_TOPOGRAPHY = 1 << 6,  /* the true surface height under the tip's axis, m
                                 * (reference: no dilation, tilt or z drift) */
    TT_CH_AMPLITUDE = 1 << 7,   /* the lock-in amplitude (filtered), m */
    /* Higher harmonics of the deflection, h = 2 to TT_CH_HARMONIC_MAX: channel index
     * TT_CH_HARMONIC_INDEX + h - 2 is "harmonicH", the lock-in amplitude of harmonic h
     * (m), and TT_CH_HARMONIC_PHASE_INDEX + h - 2 is "harmonicH_phase", its lag behind
     * cos(h w t) (deg). */
    TT_CH_HARMONIC_MAX = 8,
    TT_CH_HARMONIC_INDEX = 8,
    TT_CH_HARMONIC_PHASE_INDEX = 15,
    /* height - topography at each pixel, m: what the loop and the tip made of the
     * sample (with the standing offset of the tip's rest at the setpoint) */
    TT_CH_ARTEFACT_INDEX = 22,
    TT_CH_ARTEFACT = 1 << 22,
    /* the dissipation per mechanism, J per cycle, adding up to dissipation: adhesion
     * hysteresis (the jumps' energy), interaction damping (c_i) and the sample's
     * viscosity; NaN on the averaged tier, which books the loss as a whole */
    TT_CH_LOSS_INDEX = 23,
    TT_CH_DISSIPATION_HYSTERESIS = 1 << 23,
    TT_CH_DISSIPATION_DAMPING = 1 << 24,
    TT_CH_DISSIPATION_VISCOUS = 1 << 25,
    TT_CH_LOSSES = TT_CH_DISSIPATION_HYSTERESIS | TT_CH_DISSIPATION_DAMPING | TT_CH_DISSIPATION_VISCOUS,
    /* the true surface dilated by the tip's shape (tip.h) under the tip's axis, m: the
     * plain geometric image, no dynamics, tilt or z drift (topography for a point tip) */
    TT_CH_DILATION_INDEX = 26,
    TT_CH_DILATION = 1 << 26,
    /* a measured surface eroded by its measuring tip: 1 where the erosion is the sample
     * (its certainty map), 0 where only an upper bound, at the pixel's centre */
    TT_CH_CERTAINTY_INDEX = 27,
    TT_CH_CERTAINTY = 1 << 27,
    /* Bimodal AM-AM ([cantilever] mode2_free_amplitude): the second lock-in's amplitude
     * (m) and lag (deg) at mode 2's drive frequency */
    TT_CH_AMPLITUDE2_INDEX = 28,
    TT_CH_AMPLITUDE2 = 1 << 28,
    TT_CH_PHASE2_INDEX = 29,
    TT_CH_PHASE2 = 1 << 29,
    TT_CH_COUNT = 30
};

/* Name ("height"), unit ("m", "deg", "N", "J") and title of channel index i. */
const char *tt_scan_channel_name(int i);
const char *tt_scan_channel_unit(int i);
/* The harmonic a channel index demodulates: 1 for error, phase and amplitude, h for
 * harmonicH and harmonicH_phase, 0 for the others. */
int tt_scan_channel_harmonic(int i);
/* Parse "height, phase" into a channel mask; -1 with a message naming the channel. */
int tt_scan_channels_parse(const char *text, unsigned *mask, char *why, size_t len);
/* The number of channel indices, TT_CH_COUNT, for a caller that lists every channel by
 * index without the enum (the Python package). */
int tt_scan_channel_count(void);

/* The instrument's imperfections ([instrument]); all zero: an ideal instrument. Time t
 * is the instrument's clock: line n starts at n / line_rate, its trace takes the first
 * half of the line's period and its retrace the second (a line's settling takes none).
 * The sample at raster position (x, y) and time t is the point (x - drift_x t,
 * y - drift_y t) of the surface, raised by tilt_x x + tilt_y y + drift_z t in that
 * point's coordinates. The piezo starts each line at rest (continuous lines carry it on). */
typedef struct {
    double tilt_x, tilt_y;            /* slopes dz/dx, dz/dy */
    double drift_x, drift_y, drift_z; /* m/s */
    tt_piezo_params piezo;
} tt_instrument_params;
/* Noise of a scan (docs/dynamics.md, "Noise"), off when every amplitude is 0. Each
 * kind draws from its own stream keyed by (seed, line) and counted from the line's
 * start, so images are the same on any number of threads. */
typedef struct {
    uint64_t seed;
    double temperature; /* K: the cantilever's thermal force (tiptap/solver/noise.h); 0: off */
    int points;         /* thermal force points per drive cycle */
    double detector;    /* deflection noise density of the detector, m/sqrt(Hz) (one-sided),
                         * added to every sample the lock-in reads */
    double z_piezo;     /* position noise density of the z piezo, m/sqrt(Hz) (one-sided),
                         * through a first-order low-pass of corner z_bandwidth (an
                         * Ornstein-Uhlenbeck process, exact at each drive cycle's start and
                         * linear between): moves the sample, not the height */
    double z_bandwidth; /* Hz: the low-pass's corner, above 0 and at most half the drive
                         * frequency when z_piezo is on */
} tt_scan_noise;

/* Everything a scan needs, in SI units. */
typedef struct {
    tt_cantilever cantilever;
    tt_solver solver;
    const tt_material *materials; /* the sample's materials, indexed by the surface's map */
    size_t nmaterials;
    tt_raster raster;
    tt_surface_params surface;
    tt_lockin_params lockin;      /* harmonics: as many as the lock-in offers (the scan
                                   * demodulates up to the highest its channels need);
                                   * drive_frequency: ignored, the cantilever's */
    tt_feedback_params feedback;
    unsigned channels;            /* TT_CH_* mask */
    long settle_cycles;           /* cycles the feedback settles at each line's first pixel */
    long profile_line;            /* the line of the CSV profile; -1: the middle one */
    tt_tip_shape tip;             /* what meets the topography (TT_TIP_POINT: the apex) */
    tt_instrument_params instrument;
    tt_scan_noise noise;
    int continuous;               /* lines as an instrument runs them: each starts where
                                   * the last retrace ended (one thread) */
    int local_geometry;           /* [tip] contact_geometry = local: each cycle's law built
                                   * for the slope and curvature where the tip touches,
                                   * quantised (docs/surfaces.md); every-cycle tier only */
} tt_scan_params;

typedef struct tt_scan tt_scan;

/* Fails naming the section and the key (tt_scene_locate adds the file) when the
 * surface or a material's force law cannot be made or the parameters disagree. */
int tt_scan_alloc(tt_scan **out, const tt_scan_params *p);
void tt_scan_free(tt_scan *s);

/* Run all lines on up to threads threads (0: all cores). progress, if not NULL, is
 * called (from one thread at a time) after each finished line with the number of
 * lines done. Stops early with TT_EINTR when cancellation is requested (cancel.h);
 * finished lines keep their data, the others stay NaN. A scope attached with
 * tt_scan_scope_attach receives its line's record. It runs the lines not done yet: a
 * line finished before, by an earlier tt_scan_run or by tt_scan_step, is skipped. */
int tt_scan_run(tt_scan *s, int threads, void (*progress)(void *user, long done, long total),
                void *user);

/* A scan one line at a time, as an instrument is driven: alloc, run a line, read its
 * pixels (tt_scan_line_values) and its full-rate record (tiptap/instrument/scan_scope.h),
 * change the gains or the setpoint, run the next line, ..., free. tt_scan_run runs the
 * same line code, so stepping lines 0, 1, ... in order gives its images byte for byte.
 *
 * tt_scan_step runs line `line` (0 .. lines - 1, any order, again as often as wanted)
 * on the calling thread, its trace and retrace, and writes its pixels into the images;
 * scope, if not NULL, receives the line's record. Independent lines ([scan] lines_mode)
 * each start settled at their first pixel; continuous lines carry on from where the
 * last stepped line's retrace ended (the cantilever, lock-in, feedback and piezo), the
 * first of them (and the first after tt_scan_disengage) engaging and settling. The
 * stepped lines keep their own state, apart from tt_scan_run's; the scan owns that
 * workspace (made at the first step, freed by tt_scan_free). A line's cycles, energy
 * check and clamping add to the scan's totals (tt_scan_cycles, ...) however often it
 * runs. Not for two threads at once on one scan. TT_EINTR when cancellation is
 * requested (the line's pixels then keep their earlier values). */
typedef struct tt_scan_scope tt_scan_scope;
int tt_scan_step(tt_scan *s, long line, tt_scan_scope *scope);

/* The stepping workspace made now rather than at the first tt_scan_step (the averaged
 * tier's tables with it: 0.5 s for a material with relaxation arms), so that the first
 * line stepped costs what the others do (the console's preview). */
int tt_scan_step_prepare(tt_scan *s);
/* The next stepped line engages afresh at its first pixel and settles, as a scan's
 * first line does (continuous lines; independent lines always do). */
void tt_scan_disengage(tt_scan *s);
/* Line `line`'s pixels of a channel into out (pixels values, along the fast axis from
 * position 0, retrace included: its pixels stored in the trace's order); TT_EINVAL for
 * a channel not recorded or a line out of range. */
int tt_scan_line_values(const tt_scan *s, int channel_index, int retrace, long line, double *out);

/* What may change between two lines of a live scan, effective from the next line
 * (tt_scan_step or tt_scan_run). Anything else (pixels, lines, size, the fast axis,
 * the surface and materials, the tip, the cantilever's k, f0 and Q, the lock-in, the
 * solver and its tier, the channels, tilt and drift, the piezo's dynamics) needs a new
 * tt_scan. Each refuses a value out of range with TT_EINVAL and changes nothing then.
 *
 * The feedback: setpoint (m, above 0 and below the free amplitude), gains (kp
 * and ki 0 or more) and z range (above 0). On continuous lines the output does not
 * jump: the integrator's share of z is kept as the loop's offset and the new ki
 * integrates from there (a bumpless change, as an instrument's). The rest position the
 * heights are counted from stays the first engage's, so a new setpoint moves the height
 * image as the loop settles elsewhere, as on an instrument. */
void tt_scan_get_feedback(const tt_scan *s, tt_feedback_params *p);
int tt_scan_set_feedback(tt_scan *s, const tt_feedback_params *p);
/* The noise (all its kinds and the seed; zero amplitudes: off). Z piezo noise gives the
 * envelope tier's model the sample's travel as an input and second order, and thermal
 * noise second order, from the next line on; they are dropped when it is off again. A
 * z piezo bandwidth above half the drive frequency is refused (TT_EINVAL). */
void tt_scan_get_noise(const tt_scan *s, tt_scan_noise *n);
int tt_scan_set_noise(tt_scan *s, const tt_scan_noise *n);
/* Lines per second (the cycles of a line follow it; the images keep their size).
 * Refused with drift on: the drift's clock and the dilated surface's extent follow the
 * line rate the scan was made with. */
double tt_scan_line_rate(const tt_scan *s);
int tt_scan_set_line_rate(tt_scan *s, double line_rate);
/* The drive's free amplitude (m): the cantilever's drive strength follows, and the
 * averaged tier's tables are made again (a second or so). The next stepped line
 * engages afresh (tt_scan_disengage), since the oscillation it carried is the old
 * one's. The setpoint stays in metres: set it too. */
double tt_scan_free_amplitude(const tt_scan *s);
int tt_scan_set_free_amplitude(tt_scan *s, double A0);

/* Geometry and results. Images are stored in the sample's orientation whatever the
 * fast axis: xres columns along x, yres rows along y, row 0 at y = 0 (the top);
 * retrace images are stored in the same orientation as the trace. */
long tt_scan_xres(const tt_scan *s);
long tt_scan_yres(const tt_scan *s);
int tt_scan_fast_y(const tt_scan *s);
long tt_scan_lines(const tt_scan *s);
double tt_scan_size_x(const tt_scan *s);
double tt_scan_size_y(const tt_scan *s);
unsigned tt_scan_channels(const tt_scan *s);
int tt_scan_has_retrace(const tt_scan *s);
long tt_scan_lines_done(const tt_scan *s);
/* NULL when the channel was not asked for. */
const double *tt_scan_image(const tt_scan *s, int channel_index, int retrace);
/* The line chosen for the CSV profile ([scan] profile_line). */
long tt_scan_profile_line(const tt_scan *s);
/* Simulated instrument time of the whole scan, s (trace and retrace of every line). */
double tt_scan_instrument_time(const tt_scan *s);
/* Cantilever cycles simulated (including settling) and the energy-balance check: the
 * worst residual of a cycle relative to the free drive work per cycle. It checks the
 * integration, but it is not the error of the images (tt_scan_estimate_error is). */
long tt_scan_cycles(const tt_scan *s);
/* Cycles integrated: all of them on the every-cycle tier, fewer on the envelope tier,
 * none on the averaged tier. */
long tt_scan_cycles_integrated(const tt_scan *s);
/* The averaged tier ([solver] tier = averaged; docs/dynamics.md): the CPU seconds its
 * tables took to build (once per scan, all materials) and their largest error against
 * direct quadrature (relative to k A0); the pixels (trace and retrace) where the
 * oscillation collapsed onto the sample (the tip stuck, or the amplitude below a
 * quarter of the free amplitude), where the averaged model is wrong, with the first
 * line and pixel of them (-1: none), and those whose tip left the table (its forces
 * then from quadrature). */
double tt_scan_averaged_build_seconds(const tt_scan *s);
double tt_scan_averaged_table_error(const tt_scan *s);
long tt_scan_averaged_collapsed(const tt_scan *s, long *line, long *pixel);
long tt_scan_averaged_outside(const tt_scan *s);
/* Clears those counts and the first pixel, so that they count the lines stepped from
 * now on: a caller that steps the scan pass after pass (tiptap live) warns of each pass
 * as tiptap scan of it would (tt_run_scan_end). */
void tt_scan_averaged_marks_clear(tt_scan *s);
/* Whether a scan of these parameters runs on the envelope tier: [solver] tier asks for
 * it and the scan allows it (Q 30 or more); else every cycle. */
int tt_scan_envelope_tier(const tt_scan_params *p);
/* The bytes a scan thread's envelope plans would hold (one per state dimension its
 * materials take, kept models included: 3.5 MB each with noise); 0 off that tier. */
double tt_scan_envelope_plans_bytes(const tt_scan_params *p);
/* Whether it runs on the averaged tier: [solver] tier asks for it and the scan allows
 * it (Q 30 or more, the drive within 5 % of resonance); else on the envelope tier's
 * terms (tt_scan_envelope_tier). */
int tt_scan_averaged_tier(const tt_scan_params *p);
double tt_scan_error_estimate(const tt_scan *s);
/* The solver setting the scan runs at. */
/* The cantilever it scans with (its modes, drives). */
const tt_cantilever *tt_scan_cantilever(const tt_scan *s);
const tt_solver *tt_scan_solver(const tt_scan *s);

/* The channels a scan of p holds beyond those it asks for: the estimate's height,
 * error and phase, so that a companion covering a whole line of independent lines
 * compares the image's own line instead of running it again (the noisy blend's 16
 * lines: 78,000 companion cycles of 156,000), where they are small (at most
 * TT_SCAN_KEPT_PIXELS pixels: up to 4 MB a channel and direction); tt_scan_image
 * returns none of them. */
#define TT_SCAN_KEPT_PIXELS 262144
unsigned tt_scan_kept_channels(const tt_scan_params *p);

/* The setting of the companion run every command's error estimate comes from: a
 * hundred times tighter tolerance (not below 1e-14), rk4 four times the steps. */
tt_solver tt_companion_solver(const tt_solver *s);

/* The estimated error of the images, from a companion run where the image is hardest:
 * the line with the largest height step between neighbouring pixels (the profile line
 * on a flat image), scanned again at tt_companion_solver's setting and compared with
 * the image; each figure is twice the largest or rms difference over the pixels
 * compared. The companion spends at most TT_ESTIMATE_SHARE of the scan's work (its
 * integrator steps, accepted and rejected, and one a cycle: the same on any machine and
 * thread; on the averaged tier, whose slow flow takes no steps, of the cycles it
 * integrated): where that does not cover the line, it runs stretches of the trace, one
 * with the largest height step a quarter into it, one from that line's start (where it
 * engaged), and one with the first edge of each ordered pair of materials the trace
 * meets (a soft matrix onto a stiff disk errs most; at most 8 stretches), each engaged
 * at its start on an equal share of the budget, and the run's setting runs the same
 * stretches beside them where they start inside the line (and for continuous lines and
 * the averaged tier), on two threads. With thermal or z piezo noise on the envelope tier
 * it runs whole lines, those where the error signal strays furthest, as many as the
 * share holds (at most 8): part of a line reads low there. */
#define TT_ESTIMATE_SHARE 0.2
typedef struct {
    double height_max, height_rms;       /* m */
    double amplitude_max, amplitude_rms; /* lock-in amplitude, relative to the free amplitude */
    double phase_max, phase_rms;         /* deg */
    long line;                           /* the line it ran */
    double tolerance;                    /* the companion's tolerance */
    long pixels, pixels_line;            /* pixels compared, of the line's (trace and retrace) */
    long first;                          /* the trace's first pixel it ran from */
    double step;                         /* the line's largest height step in reach, m */
    double signal;                       /* with noise (lines > 0): the line's largest error
                                          * signal, |amplitude - setpoint|, m, by which the
                                          * lines were chosen (0: by their height steps) */
    long cycles;                         /* the companion's cycles (all its lines) */
    long work;                           /* its work: integrator steps, accepted and
                                          * rejected, and one a cycle (all its lines) */
    long scan_work, budget;              /* the scan's lines' work, and the fifth of it the
                                          * companion may spend (0: counted in the cycles
                                          * the scan integrated, the averaged tier) */
    long lines;                          /* whole lines it ran, the hardest (noise that
                                          * moves the state, on the envelope tier; 0:
                                          * otherwise) */
    double seconds;                      /* its CPU time, s (its lines' threads) */
    long stretches;                      /* the stretches it ran (1: one, or the whole line) */
    int over;                            /* the whole line ran over TT_ESTIMATE_SHARE: a scan
                                          * too short for each stretch's settling, or
                                          * with noise for one whole line */
} tt_scan_error;

/* The images are untouched. Where a fifth of the scan's work does not reach each
 * stretch's settling and two pixels (a scan of a few lines), or with noise one whole
 * line, the whole hardest line runs, over the fifth (e->over says so), compared with
 * the image's own line where lines are independent. */
int tt_scan_estimate_error(tt_scan *s, tt_scan_error *e);
/* tt_scan_estimate_error in three parts, for a caller that runs the companion's lines
 * beside other work on its own threads: plan (the stretches, on the calling thread),
 * then each of tt_scan_estimate_jobs lines by tt_scan_estimate_job (on any thread, each
 * j once, concurrently with one another and with anything that only reads the scan),
 * then finish (the comparison; it frees the plan, as free does unfinished). The same
 * figures as tt_scan_estimate_error on any order and number of threads. */
typedef struct tt_scan_estimate tt_scan_estimate;
int tt_scan_estimate_plan(tt_scan *s, tt_scan_estimate **out);
int tt_scan_estimate_jobs(const tt_scan_estimate *e);
int tt_scan_estimate_job(tt_scan_estimate *e, int j);
int tt_scan_estimate_finish(tt_scan_estimate *e, tt_scan_error *out);
void tt_scan_estimate_free(tt_scan_estimate *e);
/* Whether the z piezo hit its range limits during the scan. */
int tt_scan_clamped(const tt_scan *s);
/* [tip] contact_geometry = local: the force laws built for the geometries the tip met,
 * over every thread (each builds its own; 0 for axis or a flat sample), and in *tables
 * (if not NULL) the adhesive tables rebuilt at an R_eff among them (the rest copies). */
long tt_scan_contact_laws_built(const tt_scan *s, long *tables);
/* The tip's dilation of the surface, made when the scan is (NULL for a point tip or a
 * flat surface). */
const tt_dilation *tt_scan_dilation(const tt_scan *s);

/* The scan's materials, in the order of tt_scan_params materials, and their names. */
size_t tt_scan_materials(const tt_scan *s);
const char *tt_scan_material_name(const tt_scan *s, size_t i);

/* How far the contact went in one material over the scan's trace and retrace cycles. */
typedef struct {
    double indentation; /* the greatest penetration, m (NaN: none tracked, as without
                         * the peak_force and indentation channels; <= 0: no contact) */
    double radius;      /* the contact radius there, m (NaN without contact) */
    double tip_radius;  /* the radius of the material's force law, m */
} tt_contact_extent;

/* Fills e for material i; returns 1 when that contact is beyond the force laws'
 * small-contact assumption (tt_contact_beyond_validity), else 0. Deterministic: the
 * greatest over every line, whichever thread ran it. */
int tt_scan_contact_extent(const tt_scan *s, size_t i, tt_contact_extent *e);

TT_END_DECLS
#endif
