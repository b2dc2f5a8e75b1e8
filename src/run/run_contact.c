/* tiptap contact's force law from a scene and its curve and summary as a table (see
 * include/tiptap/run/run.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "run_common.h"
#include "tiptap/config/config.h"
#include "tiptap/run/run.h"
#include "tiptap/util/error.h"

int tt_run_contact_alloc(const tt_scene *s, const char *material, const char *model,
                         tt_contact **out, tt_contact_params *params, double *Qi)
{
    tt_contact_model m = TT_CONTACT_MAUGIS;
    tt_material *mats = NULL;
    size_t nmat = 0, pick = 0;
    *out = NULL;
    if (model && tt_contact_model_parse(model, &m) != 0)
        return tt_error(TT_EINVAL, "model: '%s' is not one of maugis, hertz, dmt, jkr", model);
    int rc = tt_config_materials(s, &mats, &nmat);
    if (rc)
        return rc;
    while (material && pick < nmat && strcmp(mats[pick].name, material) != 0)
        pick++;
    if (pick == nmat) {
        free(mats);
        return tt_error(TT_EINVAL, "%s: no [material %s] section", tt_scene_origin(s), material);
    }
    char name[sizeof mats->name];
    snprintf(name, sizeof name, "%s", mats[pick].name);
    *params = mats[pick].contact;
    *Qi = mats[pick].Qi;
    free(mats);
    if (model)
        params->model = m;
    if ((rc = tt_contact_alloc(out, params))) {
        char why[512];
        snprintf(why, sizeof why, "%s", tt_error_message());
        return tt_scene_locate(s, tt_error(rc, "[material %s]: %s", name, why));
    }
    return TT_OK;
}

/* tiptap contact's summary lines as metadata: normalised, then with params physical. */
static int summary(tt_table *t, const tt_contact *c, const tt_contact_params *phys, double Qi)
{
    const tt_contact_summary *s = tt_contact_summary_of(c);
    double F = s->force_scale, d = s->depth_scale;
    const struct {
        const char *key;
        double value;
        int adhesive, physical;
    } items[] = {
        {"lambda", s->adhesive ? s->lambda : 0, 0, 0}, {"P0", s->P0, 1, 0}, {"Delta0", s->Delta0, 1, 0},
        {"pulloff_load", s->pulloff_load, 1, 0}, {"pulloff_delta", s->pulloff_delta, 1, 0},
        {"jumpout_delta", s->jumpout_delta, 1, 0}, {"jumpout_load", s->jumpout_load, 1, 0},
        {"jumpin_delta", s->jumpin_delta, 1, 0}, {"jumpin_load", s->jumpin_load, 1, 0},
        {"hysteresis", s->hysteresis, 1, 0},
        {"loop_area", phys && s->adhesive ? s->loop_energy / (F * d) : s->loop_energy, 1, 0},
        {"reduced_modulus_Pa", phys ? phys->K : 0, 0, 1}, {"radius_m", phys ? phys->R : 0, 0, 1},
        {"adhesion_energy_J_per_m2", phys ? phys->w : 0, 0, 1}, {"xi0_m", s->xi0, 1, 1},
        {"force_scale_N", F, 1, 1}, {"depth_scale_m", d, 1, 1}, {"radius_scale_m", s->radius_scale, 1, 1},
        {"P0_N", s->P0 * F, 1, 1}, {"delta0_m", s->Delta0 * d, 1, 1},
        {"pulloff_load_N", s->pulloff_load * F, 1, 1}, {"jumpout_delta_m", s->jumpout_delta * d, 1, 1},
        {"jumpin_load_N", s->jumpin_load * F, 1, 1}, {"hamaker_J", s->adhesive ? s->hamaker : 0, 0, 1},
        {"loop_energy_J", s->adhesive ? s->loop_energy : 0, 0, 1},
    };
    int rc = run_meta_number(t, "adhesive", s->adhesive);
    for (size_t i = 0; i < sizeof items / sizeof items[0] && rc == TT_OK; i++)
        if ((!items[i].adhesive || s->adhesive) && (!items[i].physical || phys))
            rc = run_meta_number(t, items[i].key, items[i].value);
    if (rc == TT_OK && phys && isfinite(Qi))
        rc = run_meta_number(t, "interaction_quality_factor", Qi);
    return rc;
}

int tt_run_contact_table(const tt_contact *c, const tt_contact_params *params, double Qi,
                         size_t n, double Amax, tt_table **out)
{
    static const run_column columns[] = {{"A", "", 0}, {"Delta", "", 0}, {"P", "", 0}, {"stable", "", 0}};
    double *A = malloc(n * sizeof *A), *D = malloc(n * sizeof *D), *P = malloc(n * sizeof *P);
    int *st = malloc(n * sizeof *st);
    tt_table *t = run_table(columns, 4);
    int rc = A && D && P && st && t ? TT_OK : tt_error_nomem("a contact curve of %zu points", n);
    const tt_contact_summary *s = tt_contact_summary_of(c);
    if (rc == TT_OK)
        rc = tt_contact_curve(c, n, Amax, A, D, P, st);
    /* the A -> 0 end first, as the CSV has it */
    if (rc == TT_OK && s->adhesive && (rc = tt_table_row(t)) == TT_OK) {
        const double v[4] = {0, s->Delta0, s->P0, !s->hysteresis};
        for (size_t k = 0; k < 4; k++)
            tt_table_set(t, k, v[k]);
    }
    for (size_t i = 0; i < n && rc == TT_OK; i++)
        if ((rc = tt_table_row(t)) == TT_OK) {
            const double v[4] = {A[i], D[i], P[i], st[i]};
            for (size_t k = 0; k < 4; k++)
                tt_table_set(t, k, v[k]);
        }
    if (rc == TT_OK)
        rc = summary(t, c, params, Qi);
    free(A);
    free(D);
    free(P);
    free(st);
    if (rc) {
        tt_table_free(t);
        t = NULL;
    }
    *out = t;
    return rc;
}
