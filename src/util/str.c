/* String helpers (see include/tiptap/util/str.h). */
#include "tiptap/util/str.h"

#include <locale.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

char *tt_strdup(const char *s)
{
    if (!s)
        return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

void tt_free(void *p) { free(p); }

/* A C locale made once, whichever thread parses first; strtod_l never consults the
 * process locale. */
static locale_t c_locale = (locale_t)0;
static pthread_once_t c_locale_once = PTHREAD_ONCE_INIT;

static void make_c_locale(void) { c_locale = newlocale(LC_NUMERIC_MASK, "C", (locale_t)0); }

double tt_strtod(const char *s, char **end)
{
    pthread_once(&c_locale_once, make_c_locale);
    return strtod_l(s, end, c_locale);
}
