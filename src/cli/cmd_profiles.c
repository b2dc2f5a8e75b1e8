/* tiptap profiles: the profile lines of several scans in one figure, one panel each:
 * trace, retrace and the true topography, so that a loop's errors read at a glance. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "tiptap/util/str.h"
#include "tiptap/io/files.h"
#include "tiptap/io/plot.h"
#include "tiptap/util/error.h"

static void help(void)
{
    printf("Usage: tiptap profiles [-o FIG.png] [--title T] [--minus-surface] [--range LO:HI]\n"
           "                        [-q] DIR...\n"
           "Overlay, for each scan output folder DIR (tiptap scan -o DIR), the heights of\n"
           "its profile line (DIR/profile.csv): trace, retrace and, where the scan recorded\n"
           "the topography channel, the true surface. One panel per folder, titled by it.\n\n"
           "  -o FIG.png   output (default profiles.png)\n"
           "  --title T    the figure's title\n"
           "  --minus-surface  draw height - true surface (the loop's tracking error, on\n"
           "               its own scale: needs the topography channel)\n"
           "  --range LO:HI  the height axis from LO to HI nm in every panel (what lies\n"
           "               outside is cut off at the frame)\n");
}

enum { COLS = 64 };

/* The profile's position (nm) and the named columns (nm); n rows. */
typedef struct {
    double *col[4]; /* position, height trace, height retrace, topography */
    int have[4];    /* the columns the file has */
    size_t n;
} profile;

static void profile_free(profile *p)
{
    for (int i = 0; i < 4; i++)
        free(p->col[i]);
}

/* Which of our columns a header name is (-1: none). */
static int column_of(const char *name)
{
    static const char *const names[4] = {"position_nm", "height_trace_m", "height_retrace_m",
                                         "topography_trace_m"};
    for (int i = 0; i < 4; i++)
        if (strcmp(name, names[i]) == 0)
            return i;
    return -1;
}

static int read_profile(const char *dir, profile *p)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/profile.csv", dir);
    /* a regular file only (a pipe or a link to /dev/zero would be read for ever) */
    FILE *f;
    int rc = tt_input_fopen(path, "profile CSV", "profile", TT_INPUT_MAX_BYTES, &f);
    if (rc)
        return rc;
    char line[8192];
    int map[COLS], ncol = 0;
    memset(p, 0, sizeof *p);
    if (!fgets(line, sizeof line, f)) {
        fclose(f);
        return tt_error(TT_EIO, "%s: empty", path);
    }
    for (char *tok = strtok(line, ",\r\n"); tok && ncol < COLS; tok = strtok(NULL, ",\r\n")) {
        map[ncol] = column_of(tok);
        if (map[ncol] >= 0)
            p->have[map[ncol]] = 1;
        ncol++;
    }
    size_t cap = 0;
    while (rc == TT_OK && fgets(line, sizeof line, f)) {
        if (p->n == cap) {
            cap = cap ? 2 * cap : 256;
            for (int i = 0; i < 4 && rc == TT_OK; i++) {
                double *q = realloc(p->col[i], cap * sizeof *q);
                if (!q)
                    rc = tt_error_nomem("the profile read from %s", path);
                else
                    p->col[i] = q;
            }
            if (rc)
                break;
        }
        for (int i = 0; i < 4; i++)
            p->col[i][p->n] = NAN;
        char *s = line;
        for (int c = 0; c < ncol && s; c++) {
            char *end;
            double v = tt_strtod(s, &end);
            if (map[c] >= 0)
                p->col[map[c]][p->n] = map[c] == 0 ? v : v * 1e9;
            s = strchr(end, ',');
            if (s)
                s++;
        }
        p->n++;
    }
    fclose(f);
    if (rc == TT_OK && (p->n == 0 || !p->have[0] || !p->have[1]))
        rc = tt_error(TT_EIO, "%s: no rows", path);
    return rc;
}

static const char *base_name(const char *dir)
{
    size_t n = strlen(dir);
    while (n > 1 && dir[n - 1] == '/')
        n--;
    static char buf[256];
    size_t s = n;
    while (s > 0 && dir[s - 1] != '/')
        s--;
    snprintf(buf, sizeof buf, "%.*s", (int)(n - s), dir + s);
    return buf;
}

