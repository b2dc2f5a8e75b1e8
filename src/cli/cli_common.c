/* Helpers shared by the subcommands: errors, scene loading, progress, interrupts. */
#include <signal.h>
#include <stdio.h>
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

/* The merged table: the common options the command takes, then its own. */
static void build_table(const cli_spec *spec, cli_args *a)
{
    static const struct {
        unsigned bit;
        struct option opt;
        const char *shorts;
    } common[] = {
        {CLI_OPT_OUTPUT, {"output", required_argument, NULL, 'o'}, "o:"},
        {CLI_OPT_PLOT, {"plot", required_argument, NULL, CLI_CODE_PLOT}, ""},
        {CLI_OPT_SET, {"set", required_argument, NULL, CLI_CODE_SET}, ""},
        {CLI_OPT_QUIET, {"quiet", no_argument, NULL, 'q'}, "q"},
        {0, {"help", no_argument, NULL, 'h'}, "h"},
    };
    size_t n = 0;
    snprintf(a->shorts, sizeof a->shorts, "%s", spec->own_short ? spec->own_short : "");
    for (size_t i = 0; i < sizeof common / sizeof common[0]; i++)
        if (!common[i].bit || (spec->common & common[i].bit)) {
            a->table[n++] = common[i].opt;
            strncat(a->shorts, common[i].shorts, sizeof a->shorts - strlen(a->shorts) - 1);
        }
    for (const struct option *o = spec->own; o && o->name && n + 1 < sizeof a->table / sizeof a->table[0]; o++)
        a->table[n++] = *o;
    memset(&a->table[n], 0, sizeof a->table[n]);
}

int cli_getopt(const cli_spec *spec, cli_args *a, int argc, char **argv)
{
    if (!a->table[0].name)
        build_table(spec, a);
    for (;;) {
        int c = getopt_long(argc, argv, a->shorts, a->table, NULL);
        switch (c) {
        case -1: return CLI_END;
        case 'o': a->output = optarg; continue;
        case 'q': a->quiet = 1; continue;
        case CLI_CODE_PLOT: a->plot = optarg; continue;
        case CLI_CODE_SET:
            if (!a->sets && !(a->sets = calloc((size_t)argc, sizeof *a->sets))) {
                a->exit = cli_fail(TT_ENOMEM, "out of memory");
                return CLI_EXIT;
            }
            a->sets[a->nsets++] = optarg;
            continue;
        case 'h':
            spec->help();
            a->exit = CLI_OK;
            break;
        case '?':
        case ':':
            a->exit = CLI_USAGE;
            break;
        default: return c;
        }
        cli_args_free(a);
        return CLI_EXIT;
    }
}

void cli_args_free(cli_args *a)
{
    free(a->sets);
    a->sets = NULL;
    a->nsets = 0;
}

tt_scene *cli_args_scene(const cli_spec *spec, cli_args *a, int argc, char **argv, int *exit_code)
{
    tt_scene *scene = cli_scene_args(spec->cmd, argc, argv, optind, a->sets, a->nsets, exit_code);
    a->sets = NULL;
    a->nsets = 0;
    return scene;
}

tt_scene *cli_options_scene(const cli_spec *spec, cli_args *a, int argc, char **argv, int *exit_code)
{
    int c;
    while ((c = cli_getopt(spec, a, argc, argv)) > 0)
        ; /* no own options: getopt refuses any other with '?' */
    if (c == CLI_EXIT) {
        *exit_code = a->exit;
        return NULL;
    }
    return cli_args_scene(spec, a, argc, argv, exit_code);
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
