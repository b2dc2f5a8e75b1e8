/* tiptap: force volume (tiptap force --volume): a force-distance curve at every pixel
 * of the scene's [scan] raster, over its [surface] and materials, with no feedback, and
 * maps of what each curve shows (docs/force-and-tune.md, "Force volume").
 *
 * Each pixel's curve is tiptap force's ([force] from, to, speed, dwell) with the ramp
 * placed at the pixel's surface height and the force law of the pixel's material, its
 * thermal force (when [noise] temperature is set) seeded by the pixel's place in the
 * raster, so that the maps are the same bytes on any number of threads. Lines run in
 * parallel, each with its own lever; a run cut short (cancel, a solver failure) keeps
 * the lines it finished, the others NAN.
 *
 * Ownership: tt_run_force_volume returns a volume the caller frees with
 * tt_force_volume_free (also after a failure once the lines began: it holds those
 * finished); the scene is borrowed. Maps are stored as a scan's images (row 0 the top,
 * tt_raster_index), xres by yres.
 */
#ifndef TIPTAP_RUN_FORCE_VOLUME_H
#define TIPTAP_RUN_FORCE_VOLUME_H

#include "tiptap/export.h"
#include "tiptap/config/scene.h"
#include "tiptap/run/force.h"
#include "tiptap/run/run.h"

TT_BEGIN_DECLS

/* The maps. height: the pixel's surface height plus the rest separation at first
 * contact (the topography the contact points draw); adhesion: the retract's largest
 * attraction; stiffness: the approach's contact slope -dF/dz; pulloff_distance: the rest
 * separation where the tip leaves on the retract; pulloff_force: the force just before;
 * indentation: the largest; max_force: the largest force; material: the pixel's material
 * (its index in scene order). */
typedef enum {
    TT_FV_HEIGHT, TT_FV_ADHESION, TT_FV_STIFFNESS, TT_FV_PULLOFF_DISTANCE, TT_FV_PULLOFF_FORCE,
    TT_FV_INDENTATION, TT_FV_MAX_FORCE, TT_FV_MATERIAL, TT_FV_COUNT
} tt_force_volume_channel;

typedef struct tt_force_volume tt_force_volume;

const char *tt_force_volume_channel_name(int ch);
const char *tt_force_volume_channel_unit(int ch); /* SI: "m", "N", "N/m", "" */

/* What to run and write: threads (0: all cores); folder (NULL: no files), checked and
 * made once the scene is read and before a line runs, and written with the lines
 * finished also after a cancel or a failure (whose message is kept); hdf5: add
 * force_volume.h5; progress after each line (lines done, lines). */
typedef struct {
    int threads;
    const char *folder;
    int hdf5;
    tt_progress_fn progress;
    void *user;
} tt_force_volume_job;

/* *written counts the files written (may be NULL). */
int tt_run_force_volume(const tt_scene *s, const tt_force_volume_job *job, tt_force_volume **out,
                        int *written);
void tt_force_volume_free(tt_force_volume *v);

long tt_force_volume_xres(const tt_force_volume *v);
long tt_force_volume_yres(const tt_force_volume *v);
double tt_force_volume_size_x(const tt_force_volume *v);
double tt_force_volume_size_y(const tt_force_volume *v);
long tt_force_volume_lines(const tt_force_volume *v);
long tt_force_volume_lines_done(const tt_force_volume *v);
long tt_force_volume_cycles(const tt_force_volume *v); /* drive periods integrated */
const double *tt_force_volume_map(const tt_force_volume *v, int ch);
/* What one pixel's curve reported (NULL outside the raster). */
const tt_force_summary *tt_force_volume_pixel(const tt_force_volume *v, long line, long pixel);

/* The files it can write in dir checked (tt_output_check) and dir made, before a run. */
int tt_force_volume_check_outputs(const char *dir, int hdf5);
/* dir/NAME.gsf and NAME.png per map, force_volume.gwy, scene.ini (the effective scene),
 * and force_volume.h5 with hdf5, each carrying the version, the lines finished and the
 * effective scene's keys; *written counts the files. */
int tt_force_volume_write(const tt_force_volume *v, const tt_scene *s, const char *dir, int hdf5,
                          int *written);

TT_END_DECLS
#endif
