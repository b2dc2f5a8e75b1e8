/* Helpers shared by the subcommands: errors, scene loading, progress, interrupts. */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "commands.h"
#include "tiptap/config/config.h"
#include "tiptap/config/units.h"
#include "tiptap/util/str.h"
#include "tiptap/io/files.h"
#include "tiptap/io/lock.h"
#include "tiptap/io/outfile.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/util/clock.h"

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
        cli_fail(tt_error_nomem("the scene"), NULL);
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
    tt_config_note_inputs(s); /* its PNG maps: no output may replace them */
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

/* A decimal number and nothing else: digits, one sign, a point, an exponent. strtod
 * alone would also take blanks before it, hexadecimal, "inf" and "nan". */
static int plain_number(const char *text, double *v)
{
    if (!text[0] || strspn(text, "0123456789+-.eE") != strlen(text))
        return -1;
    char *end;
    errno = 0;
    *v = tt_strtod(text, &end);
    return end == text || *end || errno == ERANGE || !isfinite(*v) ? -1 : 0;
}

int cli_whole(const char *cmd, const char *opt, const char *text, long min, long max,
              const char *what, long *out)
{
    double v;
    if (plain_number(text, &v) != 0 || v != floor(v) || v < (double)min || v > (double)max) {
        fprintf(stderr, "tiptap %s: %s: '%s' is not %s from %ld to %ld\n", cmd, opt, text,
                what ? what : "a whole number", min, max);
        return CLI_USAGE;
    }
    *out = (long)v;
    return CLI_OK;
}

int cli_real(const char *cmd, const char *opt, const char *text, double lo, double hi,
             const char *expected, double *out)
{
    double v;
    if (plain_number(text, &v) != 0 || !(v >= lo) || !(v <= hi)) {
        fprintf(stderr, "tiptap %s: %s: '%s' is not %s\n", cmd, opt, text, expected);
        return CLI_USAGE;
    }
    *out = v;
    return CLI_OK;
}

