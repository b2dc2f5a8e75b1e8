/* tiptap trace's rows as a table (see include/tiptap/run/run.h). */
#include <stdlib.h>

#include "run_common.h"
#include "tiptap/config/read_trace.h"
#include "tiptap/config/setup.h"
#include "tiptap/instrument/trace.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

enum { CYCLE, T, BASE, TIP, SAMPLE, DEFLECTION, FORCE, RADIUS, PRESSURE, CONTACT, RAMP, NCOL };

static const run_column columns[RAMP] = {
    {"cycle", "", 0}, {"t", "s", 0},     {"base", "m", 0},           {"tip", "m", 0},
    {"sample", "m", 0}, {"deflection", "m", 0}, {"force", "N", 0}, {"contact_radius", "m", 0},
    {"pressure", "Pa", 0}, {"contact", "", 0},
};

/* A recorded cycle's samples as rows (tiptap trace's write_row, in SI). */
static int put(tt_table *t, const tt_trace_row *r, int ramp)
{
    int rc = TT_OK;
    for (size_t k = 0; k < r->nsamples && rc == TT_OK; k++) {
        const tt_trace_sample *x = &r->samples[k];
        if ((rc = tt_table_row(t)))
            break;
        const double v[NCOL] = {(double)r->cycle, x->t, x->base, x->tip, x->sample, x->tip - x->base,
                                x->force, x->contact_radius, x->pressure, x->contact, r->ramp_value};
        for (int c = 0; c < (ramp ? NCOL : RAMP); c++)
            tt_table_set(t, (size_t)c, v[c]);
    }
    return rc;
}

int tt_run_trace(const tt_scene *s, tt_table **out, tt_progress_fn progress, void *user)
{
    tt_setup *st;
    tt_scene *copy;
    tt_trace *tr = NULL;
    tt_trace_params p;
    *out = NULL;
    int rc;
    /* a ramp changes the setup's scene: run_setup's copy */
    if ((rc = run_setup(s, &copy, &st)) || (rc = tt_config_trace(copy, &p)) ||
        (rc = tt_scene_locate(copy, tt_trace_alloc(&tr, st, &p))))
        goto done;
    tt_table *t = run_table(columns, RAMP);
    if (!t || (p.ramp && (rc = tt_table_add(t, p.ramp, run_key_unit(p.ramp), 0)))) {
        rc = t ? rc : TT_ENOMEM;
        tt_table_free(t);
        goto done;
    }
    *out = t;
    long total = (long)tt_trace_rows(tr), done = 0;
    while (!tt_trace_done(tr) && rc == TT_OK) {
        tt_trace_row row;
        if (tt_cancel_requested())
            rc = tt_error(TT_EINTR, "interrupted: %ld of %ld cycles finished", done, total);
        else if ((rc = tt_trace_iterate(tr, &row)) == TT_OK && (rc = put(t, &row, p.ramp != NULL)) == TT_OK) {
            done++;
            /* a cycle takes a millisecond or less: progress every 64 */
            if (progress && (done % 64 == 0 || tt_trace_done(tr)))
                progress(user, done, total);
        }
    }
    if (done > 0)
        tt_trace_warn_contact(tr);
done:
    tt_trace_free(tr);
    tt_setup_free(st);
    tt_scene_free(copy);
    return rc;
}
