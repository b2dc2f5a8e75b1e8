/* The configuration layer's imaging sections: [scan], [lockin], [feedback] ([surface]: read_surface.c)
 * (see include/tiptap/config/config.h). */
#include "tiptap/config/config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "scene_private.h"
#include "tiptap/instrument/tip.h"
#include "tiptap/io/files.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

int tt_config_raster(const tt_scene *s, tt_raster *r)
{
    int rc;
    memset(r, 0, sizeof *r);
    if ((rc = tt_scene_get_double(s, "scan", NULL, "size", &r->size_x)) ||
        (rc = tt_scene_get_int(s, "scan", NULL, "pixels", &r->pixels)) ||
        (rc = tt_scene_get_int(s, "scan", NULL, "lines", &r->lines)) ||
        (rc = tt_scene_get_double(s, "scan", NULL, "line_rate", &r->line_rate)) ||
        (rc = tt_scene_get_bool(s, "scan", NULL, "retrace", &r->retrace)))
        return rc;
    r->size_y = r->size_x;
    if (tt_scene_has(s, "scan", NULL, "size_y") &&
        (rc = tt_scene_get_double(s, "scan", NULL, "size_y", &r->size_y)))
        return rc;
    const char *fast = tt_scene_get_string(s, "scan", NULL, "fast_axis");
    r->fast_y = fast && strcmp(fast, "y") == 0;
    if ((rc = tt_scene_get_double(s, "scan", NULL, "angle", &r->angle)) ||
        (rc = tt_scene_get_double(s, "scan", NULL, "offset_x", &r->offset_x)))
        return rc;
    return tt_scene_get_double(s, "scan", NULL, "offset_y", &r->offset_y);
}

/* The measured image read and prepared once, before the run is estimated: a bad file,
 * crop or size is refused here in one line. */
static int check_measured(const tt_scene *s, tt_scan_params *p)
{
    const tt_raster *r = &p->raster;
    if (r->angle != 0 || r->offset_x != 0 || r->offset_y != 0)
        tt_raster_bounds(r, p->surface.visit);
    const int eroded = p->surface.type == TT_SURFACE_MEASURED && p->surface.measured_tip != TT_TIP_POINT;
    if ((p->channels & TT_CH_CERTAINTY) && !eroded)
        return tt_scene_fail(s, "scan", NULL, "channels",
                             "certainty is the certainty map of a measured image's erosion; it needs "
                             "[surface] type = measured with a measured_tip_shape");
    if (p->surface.type != TT_SURFACE_MEASURED)
        return TT_OK;
    /* the comparison with the input (and where the erosion is certain), unless the scene
     * chose its channels */
    if (!tt_scene_has(s, "scan", NULL, "channels"))
        p->channels |= TT_CH_TOPOGRAPHY | TT_CH_ARTEFACT | (eroded ? TT_CH_CERTAINTY : 0);
    return tt_scene_locate(s, tt_surface_check_measured(&p->surface, p->raster.size_x, p->raster.size_y));
}

/* A labels or threshold map read and built once, before the run is estimated. */
static int check_map_image(const tt_scene *s, tt_scan_params *p)
{
    return tt_scene_locate(s, tt_surface_check_map_image(&p->surface, p->materials, p->nmaterials,
                                                         p->raster.size_x, p->raster.size_y));
}

int tt_config_lockin(const tt_scene *s, tt_lockin_params *p)
{
    long spp, order, harm, ppb;
    int rc;
    memset(p, 0, sizeof *p);
    if ((rc = tt_scene_get_double(s, "lockin", NULL, "time_constant", &p->time_constant)) ||
        (rc = tt_scene_get_int(s, "lockin", NULL, "filter_order", &order)) ||
        (rc = tt_scene_get_int(s, "lockin", NULL, "samples_per_period", &spp)) ||
        (rc = tt_scene_get_int(s, "lockin", NULL, "harmonics", &harm)) ||
        (rc = tt_scene_get_int(s, "lockin", NULL, "periods_per_block", &ppb)))
        return rc;
    if (2 * harm >= spp)
        return tt_scene_fail(s, "lockin", NULL, "harmonics",
                             "%ld harmonics need more than %ld samples per period "
                             "([lockin] samples_per_period is %ld)",
                             harm, 2 * harm, spp);
    p->samples_per_period = (int)spp;
    p->filter_order = (int)order;
    p->periods_per_block = (int)ppb;
    p->harmonics = (int)harm;
    return TT_OK;
}

