/* tiptap: the command-line program, a thin layer over libtiptap. */
#include <errno.h>
#include <getopt.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "tiptap/io/files.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/warning.h"
#include "tiptap/version.h"

/* The subcommands, in the order --help lists them. */
static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} commands[] = {
    {"contact", cmd_contact, "contact mechanics: a Maugis-Dugdale curve and its summary"},
    {"approach", cmd_approach, "approach curve: amplitude, phase, force against separation"},
    {"trace", cmd_trace, "time series of the tapping cantilever, with optional ramps"},
    {"force", cmd_force, "force-distance curve: jump-in, contact slope, pull-off, adhesion"},
    {"tune", cmd_tune, "thermal tune: the free lever's noise spectrum, fitted for f, Q and k"},
    {"scan", cmd_scan, "closed-loop tapping image: height, phase, force, dissipation"},
    {"sweep", cmd_sweep, "parameter grid: steady points, approach curves or scans, on every core"},
    {"profiles", cmd_profiles, "overlay the profile lines of scans: trace, retrace, true surface"},
    {"live", cmd_live, "the instrument's console in a browser: scope, image, gains (docs/live.md)"},
    {"accuracy", cmd_accuracy, "work-precision: error against run time of each solver setting"},
    {"bench", cmd_bench, "benchmark: cycles per second and accuracy on the standard scene"},
    {"keys", cmd_keys, "list every scene section and key with unit and default"},
};

#define NCOMMANDS (sizeof commands / sizeof commands[0])

static void usage(FILE *out)
{
    fprintf(out,
            "Usage: tiptap COMMAND [OPTIONS] [SCENE...]\n"
            "Tapping-mode AFM simulator (Burnham et al., \"How does a tip tap?\").\n\n"
            "Commands:\n");
    for (size_t i = 0; i < NCOMMANDS; i++)
        fprintf(out, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(out,
            "\nOptions:\n"
            "  -h, --help     this help; 'tiptap COMMAND --help' for a command's\n"
            "  -V, --version  the version\n\n"
            "Scenes are INI files (docs/scene-format.md); values carry SI units.\n"
            "Exit status: 0 success, 1 bad input or failure, 2 usage, 130 interrupted\n"
            "(Ctrl-C), 143 stopped by SIGTERM.\n");
}

/* Results printed on stdout are output too: redirected into a file past ulimit -f or on
 * a full disk, the command fails and says so rather than exit 0 with a short file. */
static int check_stdout(int code)
{
    errno = 0;
    int bad = fflush(stdout) != 0, e = errno;
    if (!bad && !ferror(stdout))
        return code;
    fprintf(stderr, "tiptap: standard output: cannot write: %s\n", e ? strerror(e) : "write error");
    return code == CLI_OK ? CLI_FAIL : code;
}

/* The library's warnings (tiptap/util/warning.h) on stderr, naming the command (data). */
static void print_warning(const char *category, const char *message, void *data)
{
    (void)category;
    fprintf(stderr, "tiptap %s: warning: %s\n", (const char *)data, message);
}

int main(int argc, char **argv)
{
    /* Past ulimit -f, SIGXFSZ would end the program without a word and leave a
     * temporary file; ignored, the write fails with EFBIG and says so, naming the file. */
    signal(SIGXFSZ, SIG_IGN);
    /* every file a command reads is remembered, so that no output replaces one */
    tt_inputs_track(1);
    if (argc < 2) {
        usage(stderr);
        return CLI_USAGE;
    }
    for (size_t i = 0; i < NCOMMANDS; i++)
        if (strcmp(argv[1], commands[i].name) == 0) {
            cli_interrupt_at_once("interrupted before any output file was begun");
            tt_warning_push(print_warning, (void *)commands[i].name);
            int code = commands[i].run(argc - 1, argv + 1);
            code = check_stdout(code);
            /* stopped by a signal: 128 + its number, the shells' convention (143: SIGTERM),
             * also when it came as the last output was being finished */
            if (code == CLI_OK && tt_cancel_signal())
                fprintf(stderr, "tiptap: interrupted as the run ended; its outputs are complete\n");
            if ((code == CLI_INTERRUPTED || code == CLI_OK) && tt_cancel_signal())
                code = 128 + tt_cancel_signal();
            return code;
        }

    static const struct option opts[] = {
        {"help", no_argument, NULL, 'h'}, {"version", no_argument, NULL, 'V'}, {NULL, 0, NULL, 0}};
    int c = getopt_long(argc, argv, "hV", opts, NULL);
    if (c == 'h') {
        usage(stdout);
        return CLI_OK;
    }
    if (c == 'V') {
        printf("tiptap %s\n", TIPTAP_VERSION_STRING);
        return CLI_OK;
    }
    fprintf(stderr, "tiptap: unknown command '%s'; see 'tiptap --help'\n", argv[1]);
    return CLI_USAGE;
}
