/* A force volume's files: GSF and PNG per map, a .gwy of all and an HDF5 file, through
 * the writers of a scan's folder (see include/tiptap/run/force_volume.h). */
#include "tiptap/run/force_volume.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/config/meta.h"
#include "tiptap/io/files.h"
#include "tiptap/io/gsf.h"
#include "tiptap/io/gwy.h"
#include "tiptap/io/hdf5.h"
#include "tiptap/io/image.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/error.h"
#include "tiptap/version.h"

/* The PNG's unit and scale for a map's SI unit. */
static double display_scale(int ch, const char **unit)
{
    const char *si = tt_force_volume_channel_unit(ch);
    *unit = strcmp(si, "m") == 0 ? "nm" : strcmp(si, "N") == 0 ? "nN" : si;
    return strcmp(si, "m") == 0 || strcmp(si, "N") == 0 ? 1e9 : 1;
}

int tt_force_volume_check_outputs(const char *dir, int hdf5)
{
    char path[4200];
    int rc = TT_OK;
    for (int k = 0; k < 2 * TT_FV_COUNT && !rc; k++) {
        snprintf(path, sizeof path, "%s/%s.%s", dir, tt_force_volume_channel_name(k / 2), k % 2 ? "png" : "gsf");
        rc = tt_output_check(path);
    }
    static const char *const other[] = {"force_volume.gwy", "scene.ini", "force_volume.h5"};
    for (int i = 0; i < 2 + hdf5 && !rc; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, other[i]);
        rc = tt_output_check(path);
    }
    return rc ? rc : tt_mkdirs(dir);
}

/* A spatial axis of a map's group: its pixel centres c (n of them) as a dimension scale. */
static int axis(tt_h5 *f, const char *chan, const char *name, const double *c, long n)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", chan, name);
    size_t dim = (size_t)n;
    int rc;
    if ((rc = tt_h5_doubles(f, path, 1, &dim, c)) || (rc = tt_h5_scale(f, path, name)) ||
        (rc = tt_h5_attr_text(f, path, "units", "m")))
        return rc;
    return tt_h5_attr_text(f, path, "dimension_type", "SPATIAL");
}

/* /Measurement_000 with the metadata as attributes, the scene, and a group per map
 * (docs/force-and-tune.md, "Force volume"). */
static int write_hdf5(const tt_force_volume *v, const tt_scene *s, const char *path, const tt_meta *m)
{
    tt_h5 *f;
    const char *g = "/Measurement_000";
    int rc = tt_h5_create(&f, path);
    if (rc)
        return rc;
    const long xres = tt_force_volume_xres(v), yres = tt_force_volume_yres(v);
    char *scene = tt_scene_write_string(s, NULL);
    /* the pixel centres, x's then y's */
    double *cx = malloc((size_t)(xres + yres) * sizeof *cx), *cy = cx ? cx + xres : NULL;
    if (!scene || !cx)
        rc = tt_error_nomem("the HDF5 file %s", path);
    for (long i = 0; cx && i < xres + yres; i++)
        cx[i] = i < xres ? ((double)i + 0.5) * tt_force_volume_size_x(v) / (double)xres
                         : ((double)(i - xres) + 0.5) * tt_force_volume_size_y(v) / (double)yres;
    if (!rc && !(rc = tt_h5_attr_text(f, "/", "file_kind", "tiptap force volume")))
        rc = tt_h5_group(f, g);
    for (size_t i = 0; i < m->n && !rc; i++)
        rc = tt_h5_attr_text(f, g, m->keys[i], m->values[i]);
    if (!rc)
        rc = tt_h5_text(f, "/Measurement_000/scene", scene);
    const size_t dims[2] = {(size_t)yres, (size_t)xres};
    for (int ch = 0; ch < TT_FV_COUNT && !rc; ch++) {
        char chan[256], data[512], x[512], y[512];
        const char *name = tt_force_volume_channel_name(ch);
        snprintf(chan, sizeof chan, "%s/Channel_%03d", g, ch);
        snprintf(data, sizeof data, "%s/%s", chan, name);
        snprintf(x, sizeof x, "%s/x", chan);
        snprintf(y, sizeof y, "%s/y", chan);
        if ((rc = tt_h5_group(f, chan)) || (rc = tt_h5_doubles(f, data, 2, dims, tt_force_volume_map(v, ch))) ||
            (rc = axis(f, chan, "y", cy, yres)) || (rc = axis(f, chan, "x", cx, xres)) || (rc = tt_h5_attach(f, data, y, 0, "y")) ||
            (rc = tt_h5_attach(f, data, x, 1, "x")) || (rc = tt_h5_attr_text(f, data, "quantity", name)) ||
            (rc = tt_h5_attr_text(f, data, "units", tt_force_volume_channel_unit(ch))) ||
            (rc = tt_h5_attr_text(f, data, "data_type", "IMAGE")))
            break;
        rc = tt_h5_attr_text(f, data, "source", "tiptap force --volume");
    }
    free(scene);
    free(cx);
    int crc = tt_h5_close(f, rc == TT_OK);
    return rc ? rc : crc;
}

