/* An RGB24 cairo surface as PNG bytes, the same bytes as cairo's writer through libpng
 * 1.6 at its defaults (see src/io/png_internal.h): IHDR (8-bit RGB), bKGD (white), the
 * rows filtered by libpng's rule, zlib at libpng's setting in IDAT chunks of 8192
 * bytes, IEND. Why: libpng tries its five filters on each row in five byte-at-a-time
 * passes, 56 % of a channel preview's writing (the noisy blend's 20 previews: 0.17 s
 * of CPU); here one pass computes all five. */
#include "png_internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

enum { ZBUF = 8192 }; /* libpng's PNG_ZBUF_SIZE: each IDAT chunk holds one */

/* libpng's cost of a filtered byte: its distance from 0, bytes >= 128 as negative */
static inline unsigned cost(uint8_t v)
{
    const uint8_t m = (uint8_t)-v;
    return v < m ? v : m;
}

static inline int16_t abs16(int16_t x)
{
    return x < 0 ? (int16_t)-x : x;
}

/* Row raw (n bytes, 3 a pixel) under prev: the four filtered rows into s, u, v, p (sub,
 * up, average, Paeth), and the filter libpng picks: the least sum of costs, the first
 * of equals, in the order none, sub, up, average, Paeth. One pass in 16-bit lanes,
 * without branches, which the compiler vectorizes (libpng makes a pass a filter, a
 * byte at a time: 107 M instructions a channel preview, against 47 M here). Not
 * inlined: inlined, GCC 12 no longer counts the loop's iterations and leaves it
 * scalar. */
__attribute__((noinline)) static int filter_row(const uint8_t *restrict raw,
                                                const uint8_t *restrict prev, size_t n,
                                                uint8_t *restrict s, uint8_t *restrict u,
                                                uint8_t *restrict v, uint8_t *restrict p)
{
    unsigned s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0; /* at most 128 a byte: no overflow */
    for (size_t i = 0; i < n && i < 3; i++) { /* the first pixel: no left neighbour */
        s[i] = raw[i];
        u[i] = p[i] = (uint8_t)(raw[i] - prev[i]);
        v[i] = (uint8_t)(raw[i] - prev[i] / 2);
        s0 += cost(raw[i]);
        s1 += cost(s[i]);
        s2 += cost(u[i]);
        s3 += cost(v[i]);
        s4 += cost(p[i]);
    }
    for (size_t i = 3; i < n; i++) {
        const int16_t r = raw[i], a = raw[i - 3], b = prev[i], c = prev[i - 3];
        const int16_t pa = abs16((int16_t)(b - c)), pb = abs16((int16_t)(a - c)),
                      pc = abs16((int16_t)(a + b - 2 * c));
        const int16_t pred = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
        const uint8_t fs = (uint8_t)(r - a), fu = (uint8_t)(r - b), fv = (uint8_t)(r - ((a + b) >> 1)),
                      fp = (uint8_t)(r - pred);
        s[i] = fs;
        u[i] = fu;
        v[i] = fv;
        p[i] = fp;
        s0 += cost(raw[i]);
        s1 += cost(fs);
        s2 += cost(fu);
        s3 += cost(fv);
        s4 += cost(fp);
    }
    const unsigned sum[5] = {s0, s1, s2, s3, s4};
    int best = 0;
    for (int k = 1; k < 5; k++)
        if (sum[k] < sum[best])
            best = k;
    return best;
}

static void put32(uint8_t *b, uint32_t v)
{
    b[0] = (uint8_t)(v >> 24);
    b[1] = (uint8_t)(v >> 16);
    b[2] = (uint8_t)(v >> 8);
    b[3] = (uint8_t)v;
}

/* One chunk: length, type, data, CRC of type and data. */
static int chunk(FILE *f, const char *type, const uint8_t *data, uint32_t len)
{
    uint8_t head[8], tail[4];
    put32(head, len);
    memcpy(head + 4, type, 4);
    uLong crc = crc32(0L, head + 4, 4);
    if (len)
        crc = crc32(crc, data, len);
    put32(tail, (uint32_t)crc);
    return fwrite(head, 1, 8, f) != 8 || (len && fwrite(data, 1, len, f) != len) ||
           fwrite(tail, 1, 4, f) != 4;
}

