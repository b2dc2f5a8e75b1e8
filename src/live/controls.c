/* The live console's knobs (include/tiptap/live/controls.h): messages read into scene
 * text and checked by the configuration layer, the same checks as tiptap scan's. */
#include "tiptap/live/controls.h"

#include <ctype.h>
#include <dirent.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "live_private.h"
#include "tiptap/config/config.h"
#include "tiptap/config/read_force_tune.h"
#include "tiptap/live/lesson.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

enum { K_SAMPLE = 0, K_NOISE = 1 }; /* the console's own knobs, first in the table */

static const tt_live_control table[] = {
    {"sample", "sample", "", 1, NULL},
    {"noise", "noise", "", 0, NULL},
    {"noise.seed", "noise seed", "", 0, NULL},
    /* in % of the free amplitude, as the scene writes it (scene_schema.c: 80 %) */
    {"feedback.setpoint", "setpoint", "%", 0, NULL},
    {"feedback.proportional_gain", "P gain", "", 0, NULL},
    {"feedback.integral_gain", "I gain", "Hz", 0, NULL},
    {"scan.line_rate", "line rate", "Hz", 0, NULL},
    {"scan.size", "scan size", "nm", 1, NULL},
    {"scan.fast_axis", "fast axis (angle)", "", 1, NULL},
    {"scan.pixels", "pixels", "", 1, NULL},
    {"scan.lines", "lines", "", 1, NULL},
    {"cantilever.free_amplitude", "free amplitude", "nm", 0, NULL},
    {"solver.tier", "tier", "", 1, NULL},
    /* the benches' own knobs, checked with the rest (tt_config_force at each change) */
    {"force.speed", "ramp speed", "um/s", 0, "force"},
    {"force.range", "ramp range", "nm", 0, "force"},
    {"tune.duration", "record", "s", 0, "tune"},
};
enum { NKNOBS = sizeof table / sizeof table[0], NSAMPLES_MAX = 64 };

/* The noise that "noise = on" gives a scene without any: a good instrument's thermal
 * and detector noise (examples/feedback-tuning/common.ini), which the envelope tier
 * carries; not its z piezo's 0.3 pm/sqrt(Hz), which no image of the teaching scene
 * shows and which adds the sample's travel to the envelope tier's inputs (more cycles
 * a build, and checks at its reach; docs/dynamics.md, "Noise on the envelope tier"). */
static const char good_noise[] = "temperature = 300 K\ndetector = 100 fm/sqrt(Hz)\n";

/* The benches' knobs as the accepted scene has them (tt_live_controls_value). */
typedef struct {
    double speed, range, duration; /* m/s, m, s */
} bench_values;

struct tt_live_controls {
    char **files;
    int nfiles;
    char **sets;
    int nsets;
    char *surfaces;
    char *samples[NSAMPLES_MAX];
    size_t nsamples;
    int sample_file; /* the index in files of the bundled sample given, -1: none */
    int sample;      /* the sample chosen (index into samples), -1: as the files say */
    int noise_off;
    int scene_noise; /* the files' scene has noise of its own */
    char *given[NKNOBS]; /* the values the user gave, NULL: the scene's */
    tt_scan_params params; /* of the accepted scene */
    bench_values bench;    /* its [force] ramp and [tune] record */
    int have_params;
    double (*memory)(void); /* the bytes this process may still take (NULL: no check) */
    tt_live_lesson *lesson; /* NULL: none */
    int owns_lesson;        /* 0: a copy's, borrowed from the controls it was copied from */
};

