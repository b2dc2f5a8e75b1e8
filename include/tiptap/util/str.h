/* tiptap: string helpers.
 *
 * Ownership: a copy belongs to the caller, who frees it with free() or tt_free().
 */
#ifndef TIPTAP_STR_H
#define TIPTAP_STR_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* A malloc'd copy of s; NULL when s is NULL or memory runs out (C11 has no strdup). */
char *tt_strdup(const char *s);

/* Free memory the library allocated and handed to the caller (a string, a copy): the
 * same free() the library uses, for callers that do not share its C library (a
 * binding, another language's runtime). NULL is ignored. */
void tt_free(void *p);

/* strtod in the C locale, whatever the process locale: scene values, GSF headers and
 * sweep journals read the same on any machine. */
double tt_strtod(const char *s, char **end);

/* x into buf (32 bytes at least) as printf's "%.9g" writes it in the C locale, the same
 * bytes, several times faster (src/util/format_g9.c: printf itself where the ninth digit
 * sits within 1e-9 of a rounding tie, and for zero, non-finite and extreme values);
 * returns the length. */
int tt_format_g9(char *buf, double x);

TT_END_DECLS
#endif
