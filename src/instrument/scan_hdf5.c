/* A scan as HDF5 in the layout of docs/hdf5.md (see include/tiptap/instrument/
 * scan_hdf5.h). */
#include "tiptap/instrument/scan_hdf5.h"

#include <stdio.h>
#include <stdlib.h>

#include "scan_nexus.h"
#include "tiptap/util/error.h"

/* The pyNSID release whose reader (pyNSID.io.hdf_utils.check_if_main) these datasets
 * satisfy: its main datasets carry this as pyNSID_version. */
#define NSID_VERSION "0.0.7.2"

/* What channel() writes beside the image: the group's metadata pairs and the scan. */
typedef struct {
    const tt_scan *s;
    const char *const *keys, *const *values;
    size_t n;
} meta;

/* The pixel centres of n pixels over size metres. */
static int centres(tt_h5 *f, const char *path, long n, double size)
{
    double *c = malloc((size_t)n * sizeof *c);
    if (!c)
        return tt_error_nomem("the HDF5 file's %ld pixel positions", n);
    for (long i = 0; i < n; i++)
        c[i] = ((double)i + 0.5) * size / (double)n;
    size_t dim = (size_t)n;
    int rc = tt_h5_doubles(f, path, 1, &dim, c);
    free(c);
    return rc;
}

/* A spatial dimension of a channel: its dataset, a scale with its NSID attributes. */
static int spatial(tt_h5 *f, const char *chan, const char *axis, long n, double size)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", chan, axis);
    int rc;
    if ((rc = centres(f, path, n, size)) || (rc = tt_h5_scale(f, path, axis)) ||
        (rc = tt_h5_attr_text(f, path, "name", axis)) || (rc = tt_h5_attr_text(f, path, "units", "m")) ||
        (rc = tt_h5_attr_text(f, path, "quantity", axis[0] == 'x' ? "x position" : "y position")))
        return rc;
    return tt_h5_attr_text(f, path, "dimension_type", "SPATIAL");
}

/* The run's figures (tiptap scan's summary on stderr) as attributes of group, each
 * name prefix + figure ("run." on the measurement, "" in a channel's metadata). */
static int figures(tt_h5 *f, const char *group, const char *prefix, const tt_scan *s)
{
    static const char *const name[] = {"lines_finished", "lines_total", "fast_axis", "profile_line",
                                       "instrument_time_s", "cycles", "cycles_integrated",
                                       "energy_balance", "z_clamped"};
    char k[9][64];
    for (int i = 0; i < 9; i++)
        snprintf(k[i], sizeof k[i], "%s%s", prefix, name[i]);
    int rc;
    if ((rc = tt_h5_attr_long(f, group, k[0], tt_scan_lines_done(s))) ||
        (rc = tt_h5_attr_long(f, group, k[1], tt_scan_lines(s))) ||
        (rc = tt_h5_attr_text(f, group, k[2], tt_scan_fast_y(s) ? "y" : "x")) ||
        (rc = tt_h5_attr_long(f, group, k[3], tt_scan_profile_line(s))) ||
        (rc = tt_h5_attr_double(f, group, k[4], tt_scan_instrument_time(s))) ||
        (rc = tt_h5_attr_long(f, group, k[5], tt_scan_cycles(s))) ||
        (rc = tt_h5_attr_long(f, group, k[6], tt_scan_cycles_integrated(s))) ||
        (rc = tt_h5_attr_double(f, group, k[7], tt_scan_error_estimate(s))))
        return rc;
    return tt_h5_attr_long(f, group, k[8], tt_scan_clamped(s));
}

/* A channel's metadata as pyNSID lays out a sidpy.Dataset's dictionaries, groups of
 * attributes beside the image that its reader hands to sidpy: original_metadata the
 * scene's keys (as the GSF headers), metadata the run's figures. The first channel's
 * groups are written, the others' are hard links to them (stored once). */
static int channel_meta(tt_h5 *f, const char *group, const char *chan, int number, const meta *m)
{
    static const char *const name[] = {"original_metadata", "metadata"};
    char path[2][512], first[2][512];
    for (int i = 0; i < 2; i++) {
        snprintf(path[i], sizeof path[i], "%s/%s", chan, name[i]);
        snprintf(first[i], sizeof first[i], "%s/Channel_000/%s", group, name[i]);
    }
    int rc;
    if (number > 0)
        return (rc = tt_h5_link(f, first[0], path[0])) ? rc : tt_h5_link(f, first[1], path[1]);
    rc = tt_h5_group(f, path[0]);
    for (size_t i = 0; i < m->n && !rc; i++)
        rc = tt_h5_attr_text(f, path[0], m->keys[i], m->values[i]);
    if (!rc)
        rc = tt_h5_group(f, path[1]);
    return rc ? rc : figures(f, path[1], "", m->s);
}