int tt_config_feedback(const tt_scene *s, double A0, tt_feedback_params *p)
{
    tt_dim dim;
    int rc;
    if ((rc = tt_scene_get_quantity(s, "feedback", NULL, "setpoint", &p->setpoint, &dim)) ||
        (rc = tt_scene_get_double(s, "feedback", NULL, "proportional_gain", &p->kp)) ||
        (rc = tt_scene_get_double(s, "feedback", NULL, "integral_gain", &p->ki)) ||
        (rc = tt_scene_get_double(s, "feedback", NULL, "z_range", &p->z_range)))
        return rc;
    if (dim == TT_DIM_FRACTION) {
        if (!(p->setpoint > 0 && p->setpoint < 1))
            return tt_scene_fail(s, "feedback", NULL, "setpoint",
                                 "a percentage must lie between 0 and 100 %% (exclusive)");
        p->setpoint *= A0;
    } else if (!(p->setpoint > 0 && p->setpoint < A0)) {
        return tt_scene_fail_set(s, (const char *const[]){"feedback.setpoint", "cantilever.free_amplitude", NULL},
                                 "setpoint %g nm must lie between 0 and the free amplitude (%g nm)",
                                 p->setpoint * 1e9, A0 * 1e9);
    }
    return TT_OK;
}

/* The loss per mechanism: recorded by default where a material is viscous (a scene
 * that chose its channels gets what it named); the averaged tier books the loss as a
 * whole, so asking it for them is refused. */
static int loss_channels(const tt_scene *s, tt_scan_params *p, int chosen)
{
    const int averaged = tt_scan_averaged_tier(p);
    if (chosen && averaged && (p->channels & TT_CH_LOSSES))
        return tt_scene_fail(s, "scan", NULL, "channels",
                             "the averaged tier books the tip-sample loss as a whole; expected "
                             "[solver] tier = every or envelope for dissipation_hysteresis, "
                             "dissipation_damping and dissipation_viscous");
    for (size_t i = 0; i < p->nmaterials && !chosen && !averaged; i++)
        if (tt_material_viscous(&p->materials[i]))
            p->channels |= TT_CH_LOSSES;
    return TT_OK;
}

/* [scan] channels, settle_cycles, profile_line, and what the channels need of the
 * raster and the lock-in. */
static int read_scan_keys(const tt_scene *s, tt_scan_params *p)
{
    char why[256];
    int rc;
    const char *ch = tt_scene_get_string(s, "scan", NULL, "channels");
    if (tt_scan_channels_parse(ch ? ch : "height", &p->channels, why, sizeof why) != 0)
        return tt_scene_fail(s, "scan", NULL, "channels", "%s", why);
    if ((rc = loss_channels(s, p, tt_scene_has(s, "scan", NULL, "channels"))))
        return rc;
    if ((rc = tt_scene_get_int(s, "scan", NULL, "settle_cycles", &p->settle_cycles)) ||
        (rc = tt_scene_get_int(s, "scan", NULL, "profile_line", &p->profile_line)))
        return rc;
    if (p->profile_line >= p->raster.lines)
        return tt_scene_fail(s, "scan", NULL, "profile_line", "%ld is past the last line (%ld)",
                             p->profile_line, p->raster.lines - 1);
    int need = 1;
    for (int c = 0; c < TT_CH_COUNT; c++)
        if ((p->channels & (1u << c)) && tt_scan_channel_harmonic(c) > need)
            need = tt_scan_channel_harmonic(c);
    if (need > p->lockin.harmonics)
        return tt_scene_fail(s, "scan", NULL, "channels",
                             "harmonic%d needs [lockin] harmonics = %d or more (it is %d)", need, need,
                             p->lockin.harmonics);
    return TT_OK;
}

/* The most drive cycles one way along a line: a raster slower than this would run for
 * days a line (and beyond about 1e18 the count overflows). */
#define TT_MAX_CYCLES_PER_DIRECTION 1e9

/* The raster runs whole drive cycles, at least one a pixel each way: a line rate that
 * asks for fewer (or absurdly many) would silently run at another rate. */
