/* String helpers (see include/tiptap/util/str.h). */
#include "tiptap/util/str.h"

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
