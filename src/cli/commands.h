/* The tiptap subcommands and helpers they share. */
#ifndef TIPTAP_CLI_COMMANDS_H
#define TIPTAP_CLI_COMMANDS_H

#include <getopt.h>
#include <stdio.h>

#include "tiptap/config/scene.h"
#include "tiptap/io/files.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/instrument/scan_oscillation.h"
#include "tiptap/physics/cantilever.h"

int cmd_contact(int argc, char **argv);
int cmd_keys(int argc, char **argv);
int cmd_approach(int argc, char **argv);
int cmd_trace(int argc, char **argv);
int cmd_force(int argc, char **argv);
int cmd_tune(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_scan(int argc, char **argv);
int cmd_accuracy(int argc, char **argv);
int cmd_sweep(int argc, char **argv);

/* Write a finished scan's images (GSF and PNG per channel and direction, scan.gwy with
 * all of them, scan.h5 with hdf5) and profile into dir, as tiptap scan does (cmd_scan.c),
 * with the scene's keys as metadata; *written counts the files written. */
int cli_scan_write_outputs(const tt_scan *scan, const tt_scene *scene, const char *dir, int hdf5,
                           int *written);
/* TT_EINVAL when a file scan writes into dir (its channels' files, scan.h5 with hdf5)
 * holds a folder, a pipe or a device (tt_output_check), or when one of those or a
 * channel file it may remove there as an earlier run's is an input of this run. */
int cli_scan_check_outputs(const char *dir, const tt_scan *scan, int hdf5);
/* A scan's folder made ready: its outputs checked (cli_scan_check_outputs), the folder
 * made, and locked for command cmd (tt_folder_lock; *lock for cli_unlock_folder). */
int cli_scan_folder_take(const char *cmd, const char *dir, const tt_scan *scan, int hdf5, int *lock);
int cmd_profiles(int argc, char **argv);
int cmd_live(int argc, char **argv);
/* A line's full-rate record of scan into dir (cli_scope.c): scope.csv (every quantity,
 * SI) and scope.png (z and the true surface, error, amplitude against the setpoint,
 * phase against time, and a zoom on the ring or the largest error), as jobs for the
 * scan's threads: prepare checks the loop's oscillation (the zoom's window) and says
 * how many files (*n: 0 when the record holds no line, else 2, scope.png the longer
 * first); cli_scope_file writes file j on any thread, each j once, *written counting
 * it. */
typedef struct {
    const tt_scan_scope *sc;
    char csv[4200], png[4200];
    tt_oscillation o;
    double setpoint;
} cli_scope_out;
int cli_scope_prepare(cli_scope_out *so, const tt_scan *scan, const tt_scan_scope *sc, const char *dir,
                      int *n);
int cli_scope_file(const cli_scope_out *so, int j, int *written);
/* The warning, when the record shows the loop oscillating (tt_run_scan_warn_oscillation),
 * and a note on stderr naming command cmd with the gain the loop's model suggests. */
void cli_scope_warn(const char *cmd, const tt_scan *scan, const tt_scan_scope *sc);
/* The note that follows an oscillation warning: the phase margin of the loop fitted to
 * the ring and the integral gain that gives 60 deg. */
void cli_scope_note(const char *cmd, const tt_scan *scan, const tt_scan_scope *sc);

/* Exit codes: 0 success, 1 bad input or failure, 2 usage, 130 interrupted (Ctrl-C);
 * 143 stopped by SIGTERM (main turns CLI_INTERRUPTED into 128 + the signal). */
enum { CLI_OK = 0, CLI_FAIL = 1, CLI_USAGE = 2, CLI_INTERRUPTED = 130 };

/* Print "tiptap: message" (the library's last error if msg is NULL) and return the
 * exit code matching status. */
int cli_fail(int status, const char *msg);

/* Numbers given to options, parsed strictly in the C locale: the whole text is a
 * decimal number (no blanks, no trailing text such as "20abc", no hexadecimal, inf or
 * nan). cli_whole takes a whole number from min to max in any decimal form ("1e3" is
 * 1000); what names the kind in the message ("a whole number" when NULL). cli_real
 * takes a finite number from lo to hi (DBL_MIN for "above 0"); expected is the message's phrase
 * ("a positive number"). Each prints one line naming the command and option and
 * returns CLI_USAGE, or returns CLI_OK with *out set. */
int cli_whole(const char *cmd, const char *opt, const char *text, long min, long max,
              const char *what, long *out);
int cli_real(const char *cmd, const char *opt, const char *text, double lo, double hi,
             const char *expected, double *out);

/* A command that takes no operands (or no more) refuses argv[first..argc) with one line
 * naming them and why: CLI_USAGE, or CLI_OK when there are none. */
int cli_no_operands(const char *cmd, int argc, char **argv, int first, const char *why);

/* The option skeleton every command shares: the options it picks from the common
 * ones (CLI_OPT_*; --help always), merged with its own into one getopt table, and the
 * --set assignments collected for the scene files that follow the options.
 *
 *   cli_args a = {.output = "trace.csv"};
 *   static const cli_spec spec = {"trace", CLI_OPT_OUTPUT | CLI_OPT_PLOT | ..., NULL, "", help};
 *   while ((c = cli_getopt(&spec, &a, argc, argv)) > 0) { ...the command's own options... }
 *   if (c == CLI_EXIT) return a.exit;
 *   tt_scene *scene = cli_args_scene(&spec, &a, argc, argv, &code);
 *
 * Ownership: the --set list belongs to the cli_args; cli_args_scene frees it, and so
 * does cli_args_free on a return before it. Texts point into argv. */
enum { CLI_OPT_OUTPUT = 1, CLI_OPT_PLOT = 2, CLI_OPT_SET = 4, CLI_OPT_QUIET = 8 };
/* With CLI_OPT_OUTPUT: -o names a folder (scan), checked only against the inputs. */
enum { CLI_OUTPUT_FOLDER = 16 };

/* getopt codes of the long-only common options, above every character */
enum { CLI_CODE_PLOT = 0x100, CLI_CODE_SET = 0x101 };

/* cli_getopt's ends: the options are read (run on), or the command returns a.exit
 * (0 after --help, 2 for a bad option, 1 out of memory). */
enum { CLI_END = -1, CLI_EXIT = -2 };

typedef struct {
    const char *cmd;           /* the command's name, for messages */
    unsigned common;           /* the CLI_OPT_* it takes */
    const struct option *own;  /* its own options, {NULL} ended; NULL: none */
    const char *own_short;     /* their short letters, getopt style ("j:") */
    void (*help)(void);        /* prints --help to stdout */
} cli_spec;

/* How an output is checked before the run: a file (tt_output_check: no folder, pipe or
 * device there, not an input), a folder (not an input), or only against the run's other
 * outputs (a file that checks itself when it is opened, the sweep's journal). */
enum { CLI_OUT_FILE, CLI_OUT_FOLDER, CLI_OUT_DISTINCT };
#define CLI_MORE_OUTPUTS 4

typedef struct {
    const char *output, *plot; /* -o, --plot: as given, else as the command set them */
    /* the run's other outputs (the sweep's FILE.h5), added before cli_args_scene */
    tt_output more[CLI_MORE_OUTPUTS];
    int more_how[CLI_MORE_OUTPUTS];
    int nmore;
    int quiet;                 /* -q */
    char **sets;               /* --set assignments in order */
    int nsets;
    int exit;                  /* the exit code when cli_getopt returns CLI_EXIT */
    struct option table[32];   /* the merged getopt table */
    char shorts[64];
} cli_args;

/* Add an output of the run (NULL: none) named what in messages, checked as how
 * (CLI_OUT_*), to those of cli_args_scene's checks. */
void cli_args_more(cli_args *a, const char *path, const char *what, int how);
/* Before anything runs, over every output of the run (-o, --plot, cli_args_more's):
 * cli_outputs_distinct refuses two naming one file ("tiptap CMD: --plot x.png: the same
 * file as -o x.png; give each its own name", CLI_USAGE); cli_outputs_check each as its
 * kind says ("tiptap: ...", CLI_FAIL), once the inputs are read. cli_args_scene calls
 * both. */
int cli_outputs_distinct(const cli_spec *spec, const cli_args *a);
int cli_outputs_check(const cli_spec *spec, const cli_args *a);

/* The next option: the command's own code (> 0), CLI_END, or CLI_EXIT. */
int cli_getopt(const cli_spec *spec, cli_args *a, int argc, char **argv);
void cli_args_free(cli_args *a);

/* cli_scene_args for the operands left after cli_getopt and the --set list. */
tt_scene *cli_args_scene(const cli_spec *spec, cli_args *a, int argc, char **argv, int *exit_code);

/* For a command without options of its own: cli_getopt to the end, then
 * cli_args_scene. NULL with *exit_code also after --help (0) and a bad option. */
tt_scene *cli_options_scene(const cli_spec *spec, cli_args *a, int argc, char **argv, int *exit_code);

/* The --help line of --set, the same in every command that takes it. */
#define CLI_HELP_SET "      --set S.K=V    override a scene key (material.NAME.key for named sections)\n"

/* Load scene files in order and apply --set assignments; NULL on error (reported). */
tt_scene *cli_load_scene(char **files, int nfiles, char **sets, int nsets);

/* The scene files left after the options (argv from optind on) and the --set
 * assignments, for command cmd. Frees sets. NULL with *exit_code set when there is no
 * scene file (usage) or it does not load (failure, reported). */
tt_scene *cli_scene_args(const char *cmd, int argc, char **argv, int optind_, char **sets,
                         int nsets, int *exit_code);

/* 1 when stderr is a terminal: progress lines go there only then. */
int cli_progress_enabled(void);

/* SIGINT and SIGTERM where nothing is left to keep: the program ends at once, 128 + the
 * signal, with "tiptap: why" on stderr, once no output file is being written (one that
 * is, is finished first). main installs it for every command before its first output,
 * also where the shell that started it ignores SIGINT (a background job); trace again
 * for its plot, drawn after the CSV is complete. */
void cli_interrupt_at_once(const char *why);
/* From the command's first output on (a file, a folder, a journal): the handler that
 * requests cooperative cancellation (util/cancel.h), so that the run stops at its next
 * poll, within a second, and keeps what it finished; a second signal ends it at once. */
void cli_catch_interrupt(void);

/* Wall-clock seconds from a monotonic clock. */
double cli_now(void);

/* A duration for people: "40 s", "12 min", "3.1 h", "2.5 days". */
const char *cli_duration(double seconds, char *buf, size_t len);
const char *cli_bytes(double bytes, char *buf, size_t len);

/* The estimate of a run (cycles, time on threads threads) on stderr unless quiet, and
 * the warning of a run longer than a minute (tt_run_warn_duration), quiet or not. */
void cli_report_estimate(const char *cmd, double cycles, double seconds, int upper_bound,
                         int threads, double f0, double fd, int quiet);

/* The run's own error estimate (cli_estimate.c). The scene at the companion setting
 * (tt_companion_solver, returned in tight); NULL when out of memory. */
tt_scene *cli_companion_scene(const tt_scene *scene, const tt_solver *s, tt_solver *tight);
/* Hold DIR/.tiptap.lock (flock) for the rest of the process: a second run into DIR is
 * refused at once, naming the pid of the first. Returns the descriptor, or -1 after
 * printing why. */
int cli_lock_folder(const char *cmd, const char *dir);
/* Remove DIR/.tiptap.lock and release it: a finished run leaves no lock file behind. */
void cli_unlock_folder(const char *dir, int fd);
/* Where stderr is not a terminal (a log, a batch job), a long run prints a plain
 * progress line at most every this many seconds instead of a line kept rewritten. */
#define CLI_PROGRESS_LOG_S 5.0

/* Progress of a run on stderr: "CMD: DONE/TOTAL UNIT, N s elapsed, about M s left",
 * on a terminal one line kept rewritten (at most ten times a second), otherwise a plain
 * line every CLI_PROGRESS_LOG_S and at the end; nothing when quiet. */
typedef struct cli_progress {
    const char *cmd, *unit;
    double t0, last;
    int tty, on;
} cli_progress;
void cli_progress_begin(cli_progress *p, const char *cmd, const char *unit, int quiet);
void cli_progress_show(cli_progress *p, long done, long total);
/* cli_progress_show as a library progress callback whose user pointer is the cli_progress. */
void cli_progress_callback(void *user, long done, long total);
/* Ends the rewritten line on a terminal. */
void cli_progress_end(const cli_progress *p);

#endif