static int check_line_rate(const tt_scene *s, const tt_scan_params *p)
{
    const tt_raster *r = &p->raster;
    double fd = p->cantilever.fd;
    double cycles = fd / (2 * r->line_rate); /* each way along a line */
    double fastest = fd / (2 * (double)r->pixels);
    double slowest = fd / (2 * TT_MAX_CYCLES_PER_DIRECTION);
    if (!(cycles >= (double)r->pixels - 0.5))
        return tt_scene_fail(s, "scan", NULL, "line_rate",
                             "%g Hz is faster than the raster can run: a line of %ld pixels "
                             "needs at least one drive cycle a pixel each way, at %g kHz a line "
                             "rate of at most %g Hz (it would be %.3g cycles a pixel); "
                             "for [lockin] periods_per_block = %d a pixel needs that many: at most %g Hz",
                             r->line_rate, r->pixels, fd * 1e-3, fastest,
                             cycles / (double)r->pixels, p->lockin.periods_per_block,
                             fastest / (p->lockin.periods_per_block > 1 ? p->lockin.periods_per_block : 1));
    if (!(cycles <= TT_MAX_CYCLES_PER_DIRECTION))
        return tt_scene_fail(s, "scan", NULL, "line_rate",
                             "%g Hz is slower than the raster can run: %.3g drive cycles each way "
                             "along a line, at most %g; at %g kHz a line rate of at least %g Hz",
                             r->line_rate, cycles, TT_MAX_CYCLES_PER_DIRECTION, fd * 1e-3, slowest);
    return TT_OK;
}

/* The first cycle of this direction's line that falls in pixel px (of the trace), as
 * the raster assigns them (tt_raster_pixel). */
static long first_cycle(const tt_raster *r, long nc, long px)
{
    if (px >= r->pixels)
        return nc;
    long k = (long)ceil((double)px * (double)nc / (double)r->pixels);
    while (k > 0 && tt_raster_pixel(r, 0, nc, k - 1) >= px)
        k--;
    while (k < nc && tt_raster_pixel(r, 0, nc, k) < px)
        k++;
    return k;
}

/* The lock-in's amplitude and phase (and the feedback's update) come once a block of
 * periods_per_block cycles and go to the pixel of the block's last cycle: a pixel of
 * fewer cycles may get none, a NaN pixel in a run that ends with exit 0. */
static int check_block(const tt_scene *s, const tt_scan_params *p)
{
    const tt_raster *r = &p->raster;
    long nc = tt_raster_cycles_per_direction(r, p->cantilever.T), fewest = nc;
    for (long px = 0; px < r->pixels && fewest >= p->lockin.periods_per_block; px++) {
        long n = first_cycle(r, nc, px + 1) - first_cycle(r, nc, px);
        if (n < fewest)
            fewest = n;
    }
    if (fewest >= p->lockin.periods_per_block)
        return TT_OK;
    double fd = p->cantilever.fd;
    /* named on a key the scene set: the line rate, else the pixels, the block, the drive */
    static const char *const keys[] = {"scan.line_rate", "scan.pixels", "lockin.periods_per_block",
                                       "cantilever.drive_frequency", NULL};
    char lead[128];
    if (tt_scene_has(s, "scan", NULL, "line_rate"))
        snprintf(lead, sizeof lead, "%g Hz gives", r->line_rate);
    else
        snprintf(lead, sizeof lead, "[scan] line_rate = %g Hz gives", r->line_rate);
    return tt_scene_fail_set(s, keys,
                         "%s a pixel as few as %ld drive cycle%s (%ld each way along a line of [scan] "
                         "pixels = %ld at %g kHz), fewer than [lockin] periods_per_block = %d: "
                         "such a pixel may get no lock-in block, so no amplitude or phase; at "
                         "most %g Hz, fewer pixels or a smaller periods_per_block",
                         lead, fewest, fewest == 1 ? "" : "s", nc, r->pixels, fd * 1e-3,
                         p->lockin.periods_per_block,
                         fd / (2.0 * (double)r->pixels * p->lockin.periods_per_block));
}

/* A sphere narrower than a pixel falls between the lines or within one pixel: the
 * image cannot show it (and a radius of picometres sized a grid of gigabytes). */
static int check_particles(const tt_scene *s, const tt_scan_params *p)
{
    if (p->surface.type != TT_SURFACE_PARTICLES)
        return TT_OK;
    const tt_raster *r = &p->raster;
    double px = (r->fast_y ? r->size_y : r->size_x) / (double)r->pixels;
    double ln = (r->fast_y ? r->size_x : r->size_y) / (double)r->lines;
    double pitch = fmax(px, ln);
    if (!(2 * p->surface.particle_radius >= pitch))
        return tt_scene_fail_set(s, (const char *const[]){"surface.particle_radius", "scan.size", "scan.size_y",
                                                          "scan.pixels", "scan.lines", NULL},
                             "spheres of %g nm across are narrower than a pixel of the image "
                             "(%g nm); it cannot resolve them: the radius must be at least %g nm, "
                             "or scan a smaller [scan] size or more pixels and lines",
                             2 * p->surface.particle_radius * 1e9, pitch * 1e9, pitch / 2 * 1e9);
    return TT_OK;
}