int cli_no_operands(const char *cmd, int argc, char **argv, int first, const char *why)
{
    if (first >= argc)
        return CLI_OK;
    char list[512];
    size_t used = 0;
    list[0] = '\0';
    for (int i = first; i < argc && used + 8 < sizeof list; i++) {
        int w = snprintf(list + used, sizeof list - used, "%s'%s'", used ? " " : "", argv[i]);
        if (w < 0 || (size_t)w >= sizeof list - used) {
            snprintf(list + used, sizeof list - used, " ...");
            break;
        }
        used += (size_t)w;
    }
    fprintf(stderr, "tiptap %s: unexpected argument%s %s: %s; see 'tiptap %s --help'\n", cmd,
            argc - first > 1 ? "s" : "", list, why, cmd);
    return CLI_USAGE;
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
                a->exit = cli_fail(tt_error_nomem("the --set list of %d arguments", argc), NULL);
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

/* Every output of the run: -o, --plot, then what the command added (cli_args.more). */
static size_t run_outputs(const cli_spec *spec, const cli_args *a, tt_output *outs, int *how)
{
    size_t n = 0;
    if (a->output) {
        how[n] = spec->common & CLI_OUTPUT_FOLDER ? CLI_OUT_FOLDER : CLI_OUT_FILE;
        outs[n++] = (tt_output){a->output, "-o"};
    }
    if (a->plot) {
        how[n] = CLI_OUT_FILE;
        outs[n++] = (tt_output){a->plot, "--plot"};
    }
    for (int i = 0; i < a->nmore; i++) {
        how[n] = a->more_how[i];
        outs[n++] = a->more[i];
    }
    return n;
}

int cli_outputs_distinct(const cli_spec *spec, const cli_args *a)
{
    tt_output outs[2 + CLI_MORE_OUTPUTS];
    int how[2 + CLI_MORE_OUTPUTS];
    size_t n = run_outputs(spec, a, outs, how);
    if (tt_outputs_distinct(outs, n) == TT_OK)
        return CLI_OK;
    fprintf(stderr, "tiptap %s: %s\n", spec->cmd, tt_error_message());
    return CLI_USAGE;
}

int cli_outputs_check(const cli_spec *spec, const cli_args *a)
{
    tt_output outs[2 + CLI_MORE_OUTPUTS];
    int how[2 + CLI_MORE_OUTPUTS];
    size_t n = run_outputs(spec, a, outs, how);
    for (size_t i = 0; i < n; i++) {
        int rc = how[i] == CLI_OUT_FILE     ? tt_output_check(outs[i].path)
                 : how[i] == CLI_OUT_FOLDER ? tt_output_check_inputs(outs[i].path)
                                            : TT_OK;
        if (rc)
            return cli_fail(rc, NULL);
    }
    return CLI_OK;
}

void cli_args_more(cli_args *a, const char *path, const char *what, int how)
{
    if (path && a->nmore < CLI_MORE_OUTPUTS) {
        a->more[a->nmore] = (tt_output){path, what};
        a->more_how[a->nmore++] = how;
    }
}

tt_scene *cli_args_scene(const cli_spec *spec, cli_args *a, int argc, char **argv, int *exit_code)
{

    /* two outputs naming one file: a usage error, before the scene is read */
    if ((*exit_code = cli_outputs_distinct(spec, a)) != CLI_OK) {
        cli_args_free(a);
        return NULL;
    }
    tt_scene *scene = cli_scene_args(spec->cmd, argc, argv, optind, a->sets, a->nsets, exit_code);
    a->sets = NULL;
    a->nsets = 0;
    /* an output that is one of the files just read (-o s.ini), or whose name holds a
     * pipe, a device or a folder, is refused before the run */
    if (scene && (*exit_code = cli_outputs_check(spec, a)) != CLI_OK) {
        tt_scene_free(scene);
        scene = NULL;
    }
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

void cli_progress_begin(cli_progress *p, const char *cmd, const char *unit, int quiet)
{
    p->cmd = cmd;
    p->unit = unit;
    p->t0 = p->last = cli_now();
    p->tty = cli_progress_enabled();
    p->on = !quiet;
}

void cli_progress_callback(void *user, long done, long total) { cli_progress_show(user, done, total); }

void cli_progress_show(cli_progress *p, long done, long total)
{
    if (!p->on || done <= 0)
        return;
    double now = cli_now(), el = now - p->t0;
    double wait = p->tty ? 0.1 : CLI_PROGRESS_LOG_S;
    if (now - p->last < wait && done != total)
        return;
    p->last = now;
    double left = el / (double)done * (double)(total - done);
    fprintf(stderr, "%s%s: %ld/%ld %s, %.0f s elapsed, about %.0f s left%s", p->tty ? "\r" : "",
            p->cmd, done, total, p->unit, el, left, p->tty ? "   " : "\n");
}

void cli_progress_end(const cli_progress *p)
{
    if (p->on && p->tty)
        fputc('\n', stderr);
}

static void on_sigint(int sig)
{
    /* A second Ctrl-C ends the program at once. */
    if (tt_cancel_requested())
        _exit(128 + sig);
    tt_cancel_request_signal(sig);
}

/* The line the at-once handler writes: two buffers, so that a new line is made in the
 * one the handler does not read, then switched to. */
static char at_once_msg[2][8448];
static size_t at_once_len[2];
static volatile sig_atomic_t at_once_cur;

/* Nothing to keep: end now (write and _exit are async-signal-safe), unless a file is
 * being written; that one is finished first, and the exit status says so after. */
static void on_signal_at_once(int sig)
{
    if (tt_outfile_open_count() > 0) {
        on_sigint(sig);
        return;
    }
    int c = at_once_cur;
    ssize_t w = write(STDERR_FILENO, at_once_msg[c], at_once_len[c]);
    (void)w;
    _exit(128 + sig);
}

static void catch_signals(void (*handler)(int))
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

void cli_interrupt_at_once(const char *why)
{
    int next = !at_once_cur;
    snprintf(at_once_msg[next], sizeof at_once_msg[next], "tiptap: %s\n", why);
    at_once_len[next] = strlen(at_once_msg[next]);
    atomic_signal_fence(memory_order_seq_cst); /* the line is whole before it is used */
    at_once_cur = next;
    catch_signals(on_signal_at_once);
}
void cli_catch_interrupt(void) { catch_signals(on_sigint); }

double cli_now(void) { return tt_clock(TT_CLOCK_WALL); }

const char *cli_duration(double s, char *buf, size_t len) { return tt_run_duration(s, buf, len); }

const char *cli_bytes(double b, char *buf, size_t len) { return tt_run_bytes(b, buf, len); }

void cli_report_estimate(const char *cmd, double cycles, double seconds, int upper_bound,
                         int threads, double f0, double fd, int quiet)
{
    char t[32];
    double wall = seconds / (threads > 0 ? threads : 1);
    if (!quiet)
        fprintf(stderr, "%s: %s%.3g drive cycles, %s%s by estimate%s\n", cmd,
                upper_bound ? "at most " : "", cycles, upper_bound ? "at most " : "about ",
                cli_duration(wall, t, sizeof t), threads > 1 ? " on all threads" : "");
    tt_run_warn_duration(wall, upper_bound, f0, fd);
}

int cli_lock_folder(const char *cmd, const char *dir)
{
    int fd;
    if (tt_folder_lock(dir, cmd, &fd) != TT_OK) {
        fprintf(stderr, "tiptap %s: %s\n", cmd, tt_error_message());
        return -1;
    }
    return fd;
}

void cli_unlock_folder(const char *dir, int fd) { tt_folder_unlock(dir, fd); }
