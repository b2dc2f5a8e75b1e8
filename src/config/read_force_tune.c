/* The [force] and [tune] sections (see include/tiptap/config/read_force_tune.h). */
#include "tiptap/config/read_force_tune.h"

#include <math.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/config/solver_scene.h"
#include "tiptap/util/error.h"

/* The tune's longest record in samples (8 bytes each): 2e8 is 1.6 GB. */
#define TUNE_MAX_SAMPLES 2e8

int tt_config_force(const tt_scene *s, tt_force_params *p)
{
    memset(p, 0, sizeof *p);
    int rc;
    tt_cantilever c;
    p->material = tt_scene_get_string(s, "force", NULL, "material");
    if ((rc = tt_scene_get_double(s, "force", NULL, "to", &p->to)) ||
        (rc = tt_scene_get_double(s, "force", NULL, "speed", &p->speed)) ||
        (rc = tt_scene_get_double(s, "force", NULL, "dwell", &p->dwell)) ||
        (rc = tt_scene_get_int(s, "force", NULL, "samples", &p->samples)) ||
        (rc = tt_config_cantilever(s, &c)))
        return rc;
    int has_from = tt_scene_has(s, "force", NULL, "from"), has_range = tt_scene_has(s, "force", NULL, "range");
    if (has_from && has_range)
        return tt_scene_fail(s, "force", NULL, "range", "give from or range, not both");
    if (has_range) {
        double range;
        if ((rc = tt_scene_get_double(s, "force", NULL, "range", &range)))
            return rc;
        p->from = p->to + range;
    } else if ((rc = tt_scene_get_double(s, "force", NULL, "from", &p->from)))
        return rc;
    if (!(p->from > p->to))
        return tt_scene_fail(s, "force", NULL, has_range ? "range" : "from",
                             "the ramp must start farther from the sample than it turns (from %.4g nm, "
                             "to %.4g nm)", p->from * 1e9, p->to * 1e9);
    /* whole drive periods a leg: the solver's cycles */
    double leg = ceil((p->from - p->to) / (p->speed * c.T) - 1e-9), dwell = round(p->dwell / c.T);
    if (2 * leg + dwell > 1e9)
        return tt_scene_fail(s, "force", NULL, "speed",
                             "the ramp would take %.3g drive periods (more than 1e9): a faster ramp or a "
                             "shorter range", 2 * leg + dwell);
    p->leg_periods = leg < 1 ? 1 : (long)leg;
    p->dwell_periods = (long)dwell;
    return TT_OK;
}

int tt_config_tune_duration(const tt_scene *s, double *duration)
{
    return tt_scene_get_double(s, "tune", NULL, "duration", duration);
}

int tt_config_tune(const tt_scene *s, tt_tune_params *p)
{
    memset(p, 0, sizeof *p);
    int rc;
    double bw;
    tt_cantilever c;
    tt_solver solver;
    tt_scan_noise noise;
    if ((rc = tt_scene_get_double(s, "tune", NULL, "duration", &p->duration)) ||
        (rc = tt_scene_get_int(s, "tune", NULL, "samples_per_cycle", &p->samples_per_cycle)) ||
        (rc = tt_scene_get_double(s, "tune", NULL, "bin_width", &bw)) || (rc = tt_config_cantilever(s, &c)) ||
        (rc = tt_solver_from_scene(&solver, s)) || (rc = tt_config_noise(s, &solver, c.fd, &noise)))
        return rc;
    if (!(noise.temperature > 0))
        return tt_scene_fail(s, "noise", NULL, "temperature",
                             "tiptap tune needs the thermal force: a temperature above 0 K, such as 300 K");
    const double fs = (double)p->samples_per_cycle * c.fd, cycles = ceil(p->duration * c.fd);
    /* every mode's peak and its fit's window below Nyquist: 2.5 samples a period of the
     * highest mode (unfolded, the images are a correction, not the peak) */
    if (c.modes > 1 && fs < 2.5 * c.mode_f[c.modes - 1]) {
        double need = ceil(2.5 * c.mode_f[c.modes - 1] / c.fd);
        return tt_scene_fail(s, "tune", NULL, "samples_per_cycle",
                             "%ld samples a drive period put Nyquist at %.4g kHz, below mode %d's "
                             "%.4g kHz with room for its peak: at least %.0f",
                             p->samples_per_cycle, 0.5e-3 * fs, c.modes, 1e-3 * c.mode_f[c.modes - 1], need);
    }
    const double n = cycles * (double)p->samples_per_cycle;
    if (n > TUNE_MAX_SAMPLES)
        return tt_scene_fail(s, "tune", NULL, "duration",
                             "%.4g samples; at most %.0e (a shorter record or fewer samples_per_cycle)", n,
                             TUNE_MAX_SAMPLES);
    /* the shortest power of two giving at most the bin width */
    if (!(bw > 0))
        bw = c.f0 / (16 * c.Q);
    size_t l = 16;
    while ((double)l < fs / bw && l < ((size_t)1 << 30))
        l *= 2;
    if (n < 4.5 * (double)l)
        return tt_scene_fail(s, "tune", NULL, "duration",
                             "the record (%.4g s) holds fewer than 8 half-overlapping segments of "
                             "%.4g s (a bin width of %.4g Hz): at least %.4g s, or a wider bin_width",
                             n / fs, (double)l / fs, fs / (double)l, 4.5 * (double)l / fs);
    p->cycles = (long)cycles;
    p->segment = l;
    return TT_OK;
}
