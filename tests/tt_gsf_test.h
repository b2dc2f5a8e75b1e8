/* Image files a test writes by hand into its own temporary folder `dir` (made by the
 * test's main with mkdtemp): GSF files of given header keys and floats. */
#ifndef TT_GSF_TEST_H
#define TT_GSF_TEST_H

#include <stdio.h>

#include "tt_test.h"

static char dir[64];

/* A GSF file: header keys as given (the magic first), then n floats of z in the header's
 * ZUnits; returns its path (one of a few kept in turn). */
static const char *gsf(const char *name, const char *keys, const float *z, size_t n)
{
    static char paths[4][128];
    static int next;
    char *path = paths[next++ % 4];
    snprintf(path, sizeof paths[0], "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    int len = fprintf(f, "Gwyddion Simple Field 1.0\n%s", keys);
    for (int i = 0; i < 4 - len % 4; i++)
        fputc(0, f);
    fwrite(z, sizeof *z, n, f); /* little-endian machines (x86, arm64) */
    fclose(f);
    return path;
}

#endif
