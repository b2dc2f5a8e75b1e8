/* tiptap live: the instrument's console in a browser (docs/live.md). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "tiptap/io/outfile.h"
#include "tiptap/live/controls.h"
#include "tiptap/live/lesson.h"
#include "tiptap/live/server.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

static void help(void)
{
    printf("Usage: tiptap live [--lesson FILE] SCENE... [--port N] [--set section.key=value]...\n"
           "                  [--surfaces DIR] [--instruments N]\n"
           "The instrument's console in a browser: a scan of the scene run line by line on\n"
           "the instrument's clock, served on http://127.0.0.1:N/ (this machine only) with\n"
           "its controls (setpoint, P and I gains, line rate, scan size and fast axis,\n"
           "pixels, lines, free amplitude, noise on or off and its seed, the sample, the\n"
           "tier), the scope of the current line (trace and retrace of height, error,\n"
           "amplitude and phase, with the true surface), the image building line by line,\n"
           "an oscillation warning with a gain suggestion, a force curve and a thermal tune\n"
           "on the scene (tiptap force's and tiptap tune's runs, at the page's request), and\n"
           "exports: the image as .gwy and .gsf and the scene that tiptap scan turns into\n"
           "the same files. A change is checked as a scene file is (docs/scene-format.md);\n"
           "one that fails changes nothing and the page says why. See docs/live.md.\n\n"
           "  -l, --lesson FILE  a lesson: its title and instructions on the page, the\n"
           "                     controls it hides or locks (the server refuses a change to\n"
           "                     them), its scene (scene = FILE... or its own sections); a\n"
           "                     scene argument with a [lesson] section is one too. The\n"
           "                     page's lesson.ini saves the scene in force with the lesson\n"
           "  -p, --port N       the port (default 8421; 0: one the system picks); the URL\n"
           "                     is printed on stdout once it listens\n"
           "      --instruments N  instruments at once (default 4, at most 64): each page\n"
           "                     (browser tab) drives its own scan, controls and exports; a\n"
           "                     page beyond N is told so and waits for one to free\n"
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
    const tt_live_lesson *lesson = user;
    char path[4200];
    tt_outfile *of;
    int n = 0, rc;
    /* the saved lesson: its [lesson] section (a new one where none was given), then the
     * scene in force, which tiptap live --lesson reads back */
    snprintf(path, sizeof path, "%s/lesson.ini", dir);
    if ((rc = tt_outfile_open(&of, path)))
        return rc;
    if ((rc = tt_live_lesson_write(lesson, tt_outfile_stream(of))) ||
        (rc = tt_scene_write(scene, tt_outfile_stream(of), NULL))) {
        tt_outfile_close(of, 0);
        return rc;
    }
    if ((rc = tt_outfile_close(of, 1)))
        return rc;
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
                                         {"lesson", required_argument, NULL, 'l'},
                                         {"instruments", required_argument, NULL, 'I'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"live", CLI_OPT_SET, opts, "p:l:", help};
    cli_args args = {0};
    long port = 8421, instruments = 4;
    const char *surfaces = TT_SURFACES_DIR, *lesson_path = NULL;
    int c;
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        if (c == 'S') {
            surfaces = optarg;
        } else if (c == 'l') {
            lesson_path = optarg;
        } else if (c == 'I') {
            if (cli_whole("live", "--instruments", optarg, 1, 64, "a number of instruments", &instruments)) {
                cli_args_free(&args);
                return CLI_USAGE;
            }
        } else if (cli_whole("live", "--port", optarg, 0, 65535, "a port", &port)) {
            cli_args_free(&args);
            return CLI_USAGE;
        }
    }
    if (c == CLI_EXIT)
        return args.exit;
    /* a scene argument with a [lesson] section is the lesson (one at most) */
    char **files = argv + optind;
    int nfiles = argc - optind, k = 0;
    for (int i = 0; i < nfiles; i++) {
        if (tt_live_lesson_is_one(files[i])) {
            if (lesson_path) {
                cli_args_free(&args);
                fprintf(stderr, "tiptap live: %s: a second lesson (the first: %s); expected one lesson\n",
                        files[i], lesson_path);
                return CLI_USAGE;
            }
            lesson_path = files[i];
        } else {
            files[k++] = files[i];
        }
    }
    nfiles = k;
    if (nfiles == 0 && !lesson_path) {
        cli_args_free(&args);
        fprintf(stderr, "tiptap live: needs a scene file; see 'tiptap live --help'\n");
        return CLI_USAGE;
    }
    tt_live_lesson *lesson = NULL;
    int rc = lesson_path ? tt_live_lesson_load(&lesson, lesson_path) : TT_OK;
    if (rc) {
        cli_args_free(&args);
        return cli_fail(rc, NULL);
    }
    tt_live_controls *controls = NULL;
    /* the same memory as tiptap scan's check of its own scene (run.h) */
    rc = tt_live_controls_alloc_lesson(&controls, lesson, files, nfiles, args.sets, args.nsets, surfaces,
                                       tt_run_memory_available);
    cli_args_free(&args);
    if (rc)
        return cli_fail(rc, NULL);
    tt_live_options o = {.port = (int)port, .max_clients = 16, .max_instruments = (int)instruments,
                         .write = write_outputs, .write_user = (void *)tt_live_controls_lesson(controls),
                         .ready = ready, .ready_user = NULL};
    cli_catch_interrupt();
    rc = tt_live_serve(controls, &o);
    tt_live_controls_free(controls);
    if (rc)
        return cli_fail(rc, NULL);
    fprintf(stderr, "tiptap live: stopped\n");
    return tt_cancel_requested() ? CLI_INTERRUPTED : CLI_OK;
}
