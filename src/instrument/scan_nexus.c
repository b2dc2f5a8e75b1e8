/* A scan as a NeXus NXafm entry (see scan_nexus.h): the names and classes of FAIRmat's
 * NXafm application definition and the base classes it uses (NXspm_cantilever,
 * NXlockin, NXpid_controller, NXspm_scan_control, NXsample); the fields it requires are
 * listed, with the definition's commit, in tests/data/nxafm-required.txt. */
#include "scan_nexus.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

typedef struct {
    tt_h5 *f;
    const char *const *keys, *const *values;
    size_t n;
    char path[512];
} nx;

/* The scene's value of key, NULL if the scene has none. */
static const char *value(const nx *x, const char *key)
{
    for (size_t i = 0; i < x->n; i++)
        if (!strcmp(x->keys[i], key))
            return x->values[i];
    return NULL;
}

static const char *at(nx *x, const char *base, const char *name)
{
    snprintf(x->path, sizeof x->path, "%s/%s", base, name);
    return x->path;
}

/* The group base/name of NeXus class cls. */
static int group(nx *x, const char *base, const char *name, const char *cls)
{
    int rc = tt_h5_group(x->f, at(x, base, name));
    return rc ? rc : tt_h5_attr_text(x->f, x->path, "NX_class", cls);
}

static int text(nx *x, const char *base, const char *name, const char *v)
{
    return tt_h5_text(x->f, at(x, base, name), v);
}

/* A number field with its units attribute ("" for none). */
static int number(nx *x, const char *base, const char *name, double v, const char *units)
{
    int rc = tt_h5_doubles(x->f, at(x, base, name), 0, NULL, &v);
    return rc || !units[0] ? rc : tt_h5_attr_text(x->f, x->path, "units", units);
}

/* The scene's key as a number field in the units the scene writes it with ("40 N/m":
 * 40, units N/m); a key the scene lacks or a value that is not a number is left out. */
static int scene_number(nx *x, const char *base, const char *name, const char *key)
{
    const char *v = value(x, key);
    char *end;
    double d = v ? strtod(v, &end) : 0;
    if (!v || end == v)
        return TT_OK;
    while (*end == ' ')
        end++;
    return number(x, base, name, d, end);
}

static int instrument(nx *x, const char *entry, const tt_scan *s)
{
    char ins[256], hw[300], sw[300], cant[300], osc[400], lock[300], pos[300], zc[400], env[300], ctl[400], reg[500], mesh[500];
    snprintf(ins, sizeof ins, "%s/instrument", entry);
    snprintf(hw, sizeof hw, "%s/hardware", ins);
    snprintf(sw, sizeof sw, "%s/software", ins);
    snprintf(cant, sizeof cant, "%s/cantilever_spm", ins);
    snprintf(osc, sizeof osc, "%s/cantilever_oscillator", cant);
    snprintf(lock, sizeof lock, "%s/lockin_amplifier", ins);
    snprintf(pos, sizeof pos, "%s/positioner_spm", ins);
    snprintf(zc, sizeof zc, "%s/z_controller", pos);
    snprintf(env, sizeof env, "%s/scan_environment", ins);
    snprintf(ctl, sizeof ctl, "%s/scan_control", env);
    snprintf(reg, sizeof reg, "%s/scan_region", ctl);
    snprintf(mesh, sizeof mesh, "%s/mesh_scan", ctl);
    const char *version = value(x, "tiptap_version");
    int rc;
    if ((rc = group(x, entry, "instrument", "NXinstrument")) ||
        (rc = group(x, ins, "hardware", "NXfabrication")) ||
        (rc = text(x, hw, "vendor", "none: simulated by tiptap")) ||
        (rc = text(x, hw, "model", "tiptap tapping-mode AFM simulator")) ||
        (rc = group(x, ins, "software", "NXfabrication")) ||
        (rc = text(x, sw, "vendor", "tiptap")) ||
        (rc = text(x, sw, "model", version ? version : "")))
        return rc;
    /* the cantilever and its drive: the free amplitude the setpoint is a fraction of */
    if ((rc = group(x, ins, "cantilever_spm", "NXspm_cantilever")) ||
        (rc = scene_number(x, cant, "spring_constant", "cantilever.spring_constant")) ||
        (rc = scene_number(x, cant, "resonance_frequency", "cantilever.resonance_frequency")) ||
        (rc = scene_number(x, cant, "quality_factor", "cantilever.quality_factor")) ||
        (rc = scene_number(x, cant, "tip_radius", "tip.radius")) ||
        (rc = group(x, cant, "cantilever_oscillator", "NXspm_cantilever_oscillator")) ||
        (rc = scene_number(x, osc, "reference_amplitude", "cantilever.free_amplitude")) ||
        (rc = scene_number(x, osc, "reference_frequency", "cantilever.resonance_frequency")))
        return rc;
    /* the lock-in that demodulates the deflection at the drive */
    if ((rc = group(x, ins, "lockin_amplifier", "NXlockin")) ||
        (rc = scene_number(x, lock, "reference_frequency", "cantilever.resonance_frequency")) ||
        (rc = scene_number(x, lock, "time_constant", "lockin.time_constant")) ||
        (rc = scene_number(x, lock, "lp_filter_order_1", "lockin.filter_order")) ||
        (rc = number(x, lock, "harmonic_order_1", 1, "")))
        return rc;
    /* the z feedback: an amplitude setpoint (a fraction of the free amplitude) */
    if ((rc = group(x, ins, "positioner_spm", "NXspm_positioner")) ||
        (rc = group(x, pos, "z_controller", "NXpid_controller")) ||
        (rc = scene_number(x, zc, "setpoint", "feedback.setpoint")) ||
        (rc = scene_number(x, zc, "K_p", "feedback.proportional_gain")) ||
        (rc = scene_number(x, zc, "K_i", "feedback.integral_gain")) ||
        (rc = number(x, zc, "K_d", 0, "")) || (rc = scene_number(x, pos, "z_range", "feedback.z_range")))
        return rc;
    /* the scanned region from (0, 0) to (size x, size y), pixels and lines */
    if ((rc = group(x, ins, "scan_environment", "NXenvironment")) ||
        (rc = group(x, env, "scan_control", "NXspm_scan_control")) ||
        (rc = text(x, ctl, "scan_type", "mesh")) || (rc = group(x, ctl, "scan_region", "NXspm_scan_region")) ||
        (rc = number(x, reg, "scan_start_x", 0, "m")) || (rc = number(x, reg, "scan_start_y", 0, "m")) ||
        (rc = number(x, reg, "scan_end_x", tt_scan_size_x(s), "m")) ||
        (rc = number(x, reg, "scan_end_y", tt_scan_size_y(s), "m")) ||
        (rc = number(x, reg, "scan_range_x", tt_scan_size_x(s), "m")) ||
        (rc = number(x, reg, "scan_range_y", tt_scan_size_y(s), "m")) ||
        (rc = group(x, ctl, "mesh_scan", "NXspm_scan_pattern")) ||
        (rc = number(x, mesh, "scan_points_x", (double)tt_scan_xres(s), "")) ||
        (rc = number(x, mesh, "scan_points_y", (double)tt_scan_yres(s), "")))
        return rc;
    return scene_number(x, mesh, "line_rate", "scan.line_rate");
}

