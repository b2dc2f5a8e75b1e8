/* The live console's benches (src/live/bench.c): a force curve (tt_run_force) and a
 * thermal tune (tt_run_tune) on an instrument's scene, run at the page's request on a
 * thread of their own, beside the engine's scan thread (docs/live.md, "Force curve and
 * thermal tune"). Nothing outside src/live/ includes it.
 *
 * Ownership: a bench owns its thread, the scene it was handed and its messages; free it
 * (which stops a run under way and waits for it) before the server's loop ends.
 */
#ifndef TIPTAP_LIVE_BENCH_PRIVATE_H
#define TIPTAP_LIVE_BENCH_PRIVATE_H

#include "live_private.h"
#include "tiptap/config/scene.h"

enum { TT_BENCH_FORCE = 0, TT_BENCH_TUNE = 1, TT_BENCH_KINDS = 2 };

typedef struct tt_live_bench tt_live_bench;

/* wake(user) is called from the bench's thread when a message is ready. */
int tt_live_bench_alloc(tt_live_bench **out, void (*wake)(void *), void *user);
void tt_live_bench_free(tt_live_bench *b);

/* Run kind on scene (taken, whatever it returns): its section checked first (TT_EINVAL
 * with the configuration layer's line), refused while either bench runs; TT_OK once its
 * thread started, a "running" message published. */
int tt_live_bench_run(tt_live_bench *b, int kind, tt_scene *scene);

/* The newest message of kind into out when its version is past *seen (which it sets):
 * 1 when it wrote one, else 0. */
int tt_live_bench_message(tt_live_bench *b, int kind, unsigned long *seen, tt_live_buf *out);

/* The JSON writers of messages.c: a string (escaped, UTF-8 always), a number and an
 * array (NaN and infinities as null). */
void tt_live_json_str(tt_live_buf *b, const char *s);
void tt_live_json_num(tt_live_buf *b, double x);
void tt_live_json_array(tt_live_buf *b, const double *x, size_t n);

#endif