/* Channel ch's image in direction r as group/Channel_NNN/NAME_DIRECTION, an NSID main
 * dataset. */
static int channel(tt_h5 *f, const char *group, int number, const meta *m, int ch, int r)
{
    const tt_scan *s = m->s;
    char chan[256], data[512], title[128], x[512], y[512];
    const char *name = tt_scan_channel_name(ch), *dir = r ? "retrace" : "trace";
    long xres = tt_scan_xres(s), yres = tt_scan_yres(s);
    size_t dims[2] = {(size_t)yres, (size_t)xres};
    snprintf(chan, sizeof chan, "%s/Channel_%03d", group, number);
    snprintf(data, sizeof data, "%s/%s_%s", chan, name, dir);
    snprintf(title, sizeof title, "%s (%s)", name, dir);
    snprintf(x, sizeof x, "%s/x", chan);
    snprintf(y, sizeof y, "%s/y", chan);
    int rc;
    if ((rc = tt_h5_group(f, chan)) || (rc = tt_h5_doubles(f, data, 2, dims, tt_scan_image(s, ch, r))) ||
        (rc = spatial(f, chan, "y", yres, tt_scan_size_y(s))) ||
        (rc = spatial(f, chan, "x", xres, tt_scan_size_x(s))) || (rc = tt_h5_attach(f, data, y, 0, "y")) ||
        (rc = tt_h5_attach(f, data, x, 1, "x")) || (rc = tt_h5_attr_text(f, data, "title", title)) ||
        (rc = tt_h5_attr_text(f, data, "quantity", name)) ||
        (rc = tt_h5_attr_text(f, data, "units", tt_scan_channel_unit(ch))) ||
        (rc = tt_h5_attr_text(f, data, "direction", dir)) ||
        (rc = tt_h5_attr_long(f, data, "harmonic", tt_scan_channel_harmonic(ch))) ||
        (rc = tt_h5_attr_text(f, data, "data_type", "IMAGE")) ||
        (rc = tt_h5_attr_text(f, data, "modality", "tapping-mode AFM (simulated)")) ||
        (rc = tt_h5_attr_text(f, data, "source", "tiptap scan")) ||
        (rc = tt_h5_attr_text(f, data, "main_data_name", title)) ||
        (rc = tt_h5_attr_text(f, data, "pyNSID_version", NSID_VERSION)))
        return rc;
    return channel_meta(f, group, chan, number, m);
}

int tt_scan_hdf5_group(tt_h5 *f, const char *group, const tt_scan *s, const char *const *keys,
                       const char *const *values, size_t n, const char *scene)
{
    char path[512];
    int rc = tt_h5_group(f, group);
    for (size_t i = 0; i < n && !rc; i++)
        rc = tt_h5_attr_text(f, group, keys[i], values[i]);
    if (!rc)
        rc = figures(f, group, "run.", s);
    snprintf(path, sizeof path, "%s/scene", group);
    if (!rc && scene)
        rc = tt_h5_text(f, path, scene);
    int number = 0;
    meta m = {s, keys, values, n};
    for (int ch = 0; ch < TT_CH_COUNT && !rc; ch++)
        for (int r = 0; r < 2 && !rc; r++)
            if (tt_scan_image(s, ch, r))
                rc = channel(f, group, number++, &m, ch, r);
    return rc;
}

int tt_scan_write_hdf5(const char *path, const tt_scan *s, const char *const *keys,
                       const char *const *values, size_t n, const char *scene)
{
    tt_h5 *f;
    int rc = tt_h5_create(&f, path);
    if (rc)
        return rc;
    if (!(rc = tt_h5_attr_text(f, "/", "file_kind", "tiptap scan")) &&
        !(rc = tt_h5_attr_text(f, "/", "layout", "tiptap HDF5 1 (docs/hdf5.md), after pycroscopy's NSID")))
        rc = tt_scan_hdf5_group(f, "/Measurement_000", s, keys, values, n, scene);
    /* the same images as a NeXus NXafm entry, linked (docs/hdf5.md) */
    if (!rc && !(rc = tt_h5_attr_text(f, "/", "default", "entry")))
        rc = tt_scan_nexus_entry(f, "/entry", "/Measurement_000", s, keys, values, n);
    int crc = tt_h5_close(f, rc == TT_OK);
    return rc ? rc : crc;
}
