/* Gwyddion native files read back (see include/tiptap/io/gwy.h): tiptap's own, for tests
 * and tools, and any Gwyddion file's channel as a height image (height_image.h). */
#include "tiptap/io/gwy.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/files.h"
#include "tiptap/io/height_image.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

/* ---- reading (tests, tools): a cursor over the file's bytes ---- */

typedef struct {
    const unsigned char *b;
    size_t n, pos;
    int bad;
} cur;

static const char *get_str(cur *C)
{
    const unsigned char *z = C->pos < C->n ? memchr(C->b + C->pos, 0, C->n - C->pos) : NULL;
    if (!z) {
        C->bad = 1;
        return "";
    }
    const char *s = (const char *)C->b + C->pos;
    C->pos = (size_t)(z - C->b) + 1;
    return s;
}

static uint32_t get_u32(cur *C)
{
    if (C->n - C->pos < 4 || C->pos > C->n) {
        C->bad = 1;
        return 0;
    }
    const unsigned char *p = C->b + C->pos;
    C->pos += 4;
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static double get_f64(cur *C)
{
    uint64_t lo = get_u32(C), hi = get_u32(C);
    uint64_t u = lo | hi << 32;
    double v;
    memcpy(&v, &u, 8);
    return v;
}

/* Skip a value of the given type (objects by their size). */
static void skip(cur *C, char type)
{
    static const char *sizes = "b1c1i4q8d8";
    const char *s = strchr(sizes, type);
    if (type == 's') {
        get_str(C);
    } else if (type == 'o') {
        get_str(C);
        uint32_t sz = get_u32(C);
        C->pos += sz;
    } else if (s && type >= 'a') {
        C->pos += (size_t)(s[1] - '0');
    } else if (type == 'C' || type == 'I' || type == 'Q' || type == 'D') {
        uint32_t cnt = get_u32(C);
        C->pos += (size_t)cnt * (type == 'C' ? 1 : type == 'I' ? 4 : 8);
    } else if (type == 'S' || type == 'O') {
        uint32_t cnt = get_u32(C);
        for (uint32_t i = 0; i < cnt && !C->bad; i++)
            skip(C, (char)(type - 'A' + 'a'));
    } else {
        C->bad = 1;
    }
    if (C->pos > C->n)
        C->bad = 1;
}

/* The object at the cursor: its type must be want; returns where its components end. */
static size_t obj_open(cur *C, const char *want)
{
    const char *type = get_str(C);
    uint32_t sz = get_u32(C);
    if (strcmp(type, want) != 0 || C->pos + sz > C->n)
        C->bad = 1;
    return C->bad ? C->pos : C->pos + sz;
}

static char *read_unit(cur *C)
{
    size_t end = obj_open(C, "GwySIUnit");
    char *u = NULL;
    while (!C->bad && C->pos < end) {
        const char *name = get_str(C);
        char t = C->pos < C->n ? (char)C->b[C->pos++] : 0;
        if (!strcmp(name, "unitstr") && t == 's')
            u = tt_strdup(get_str(C));
        else
            skip(C, t);
    }
    return u ? u : tt_strdup("");
}

static void read_field(cur *C, struct tt_gwy_read_channel *c)
{
    size_t end = obj_open(C, "GwyDataField");
    while (!C->bad && C->pos < end) {
        const char *name = get_str(C);
        char t = C->pos < C->n ? (char)C->b[C->pos++] : 0;
        if (t == 'i' && !strcmp(name, "xres"))
            c->xres = get_u32(C);
        else if (t == 'i' && !strcmp(name, "yres"))
            c->yres = get_u32(C);
        else if (t == 'd' && !strcmp(name, "xreal"))
            c->xreal = get_f64(C);
        else if (t == 'd' && !strcmp(name, "yreal"))
            c->yreal = get_f64(C);
        else if (t == 'o' && !strcmp(name, "si_unit_xy"))
            c->xyunits = read_unit(C);
        else if (t == 'o' && !strcmp(name, "si_unit_z"))
            c->zunits = read_unit(C);
        else if (t == 'D' && !strcmp(name, "data") && !c->data) {
            uint32_t cnt = get_u32(C);
            if ((size_t)cnt * 8 > C->n - C->pos || cnt == 0 || !(c->data = malloc(cnt * sizeof *c->data))) {
                C->bad = 1;
                break;
            }
            for (uint32_t i = 0; i < cnt; i++)
                c->data[i] = get_f64(C);
            c->ndata = cnt;
        } else
            skip(C, t);
    }
}

static void read_meta(cur *C, tt_gwy_file *f)
{
    size_t end = obj_open(C, "GwyContainer");
    while (!C->bad && C->pos < end) {
        const char *name = get_str(C);
        char t = C->pos < C->n ? (char)C->b[C->pos++] : 0;
        if (t != 's') {
            skip(C, t);
            continue;
        }
        char **k = realloc(f->keys, (f->nmeta + 1) * sizeof *k);
        if (k)
            f->keys = k;
        char **v = realloc(f->values, (f->nmeta + 1) * sizeof *v);
        if (v)
            f->values = v;
        if (!k || !v) {
            C->bad = 1;
            return;
        }
        f->keys[f->nmeta] = tt_strdup(name);
        f->values[f->nmeta] = tt_strdup(get_str(C));
        f->nmeta++;
        if (!f->keys[f->nmeta - 1] || !f->values[f->nmeta - 1]) {
            C->bad = 1; /* the file's free releases what was made */
            return;
        }
    }
}

/* The channel numbered in "/N/..." (growing the list to hold it), or NULL. */
static struct tt_gwy_read_channel *channel(tt_gwy_file *f, const char *name, const char **rest)
{
    char *end;
    unsigned long i = strtoul(name + 1, &end, 10);
    if (name[0] != '/' || end == name + 1 || i > 4096)
        return NULL;
    *rest = end;
    if (i >= f->nch) {
        struct tt_gwy_read_channel *c = realloc(f->ch, (i + 1) * sizeof *c);
        if (!c)
            return NULL;
        memset(c + f->nch, 0, (i + 1 - f->nch) * sizeof *c);
        f->ch = c;
        f->nch = i + 1;
    }
    return &f->ch[i];
}

static void read_top(cur *C, tt_gwy_file *f)
{
    size_t end = obj_open(C, "GwyContainer");
    while (!C->bad && C->pos < end) {
        const char *name = get_str(C), *rest = "";
        char t = C->pos < C->n ? (char)C->b[C->pos++] : 0;
        struct tt_gwy_read_channel *c = channel(f, name, &rest);
        if (c && t == 'o' && !strcmp(rest, "/data") && !c->data)
            read_field(C, c);
        else if (c && t == 's' && !strcmp(rest, "/data/title") && !c->title)
            c->title = tt_strdup(get_str(C));
        else if (c && t == 'o' && !strcmp(rest, "/meta") && c == f->ch && f->nmeta == 0)
            read_meta(C, f);
        else
            skip(C, t);
    }
}

static int gwy_load(const char *path, tt_gwy_file **out, int lenient)
{
    *out = NULL;
    FILE *fp;
    int rc = tt_input_fopen(path, "GWY file", "GWY file", TT_IMAGE_FILE_MAX_BYTES, &fp);
    if (rc)
        return rc;
    unsigned char *b = NULL;
    size_t n = 0, cap = 0, got = 1;
    while (got > 0) {
        if (n == cap) {
            unsigned char *nb = realloc(b, cap = cap ? 2 * cap : 65536);
            if (!nb) {
                free(b);
                fclose(fp);
                return tt_error(TT_ENOMEM, "out of memory");
            }
            b = nb;
        }
        n += got = fread(b + n, 1, cap - n, fp);
    }
    fclose(fp);
    tt_gwy_file *f = calloc(1, sizeof *f);
    if (!f) {
        free(b);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    cur C = {b, n, 4, n < 4 || memcmp(b, "GWYP", 4) != 0};
    if (!C.bad)
        read_top(&C, f);
    /* strict: channels 0, 1, ... each with a title, as tiptap writes them; lenient:
     * Gwyddion's files, whose numbers have gaps where a channel was removed */
    for (size_t i = 0; !C.bad && i < f->nch; i++)
        if ((!f->ch[i].data && (!lenient || f->ch[i].title)) || (!lenient && !f->ch[i].title) ||
            (f->ch[i].data && f->ch[i].xres * f->ch[i].yres != f->ch[i].ndata))
            C.bad = 1;
    free(b);
    if (C.bad) {
        tt_gwy_file_free(f);
        return tt_error(TT_EIO, "%s: not a GWY file of data fields, or damaged or truncated", path);
    }
    *out = f;
    return TT_OK;
}

int tt_gwy_read(const char *path, tt_gwy_file **out) { return gwy_load(path, out, 0); }

void tt_gwy_file_free(tt_gwy_file *f)
{
    if (!f)
        return;
    for (size_t i = 0; i < f->nch; i++) {
        free(f->ch[i].title);
        free(f->ch[i].xyunits);
        free(f->ch[i].zunits);
        free(f->ch[i].data);
    }
    for (size_t i = 0; i < f->nmeta; i++) {
        free(f->keys[i]);
        free(f->values[i]);
    }
    free(f->ch);
    free(f->keys);
    free(f->values);
    free(f);
}

/* The channel sel names: its number ("3": "/3/data") or its title; -1 when none. */
static long find_channel(const tt_gwy_file *f, const char *sel)
{
    char *end;
    if (!sel || !*sel) {
        for (size_t i = 0; i < f->nch; i++)
            if (f->ch[i].data)
                return (long)i;
        return -1;
    }
    unsigned long n = strtoul(sel, &end, 10);
    if (*end == 0 && sel[0] >= '0' && sel[0] <= '9')
        return n < f->nch && f->ch[n].data ? (long)n : -1;
    for (size_t i = 0; i < f->nch; i++)
        if (f->ch[i].data && f->ch[i].title && strcmp(f->ch[i].title, sel) == 0)
            return (long)i;
    return -1;
}

/* The channels a file holds, "0 'Height', 1 'Phase'", for the refusal of a missing one. */
static void list_channels(const tt_gwy_file *f, char *out, size_t len)
{
    size_t at = 0;
    out[0] = 0;
    for (size_t i = 0; i < f->nch && at < len; i++)
        if (f->ch[i].data) {
            int w = snprintf(out + at, len - at, "%s%zu '%s'", at ? ", " : "", i,
                             f->ch[i].title ? f->ch[i].title : "");
            at += w > 0 ? (size_t)w : 0;
        }
}

/* A channel into out: lateral sizes in metres; the values converted to metres when zunit
 * is NULL (a height image, checked), else as stored, with their unit copied into zunit. */
static int gwy_read_channel(const char *key, const char *path, const char *sel, tt_height_image *out,
                            char *zunit, size_t nz)
{
    memset(out, 0, sizeof *out);
    tt_gwy_file *f;
    if (gwy_load(path, &f, 1)) {
        char why[1024];
        snprintf(why, sizeof why, "%s", tt_error_message());
        return tt_error(TT_EINVAL, "%s: %s", key, why);
    }
    long i = find_channel(f, sel);
    int rc = TT_OK;
    char list[512];
    const struct tt_gwy_read_channel *c = i >= 0 ? &f->ch[i] : NULL;
    double xy = c ? tt_length_unit(c->xyunits) : 0, zu = c && !zunit ? tt_length_unit(c->zunits) : 1;
    if (!c) {
        list_channels(f, list, sizeof list);
        rc = tt_error(TT_EINVAL, "%s: %s: no channel '%s'; expected a title or number of those "
                                 "it holds: %s",
                      key, path, sel && *sel ? sel : "(any)", *list ? list : "none");
    } else if (!c->xyunits || !*c->xyunits || (!zunit && (!c->zunits || !*c->zunits)))
        rc = tt_error(TT_EINVAL, "%s: %s: channel %ld has no %s unit; expected a length unit (m)",
                      key, path, i, !c->xyunits || !*c->xyunits ? "lateral (si_unit_xy)" : "height (si_unit_z)");
    else if (xy < 0 || zu < 0)
        rc = tt_error(TT_EINVAL, "%s: %s: channel %ld is in '%s' across and '%s' high; expected "
                                 "lengths (m): a height image",
                      key, path, i, c->xyunits, c->zunits);
    else if (!c->xres || !c->yres)
        rc = tt_error(TT_EINVAL, "%s: %s: channel %ld has %zu x %zu pixels; expected at least 2 x 2",
                      key, path, i, c->xres, c->yres);
    if (rc == TT_OK) {
        out->xres = c->xres;
        out->yres = c->yres;
        out->dx = c->xreal * xy / (double)c->xres;
        out->dy = c->yreal * xy / (double)c->yres;
        out->z = f->ch[i].data;
        f->ch[i].data = NULL; /* taken over */
        for (size_t k = 0; k < out->xres * out->yres; k++)
            out->z[k] *= zu;
        if (zunit)
            snprintf(zunit, nz, "%s", c->zunits ? c->zunits : "");
        else if ((rc = tt_height_image_check(key, path, out)))
            tt_height_image_free(out);
    }
    tt_gwy_file_free(f);
    return rc;
}

int tt_gwy_read_height(const char *key, const char *path, const char *sel, tt_height_image *out)
{
    return gwy_read_channel(key, path, sel, out, NULL, 0);
}

int tt_gwy_read_values(const char *key, const char *path, const char *sel, tt_height_image *out,
                       char *zunit, size_t n)
{
    return gwy_read_channel(key, path, sel, out, zunit, n);
}
