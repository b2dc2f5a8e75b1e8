/* tiptap sweep: one combination's run into CSV rows (see sweep.h). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "commands.h"
#include "sweep.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/config/solver_scene.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/cancel.h"
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

/* The combination number and its varied keys: SI numbers, or the text. */
static void put_keys(FILE *f, const tt_sweep *g, size_t i)
{
    fprintf(f, "%zu", i + 1);
    for (size_t k = 0; k < tt_sweep_keys(g); k++) {
        fputc(',', f);
        double v = tt_sweep_value(g, i, k);
        if (isnan(v))
            put_field(f, tt_sweep_text(g, i, k));
        else
            fprintf(f, "%.9g", v);
    }
}

static const char point_columns[] =
    "z_nm,amplitude_nm,phase_deg,mean_deflection_nm,peak_force_nN,max_indentation_nm,"
    "contact_fraction,dissipated_aJ,drive_work_aJ,energy_residual,regime,direction,settled,"
    "cycles,found";
static const char scan_columns[] =
    "folder,lines_done,error_estimate,material,pixels,height_mean_nm,height_std_nm,phase_mean_deg,"
    "phase_std_deg,height_contrast_nm,phase_contrast_deg";

void sweep_header(const sweep_job *job, char *buf, size_t len)
{
    size_t used = (size_t)snprintf(buf, len, "combination");
    for (size_t k = 0; k < tt_sweep_keys(job->grid) && used < len; k++) {
        const char *u = tt_sweep_unit(job->grid, k);
        used += (size_t)snprintf(buf + used, len - used, ",%s%s%s%s", tt_sweep_key(job->grid, k),
                                 u[0] ? "[" : "", u, u[0] ? "]" : "");
    }
    if (used < len)
        snprintf(buf + used, len - used, ",%s%s\n", job->kind == SWEEP_SETPOINT ? "setpoint_nm," : "",
                 job->kind == SWEEP_SCAN ? scan_columns : point_columns);
}

/* Free oscillation, or the attractive (phase lag above 90 degrees) or repulsive regime
 * of tapping (Burnham et al.'s two branches of the approach curve). */
static const char *regime(const tt_cycle *c, double A0)
{
    if (c->contact_fraction == 0 && c->max_indentation < 0 && fabs(c->amplitude - A0) < 1e-3 * A0)
        return "free";
    return c->phase > M_PI / 2 ? "attractive" : "repulsive";
}

/* A point's row; found: the last column when not how the point was found (NULL). */
static void put_point(FILE *f, const tt_approach_point *p, double A0, int ok, const char *found)
{
    const tt_cycle *c = &p->cycle;
    if (!ok) {
        fprintf(f, "%.9g,nan,nan,nan,nan,nan,nan,nan,nan,nan,failed,approach,0,0,failed\n", p->z * 1e9);
        return;
    }
    fprintf(f, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.3g,%s,%s,%d,%ld,%s\n", p->z * 1e9,
            c->amplitude * 1e9, c->phase * 180 / M_PI, c->mean * 1e9, c->peak_force * 1e9,
            c->max_indentation * 1e9, c->contact_fraction, c->e_ts * 1e18, c->e_drive * 1e18,
            c->residual_rel, regime(c, A0), p->retract ? "retract" : "approach", p->settled,
            p->cycles, found ? found : p->shot.how == TT_SHOOT_NEWTON && p->cycles >= 0 ? "newton" : "settled");
}

/* rc with the combination named in front of the message. */
static int name_combination(const sweep_job *job, size_t i, int rc)
{
    char label[512], msg[1024];
    tt_sweep_label(job->grid, i, label, sizeof label);
    snprintf(msg, sizeof msg, "%s", tt_error_message());
    return tt_error(rc, "combination %zu (%s): %s", i + 1, label, msg);
}

/* One combination made ready: its scene, setup with the [approach] material under the
 * tip, and [approach]. */
