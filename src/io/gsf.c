/* Gwyddion Simple Field files (see include/tiptap/io/gsf.h). */
#include "tiptap/io/gsf.h"

#include <locale.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"
#include "tiptap/io/files.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/str.h"

static void put_f32le(FILE *f, double v)
{
    float x = (float)v;
    uint32_t u;
    memcpy(&u, &x, 4);
    unsigned char b[4] = {(unsigned char)u, (unsigned char)(u >> 8), (unsigned char)(u >> 16),
                          (unsigned char)(u >> 24)};
    fwrite(b, 1, 4, f);
}

int tt_gsf_write(const char *path, const tt_gsf_field *g)
{
    if (!g->xres || !g->yres || !g->data)
        return tt_error(TT_EINVAL, "%s: empty field", path);
    tt_outfile *o;
    int rc = tt_outfile_open(&o, path);
    if (rc)
        return rc;
    FILE *f = tt_outfile_stream(o);
    /* the header's numbers in the C locale whatever the program's locale */
    locale_t c = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0);
    locale_t old = c ? uselocale(c) : (locale_t)0;
    long n = 0;
    n += fprintf(f, "Gwyddion Simple Field 1.0\n");
    n += fprintf(f, "XRes = %zu\nYRes = %zu\n", g->xres, g->yres);
    n += fprintf(f, "XReal = %.10g\nYReal = %.10g\n", g->xreal, g->yreal);
    n += fprintf(f, "XOffset = %.10g\nYOffset = %.10g\n", g->xoffset, g->yoffset);
    n += fprintf(f, "XYUnits = %s\nZUnits = %s\n", g->xyunits ? g->xyunits : "m",
                 g->zunits ? g->zunits : "");
    if (g->title)
        n += fprintf(f, "Title = %s\n", g->title);
    for (size_t i = 0; i < g->nextra; i++)
        n += fprintf(f, "%s = %s\n", g->keys[i], g->values[i]);
    if (old)
        uselocale(old);
    if (c)
        freelocale(c);
    /* 1 to 4 NULs so that the data start at a multiple of 4 */
    int pad = 4 - (int)(n % 4);
    for (int i = 0; i < pad; i++)
        fputc(0, f);
    for (size_t i = 0; i < g->xres * g->yres; i++)
        put_f32le(f, g->data[i]);
    return tt_outfile_close(o, 1);
}

int tt_gsf_read(const char *path, size_t *xres, size_t *yres, double *xreal, double *yreal,
                double **data)
{
    *data = NULL;
    FILE *f;
    int rc = tt_input_fopen(path, "GSF file", "GSF file", TT_IMAGE_FILE_MAX_BYTES, &f);
    if (rc)
        return rc;
    char line[1024];
    long n = 0;
    *xres = *yres = 0;
    if (!fgets(line, sizeof line, f) || strcmp(line, "Gwyddion Simple Field 1.0\n") != 0) {
        fclose(f);
        return tt_error(TT_EIO, "%s: not a GSF file", path);
    }
    n += (long)strlen(line);
    int c;
    while ((c = fgetc(f)) != EOF && c != 0) {
        ungetc(c, f);
        if (!fgets(line, sizeof line, f))
            break;
        n += (long)strlen(line);
        char key[256], val[768];
        if (sscanf(line, "%255s = %767[^\n]", key, val) == 2) {
            if (!strcmp(key, "XRes"))
                *xres = (size_t)strtoul(val, NULL, 10);
            else if (!strcmp(key, "YRes"))
                *yres = (size_t)strtoul(val, NULL, 10);
            else if (!strcmp(key, "XReal"))
                *xreal = tt_strtod(val, NULL);
            else if (!strcmp(key, "YReal"))
                *yreal = tt_strtod(val, NULL);
        }
    }
    if (c != 0 || !*xres || !*yres) {
        fclose(f);
        return tt_error(TT_EIO, "%s: malformed GSF header", path);
    }
    fseek(f, (n / 4 + 1) * 4, SEEK_SET);
    size_t N = *xres * *yres;
    *data = malloc(N * sizeof **data);
    if (!*data) {
        fclose(f);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    for (size_t i = 0; i < N; i++) {
        unsigned char b[4];
        if (fread(b, 1, 4, f) != 4) {
            free(*data);
            *data = NULL;
            fclose(f);
            return tt_error(TT_EIO, "%s: truncated data", path);
        }
        uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
        float x;
        memcpy(&x, &u, 4);
        (*data)[i] = x;
    }
    fclose(f);
    return TT_OK;
}