/* Deflate what z holds (flush: Z_NO_FLUSH or Z_FINISH), an IDAT chunk for each full
 * buffer, and at the finish the rest. */
static int deflate_rows(z_stream *z, uint8_t *out, int flush, FILE *f)
{
    for (;;) {
        int ret = deflate(z, flush);
        if (ret == Z_STREAM_ERROR)
            return -1;
        if (z->avail_out == 0) {
            if (chunk(f, "IDAT", out, ZBUF))
                return -1;
            z->next_out = out;
            z->avail_out = ZBUF;
        }
        if (ret == Z_STREAM_END)
            return z->avail_out < ZBUF ? chunk(f, "IDAT", out, ZBUF - z->avail_out) : 0;
        if (flush == Z_NO_FLUSH && z->avail_in == 0)
            return 0;
    }
}

/* The IHDR and bKGD chunks after the signature. */
static int header(FILE *f, int w, int h)
{
    static const uint8_t sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
    static const uint8_t white[6] = {0, 255, 0, 255, 0, 255};
    uint8_t ihdr[13] = {0};
    put32(ihdr, (uint32_t)w);
    put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 8; /* bits a sample */
    ihdr[9] = 2; /* RGB */
    return fwrite(sig, 1, 8, f) != 8 || chunk(f, "IHDR", ihdr, 13) || chunk(f, "bKGD", white, 6);
}

int tt_png_encode_rgb24(cairo_surface_t *sf, FILE *f)
{
    cairo_surface_flush(sf);
    const int w = cairo_image_surface_get_width(sf), h = cairo_image_surface_get_height(sf);
    const int stride = cairo_image_surface_get_stride(sf);
    const unsigned char *data = cairo_image_surface_get_data(sf);
    const size_t n = (size_t)w * 3;
    /* cairo's writer does the rest: below 16 kB of rows libpng narrows zlib's window,
     * and on a row or a column of one pixel it tries fewer filters */
    if (cairo_image_surface_get_format(sf) != CAIRO_FORMAT_RGB24 || !data || w < 2 || h < 2 ||
        (n + 1) * (size_t)h <= 16384)
        return 1;
    /* the row, the one above (zeros above the first), the filtered rows 1 to 4 */
    uint8_t *buf = calloc(6 * (n + 1) + ZBUF, 1);
    if (!buf)
        return -1;
    uint8_t *raw = buf, *prev = buf + (n + 1), *f5[5] = {NULL}, *out = buf + 6 * (n + 1);
    for (int k = 1; k < 5; k++)
        f5[k] = buf + (size_t)(1 + k) * (n + 1);
    z_stream z = {0};
    /* libpng's: the default level, a 32 kB window, memory level 8, filtered data */
    int rc = deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15, 8, Z_FILTERED) != Z_OK ? -1 : 0;
    z.next_out = out;
    z.avail_out = ZBUF;
    if (!rc)
        rc = header(f, w, h) ? -1 : 0;
    for (int y = 0; y < h && !rc; y++) {
        const uint32_t *px = (const uint32_t *)(const void *)(data + (size_t)y * (size_t)stride);
        for (int x = 0; x < w; x++) { /* xRGB in native order to R, G, B */
            raw[3 * x] = (uint8_t)(px[x] >> 16);
            raw[3 * x + 1] = (uint8_t)(px[x] >> 8);
            raw[3 * x + 2] = (uint8_t)px[x];
        }
        int k = filter_row(raw, prev, n, f5[1] + 1, f5[2] + 1, f5[3] + 1, f5[4] + 1);
        uint8_t *row = k ? f5[k] : f5[1]; /* none copies the row behind the type byte */
        if (!k)
            memcpy(row + 1, raw, n);
        row[0] = (uint8_t)k;
        z.next_in = row;
        z.avail_in = (uInt)(n + 1);
        rc = deflate_rows(&z, out, Z_NO_FLUSH, f);
        uint8_t *t = prev; /* this row is the next one's above */
        prev = raw;
        raw = t;
    }
    if (!rc)
        rc = deflate_rows(&z, out, Z_FINISH, f);
    deflateEnd(&z);
    free(buf);
    return rc || chunk(f, "IEND", NULL, 0) ? -1 : 0;
}
