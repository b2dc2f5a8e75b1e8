/* Gwyddion Simple Field files read as height images (see
 * include/tiptap/io/height_image.h): every key a measured surface needs is required. */
#include "tiptap/io/height_image.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/io/files.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

/* A header longer than this is no GSF header (the format's are a few hundred bytes). */
#define GSF_HEADER_MAX 65536
/* Pixels a side: beyond any instrument's image, and XRes * YRes * 4 stays far from overflow. */
#define GSF_RES_MAX 65536

typedef struct {
    char xres[64], yres[64], xreal[64], yreal[64], xyunits[64], zunits[64];
} gsf_header;

/* The value of the header line "Key = Value" into h (unknown keys are kept by no one). */
static void header_line(gsf_header *h, char *line)
{
    char *eq = strchr(line, '=');
    if (!eq)
        return;
    char *k = line, *v = eq + 1, *e = eq;
    while (e > k && (e[-1] == ' ' || e[-1] == '\t'))
        e--;
    *e = 0;
    while (*v == ' ' || *v == '\t')
        v++;
    size_t n = strlen(v);
    while (n && (v[n - 1] == ' ' || v[n - 1] == '\t' || v[n - 1] == '\r'))
        v[--n] = 0;
    static const char *const keys[] = {"XRes", "YRes", "XReal", "YReal", "XYUnits", "ZUnits"};
    char *slot[] = {h->xres, h->yres, h->xreal, h->yreal, h->xyunits, h->zunits};
    for (int i = 0; i < 6; i++)
        if (strcmp(k, keys[i]) == 0)
            snprintf(slot[i], 64, "%s", v);
}

static int missing(const char *key, const char *path, const char *name, const char *expected)
{
    return tt_error(TT_EINVAL, "%s: %s: no %s in the GSF header; expected %s", key, path, name, expected);
}

/* XRes or YRes: a whole number of pixels, 1 to GSF_RES_MAX. */
static int res_of(const char *key, const char *path, const char *name, const char *v, size_t *out)
{
    char *end;
    long n = *v ? strtol(v, &end, 10) : 0;
    if (!*v)
        return missing(key, path, name, "the number of pixels");
    if (*end || n < 1 || n > GSF_RES_MAX)
        return tt_error(TT_EINVAL, "%s: %s: %s = %s; expected a number of pixels from 1 to %d",
                        key, path, name, v, GSF_RES_MAX);
    *out = (size_t)n;
    return TT_OK;
}

/* XReal or YReal in XYUnits, into metres. */
static int real_of(const char *key, const char *path, const char *name, const char *v, double unit,
                   double *out)
{
    char *end;
    if (!*v)
        return missing(key, path, name, "the image's width or height with XYUnits");
    double x = tt_strtod(v, &end);
    if (*end || !(x > 0))
        return tt_error(TT_EINVAL, "%s: %s: %s = %s; expected a size above 0", key, path, name, v);
    *out = x * unit;
    return TT_OK;
}

static int unit_of(const char *key, const char *path, const char *name, const char *v, double *f)
{
    if (!*v)
        return missing(key, path, name, "a length unit (m, nm, um)");
    if ((*f = tt_length_unit(v)) < 0)
        return tt_error(TT_EINVAL, "%s: %s: %s = %s; expected a length unit (m, nm, um): a "
                                   "height image",
                        key, path, name, v);
    return TT_OK;
}

