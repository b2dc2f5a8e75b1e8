/* tiptap approach's rows as a table (see include/tiptap/run/run.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run_common.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/run/run.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"

enum { Z, AMP, PHASE, MEAN, PEAK, INDENT, FRACTION, DISS, BRANCH, SETTLED, CYCLES, DRIVE,
       RESIDUAL, YMIN, YMAX, PERIOD, NCOL_ELASTIC, HYST = NCOL_ELASTIC, CI, VISC, NCOL };
/* mode 2 driven: its lock-in's two columns after the rest */
enum { NCOL_MODE2 = 2 };

static const run_column columns[NCOL] = {
    {"z", "m", 0}, {"amplitude", "m", 0}, {"phase", "deg", 0}, {"mean_deflection", "m", 0},
    {"peak_force", "N", 0}, {"max_indentation", "m", 0}, {"contact_fraction", "", 0},
    {"dissipated", "J", 0}, {"branch", "", 1}, {"settled", "", 0}, {"cycles", "", 0},
    {"drive_work", "J", 0}, {"energy_residual", "", 0}, {"deflection_min", "m", 0},
    {"deflection_max", "m", 0}, {"period", "", 0},
    /* viscous scenes only (tt_setup_viscous): the loss per mechanism */
    {"dissipated_hysteresis", "J", 0}, {"dissipated_damping", "J", 0},
    {"dissipated_viscous", "J", 0},
};
static const run_column mode2_columns[NCOL_MODE2] = {{"amplitude_2", "m", 0}, {"phase_2", "deg", 0}};

/* One point as the CSV's row, in SI (tiptap approach's write_row). */
static int put(tt_table *t, const tt_approach_point *p, int ncol, int bimodal)
{
    const tt_cycle *c = &p->cycle;
    int rc = tt_table_row(t);
    if (rc)
        return rc;
    const double v[NCOL] = {p->z, c->amplitude, c->phase * 180 / M_PI, c->mean, c->peak_force,
                            c->max_indentation, c->contact_fraction, c->e_ts, NAN, p->settled,
                            (double)p->cycles, c->e_drive, c->residual_rel,
                            isfinite(c->y_min) ? c->y_min : NAN, isfinite(c->y_max) ? c->y_max : NAN,
                            (double)p->period, c->e_hyst, c->e_ci, c->e_visc};
    for (int k = 0; k < ncol; k++)
        tt_table_set(t, (size_t)k, v[k]);
    if (bimodal) {
        tt_table_set(t, (size_t)ncol, p->amplitude2);
        tt_table_set(t, (size_t)ncol + 1, p->phase2 * 180 / M_PI);
    }
    return tt_table_set_text(t, BRANCH, p->retract ? "retract" : "approach");
}

int tt_run_approach(const tt_scene *s, tt_table **out, tt_progress_fn progress, void *user)
{
    tt_setup *st;
    tt_scene *copy;
    tt_approach *ap = NULL;
    tt_approach_params p;
    *out = NULL;
    int rc;
    if ((rc = run_setup(s, &copy, &st)) || (rc = tt_config_approach_alloc(&ap, st, copy, &p)))
        goto done;
    int ncol = tt_setup_viscous(st) ? NCOL : NCOL_ELASTIC, bimodal = tt_setup_cantilever(st)->A2 > 0;
    run_column cols[NCOL + NCOL_MODE2];
    memcpy(cols, columns, (size_t)ncol * sizeof cols[0]);
    memcpy(cols + ncol, mode2_columns, sizeof mode2_columns);
    tt_table *t = run_table(cols, (size_t)ncol + (bimodal ? NCOL_MODE2 : 0));
    if (!t) {
        rc = TT_ENOMEM;
        goto done;
    }
    *out = t;
    long total = (long)tt_approach_rows(ap);
    while (!tt_approach_done(ap) && rc == TT_OK) {
        tt_approach_point pt;
        if (tt_cancel_requested())
            rc = tt_error(TT_EINTR, "interrupted: %zu of %ld points finished", tt_table_rows(t), total);
        else if ((rc = tt_approach_iterate(ap, &pt)) == TT_OK && (rc = put(t, &pt, ncol, bimodal)) == TT_OK &&
                 progress)
            progress(user, (long)tt_table_rows(t), total);
    }
    if (tt_table_rows(t) > 0)
        tt_approach_warn(ap);
done:
    tt_approach_free(ap);
    tt_setup_free(st);
    tt_scene_free(copy);
    return rc;
}