int cmd_profiles(int argc, char **argv)
{
    static const struct option own[] = {{"title", required_argument, NULL, 't'},
                                        {"minus-surface", no_argument, NULL, 'm'},
                                        {"range", required_argument, NULL, 'r'},
                                        {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"profiles", CLI_OPT_OUTPUT | CLI_OPT_QUIET, own, "", help};
    cli_args a = {.output = "profiles.png"};
    const char *title = "profile line: trace, retrace, true surface";
    int c, minus = 0;
    double lo = NAN, hi = NAN;
    while ((c = cli_getopt(&spec, &a, argc, argv)) > 0) {
        if (c == 't')
            title = optarg;
        if (c == 'm')
            minus = 1;
        if (c == 'r') {
            char *end, *mid;
            lo = tt_strtod(optarg, &mid);
            hi = *mid == ':' ? tt_strtod(mid + 1, &end) : NAN;
            if (mid == optarg || *mid != ':' || end == mid + 1 || *end || !(hi > lo)) {
                cli_args_free(&a);
                fprintf(stderr, "tiptap profiles: --range '%s': expected LO:HI in nm with LO < HI\n", optarg);
                return CLI_USAGE;
            }
        }
    }
    if (minus && strcmp(title, "profile line: trace, retrace, true surface") == 0)
        title = "profile line: height - true surface, trace and retrace";
    if (c == CLI_EXIT)
        return a.exit;
    int n = argc - optind;
    if (n < 1) {
        cli_args_free(&a);
        fprintf(stderr, "tiptap profiles: name at least one scan output folder\n");
        return CLI_USAGE;
    }
    int code = cli_outputs_check(&spec, &a); /* a pipe or a device at -o: refused before reading */
    if (code != CLI_OK)
        return code;
    tt_figure *f = tt_figure_alloc(n, title);
    int rc = f ? TT_OK : tt_error_nomem("the plot %s", a.output);
    for (int i = 0; i < n && rc == TT_OK; i++) {
        profile p;
        if ((rc = read_profile(argv[optind + i], &p)))
            break;
        char label[300];
        snprintf(label, sizeof label, "%s: %s (nm)", base_name(argv[optind + i]),
                 minus ? "height - surface" : "height");
        tt_figure_axes(f, i, i == n - 1 ? "position along the line (nm)" : "", label);
        if (minus && !p.have[3]) {
            rc = tt_error(TT_EINVAL, "--minus-surface: %s/profile.csv has no topography "
                                     "(add topography to [scan] channels)", argv[optind + i]);
            profile_free(&p);
            break;
        }
        for (size_t k = 0; minus && k < p.n; k++) {
            p.col[1][k] -= p.col[3][k];
            if (p.have[2])
                p.col[2][k] -= p.col[3][k];
        }
        if (isfinite(lo))
            tt_figure_ylim(f, i, lo, hi);
        if (p.have[3] && !minus)
            rc = tt_figure_line(f, i, p.col[0], p.col[3], p.n, i == 0 ? "true surface" : NULL,
                                7 | TT_PLOT_DASHED);
        if (rc == TT_OK)
            rc = tt_figure_line(f, i, p.col[0], p.col[1], p.n, i == 0 ? "trace" : NULL, 1 | TT_PLOT_THICK);
        if (rc == TT_OK && p.have[2])
            rc = tt_figure_line(f, i, p.col[0], p.col[2], p.n, i == 0 ? "retrace" : NULL, 2 | TT_PLOT_THICK);
        /* a line the scan never finished (interrupted) is NaN: said in its panel, not
         * left an empty frame */
        int any = 0;
        for (size_t k = 0; k < p.n; k++)
            any |= isfinite(p.col[1][k]) || (p.have[2] && isfinite(p.col[2][k]));
        if (rc == TT_OK && !any && p.n > 0) {
            tt_figure_ylim(f, i, 0, 1);
            rc = tt_figure_text(f, i, p.col[0][0], 0.5,
                                "no height on this line: the scan did not finish it (an "
                                "interrupted run; its lines_finished < lines_total)");
            fprintf(stderr, "tiptap profiles: %s: the profile line holds no height (the scan did not "
                            "finish it)\n", argv[optind + i]);
        }
        profile_free(&p);
    }
    cli_catch_interrupt(); /* the figure is finished, not left half-written */
    if (rc == TT_OK)
        rc = tt_figure_write_png(f, a.output, 900, 260 * n + 80);
    tt_figure_free(f);
    cli_args_free(&a);
    if (rc)
        return cli_fail(rc, NULL);
    if (!a.quiet)
        fprintf(stderr, "wrote %s\n", a.output);
    return CLI_OK;
}
