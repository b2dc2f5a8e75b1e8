/* tiptap: string helpers.
 *
 * Ownership: a copy belongs to the caller, who frees it with free().
 */
#ifndef TIPTAP_STR_H
#define TIPTAP_STR_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* A malloc'd copy of s; NULL when s is NULL or memory runs out (C11 has no strdup). */
char *tt_strdup(const char *s);

TT_END_DECLS
#endif
