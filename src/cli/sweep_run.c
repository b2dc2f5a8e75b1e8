/* tiptap sweep: one combination's run (the library's rows, tiptap/run/sweep.h) into
 * CSV rows (see sweep.h). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "commands.h"
#include "sweep.h"
#include "tiptap/config/config.h"
#include "tiptap/util/str.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/error.h"

/* A growing text buffer (open_memstream keeps the formatting in one place). */
typedef struct {
    char *buf;
    size_t len;
    FILE *f;
} text;

static int text_open(text *t)
{
    t->buf = NULL;
    t->f = open_memstream(&t->buf, &t->len);
    return t->f ? TT_OK : tt_error(TT_ENOMEM, "out of memory");
}

static char *text_take(text *t)
{
    if (fclose(t->f) != 0) {
        free(t->buf);
        return NULL;
    }
    return t->buf;
}

/* CSV field: text values with a comma or quote are quoted. */
static void put_field(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\n")) {
        fputs(s, f);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputc('"', f);
}

static const char point_columns[] =
    "z_nm,amplitude_nm,phase_deg,mean_deflection_nm,peak_force_nN,max_indentation_nm,"
    "contact_fraction,dissipated_aJ,drive_work_aJ,energy_residual,regime,direction,settled,"
    "cycles,period,found";
static const char point_columns_viscous[] =
    ",dissipated_hysteresis_aJ,dissipated_damping_aJ,dissipated_viscous_aJ";
static const char point_columns_bimodal[] = ",amplitude_2_nm,phase_2_deg";
static const char scan_columns_bimodal[] =
    ",amplitude_2_mean_nm,phase_2_mean_deg,phase_2_std_deg,phase_2_contrast_deg";
static const char scan_columns[] =
    "folder,lines_done,energy_balance,error_estimate_height_nm,error_estimate_phase_deg,material,"
    "pixels,height_mean_nm,height_std_nm,phase_mean_deg,"
    "phase_std_deg,height_contrast_nm,phase_contrast_deg";

/* How the CSV writes each column of the library's rows after the varied keys: the
 * number times scale with %.9g ('g') or %.3g ('3'), a whole number ('d'), a text ('s'). */
typedef struct {
    double scale;
    char conv;
} csv_format;

static const csv_format setpoint_format = {1e9, 'g'};
static const csv_format point_format[] = {
    {1e9, 'g'}, {1e9, 'g'}, {1, 'g'}, {1e9, 'g'}, {1e9, 'g'}, {1e9, 'g'}, {1, 'g'}, {1e18, 'g'},
    {1e18, 'g'}, {1, '3'}, {1, 's'}, {1, 's'}, {1, 'd'}, {1, 'd'}, {1, 's'}, {1, 'd'},
    {1e18, 'g'}, {1e18, 'g'}, {1e18, 'g'}, /* viscous grids: the loss per mechanism */
    {1e9, 'g'}, {1, 'g'},                  /* bimodal grids: mode 2's lock-in */
};
enum { POINT_PLAIN = 16, POINT_VISCOUS = 3 }; /* point_format's columns, its viscous ones */
static const csv_format scan_format[] = {
    {1, 's'}, {1, 'd'}, {1, '3'}, {1e9, '3'}, {1, '3'}, {1, 's'}, {1, 'd'}, {1e9, 'g'}, {1e9, 'g'},
    {1, 'g'}, {1, 'g'}, {1e9, 'g'}, {1, 'g'},
    {1e9, 'g'}, {1, 'g'}, {1, 'g'}, {1, 'g'}, /* bimodal grids: mode 2's lock-in */
};

/* skip: point_format's viscous columns a grid without them skips (format_skip). */
static const csv_format *sweep_format(tt_sweep_kind kind, size_t j, size_t skip)
{
    if (kind == TT_SWEEP_SETPOINT && j == 0)
        return &setpoint_format;
    if (kind == TT_SWEEP_SETPOINT)
        j--;
    if (kind != TT_SWEEP_SCAN && j >= POINT_PLAIN)
        j += skip;
    return kind == TT_SWEEP_SCAN ? &scan_format[j] : &point_format[j];
}

