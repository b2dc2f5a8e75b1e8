/* Gwyddion native files (see include/tiptap/io/gwy.h). Written by hand rather than
 * with libgwyddion (docs/dependencies.md): the serialisation is a few component types. */
#include "tiptap/io/gwy.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/files.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

/* A growing byte buffer; err is set once an allocation failed. */
typedef struct {
    unsigned char *b;
    size_t n, cap;
    int err;
} buf;

static void put(buf *B, const void *p, size_t n)
{
    if (B->err)
        return;
    if (B->n + n > B->cap) {
        size_t cap = B->cap ? B->cap : 4096;
        while (cap < B->n + n)
            cap *= 2;
        unsigned char *nb = realloc(B->b, cap);
        if (!nb) {
            B->err = 1;
            return;
        }
        B->b = nb;
        B->cap = cap;
    }
    memcpy(B->b + B->n, p, n);
    B->n += n;
}

/* The file's integers are little-endian, whatever the machine. */
static void le32(unsigned char b[4], uint32_t u)
{
    for (int i = 0; i < 4; i++)
        b[i] = (unsigned char)(u >> (8 * i));
}

static void put_u32(buf *B, uint32_t u)
{
    unsigned char b[4];
    le32(b, u);
    put(B, b, 4);
}

static void put_f64(buf *B, double v)
{
    uint64_t u;
    memcpy(&u, &v, 8);
    put_u32(B, (uint32_t)u);
    put_u32(B, (uint32_t)(u >> 32));
}

static void put_str(buf *B, const char *s) { put(B, s, strlen(s) + 1); }

/* A component's name and type letter. */
static void comp(buf *B, const char *name, char type)
{
    put_str(B, name);
    put(B, &type, 1);
}

/* An object's header; returns where its size goes, patched by obj_end. */
static size_t obj_begin(buf *B, const char *type)
{
    put_str(B, type);
    size_t at = B->n;
    put_u32(B, 0);
    return at;
}

static void obj_end(buf *B, size_t at)
{
    if (B->err)
        return;
    le32(B->b + at, (uint32_t)(B->n - at - 4));
}

static void si_unit(buf *B, const char *name, const char *unit)
{
    comp(B, name, 'o');
    size_t at = obj_begin(B, "GwySIUnit");
    comp(B, "unitstr", 's');
    put_str(B, unit ? unit : "");
    obj_end(B, at);
}

static void data_field(buf *B, const tt_gwy_channel *c)
{
    size_t at = obj_begin(B, "GwyDataField");
    comp(B, "xres", 'i');
    put_u32(B, (uint32_t)c->xres);
    comp(B, "yres", 'i');
    put_u32(B, (uint32_t)c->yres);
    comp(B, "xreal", 'd');
    put_f64(B, c->xreal);
    comp(B, "yreal", 'd');
    put_f64(B, c->yreal);
    comp(B, "xoff", 'd');
    put_f64(B, c->xoffset);
    comp(B, "yoff", 'd');
    put_f64(B, c->yoffset);
    si_unit(B, "si_unit_xy", c->xyunits ? c->xyunits : "m");
    si_unit(B, "si_unit_z", c->zunits);
    comp(B, "data", 'D');
    put_u32(B, (uint32_t)(c->xres * c->yres));
    for (size_t i = 0; i < c->xres * c->yres; i++)
        put_f64(B, c->data[i]);
    obj_end(B, at);
}

char *tt_gwy_title(char *out, size_t n, const char *channel, int retrace)
{
    if (!n)
        return out;
    snprintf(out, n, "%s%s", channel, retrace ? " (retrace)" : "");
    for (char *c = out; *c; c++)
        if (*c == '_')
            *c = ' ';
    if (out[0] >= 'a' && out[0] <= 'z')
        out[0] = (char)(out[0] - 'a' + 'A');
    return out;
}

int tt_gwy_write(const char *path, const tt_gwy_channel *ch, size_t n, const char *const *keys,
                 const char *const *values, size_t nmeta)
{
    if (n == 0)
        return tt_error(TT_EINVAL, "%s: no channels", path);
    for (size_t i = 0; i < n; i++) {
        if (!ch[i].xres || !ch[i].yres || !ch[i].data)
            return tt_error(TT_EINVAL, "%s: empty channel %zu", path, i);
        /* the format's sizes are 32-bit: xres and yres signed, the array's length not */
        if (ch[i].xres > INT32_MAX || ch[i].yres > INT32_MAX ||
            ch[i].xres > UINT32_MAX / ch[i].yres)
            return tt_error(TT_EINVAL, "%s: channel %zu of %zu x %zu values is too large for the "
                                       "GWY format",
                            path, i, ch[i].xres, ch[i].yres);
    }
    buf B = {0};
    char key[64];
    put(&B, "GWYP", 4);
    size_t top = obj_begin(&B, "GwyContainer");
    for (size_t i = 0; i < n; i++) {
        snprintf(key, sizeof key, "/%zu/data", i);
        comp(&B, key, 'o');
        data_field(&B, &ch[i]);
        snprintf(key, sizeof key, "/%zu/data/title", i);
        comp(&B, key, 's');
        put_str(&B, ch[i].title ? ch[i].title : "");
        if (nmeta) {
            snprintf(key, sizeof key, "/%zu/meta", i);
            comp(&B, key, 'o');
            size_t at = obj_begin(&B, "GwyContainer");
            for (size_t k = 0; k < nmeta; k++) {
                comp(&B, keys[k], 's');
                put_str(&B, values[k]);
            }
            obj_end(&B, at);
        }
    }
    obj_end(&B, top);
    if (B.err) {
        free(B.b);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    tt_outfile *o;
    int rc = tt_outfile_open(&o, path);
    if (rc == TT_OK) {
        fwrite(B.b, 1, B.n, tt_outfile_stream(o));
        rc = tt_outfile_close(o, 1);
    }
    free(B.b);
    return rc;
}

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

int tt_gwy_read(const char *path, tt_gwy_file **out)
{
    *out = NULL;
    FILE *fp;
    int rc = tt_input_fopen(path, "GWY file", "GWY file", TT_IMAGE_FILE_MAX_BYTES, &fp);
    if (rc)
        return rc;
    buf B = {0};
    unsigned char chunk[65536];
    size_t got;
    while ((got = fread(chunk, 1, sizeof chunk, fp)) > 0)
        put(&B, chunk, got);
    fclose(fp);
    tt_gwy_file *f = calloc(1, sizeof *f);
    if (B.err || !f) {
        free(B.b);
        free(f);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    cur C = {B.b, B.n, 4, B.n < 4 || memcmp(B.b, "GWYP", 4) != 0};
    if (!C.bad)
        read_top(&C, f);
    for (size_t i = 0; !C.bad && i < f->nch; i++)
        if (!f->ch[i].data || !f->ch[i].title || f->ch[i].xres * f->ch[i].yres != f->ch[i].ndata)
            C.bad = 1;
    free(B.b);
    if (C.bad) {
        tt_gwy_file_free(f);
        return tt_error(TT_EIO, "%s: not a GWY file of data fields, or damaged", path);
    }
    *out = f;
    return TT_OK;
}

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
