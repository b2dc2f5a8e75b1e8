/* tiptap accuracy's rows as a table (see include/tiptap/run/run.h). */
#include <stdio.h>
#include <string.h>

#include "run_common.h"
#include "tiptap/config/config.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

enum { METHOD, TIER, KNOB, VALUE, RUN_TIME, CPU_TIME, STEPS, INTEGRATED, NFIRST };

static const run_column first[NFIRST] = {
    {"method", "", 1},   {"tier", "", 1},     {"knob", "", 1},            {"value", "", 0},
    {"run_time", "s", 0}, {"cpu_time", "s", 0}, {"steps_per_cycle", "", 0}, {"integrated", "", 0},
};

/* The observables' columns, named as in the CSV ("amplitude_err_rel", "height_err_max_m"),
 * then residual_rel, role, is_default, status. */
static tt_table *columns(const tt_accuracy *a)
{
    const tt_accuracy_observable *obs;
    size_t nobs = tt_accuracy_observables(a, &obs);
    tt_table *t = run_table(first, NFIRST);
    int rc = t ? TT_OK : TT_ENOMEM;
    for (size_t i = 0; i < nobs && rc == TT_OK; i++) {
        const char *c = obs[i].column, *u = "";
        size_t n = strlen(c);
        /* the unit the name ends in: _m, _deg; _rel is a fraction */
        if (n > 2 && strcmp(c + n - 2, "_m") == 0)
            u = "m";
        else if (n > 4 && strcmp(c + n - 4, "_deg") == 0)
            u = "deg";
        rc = tt_table_add(t, c, u, 0);
    }
    if (rc == TT_OK && !(rc = tt_table_add(t, "residual_rel", "", 0)) && !(rc = tt_table_add(t, "role", "", 1)) &&
        !(rc = tt_table_add(t, "is_default", "", 0)))
        rc = tt_table_add(t, "status", "", 1);
    if (rc) {
        tt_table_free(t);
        return NULL;
    }
    return t;
}

static int put(tt_table *t, const tt_accuracy_row *r, size_t nobs)
{
    int rc = tt_table_row(t);
    if (rc || (rc = tt_table_set_text(t, METHOD, tt_method_name(r->method))) ||
        (rc = tt_table_set_text(t, TIER, tt_accuracy_tier_name(r->tier))) || (rc = tt_table_set_text(t, KNOB, r->knob)))
        return rc;
    const double v[NFIRST] = {0, 0, 0, r->value, r->run_time, r->cpu_time, r->steps_per_cycle, r->integrated};
    for (size_t k = VALUE; k < NFIRST; k++)
        tt_table_set(t, k, v[k]);
    for (size_t i = 0; i < nobs; i++)
        tt_table_set(t, NFIRST + i, r->err[i]);
    tt_table_set(t, NFIRST + nobs, r->residual_rel);
    tt_table_set(t, NFIRST + nobs + 2, r->is_default);
    if ((rc = tt_table_set_text(t, NFIRST + nobs + 1, tt_accuracy_role_name(r->role))))
        return rc;
    return tt_table_set_text(t, NFIRST + nobs + 3, r->status == TT_OK ? "ok" : "failed");
}

int tt_run_accuracy(const tt_scene *s, const tt_accuracy_params *p, tt_table **out,
                    tt_progress_fn progress, void *user)
{
    tt_accuracy *a = NULL;
    *out = NULL;
    int rc = tt_config_accuracy_alloc(&a, s, p);
    long n = 0;
    while (rc == TT_OK && !tt_accuracy_done(a)) {
        const tt_accuracy_row *r;
        int pass = tt_accuracy_pass(a);
        if (tt_cancel_requested())
            rc = tt_error(TT_EINTR, "interrupted: %ld of %zu settings finished", n, tt_accuracy_rows(a));
        else if ((rc = tt_accuracy_iterate(a, &r)) == TT_OK && pass == 1) {
            n++; /* a new row; the later passes only time the cheap ones again */
            if (progress)
                progress(user, n, (long)tt_accuracy_rows(a));
        }
    }
    /* the rows of the first pass, with the best times of the passes that finished */
    if (a && n > 0) {
        const tt_accuracy_observable *obs;
        size_t nobs = tt_accuracy_observables(a, &obs);
        tt_table *t = columns(a);
        int trc = t ? TT_OK : TT_ENOMEM;
        for (long i = 0; i < n && trc == TT_OK; i++)
            trc = put(t, tt_accuracy_row_at(a, (size_t)i), nobs);
        if (trc == TT_OK && tt_accuracy_kind_of(a) == TT_ACCURACY_LINE)
            trc = run_meta_number(t, "line_pixels", (double)tt_accuracy_line_pixels(a));
        else if (trc == TT_OK && (trc = run_meta_number(t, "point", tt_accuracy_point(a))) == TT_OK)
            trc = run_meta_number(t, "cycles", (double)tt_accuracy_cycles(a));
        if (trc == TT_OK)
            trc = tt_table_meta(t, "kind", tt_accuracy_kind_of(a) == TT_ACCURACY_LINE ? "line" : "point");
        if (trc) {
            tt_table_free(t);
            t = NULL;
            rc = rc ? rc : trc;
        }
        *out = t;
    }
    tt_accuracy_free(a);
    return rc;
}
