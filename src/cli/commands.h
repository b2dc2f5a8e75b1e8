/* The tiptap subcommands and helpers they share. */
#ifndef TIPTAP_CLI_COMMANDS_H
#define TIPTAP_CLI_COMMANDS_H

#include <stdio.h>

#include "tiptap/config/scene.h"

int cmd_contact(int argc, char **argv);
int cmd_keys(int argc, char **argv);
int cmd_approach(int argc, char **argv);
int cmd_trace(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_scan(int argc, char **argv);
int cmd_accuracy(int argc, char **argv);

/* Exit codes: 0 success, 1 bad input or failure, 2 usage, 130 interrupted (Ctrl-C);
 * 143 stopped by SIGTERM (main turns CLI_INTERRUPTED into 128 + the signal). */
enum { CLI_OK = 0, CLI_FAIL = 1, CLI_USAGE = 2, CLI_INTERRUPTED = 130 };

/* Print "tiptap: message" (the library's last error if msg is NULL) and return the
 * exit code matching status. */
int cli_fail(int status, const char *msg);

/* Load scene files in order and apply --set assignments; NULL on error (reported). */
tt_scene *cli_load_scene(char **files, int nfiles, char **sets, int nsets);

/* The scene files left after the options (argv from optind on) and the --set
 * assignments, for command cmd. Frees sets. NULL with *exit_code set when there is no
 * scene file (usage) or it does not load (failure, reported). */
tt_scene *cli_scene_args(const char *cmd, int argc, char **argv, int optind_, char **sets,
                         int nsets, int *exit_code);

/* 1 when stderr is a terminal: progress lines go there only then. */
int cli_progress_enabled(void);

/* Install the SIGINT and SIGTERM handler that requests cooperative cancellation. */
void cli_catch_interrupt(void);

/* Wall-clock seconds from a monotonic clock. */
double cli_now(void);

#endif