/* A bimodal grid's mode 2 columns follow the viscous ones, or take their place. */
static size_t format_skip(const sweep_job *job)
{
    return job->kind != TT_SWEEP_SCAN && !tt_sweep_viscous(job->grid) ? POINT_VISCOUS : 0;
}

void sweep_header(const sweep_job *job, char *buf, size_t len)
{
    size_t used = (size_t)snprintf(buf, len, "combination");
    for (size_t k = 0; k < tt_sweep_keys(job->grid) && used < len; k++) {
        const char *u = tt_sweep_unit(job->grid, k);
        used += (size_t)snprintf(buf + used, len - used, ",%s%s%s%s", tt_sweep_key(job->grid, k),
                                 u[0] ? "[" : "", u, u[0] ? "]" : "");
    }
    int points = job->kind != TT_SWEEP_SCAN, bimodal = tt_sweep_bimodal(job->grid);
    if (used < len)
        snprintf(buf + used, len - used, ",%s%s%s%s\n", job->kind == TT_SWEEP_SETPOINT ? "setpoint_nm," : "",
                 points ? point_columns : scan_columns,
                 points && tt_sweep_viscous(job->grid) ? point_columns_viscous
                 : !points && bimodal                  ? scan_columns_bimodal
                                                       : "",
                 points && bimodal ? point_columns_bimodal : "");
}

/* The table's rows as CSV: the combination, the varied keys (SI numbers, or the text),
 * then the run's columns in the CSV's units. */
static void put_rows(FILE *f, const sweep_job *job, const tt_table *t)
{
    size_t nk = tt_sweep_keys(job->grid), skip = format_skip(job);
    for (size_t r = 0; r < tt_table_rows(t); r++) {
        fprintf(f, "%zu", (size_t)tt_table_numbers(t, 0)[r]);
        for (size_t c = 1; c < tt_table_columns(t); c++) {
            const csv_format *fm = c > nk ? sweep_format(job->kind, c - nk - 1, skip) : NULL;
            double v = tt_table_is_text(t, c) ? NAN : tt_table_numbers(t, c)[r];
            fputc(',', f);
            if (tt_table_is_text(t, c))
                put_field(f, tt_table_text(t, c, r));
            else if (!fm || fm->conv == 'g')
                fprintf(f, "%.9g", fm ? v * fm->scale : v);
            else if (fm->conv == '3')
                fprintf(f, "%.3g", v * fm->scale);
            else
                fprintf(f, "%ld", (long)v);
        }
        fputc('\n', f);
    }
}

/* The next CSV field of *p into buf (quotes undone); *p moves past its comma. */
static void get_field(const char **p, char *buf, size_t len)
{
    const char *s = *p;
    size_t n = 0;
    int quoted = *s == '"';
    for (s += quoted; *s && (quoted || (*s != ',' && *s != '\n')); s++) {
        if (quoted && *s == '"') {
            if (s[1] != '"') {
                quoted = 0;
                continue;
            }
            s++;
        }
        if (n + 1 < len)
            buf[n++] = *s;
    }
    buf[n] = '\0';
    *p = *s == ',' ? s + 1 : s;
}

/* One CSV line back into a row of t: put_rows undone. */
static int get_row(const sweep_job *job, tt_table *t, const char **p)
{
    size_t nk = tt_sweep_keys(job->grid), skip = format_skip(job);
    char field[4096];
    int rc = tt_table_row(t);
    for (size_t c = 0; c < tt_table_columns(t) && !rc; c++) {
        const csv_format *fm = c > nk ? sweep_format(job->kind, c - nk - 1, skip) : NULL;
        get_field(p, field, sizeof field);
        if (tt_table_is_text(t, c))
            rc = tt_table_set_text(t, c, field);
        else
            tt_table_set(t, c, tt_strtod(field, NULL) / (fm && fm->conv == 'g' ? fm->scale : 1));
    }
    if (**p == '\n')
        (*p)++;
    return rc;
}