typedef struct {
    tt_scene *scene;
    tt_setup *st;
    tt_approach_params p;
} combo;

static void combo_close(combo *c)
{
    tt_setup_free(c->st);
    tt_scene_free(c->scene);
}

static int combo_open(const sweep_job *job, size_t i, combo *c)
{
    memset(c, 0, sizeof *c);
    int rc;
    if ((rc = tt_sweep_scene(job->grid, i, &c->scene)))
        return rc;
    if ((rc = tt_setup_alloc(&c->st, c->scene)) || (rc = tt_config_approach_setup(c->st, c->scene, &c->p))) {
        combo_close(c);
        return name_combination(job, i, rc);
    }
    return TT_OK;
}

/* The steady oscillation at rest separation z, from a fresh approach of one point. */
static int steady_at(combo *c, double z, tt_approach_point *pt)
{
    tt_approach_params p = c->p;
    p.from = p.to = z;
    p.points = 1;
    p.retract = 0;
    p.mode = TT_APPROACH_STEADY;
    tt_approach *ap = NULL;
    memset(pt, 0, sizeof *pt);
    pt->z = z;
    int rc = tt_approach_alloc(&ap, tt_setup_sim(c->st), &p);
    if (!rc)
        rc = tt_approach_iterate(ap, pt);
    tt_approach_free(ap);
    return rc;
}

/* The rest separation where the steady amplitude equals the setpoint (to 1e-3 of A0,
 * below what an image resolves): secant steps
 * from the guess A(z) = z (the repulsive branch's slope, Burnham et al. fig. 1), kept
 * inside a bracket once one is found (regula falsi, Illinois). *reached: whether it
 * was; when not (an amplitude that never comes down to the setpoint, as at Q = 1, or
 * jumps across it), *pt is the closest point. */
static int setpoint_point(combo *c, double target, tt_approach_point *pt, int *reached)
{
    double A0 = tt_setup_cantilever(c->st)->A0, tol = 1e-3 * A0;
    double zl = NAN, fl = NAN, zh = NAN, fh = NAN, z = target;
    tt_approach_point best = {0};
    double bestf = INFINITY;
    int side = 0;
    for (int it = 0; it < 16; it++) {
        int rc = steady_at(c, z, pt);
        if (rc)
            return rc;
        double f = pt->cycle.amplitude - target;
        if (fabs(f) < fabs(bestf))
            bestf = f, best = *pt;
        if (fabs(f) < tol)
            break;
        if (f < 0)
            zl = z, fl = f;
        else
            zh = z, fh = f;
        if (!isnan(zl) && !isnan(zh)) {
            if (fabs(zh - zl) < 1e-6 * A0)
                break;
            if (side == (f < 0 ? -1 : 1)) {
                if (f < 0)
                    fh /= 2;
                else
                    fl /= 2;
            }
            side = f < 0 ? -1 : 1;
            z = zl - fl * (zh - zl) / (fh - fl);
        } else
            z -= f; /* amplitude rises about one to one with the separation */
    }
    *pt = best;
    *reached = fabs(bestf) < tol;
    return TT_OK;
}

