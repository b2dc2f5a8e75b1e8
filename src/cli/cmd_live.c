/* tiptap live: the instrument's console in a browser (docs/live.md). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "tiptap/io/outfile.h"
#include "tiptap/live/controls.h"
#include "tiptap/live/server.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

static void help(void)
{
    printf("Usage: tiptap live SCENE... [--port N] [--set section.key=value]... [--surfaces DIR]\n"
           "The instrument's console in a browser: a scan of the scene run line by line on\n"
           "the instrument's clock, served on http://127.0.0.1:N/ (this machine only) with\n"
           "its controls (setpoint, P and I gains, line rate, scan size and fast axis,\n"
           "pixels, lines, free amplitude, noise on or off and its seed, the sample, the\n"
           "tier), the scope of the current line (trace and retrace of height, error,\n"
           "amplitude and phase, with the true surface), the image building line by line,\n"
           "an oscillation warning with a gain suggestion, and exports: the image as .gwy\n"
           "and .gsf and the scene that tiptap scan turns into the same files. A change is\n"
           "checked as a scene file is (docs/scene-format.md); one that fails changes\n"
           "nothing and the page says why. See docs/live.md.\n\n"
           "  -p, --port N       the port (default 8421; 0: one the system picks); the URL\n"
           "                     is printed on stdout once it listens\n"
           "      --surfaces DIR the bundled samples the console offers (default: the\n"
           "                     source tree's surfaces/)\n"
           CLI_HELP_SET
           "Ctrl-C (or SIGTERM) stops the server: the line under way is abandoned, every\n"
           "connection closed, exit 130 (143).\n");
}

/* The exports: the files tiptap scan writes for the scan and scene, into dir: the
 * effective scene (scene.ini, as tiptap scan writes it) and the images. */
static int write_outputs(void *user, const tt_scan *scan, const tt_scene *scene, const char *dir)
{
    (void)user;
    char path[4200];
    tt_outfile *of;
    int n = 0, rc;
    snprintf(path, sizeof path, "%s/scene.ini", dir);
    if ((rc = tt_outfile_open(&of, path)))
        return rc;
    if ((rc = tt_scene_write(scene, tt_outfile_stream(of), NULL))) {
        tt_outfile_close(of, 0);
        return rc;
    }
    if ((rc = tt_outfile_close(of, 1)))
        return rc;
    return cli_scan_write_outputs(scan, scene, dir, 0, &n); /* no HDF5 from the console */
}

static void ready(void *user, int port)
{
    (void)user;
    printf("tiptap live: http://127.0.0.1:%d/ (Ctrl-C stops it)\n", port);
    fflush(stdout);
}

int cmd_live(int argc, char **argv)
{
    static const struct option opts[] = {{"port", required_argument, NULL, 'p'},
                                         {"surfaces", required_argument, NULL, 'S'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"live", CLI_OPT_SET, opts, "p:", help};
    cli_args args = {0};
    long port = 8421;
    const char *surfaces = TT_SURFACES_DIR;
    int c;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        if (c == 'S') {
            surfaces = optarg;
        } else if (cli_whole("live", "--port", optarg, 0, 65535, "a port", &port)) {
            cli_args_free(&args);
            return CLI_USAGE;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    if (optind >= argc) {
        cli_args_free(&args);
        fprintf(stderr, "tiptap live: needs a scene file; see 'tiptap live --help'\n");
        return CLI_USAGE;
    }
    tt_live_controls *controls = NULL;
    /* the same memory as tiptap scan's check of its own scene (run.h) */
    int rc = tt_live_controls_alloc(&controls, argv + optind, argc - optind, args.sets, args.nsets,
                                    surfaces, tt_run_memory_available);
    cli_args_free(&args);
    if (rc)
        return cli_fail(rc, NULL);
    tt_live_options o = {(int)port, 16, write_outputs, NULL, ready, NULL};
    cli_catch_interrupt();
    rc = tt_live_serve(controls, &o);
    tt_live_controls_free(controls);
    if (rc)
        return cli_fail(rc, NULL);
    fprintf(stderr, "tiptap live: stopped\n");
    return tt_cancel_requested() ? CLI_INTERRUPTED : CLI_OK;
}