int tt_force_volume_write(const tt_force_volume *v, const tt_scene *s, const char *dir, int hdf5,
                          int *written)
{
    char path[4200], vals[3][64], gwy_title[TT_FV_COUNT][128];
    snprintf(vals[0], sizeof vals[0], "%s", TIPTAP_VERSION_STRING);
    snprintf(vals[1], sizeof vals[1], "%ld", tt_force_volume_lines_done(v));
    snprintf(vals[2], sizeof vals[2], "%ld", tt_force_volume_lines(v));
    const char *keys[] = {"tiptap_version", "lines_finished", "lines_total"};
    const char *vp[] = {vals[0], vals[1], vals[2]};
    tt_meta m;
    int rc = tt_meta_scene(&m, s, keys, vp, 3);
    if (rc)
        return rc;
    const size_t xres = (size_t)tt_force_volume_xres(v), yres = (size_t)tt_force_volume_yres(v);
    const double sx = tt_force_volume_size_x(v), sy = tt_force_volume_size_y(v);
    tt_gwy_channel gch[TT_FV_COUNT];
    for (int ch = 0; ch < TT_FV_COUNT && !rc; ch++) {
        const char *name = tt_force_volume_channel_name(ch), *unit = tt_force_volume_channel_unit(ch);
        const double *img = tt_force_volume_map(v, ch);
        tt_gsf_field g = {xres, yres, sx, sy, 0, 0, "m", unit, name, img,
                          (const char *const *)m.keys, (const char *const *)m.values, m.n};
        tt_gwy_title(gwy_title[ch], sizeof gwy_title[ch], name, 0);
        gch[ch] = (tt_gwy_channel){gwy_title[ch], xres, yres, sx, sy, 0, 0, "m", unit, img};
        snprintf(path, sizeof path, "%s/%s.gsf", dir, name);
        if ((rc = tt_gsf_write(path, &g)))
            break;
        tt_image im = {xres, yres, sx, sy, img, name, NULL, 1, ch == TT_FV_MATERIAL ? TT_CMAP_VIRIDIS : TT_CMAP_GOLD};
        im.unit_scale = display_scale(ch, &im.unit);
        snprintf(path, sizeof path, "%s/%s.png", dir, name);
        rc = tt_image_write_png(path, &im);
        *written += rc == TT_OK ? 2 : 1;
    }
    snprintf(path, sizeof path, "%s/force_volume.gwy", dir);
    if (!rc && !(rc = tt_gwy_write(path, gch, TT_FV_COUNT, (const char *const *)m.keys,
                                   (const char *const *)m.values, m.n)))
        ++*written;
    snprintf(path, sizeof path, "%s/scene.ini", dir);
    tt_outfile *of;
    if (!rc && !(rc = tt_outfile_open(&of, path))) {
        rc = tt_scene_write(s, tt_outfile_stream(of), NULL);
        int crc = tt_outfile_close(of, rc == TT_OK);
        rc = rc ? rc : crc;
        *written += rc == TT_OK;
    }
    snprintf(path, sizeof path, "%s/force_volume.h5", dir);
    if (!rc && hdf5 && !(rc = write_hdf5(v, s, path, &m)))
        ++*written;
    tt_meta_free(&m);
    return rc;
}