static int compute_points(const sweep_job *job, size_t i, FILE *f)
{
    combo c;
    int rc = combo_open(job, i, &c);
    if (rc)
        return rc;
    double A0 = tt_setup_cantilever(c.st)->A0;
    tt_approach_point pt;
    if (job->kind == SWEEP_STEADY || job->kind == SWEEP_SETPOINT) {
        double target = 0;
        tt_feedback_params fp;
        if (job->kind == SWEEP_SETPOINT && !(rc = tt_config_feedback(c.scene, A0, &fp)))
            target = fp.setpoint;
        int run = TT_OK, reached = 1;
        if (!rc)
            run = job->kind == SWEEP_STEADY ? steady_at(&c, c.p.from, &pt)
                                            : setpoint_point(&c, target, &pt, &reached);
        /* a cancelled point is no failed one: the combination is left for the resume */
        if (run == TT_EINTR)
            rc = run;
        else if (!rc) {
            put_keys(f, job->grid, i);
            if (job->kind == SWEEP_SETPOINT)
                fprintf(f, ",%.9g", target * 1e9);
            fputc(',', f);
            put_point(f, &pt, A0, run == TT_OK, reached ? NULL : SWEEP_UNREACHABLE);
        }
    } else {
        tt_approach *ap = NULL;
        if (!(rc = tt_approach_alloc(&ap, tt_setup_sim(c.st), &c.p))) {
            while (!tt_approach_done(ap) && !rc) {
                if (tt_cancel_requested()) {
                    rc = TT_EINTR;
                    break;
                }
                int run = tt_approach_iterate(ap, &pt);
                if (run == TT_EINTR) {
                    rc = run;
                    break;
                }
                put_keys(f, job->grid, i);
                fputc(',', f);
                put_point(f, &pt, A0, run == TT_OK, NULL);
                if (run)
                    break; /* the branch cannot go on from a failed point */
            }
        }
        tt_approach_free(ap);
    }
    combo_close(&c);
    return rc;
}

/* Mean and standard deviation of an image over the pixels of material m (m < 0: all). */
static void image_stats(const double *img, const int *mat, size_t n, int m, double *mean, double *sd,
                        size_t *count)
{
    double s = 0, s2 = 0;
    size_t k = 0;
    for (size_t j = 0; j < n; j++)
        if ((m < 0 || mat[j] == m) && isfinite(img[j]))
            s += img[j], k++;
    *mean = k ? s / (double)k : NAN;
    for (size_t j = 0; j < n; j++)
        if ((m < 0 || mat[j] == m) && isfinite(img[j]))
            s2 += (img[j] - *mean) * (img[j] - *mean);
    *sd = k > 1 ? sqrt(s2 / (double)(k - 1)) : NAN;
    *count = k;
}

/* The scan's summary rows: every material (the one at each pixel's centre), and its
 * height and phase contrast against the first material. */
static int scan_summary(const sweep_job *job, size_t i, const tt_scene *scene, tt_scan *scan,
                        const char *folder, FILE *f)
{
    long xr = tt_scan_xres(scan), yr = tt_scan_yres(scan);
    size_t n = (size_t)(xr * yr);
    const double *h = tt_scan_image(scan, 0, 0), *ph = tt_scan_image(scan, 2, 0);
    tt_material *mats = NULL;
    size_t nm = 0;
    tt_surface *surf = NULL;
    int *mat = calloc(n, sizeof *mat);
    int rc = mat ? TT_OK : tt_error(TT_ENOMEM, "out of memory");
    if (!rc && !(rc = tt_config_materials(scene, &mats, &nm)))
        rc = tt_config_surface_alloc(&surf, scene, tt_scan_size_x(scan), tt_scan_size_y(scan));
    for (long y = 0; y < yr && !rc; y++)
        for (long x = 0; x < xr; x++)
            mat[y * xr + x] = tt_surface_material(surf, ((double)x + 0.5) * tt_scan_size_x(scan) / (double)xr,
                                                  ((double)y + 0.5) * tt_scan_size_y(scan) / (double)yr);
    double h0 = NAN, p0 = NAN;
    for (int m = -1; m < (int)nm && !rc; m++) {
        double hm, hs, pm = NAN, ps = NAN;
        size_t cnt;
        image_stats(h, mat, n, m, &hm, &hs, &cnt);
        if (ph)
            image_stats(ph, mat, n, m, &pm, &ps, &cnt);
        if (m >= 0 && cnt == 0)
            continue;
        if (m >= 0 && isnan(h0))
            h0 = hm, p0 = pm;
        put_keys(f, job->grid, i);
        fprintf(f, ",%s,%ld,%.3g,", folder, tt_scan_lines_done(scan), tt_scan_error_estimate(scan));
        put_field(f, m < 0 ? "all" : mats[m].name);
        fprintf(f, ",%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", cnt, hm * 1e9, hs * 1e9, pm, ps,
                m < 0 ? NAN : (hm - h0) * 1e9, m < 0 ? NAN : pm - p0);
    }
    tt_surface_free(surf);
    free(mats);
    free(mat);
    return rc;
}