size_t tt_config_scan_unused(const tt_scan_params *p, size_t *idx, size_t max)
{
    size_t k = 0;
    for (size_t i = 0; i < p->nmaterials; i++) {
        const tt_material *m = &p->materials[i];
        int used;
        switch (p->surface.map) {
        case TT_MAP_UNIFORM: used = i == 0; break;
        case TT_MAP_PNG: used = m->map_grey >= 0 || m->map_rgb >= 0; break;
        case TT_MAP_LABELS: used = m->map_grey >= 0; break;
        default: used = (int)i == p->surface.materials[0] || (int)i == p->surface.materials[1];
        }
        if (!used && k++ < max)
            idx[k - 1] = i;
    }
    return k;
}

int tt_config_noise(const tt_scene *s, const tt_solver *solver, double fd, tt_scan_noise *n)
{
    int rc;
    long seed, points;
    if ((rc = tt_scene_get_int(s, "noise", NULL, "seed", &seed)) ||
        (rc = tt_scene_get_int(s, "noise", NULL, "points", &points)) ||
        (rc = tt_scene_get_double(s, "noise", NULL, "temperature", &n->temperature)) ||
        (rc = tt_scene_get_double(s, "noise", NULL, "detector", &n->detector)) ||
        (rc = tt_scene_get_double(s, "noise", NULL, "z_piezo", &n->z_piezo)) ||
        (rc = tt_scene_get_double(s, "noise", NULL, "z_piezo_bandwidth", &n->z_bandwidth)))
        return rc;
    n->seed = (uint64_t)seed;
    n->points = (int)points;
    if (n->temperature > 0 && solver->method == TT_METHOD_RK4 && solver->steps_per_cycle % n->points)
        return tt_scene_fail(s, "noise", NULL, "points",
                             "rk4's steps_per_cycle (%d) must be a multiple of it (%d)",
                             solver->steps_per_cycle, n->points);
    /* the z piezo's noise is drawn once per drive cycle (linear between): its band must
     * lie below that rate's Nyquist frequency */
    static const char *const band[] = {"noise.z_piezo_bandwidth", "cantilever.drive_frequency",
                                       "cantilever.resonance_frequency", NULL};
    if (n->z_piezo > 0 && n->z_bandwidth > 0.5 * fd)
        return tt_scene_fail_set(s, band,
                                 "the z piezo's noise bandwidth (%.4g kHz) is above half the drive "
                                 "frequency (%.4g kHz): the noise is drawn once per drive cycle",
                                 n->z_bandwidth * 1e-3, 0.5e-3 * fd);
    return TT_OK;
}

/* [noise] and [scan] lines_mode. */
static int read_noise(const tt_scene *s, tt_scan_params *p)
{
    int rc = tt_config_noise(s, &p->solver, p->cantilever.fd, &p->noise);
    if (rc)
        return rc;
    const char *mode = tt_scene_get_string(s, "scan", NULL, "lines_mode");
    p->continuous = mode && strcmp(mode, "continuous") == 0;
    return TT_OK;
}

/* Bimodal imaging's needs: mode 2's channels a drive of mode 2, and the second lock-in
 * its mixing's sum frequency (2 f2) below the samples' Nyquist frequency. */
static int check_bimodal(const tt_scene *s, const tt_scan_params *p)
{
    const tt_cantilever *c = &p->cantilever;
    if ((p->channels & (TT_CH_AMPLITUDE2 | TT_CH_PHASE2)) && !(c->A2 > 0))
        return tt_scene_fail(s, "scan", NULL, "channels",
                             "amplitude_2 and phase_2 need mode 2 driven: expected [cantilever] "
                             "mode2_free_amplitude (and modes = 2 or more)");
    if (c->A2 > 0 && !(p->lockin.samples_per_period > 4 * c->ratio2))
        return tt_scene_fail(s, "lockin", NULL, "samples_per_period",
                             "%d: mode 2's drive at %g times the first needs more than %g",
                             p->lockin.samples_per_period, c->ratio2, 4 * c->ratio2);
    return TT_OK;
}

/* The envelope and averaged tiers model one mode: a cantilever of more than one runs
 * every cycle. A sample whose surface is a state of its own (relaxation arms) runs on
 * both: the envelope tier's plans follow the law's states (scan_worker.c), the averaged
 * tier's tables take the state's periodic cycle (src/solver/averaged_arms.c). */
