/* Helpers shared by the subcommands: errors, scene loading, progress, interrupts. */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "commands.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

int cli_fail(int status, const char *msg)
{
    fprintf(stderr, "tiptap: %s\n", msg ? msg : tt_error_message());
    if (status == TT_EINTR)
        return CLI_INTERRUPTED;
    return status == TT_OK ? CLI_OK : CLI_FAIL;
}

tt_scene *cli_load_scene(char **files, int nfiles, char **sets, int nsets)
{
    tt_scene *s = tt_scene_alloc();
    if (!s) {
        cli_fail(TT_ENOMEM, "out of memory");
        return NULL;
    }
    for (int i = 0; i < nfiles; i++) {
        int rc = tt_scene_load(s, files[i]);
        if (rc) {
            cli_fail(rc, NULL);
            tt_scene_free(s);
            return NULL;
        }
    }
    for (int i = 0; i < nsets; i++) {
        int rc = tt_scene_set(s, sets[i]);
        if (rc) {
            cli_fail(rc, NULL);
            tt_scene_free(s);
            return NULL;
        }
    }
    return s;
}

tt_scene *cli_scene_args(const char *cmd, int argc, char **argv, int optind_, char **sets,
                         int nsets, int *exit_code)
{
    tt_scene *scene = NULL;
    *exit_code = CLI_USAGE;
    if (optind_ >= argc)
        fprintf(stderr, "tiptap %s: needs a scene file; see 'tiptap %s --help'\n", cmd, cmd);
    else if (!(scene = cli_load_scene(argv + optind_, argc - optind_, sets, nsets)))
        *exit_code = CLI_FAIL;
    free(sets);
    return scene;
}

int cli_progress_enabled(void) { return isatty(STDERR_FILENO); }

static void on_sigint(int sig)
{
    /* A second Ctrl-C ends the program at once. */
    if (tt_cancel_requested())
        _exit(128 + sig);
    tt_cancel_request_signal(sig);
}

void cli_catch_interrupt(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

double cli_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