static int compute_scan(const sweep_job *job, size_t i, FILE *f)
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
        (rc = tt_config_scan_alloc(&scan, scene)) || (rc = cli_scan_folder_take("sweep", folder, &lock)) ||
        (rc = tt_outfile_open(&of, path)))
        goto done;
    rc = tt_scene_write(scene, tt_outfile_stream(of), NULL);
    int crc = tt_outfile_close(of, rc == TT_OK);
    if (rc || (rc = crc) || (rc = tt_scan_run(scan, job->scan_threads, NULL, NULL)) ||
        (rc = cli_scan_write_outputs(scan, scene, folder, 0, &(int){0})))
        goto done;
    const char *slash = strrchr(folder, '/');
    rc = scan_summary(job, i, scene, scan, slash ? slash + 1 : folder, f);
done:
    cli_unlock_folder(folder, lock);
    tt_scan_free(scan);
    tt_scene_free(scene);
    return rc;
}

size_t sweep_unreached(const sweep_results *r, size_t *list, size_t max)
{
    static const char tail[] = "," SWEEP_UNREACHABLE "\n";
    size_t count = 0, tl = sizeof tail - 1;
    for (size_t i = 0; i < r->n; i++) {
        const char *t = r->text[i];
        size_t len = t ? strlen(t) : 0;
        if (len >= tl && strcmp(t + len - tl, tail) == 0 && count++ < max)
            list[count - 1] = i;
    }
    return count;
}

int sweep_compute(const sweep_job *job, size_t i, char **out)
{
    text t;
    int rc = text_open(&t);
    if (rc)
        return rc;
    rc = job->kind == SWEEP_SCAN ? compute_scan(job, i, t.f) : compute_points(job, i, t.f);
    char *s = text_take(&t);
    if (!s && !rc)
        rc = tt_error(TT_ENOMEM, "out of memory");
    if (rc) {
        free(s);
        return rc;
    }
    *out = s;
    return TT_OK;
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
    if (job->kind == SWEEP_SCAN) {
        tt_scene *scene = NULL;
        tt_scan_params p;
        int rc = tt_sweep_scene(job->grid, i, &scene);
        if (!rc && !(rc = tt_config_scan(scene, &p)))
            tt_config_scan_free(&p);
        if (rc && scene)
            rc = name_combination(job, i, rc);
        tt_scene_free(scene);
        return rc ? rc : check_folder(job, i);
    }
    /* the configuration layer only, which checks every key and rule, without building
     * force tables (a third of a steady point's cost) */
    tt_scene *scene = NULL;
    tt_cantilever cant;
    tt_solver solver;
    tt_material *mats = NULL;
    tt_approach_params ap;
    tt_feedback_params fp;
    size_t nm = 0, mat = 0;
    int rc = tt_sweep_scene(job->grid, i, &scene);
    if (rc)
        return rc;
    if ((rc = tt_config_cantilever(scene, &cant)) || (rc = tt_solver_from_scene(&solver, scene)) ||
        (rc = tt_config_materials(scene, &mats, &nm)) ||
        (rc = tt_config_material_index(scene, "approach", mats, nm, &mat)) ||
        (rc = tt_config_approach(scene, &ap)) ||
        (job->kind == SWEEP_SETPOINT && (rc = tt_config_feedback(scene, cant.A0, &fp))))
        rc = name_combination(job, i, rc);
    free(mats);
    tt_scene_free(scene);
    return rc;
}
