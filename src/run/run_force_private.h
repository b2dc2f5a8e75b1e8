/* Shared by tiptap force's one curve (run_force.c) and its force volume
 * (run_force_volume.c): a lever made ready for curves, and one curve run on it. */
#ifndef TIPTAP_RUN_FORCE_PRIVATE_H
#define TIPTAP_RUN_FORCE_PRIVATE_H

#include <stdint.h>

#include "tiptap/config/setup.h"
#include "tiptap/run/force.h"
#include "tiptap/solver/integrator.h"

/* A setup of the scene with its lever undriven and warm, and the sample buffer the
 * curve reads; one per thread. */
typedef struct {
    tt_scene *copy;
    tt_setup *st;
    tt_force_params p;
    tt_cantilever c; /* undriven: a_d = F0 = 0 */
    double temperature;
    uint64_t seed;
    tt_sample *buf;
} force_lever;

/* The lever for scene s ([force] read and checked); release with force_lever_free. */
int force_lever_alloc(const tt_scene *s, force_lever *L);
void force_lever_free(force_lever *L);

/* One curve on material mat with the thermal force's stream key: its rows into t (the
 * columns of tt_run_force; t emptied first is the caller's), its figures into *sum.
 * *done counts the drive periods, progress (if not NULL) is told of them out of total. */
int force_curve(force_lever *L, size_t mat, uint64_t key, tt_table *t, tt_force_summary *sum,
                tt_progress_fn progress, void *user, long *done, long total);

/* The columns of a curve's table, made empty. */
tt_table *force_table(void);

#endif