/* The sample: the scene's [surface] and [material NAME] keys as texts, as written. */
static int sample(nx *x, const char *entry)
{
    char smp[256];
    snprintf(smp, sizeof smp, "%s/sample", entry);
    const char *type = value(x, "surface.type");
    int rc = group(x, entry, "sample", "NXsample");
    if (!rc)
        rc = text(x, smp, "name", type ? type : "");
    if (!rc)
        rc = text(x, smp, "description", "simulated: tiptap's [surface] and [material NAME] scene sections");
    for (size_t i = 0; i < x->n && !rc; i++) {
        const char *k = x->keys[i];
        if (strncmp(k, "surface.", 8) && strncmp(k, "material.", 9))
            continue;
        rc = text(x, smp, k, x->values[i]);
    }
    return rc;
}

/* The NXdata: every image of measurement linked by its name, the first (the height
 * trace) the signal. */
static int data(nx *x, const char *entry, const char *measurement, const tt_scan *s)
{
    char d[256], src[512], dst[512];
    snprintf(d, sizeof d, "%s/data", entry);
    int rc = group(x, entry, "data", "NXdata"), number = 0;
    char signal[128] = "";
    for (int ch = 0; ch < TT_CH_COUNT && !rc; ch++)
        for (int r = 0; r < 2 && !rc; r++) {
            if (!tt_scan_image(s, ch, r))
                continue;
            const char *name = tt_scan_channel_name(ch), *dir = r ? "retrace" : "trace";
            snprintf(src, sizeof src, "%s/Channel_%03d/%s_%s", measurement, number++, name, dir);
            snprintf(dst, sizeof dst, "%s/%s_%s", d, name, dir);
            rc = tt_h5_link(x->f, src, dst);
            if (!signal[0])
                snprintf(signal, sizeof signal, "%s_%s", name, dir);
        }
    const char *axes[2] = {"y", "x"};
    for (int i = 0; i < 2 && !rc; i++) {
        snprintf(src, sizeof src, "%s/Channel_000/%s", measurement, axes[i]);
        rc = tt_h5_link(x->f, src, at(x, d, axes[i]));
    }
    if (rc || (rc = tt_h5_attr_text(x->f, d, "signal", signal)) ||
        (rc = tt_h5_attr_texts(x->f, d, "axes", 2, axes)) || (rc = tt_h5_attr_long(x->f, d, "y_indices", 0)))
        return rc;
    return tt_h5_attr_long(x->f, d, "x_indices", 1);
}

int tt_scan_nexus_entry(tt_h5 *f, const char *entry, const char *measurement, const tt_scan *s,
                        const char *const *keys, const char *const *values, size_t n)
{
    nx x = {f, keys, values, n, ""};
    int rc;
    if ((rc = tt_h5_group(f, entry)) || (rc = tt_h5_attr_text(f, entry, "NX_class", "NXentry")) ||
        (rc = tt_h5_attr_text(f, entry, "default", "data")) ||
        (rc = text(&x, entry, "definition", "NXafm")) || (rc = text(&x, entry, "experiment_technique", "AFM")) ||
        (rc = text(&x, entry, "scan_mode", "tapping mode")) ||
        (rc = text(&x, entry, "title", "tiptap scan (simulated tapping-mode AFM)")))
        return rc;
    if ((rc = instrument(&x, entry, s)) || (rc = sample(&x, entry)))
        return rc;
    return data(&x, entry, measurement, s);
}