static int check_tier_modes(const tt_scene *s, const tt_scan_params *p)
{
    if (p->solver.tier == TT_TIER_EVERY || p->cantilever.modes <= 1)
        return TT_OK;
    return tt_scene_fail(s, "solver", NULL, "tier",
                         "%s does not serve [cantilever] modes = %d yet (its models are of "
                         "one mode): set tier = every",
                         tt_tier_name(p->solver.tier), p->cantilever.modes);
}

/* [tip] contact_geometry: local keys each cycle's law by the geometry, which only the
 * every-cycle tier follows (the envelope and averaged tiers key their models and tables
 * on the material). */
static int read_contact_geometry(const tt_scene *s, tt_scan_params *p)
{
    const char *g = tt_scene_get_string(s, "tip", NULL, "contact_geometry");
    p->local_geometry = g && strcmp(g, "local") == 0;
    if (p->local_geometry && p->solver.tier != TT_TIER_EVERY)
        return tt_scene_fail(s, "tip", NULL, "contact_geometry",
                             "local runs on the every-cycle tier only (the %s tier keys its "
                             "models on the material, not on the law of each slope): expected "
                             "[solver] tier = every",
                             tt_tier_name(p->solver.tier));
    return TT_OK;
}

int tt_config_scan(const tt_scene *s, tt_scan_params *p)
{
    memset(p, 0, sizeof *p);
    tt_material *m = NULL;
    size_t n = 0;
    int rc;
    if ((rc = tt_config_cantilever(s, &p->cantilever)) || (rc = tt_solver_from_scene(&p->solver, s)) ||
        (rc = tt_config_materials(s, &m, &n)))
        return rc;
    p->materials = m;
    p->nmaterials = n;
    /* the lock-in first: the line rate's bound names its block */
    if ((rc = tt_config_raster(s, &p->raster)) || (rc = tt_config_lockin(s, &p->lockin)) ||
        (rc = check_line_rate(s, p)) || (rc = check_block(s, p)) || (rc = read_scan_keys(s, p)) ||
        (rc = read_noise(s, p)) ||
        (rc = tt_config_feedback(s, p->cantilever.A0, &p->feedback)) ||
        (rc = tt_config_surface(s, m, n, &p->surface)) || (rc = check_particles(s, p)) ||
        (rc = check_measured(s, p)) || (rc = check_map_image(s, p)) ||
        (rc = tt_config_tip_shape(s, &p->tip)) || (rc = tt_config_instrument(s, &p->instrument)) ||
        (rc = check_tier_modes(s, p)) || (rc = check_bimodal(s, p)) ||
        (rc = read_contact_geometry(s, p))) {
        tt_config_scan_free(p);
        return rc;
    }
    p->lockin.drive_frequency = p->cantilever.fd;
    return TT_OK;
}

void tt_config_scan_free(tt_scan_params *p)
{
    free((void *)p->materials);
    p->materials = NULL;
    p->nmaterials = 0;
}

int tt_config_scan_alloc(tt_scan **out, const tt_scene *s)
{
    tt_scan_params p;
    *out = NULL;
    int rc = tt_config_scan(s, &p);
    if (rc)
        return rc;
    rc = tt_scene_locate(s, tt_scan_alloc(out, &p));
    tt_config_scan_free(&p);
    return rc;
}

int tt_config_surface_alloc(tt_surface **out, const tt_scene *s, double size_x, double size_y)
{
    tt_material *m = NULL;
    size_t n = 0;
    tt_surface_params p;
    *out = NULL;
    int rc;
    if ((rc = tt_config_materials(s, &m, &n)) || (rc = tt_config_surface(s, m, n, &p)) ||
        (rc = tt_scene_locate(s, tt_surface_alloc(out, &p, m, n, size_x, size_y)))) {
        free(m);
        return rc;
    }
    free(m);
    return TT_OK;
}

void tt_config_note_inputs(const tt_scene *s)
{
    for (size_t i = 0; i < s->nfiles; i++)
        tt_input_note(s->files[i], "scene file");
    static const char *const keys[] = {"png", "map_png", "image", "map_image"};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
        char path[4096];
        if (tt_scene_has(s, "surface", NULL, keys[i]) &&
            tt_scene_get_path(s, "surface", NULL, keys[i], path, sizeof path) == TT_OK)
            tt_input_note(path, i < 2 ? "PNG map" : i == 2 ? "height image" : "map image");
    }
}