int sweep_table(const sweep_job *job, const sweep_results *r, tt_table **out)
{
    int rc = tt_run_sweep_columns(job->grid, job->kind, out);
    for (size_t i = 0; i < r->n && !rc; i++)
        for (const char *p = r->text[i]; p && *p && !rc;)
            rc = get_row(job, *out, &p);
    if (rc) {
        tt_table_free(*out);
        *out = NULL;
    }
    return rc;
}

static int compute_scan(const sweep_job *job, size_t i, tt_table *t)
{
    char folder[4096], path[4200];
    tt_scene *scene = NULL;
    tt_scan *scan = NULL;
    tt_outfile *of = NULL;
    tt_cantilever cant;
    snprintf(folder, sizeof folder, "%s/%04zu", job->dir, i + 1);
    snprintf(path, sizeof path, "%s/scene.ini", folder);
    int rc, lock = -1;
    /* the folder locked as tiptap scan locks it: a scan running there is not mixed into */
    if ((rc = tt_sweep_scene(job->grid, i, &scene)) || (rc = tt_config_cantilever(scene, &cant)) ||
        (rc = tt_config_scan_alloc(&scan, scene)) || (rc = cli_scan_folder_take("sweep", folder, scan, job->hdf5, &lock)) ||
        (rc = tt_outfile_open(&of, path)))
        goto done;
    rc = tt_scene_write(scene, tt_outfile_stream(of), NULL);
    int crc = tt_outfile_close(of, rc == TT_OK);
    if (rc || (rc = crc) || (rc = tt_scan_run(scan, job->scan_threads, NULL, NULL)) ||
        (rc = cli_scan_write_outputs(scan, scene, folder, job->hdf5, &(int){0})))
        goto done;
    /* the scan's own error estimate, as tiptap scan reports it (a fifth of its cost at most) */
    tt_scan_error est;
    int erc = tt_scan_estimate_error(scan, &est);
    if (erc == TT_EINTR) {
        rc = erc;
        goto done;
    }
    rc = tt_run_sweep_scan_rows(job->grid, i, scene, scan, erc ? NULL : &est, t);
done:
    cli_unlock_folder(folder, lock);
    tt_scan_free(scan);
    tt_scene_free(scene);
    return rc;
}

int sweep_compute(const sweep_job *job, size_t i, char **out)
{
    tt_table *t;
    text x;
    int rc = tt_run_sweep_columns(job->grid, job->kind, &t);
    if (rc)
        return rc;
    rc = job->kind == TT_SWEEP_SCAN ? compute_scan(job, i, t) : tt_run_sweep_points(job->grid, job->kind, i, t);
    if (!rc && !(rc = text_open(&x))) {
        put_rows(x.f, job, t);
        if (!(*out = text_take(&x)))
            rc = tt_error(TT_ENOMEM, "out of memory");
    }
    tt_table_free(t);
    return rc;
}

/* A scan combination's folder, if it is there already, must be a folder it can write
 * (one left by an earlier sweep is written over). */
static int check_folder(const sweep_job *job, size_t i)
{
    char folder[4096];
    struct stat st;
    snprintf(folder, sizeof folder, "%s/%04zu", job->dir, i + 1);
    if (stat(folder, &st) != 0)
        return TT_OK;
    if (!S_ISDIR(st.st_mode))
        return tt_error(TT_EIO, "%s: is not a folder; combination %zu writes its scan there", folder, i + 1);
    if (access(folder, W_OK) != 0)
        return tt_error(TT_EIO, "%s: folder not writable: %s", folder, strerror(errno));
    return TT_OK;
}

int sweep_check(const sweep_job *job, size_t i)
{
    int rc = tt_run_sweep_check(job->grid, job->kind, i);
    return rc || job->kind != TT_SWEEP_SCAN ? rc : check_folder(job, i);
}