const tt_live_control *tt_live_control_table(size_t *count)
{
    *count = NKNOBS;
    return table;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The bundled samples: every *.ini in the folder, sorted. */
static void list_samples(tt_live_controls *c)
{
    DIR *d = opendir(c->surfaces);
    struct dirent *e;
    while (d && (e = readdir(d)) && c->nsamples < NSAMPLES_MAX) {
        size_t n = strlen(e->d_name);
        if (n > 4 && strcmp(e->d_name + n - 4, ".ini") == 0 && e->d_name[0] != '.') {
            char *s = tt_strdup(e->d_name);
            if (!s)
                break;
            s[n - 4] = '\0';
            c->samples[c->nsamples++] = s;
        }
    }
    if (d)
        closedir(d);
    qsort(c->samples, c->nsamples, sizeof c->samples[0], cmp_str);
}

/* Which of the files is one of the bundled samples (by its real path), -1: none. */
static int find_sample_file(const tt_live_controls *c, int *which)
{
    char dir[PATH_MAX], f[PATH_MAX];
    *which = -1;
    if (!realpath(c->surfaces, dir))
        return -1;
    size_t n = strlen(dir);
    for (int i = c->nfiles - 1; i >= 0; i--) {
        if (!realpath(c->files[i], f) || strncmp(f, dir, n) != 0 || f[n] != '/')
            continue;
        for (size_t k = 0; k < c->nsamples; k++) {
            size_t m = strlen(c->samples[k]);
            if (strncmp(f + n + 1, c->samples[k], m) == 0 && strcmp(f + n + 1 + m, ".ini") == 0)
                *which = (int)k;
        }
        if (*which >= 0)
            return i;
    }
    return -1;
}

static int has_noise(const tt_scan_noise *n)
{
    return n->temperature > 0 || n->detector > 0 || n->z_piezo > 0;
}

/* The console's values as scene text, section by section. */
static int console_text(const tt_live_controls *c, char *const *given, int noise_off, char *buf,
                        size_t len)
{
    size_t used = 0;
    const char *last = NULL;
    int w = 0;
    buf[0] = '\0';
    if (!c->scene_noise || noise_off)
        w = snprintf(buf, len, "[noise]\n%s", noise_off ? "temperature = 0 K\ndetector = 0 m/sqrt(Hz)\n"
                                                          "z_piezo = 0 m/sqrt(Hz)\n"
                                                        : good_noise);
    if (w < 0 || (size_t)w >= len)
        return -1;
    used = (size_t)w;
    for (size_t i = K_NOISE + 1; i < NKNOBS; i++) {
        if (!given[i])
            continue;
        const char *dot = strchr(table[i].name, '.');
        size_t sl = (size_t)(dot - table[i].name);
        int sec_new = !last || strncmp(last, table[i].name, sl) != 0 || last[sl] != '.';
        w = snprintf(buf + used, len - used, "%s%.*s%s%s = %s\n", sec_new ? "[" : "",
                     sec_new ? (int)sl : 0, table[i].name, sec_new ? "]\n" : "", dot + 1, given[i]);
        if (w < 0 || (size_t)w >= len - used)
            return -1;
        used += (size_t)w;
        last = table[i].name;
    }
    return 0;
}

/* The scene of the files, the sample, the --set texts and the console's values. */
static int build(const tt_live_controls *c, char *const *given, int sample, int noise_off,
                 tt_scene **out)
{
    tt_scene *s = tt_scene_alloc();
    char path[PATH_MAX], text[4096];
    int rc = s ? TT_OK : tt_error_nomem("the console's scene");
    int put = 0;
    for (int i = 0; i < c->nfiles && !rc; i++) {
        if (sample >= 0 && i == c->sample_file) {
            snprintf(path, sizeof path, "%s/%s.ini", c->surfaces, c->samples[sample]);
            rc = tt_scene_load(s, path);
            put = 1;
        } else {
            rc = tt_scene_load(s, c->files[i]);
        }
    }
    if (!rc && sample >= 0 && !put) {
        snprintf(path, sizeof path, "%s/%s.ini", c->surfaces, c->samples[sample]);
        rc = tt_scene_load(s, path);
    }
    /* the lesson's own sections after its files and the files given, before --set */
    if (!rc && c->lesson && c->lesson->has_scene_text)
        rc = tt_scene_load_string(s, c->lesson->scene_text, c->lesson->path);
    for (int i = 0; i < c->nsets && !rc; i++)
        rc = tt_scene_set(s, c->sets[i]);
    if (!rc && console_text(c, given, noise_off, text, sizeof text))
        rc = tt_error(TT_EINVAL, "console: the values given are too long");
    if (!rc && text[0])
        rc = tt_scene_load_string(s, text, "console");
    if (rc) {
        tt_scene_free(s);
        return rc;
    }
    *out = s;
    return TT_OK;
}

static const char *gb(double bytes, char *buf, size_t len)
{
    if (bytes < 1e6)
        snprintf(buf, len, "%.0f kB", bytes / 1e3);
    else
        snprintf(buf, len, bytes < 1e9 ? "%.0f MB" : "%.1f GB", bytes < 1e9 ? bytes / 1e6 : bytes / 1e9);
    return buf;
}

/* The memory the console holds for a scene, from tiptap scan's estimate (config.h): up
 * to three scans with the page's copy of their images (five channels, seven in a bimodal
 * scene, both ways): the running one, a change's waiting for the line's end and the next
 * change's being built; the preview's twin of the scan; and two scope records, the
 * scan's and the preview's.
 * More than the machine has is refused before anything is made. */
static int check_memory(const tt_live_controls *c, const tt_scene *s, const tt_scan_params *p)
{
    if (!c->memory)
        return TT_OK;
    tt_estimate e;
    tt_config_scan_estimate(p, &e);
    double image = (double)p->raster.pixels * (double)p->raster.lines * sizeof(double);
    /* mode 2's two images only in a bimodal scene */
    int nch = p->cantilever.A2 > 0 ? TT_LIVE_NCH : TT_LIVE_AMPLITUDE2;
    double scan = e.bytes + 2 * nch * image + e.thread_bytes;
    double need = 3 * scan + (p->solver.tier == TT_TIER_AVERAGED ? 0 : e.bytes) + 2 * e.scope_bytes;
    double avail = c->memory();
    if (need <= avail)
        return TT_OK;
    static const char *const rate[] = {"scan.line_rate", NULL};
    static const char *const raster[] = {"scan.pixels", "scan.lines", NULL};
    char a[32], b[32], d[32], f[32];
    return tt_scene_fail_set(s, 2 * e.scope_bytes > need / 2 ? rate : raster,
                             "%ld x %ld pixels at %g Hz need about %s of memory in the console "
                             "(three scans of %s and the page's images, two scope records of %s: "
                             "a point a lock-in block), more than the %s available; fewer "
                             "pixels or lines, or a faster line rate",
                             p->raster.pixels, p->raster.lines, p->raster.line_rate,
                             gb(need, a, sizeof a), gb(scan, b, sizeof b),
                             gb(e.scope_bytes, d, sizeof d), gb(avail, f, sizeof f));
}

/* What tiptap scan checks before it runs, without making the scan: every key, rule and
 * material, the rk4 setting, and the memory the console would hold. */
static int check(const tt_live_controls *c, const tt_scene *s, tt_scan_params *p, bench_values *b)
{
    int rc = tt_config_scan(s, p);
    if (rc)
        return rc;
    /* the force bench's ramp too, so that a refused ramp value never reaches a run; the
     * tune's record is checked when it runs (it needs the noise, which may be off) */
    tt_force_params fp = {0};
    if (!(rc = tt_config_check_rk4(s, NULL, 0)) && !(rc = check_memory(c, s, p)) &&
        !(rc = tt_config_force(s, &fp)))
        rc = tt_config_tune_duration(s, &b->duration);
    if (rc)
        tt_config_scan_free(p);
    b->speed = fp.speed;
    b->range = fp.from - fp.to;
    return rc;
}

int tt_live_controls_alloc(tt_live_controls **out, char *const *files, int nfiles,
                           char *const *sets, int nsets, const char *surfaces,
                           double (*memory)(void))
{
    return tt_live_controls_alloc_lesson(out, NULL, files, nfiles, sets, nsets, surfaces, memory);
}

int tt_live_controls_alloc_lesson(tt_live_controls **out, tt_live_lesson *lesson, char *const *files,
                                  int nfiles, char *const *sets, int nsets, const char *surfaces,
                                  double (*memory)(void))
{
    tt_live_controls *c = calloc(1, sizeof *c);
    if (!c) {
        tt_live_lesson_free(lesson);
        return tt_error_nomem("the console's controls");
    }
    int rc = TT_OK;
    c->memory = memory;
    c->lesson = lesson;
    c->owns_lesson = 1;
    /* the lesson's scene files first, as if given before the others */
    int nl = lesson ? lesson->nfiles : 0;
    c->files = calloc((size_t)(nfiles + nl) + 1, sizeof *c->files);
    c->sets = calloc((size_t)nsets + 1, sizeof *c->sets);
    c->surfaces = tt_strdup(surfaces);
    if (!c->files || !c->sets || !c->surfaces)
        rc = tt_error_nomem("the console's scene files");
    for (int i = 0; i < nl && !rc; i++)
        if (!(c->files[c->nfiles++] = tt_strdup(lesson->files[i])))
            rc = tt_error_nomem("the console's scene files");
    for (int i = 0; i < nfiles && !rc; i++)
        if (!(c->files[c->nfiles++] = tt_strdup(files[i])))
            rc = tt_error_nomem("the console's scene files");
    for (int i = 0; i < nsets && !rc; i++)
        if (!(c->sets[c->nsets++] = tt_strdup(sets[i])))
            rc = tt_error_nomem("the console's --set");
    int which = -1;
    if (!rc) {
        list_samples(c);
        c->sample_file = find_sample_file(c, &which);
        c->sample = -1;
        (void)which;
    }
    /* the files' own noise decides what "noise = on" means */
    tt_scene *s = NULL;
    c->scene_noise = 1;
    if (!rc && !(rc = build(c, c->given, -1, 0, &s)) && !(rc = check(c, s, &c->params, &c->bench))) {
        c->have_params = 1;
        c->scene_noise = has_noise(&c->params.noise);
        c->noise_off = !c->scene_noise;
        tt_config_scan_free(&c->params);
        c->have_params = 0;
        tt_scene_free(s);
        s = NULL;
        if (!(rc = build(c, c->given, -1, c->noise_off, &s)) && !(rc = check(c, s, &c->params, &c->bench)))
            c->have_params = 1;
    }
    tt_scene_free(s);
    if (rc) {
        tt_live_controls_free(c);
        return rc;
    }
    *out = c;
    return TT_OK;
}

void tt_live_controls_free(tt_live_controls *c)
{
    if (!c)
        return;
    for (int i = 0; i < c->nfiles; i++)
        free(c->files[i]);
    if (c->owns_lesson)
        tt_live_lesson_free(c->lesson);
    for (int i = 0; i < c->nsets; i++)
        free(c->sets[i]);
    for (size_t i = 0; i < c->nsamples; i++)
        free(c->samples[i]);
    for (size_t i = 0; i < NKNOBS; i++)
        free(c->given[i]);
    if (c->have_params)
        tt_config_scan_free(&c->params);
    free(c->files);
    free(c->sets);
    free(c->surfaces);
    free(c);
}

/* A string array's copy (n entries and a NULL), or NULL out of memory. */
static char **copy_strs(char *const *a, int n)
{
    char **b = calloc((size_t)n + 1, sizeof *b);
    for (int i = 0; b && i < n; i++)
        if (!(b[i] = tt_strdup(a[i]))) {
            while (i--)
                free(b[i]);
            free(b);
            return NULL;
        }
    return b;
}

int tt_live_controls_copy(tt_live_controls **out, const tt_live_controls *c)
{
    tt_live_controls *d = calloc(1, sizeof *d);
    if (!d)
        return tt_error_nomem("the console's controls");
    *d = *c;
    d->owns_lesson = 0;
    d->have_params = 0;
    d->files = copy_strs(c->files, c->nfiles);
    d->sets = copy_strs(c->sets, c->nsets);
    d->surfaces = tt_strdup(c->surfaces);
    memset(d->samples, 0, sizeof d->samples);
    memset(d->given, 0, sizeof d->given);
    int rc = d->files && d->sets && d->surfaces ? TT_OK : tt_error_nomem("the console's controls");
    if (!d->files)
        d->nfiles = 0;
    if (!d->sets)
        d->nsets = 0;
    for (size_t i = 0; i < c->nsamples && !rc; i++)
        if (!(d->samples[i] = tt_strdup(c->samples[i])))
            rc = tt_error_nomem("the console's samples");
    for (size_t i = 0; i < NKNOBS && !rc; i++)
        if (c->given[i] && !(d->given[i] = tt_strdup(c->given[i])))
            rc = tt_error_nomem("the console's values");
    /* the parameters anew from the same scene: a copy owns its own materials */
    tt_scene *s = NULL;
    if (!rc && !(rc = build(d, d->given, d->sample, d->noise_off, &s)) && !(rc = check(d, s, &d->params, &d->bench)))
        d->have_params = 1;
    tt_scene_free(s);
    if (rc) {
        tt_live_controls_free(d);
        return rc;
    }
    *out = d;
    return TT_OK;
}

static int knob(const char *name, size_t n)
{
    for (size_t i = 0; i < NKNOBS; i++)
        if (strlen(table[i].name) == n && strncmp(table[i].name, name, n) == 0)
            return (int)i;
    return -1;
}

/* One line "set NAME = VALUE": the knob and the value's bounds, or a refusal. */
static int parse_set(const char *line, size_t n, int *k, const char **v, size_t *vn, char *why,
                     size_t wl)
{
    const char *eq = memchr(line, '=', n);
    const char *p = line + 3, *e;
    while (p < line + n && (*p == ' ' || *p == '\t'))
        p++;
    if (!eq) {
        snprintf(why, wl, "console: '%.*s': expected set NAME = VALUE", (int)tt_live_utf8_fit(line, n > 80 ? 80 : n),
                 line);
        return -1;
    }
    for (e = eq; e > p && (e[-1] == ' ' || e[-1] == '\t'); e--)
        ;
    if ((*k = knob(p, (size_t)(e - p))) < 0) {
        char names[600] = "";
        for (size_t i = 0, u = 0; i < NKNOBS; i++)
            u += (size_t)snprintf(names + u, sizeof names - u, "%s%s", i ? ", " : "", table[i].name);
        snprintf(why, wl, "console: '%.*s': no such control; the console sets %s",
                 (int)tt_live_utf8_fit(p, (size_t)(e - p > 60 ? 60 : e - p)), p, names);
        return -1;
    }
    for (p = eq + 1; p < line + n && (*p == ' ' || *p == '\t'); p++)
        ;
    for (e = line + n; e > p && (e[-1] == ' ' || e[-1] == '\t'); e--)
        ;
    *v = p;
    *vn = (size_t)(e - p);
    if (*vn == 0 || *vn > 200) {
        snprintf(why, wl, "console: %s: %s", table[*k].name,
                 *vn ? "a value of at most 200 characters" : "no value; expected set NAME = VALUE");
        return -1;
    }
    return 0;
}

/* The console's own knobs: the sample by name, noise on or off. */
static int own_knob(const tt_live_controls *c, int k, const char *v, size_t vn, int *sample,
                    int *noise_off, char *why, size_t wl)
{
    if (k == K_NOISE) {
        if (vn == 2 && strncmp(v, "on", 2) == 0)
            *noise_off = 0;
        else if (vn == 3 && strncmp(v, "off", 3) == 0)
            *noise_off = 1;
        else {
            snprintf(why, wl, "console: noise: '%.*s': expected on or off", (int)tt_live_utf8_fit(v, vn), v);
            return -1;
        }
        return 0;
    }
    for (size_t i = 0; i < c->nsamples; i++)
        if (strlen(c->samples[i]) == vn && strncmp(c->samples[i], v, vn) == 0) {
            *sample = (int)i;
            return 0;
        }
    size_t u = (size_t)snprintf(why, wl, "console: sample: '%.*s': not a bundled sample; one of ",
                                (int)tt_live_utf8_fit(v, vn > 60 ? 60 : vn), v);
    for (size_t i = 0; i < c->nsamples && u < wl; i++)
        u += (size_t)snprintf(why + u, wl - u, "%s%s", i ? ", " : "", c->samples[i]);
    return -1;
}

/* A copy of p that owns its materials. */
static int copy_params(tt_scan_params *dst, const tt_scan_params *src)
{
    tt_material *m = malloc((src->nmaterials ? src->nmaterials : 1) * sizeof *m);
    if (!m)
        return tt_error_nomem("the console's scene");
    memcpy(m, src->materials, src->nmaterials * sizeof *m);
    *dst = *src;
    dst->materials = m;
    return TT_OK;
}

int tt_live_controls_apply(tt_live_controls *c, const char *text, size_t len, tt_live_change *ch,
                           tt_live_take_fn take, void *user)
{
    char *given[NKNOBS] = {0};
    int sample = c->sample, noise_off = c->noise_off, bad = 0, any = 0, restart = 0;
    memset(ch, 0, sizeof *ch);
    for (size_t i = 0; i < NKNOBS; i++)
        given[i] = c->given[i];
    const char *p = text, *end = text + len;
    char *fresh[NKNOBS] = {0}; /* the values this message gave */
    /* text from a page is UTF-8 (its replies quote it back) */
    if (!tt_live_utf8_valid(text, len)) {
        snprintf(ch->why, sizeof ch->why, "console: the message is not UTF-8 text");
        bad = 1;
    }
    while (p < end && !bad) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *le = nl ? nl : end;
        size_t n = (size_t)(le - p);
        if (n && p[n - 1] == '\r')
            n--;
        for (size_t i = 0; i < n; i++)
            if (p[i] == '\0' || (iscntrl((unsigned char)p[i]) && p[i] != '\t')) {
                snprintf(ch->why, sizeof ch->why, "console: a control character in the message");
                bad = 1;
            }
        if (bad || n == 0) {
        } else if (n == 7 && strncmp(p, "restart", 7) == 0) {
            restart = any = 1;
        } else if (n > 4 && strncmp(p, "set", 3) == 0 && (p[3] == ' ' || p[3] == '\t')) {
            int k;
            const char *v;
            size_t vn;
            if (parse_set(p, n, &k, &v, &vn, ch->why, sizeof ch->why))
                bad = 1;
            else if (c->lesson && ((c->lesson->lock | c->lesson->hide) >> k & 1)) {
                /* the server holds the lesson's locks, not only the page */
                snprintf(ch->why, sizeof ch->why, "console: %s is %s by the lesson %s; it keeps its value",
                         table[k].name, c->lesson->lock >> k & 1 ? "locked" : "hidden", c->lesson->path);
                bad = 1;
            }
            else if (k == K_SAMPLE || k == K_NOISE)
                bad = own_knob(c, k, v, vn, &sample, &noise_off, ch->why, sizeof ch->why) != 0;
            else {
                free(fresh[k]);
                if (!(fresh[k] = malloc(vn + 1))) {
                    snprintf(ch->why, sizeof ch->why, "console: out of memory");
                    bad = 1;
                } else {
                    memcpy(fresh[k], v, vn);
                    fresh[k][vn] = '\0';
                    given[k] = fresh[k];
                }
            }
            restart |= !bad && table[k].restarts;
            any = 1;
        } else {
            snprintf(ch->why, sizeof ch->why,
                     "console: '%.*s': expected set NAME = VALUE or restart",
                     (int)tt_live_utf8_fit(p, n > 80 ? 80 : n), p);
            bad = 1;
        }
        p = nl ? nl + 1 : end;
    }
    if (!bad && !any) {
        snprintf(ch->why, sizeof ch->why, "console: an empty message; expected set NAME = VALUE or restart");
        bad = 1;
    }
    tt_scene *s = NULL;
    tt_scan_params prm, q;
    bench_values bv = {0};
    int have_prm = 0;
    if (!bad && (build(c, given, sample, noise_off, &s) || !(have_prm = !check(c, s, &prm, &bv)))) {
        tt_live_text(ch->why, sizeof ch->why, tt_error_message());
        bad = 1;
    }
    /* the taker (the engine) makes all it needs or refuses, and owns the scene and q
     * either way: the controls change only when it took the change (a bench's knob too:
     * the engine's scene is the one exported and saved) */
    if (!bad && take) {
        tt_scene *t = s;
        s = NULL;
        if (copy_params(&q, &prm)) {
            tt_scene_free(t);
            bad = 1;
        } else if (take(user, t, &q, restart) != TT_OK) {
            bad = 1;
        }
        if (bad)
            tt_live_text(ch->why, sizeof ch->why, tt_error_message());
    }
    tt_scene_free(s);
    if (bad) {
        if (have_prm)
            tt_config_scan_free(&prm);
        for (size_t i = 0; i < NKNOBS; i++)
            free(fresh[i]);
        return TT_EINVAL;
    }
    for (size_t i = 0; i < NKNOBS; i++)
        if (fresh[i]) {
            free(c->given[i]);
            c->given[i] = fresh[i];
        }
    ch->changed = sample != c->sample || noise_off != c->noise_off;
    for (size_t i = 0; i < NKNOBS; i++)
        ch->changed |= fresh[i] != NULL;
    ch->restart = restart;
    c->sample = sample;
    c->noise_off = noise_off;
    if (c->have_params)
        tt_config_scan_free(&c->params);
    c->params = prm;
    c->bench = bv;
    c->have_params = 1;
    return TT_OK;
}

