/* A program built against the installed libtiptap (docs/library.md): the approach
 * curve of a scene, amplitude and phase against the rest separation, as
 * `tiptap approach` computes it.
 *
 *   approach SCENE... [section.key=value]...
 *
 * Each argument with '=' overrides a key (as --set does); the others are scene files,
 * read in order. Prints z_nm,amplitude_nm,phase_deg rows in the numbers' full
 * precision. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <tiptap.h>

/* The library's one-line message, and the exit status of a failure. */
static int fail(int rc)
{
    fprintf(stderr, "approach: %s\n", tt_error_message());
    return rc == TT_EINVAL ? 2 : 1;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: approach SCENE... [section.key=value]...\n");
        return 2;
    }
    printf("# libtiptap %s, compiled against %s\n", tt_version(), TIPTAP_VERSION_STRING);
    tt_scene *scene = tt_scene_alloc();
    tt_setup *setup = NULL;
    tt_approach *ap = NULL;
    tt_approach_params params;
    int rc = scene ? TT_OK : TT_ENOMEM;
    for (int i = 1; i < argc && rc == TT_OK; i++)
        rc = strchr(argv[i], '=') ? tt_scene_set(scene, argv[i]) : tt_scene_load(scene, argv[i]);
    /* the scene made ready (its cantilever, solver and force laws), then [approach] */
    if (rc == TT_OK && (rc = tt_setup_alloc(&setup, scene)) == TT_OK)
        rc = tt_config_approach_alloc(&ap, setup, scene, &params);
    if (rc == TT_OK)
        printf("z_nm,amplitude_nm,phase_deg\n");
    while (rc == TT_OK && !tt_approach_done(ap)) {
        tt_approach_point pt;
        if ((rc = tt_approach_iterate(ap, &pt)) == TT_OK)
            printf("%.9g,%.9g,%.9g\n", pt.z * 1e9, pt.cycle.amplitude * 1e9,
                   pt.cycle.phase * 180 / M_PI);
    }
    int status = rc == TT_OK ? 0 : fail(rc);
    tt_approach_free(ap);
    tt_setup_free(setup);
    tt_scene_free(scene);
    return status;
}