/* The header from buf (n bytes) into h; *data where the floats start. */
static int parse_header(const char *key, const char *path, char *buf, size_t n, gsf_header *h,
                        size_t *data)
{
    static const char magic[] = "Gwyddion Simple Field 1.0\n";
    if (n < sizeof magic - 1 || memcmp(buf, magic, sizeof magic - 1) != 0)
        return tt_error(TT_EINVAL, "%s: %s: not a GSF file (expected the line '%.25s' first)", key,
                        path, magic);
    char *nul = memchr(buf, 0, n < GSF_HEADER_MAX ? n : GSF_HEADER_MAX);
    if (!nul)
        return tt_error(TT_EINVAL, "%s: %s: the GSF header has no end (a NUL byte) in its first %d "
                                   "bytes: truncated or not a GSF file",
                        key, path, GSF_HEADER_MAX);
    size_t hl = (size_t)(nul - buf);
    *data = (hl / 4 + 1) * 4; /* 1 to 4 NULs pad the header to a multiple of 4 */
    for (char *line = buf + sizeof magic - 1; line < nul;) {
        char *eol = memchr(line, '\n', (size_t)(nul - line));
        if (!eol)
            eol = nul;
        *eol = 0;
        header_line(h, line);
        line = eol + 1;
    }
    return TT_OK;
}

/* The file into out: lateral sizes in metres; the values in ZUnits converted to metres
 * when zunit is NULL (a height image), else as stored, with ZUnits copied into zunit. */
static int gsf_read(const char *key, const char *path, tt_height_image *out, char *zunit, size_t nz)
{
    memset(out, 0, sizeof *out);
    FILE *f;
    long long size;
    int fd, rc = tt_input_open(path, "GSF file", "GSF file", TT_IMAGE_FILE_MAX_BYTES, &fd, &size);
    if (rc) {
        char why[1024];
        snprintf(why, sizeof why, "%s", tt_error_message());
        return tt_error(TT_EINVAL, "%s: %s", key, why);
    }
    if (!(f = fdopen(fd, "rb")))
        return tt_error(TT_EIO, "%s: %s: cannot read", key, path);
    char *buf = malloc(size > 0 ? (size_t)size + 1 : 1);
    size_t n = buf ? fread(buf, 1, (size_t)size, f) : 0;
    fclose(f);
    if (!buf)
        return tt_error(TT_ENOMEM, "%s: %s: out of memory for %lld bytes", key, path, size);
    gsf_header h;
    memset(&h, 0, sizeof h);
    size_t at = 0;
    double xy = 0, zu = 0;
    if ((rc = parse_header(key, path, buf, n, &h, &at)) ||
        (rc = res_of(key, path, "XRes", h.xres, &out->xres)) ||
        (rc = res_of(key, path, "YRes", h.yres, &out->yres)) ||
        (rc = unit_of(key, path, "XYUnits", h.xyunits, &xy)) ||
        (!zunit && (rc = unit_of(key, path, "ZUnits", h.zunits, &zu))) ||
        (rc = real_of(key, path, "XReal", h.xreal, xy, &out->dx)) ||
        (rc = real_of(key, path, "YReal", h.yreal, xy, &out->dy))) {
        free(buf);
        return rc;
    }
    size_t N = out->xres * out->yres;
    if (at > n || n - at < 4 * N) {
        free(buf);
        return tt_error(TT_EINVAL, "%s: %s: truncated: %zu bytes of data, %zu x %zu pixels need %zu",
                        key, path, at > n ? 0 : n - at, out->xres, out->yres, 4 * N);
    }
    out->dx /= (double)out->xres;
    out->dy /= (double)out->yres;
    if (!(out->z = malloc(N * sizeof *out->z))) {
        free(buf);
        return tt_error(TT_ENOMEM, "%s: %s: out of memory for %zu pixels", key, path, N);
    }
    const unsigned char *b = (const unsigned char *)buf + at;
    for (size_t i = 0; i < N; i++, b += 4) {
        uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
        float x;
        memcpy(&x, &u, 4);
        out->z[i] = zunit ? (double)x : (double)x * zu;
    }
    free(buf);
    if (zunit)
        snprintf(zunit, nz, "%s", h.zunits);
    return TT_OK;
}

int tt_gsf_read_height(const char *key, const char *path, tt_height_image *out)
{
    int rc = gsf_read(key, path, out, NULL, 0);
    if (!rc && (rc = tt_height_image_check(key, path, out)))
        tt_height_image_free(out);
    return rc;
}

int tt_gsf_read_values(const char *key, const char *path, tt_height_image *out, char *zunit, size_t n)
{
    return gsf_read(key, path, out, zunit, n);
}
