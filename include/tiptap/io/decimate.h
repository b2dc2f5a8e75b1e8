/* tiptap: a plot's points held to a fixed budget: parallel lines sharing an abscissa
 * (line 0), reduced bucket by bucket to each line's smallest and largest value, so
 * that envelopes and peaks survive at any length of the input.
 *
 * Ownership: tt_decimate_alloc allocates; tt_decimate_free frees it and its lines.
 */
#ifndef TIPTAP_DECIMATE_H
#define TIPTAP_DECIMATE_H

#include <stddef.h>

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct tt_decimate tt_decimate;

/* lines parallel values per sample (line 0: the abscissa); total: samples expected
 * (estimate); budget: the most points kept. */
int tt_decimate_alloc(tt_decimate **out, size_t lines, double total, size_t budget);
void tt_decimate_free(tt_decimate *d);
int tt_decimate_push(tt_decimate *d, const double *v);
/* Close the last, partial bucket. */
int tt_decimate_finish(tt_decimate *d);
size_t tt_decimate_count(const tt_decimate *d);
const double *tt_decimate_line(const tt_decimate *d, size_t line);

TT_END_DECLS
#endif
