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