const tt_live_lesson *tt_live_controls_lesson(const tt_live_controls *c) { return c->lesson; }

int tt_live_controls_scene(const tt_live_controls *c, tt_scene **scene, tt_scan_params *p)
{
    int rc = build(c, c->given, c->sample, c->noise_off, scene);
    if (rc || !p)
        return rc;
    bench_values bv;
    if ((rc = check(c, *scene, p, &bv))) {
        tt_scene_free(*scene);
        *scene = NULL;
    }
    return rc;
}

const char *tt_live_controls_value(const tt_live_controls *c, size_t i, char *buf, size_t len)
{
    const tt_scan_params *p = &c->params;
    if (i >= NKNOBS || !c->have_params)
        return "";
    int si = tt_live_controls_sample_index(c);
    if (i == K_SAMPLE)
        snprintf(buf, len, "%s", si >= 0 ? c->samples[si] : "");
    else if (i == K_NOISE)
        snprintf(buf, len, "%s", c->noise_off ? "off" : "on");
    else if (strcmp(table[i].name, "noise.seed") == 0)
        snprintf(buf, len, "%llu", (unsigned long long)p->noise.seed);
    else if (strcmp(table[i].name, "feedback.setpoint") == 0)
        snprintf(buf, len, "%.6g", 100 * p->feedback.setpoint / p->cantilever.A0);
    else if (strcmp(table[i].name, "feedback.proportional_gain") == 0)
        snprintf(buf, len, "%.6g", p->feedback.kp);
    else if (strcmp(table[i].name, "feedback.integral_gain") == 0)
        snprintf(buf, len, "%.6g", p->feedback.ki);
    else if (strcmp(table[i].name, "scan.line_rate") == 0)
        snprintf(buf, len, "%.6g", p->raster.line_rate);
    else if (strcmp(table[i].name, "scan.size") == 0)
        snprintf(buf, len, "%.6g", (p->raster.fast_y ? p->raster.size_y : p->raster.size_x) * 1e9);
    else if (strcmp(table[i].name, "scan.fast_axis") == 0)
        snprintf(buf, len, "%s", p->raster.fast_y ? "y" : "x");
    else if (strcmp(table[i].name, "scan.pixels") == 0)
        snprintf(buf, len, "%ld", p->raster.pixels);
    else if (strcmp(table[i].name, "scan.lines") == 0)
        snprintf(buf, len, "%ld", p->raster.lines);
    else if (strcmp(table[i].name, "cantilever.free_amplitude") == 0)
        snprintf(buf, len, "%.6g", p->cantilever.A0 * 1e9);
    else if (strcmp(table[i].name, "solver.tier") == 0)
        snprintf(buf, len, "%s", tt_tier_name(p->solver.tier));
    else if (strcmp(table[i].name, "force.speed") == 0)
        snprintf(buf, len, "%.6g", c->bench.speed * 1e6);
    else if (strcmp(table[i].name, "force.range") == 0)
        snprintf(buf, len, "%.6g", c->bench.range * 1e9);
    else if (strcmp(table[i].name, "tune.duration") == 0)
        snprintf(buf, len, "%.6g", c->bench.duration);
    else
        snprintf(buf, len, "%s", c->given[i] ? c->given[i] : "");
    return buf;
}

const char *tt_live_control_panel(size_t i) { return i < NKNOBS ? table[i].panel : NULL; }

int tt_live_controls_panel_hidden(const tt_live_controls *c, const char *panel)
{
    int any = 0, shown = 0;
    for (size_t i = 0; i < NKNOBS; i++)
        if (table[i].panel && strcmp(table[i].panel, panel) == 0) {
            any = 1;
            shown |= !(c->lesson && c->lesson->hide >> i & 1);
        }
    return any && !shown;
}

size_t tt_live_controls_samples(const tt_live_controls *c) { return c->nsamples; }
const char *tt_live_controls_sample(const tt_live_controls *c, size_t i)
{
    return i < c->nsamples ? c->samples[i] : NULL;
}
int tt_live_controls_sample_index(const tt_live_controls *c)
{
    if (c->sample >= 0)
        return c->sample;
    int which;
    find_sample_file(c, &which);
    return which;
}
