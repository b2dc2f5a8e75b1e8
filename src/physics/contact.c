/* Tip-sample contact mechanics (Burnham et al. section 2.2; see include/tiptap/physics/contact.h).
 * The law table, the allocation and the event thresholds are here; the tabulated curves
 * in contact_md.c, the Kelvin-Voigt sample and the bonded film in contact_visco.c, the
 * generalised Maxwell sample in contact_sls.c. */
#include "tiptap/physics/contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact_private.h"
#include "tiptap/util/error.h"
#include "tiptap/util/warning.h"

/* ------------------------------------------------------------- the laws ---- */

/* Hertz's row: its load is tt_contact_hertz_load (contact_private.h). */

static double hertz_energy(const struct tt_contact *c, double delta, int in_contact, const double *q)
{
    (void)in_contact;
    (void)q;
    return delta <= 0 ? 0 : 0.4 * c->p.K * sqrt(c->p.R) * delta * delta * sqrt(delta);
}

/* The caller's law (tt_contact_alloc_custom): no contact radius. */
static inline double custom_load(const struct tt_contact *c, double delta, int in_contact,
                                 double *dPdd, double *a)
{
    if (a)
        *a = 0;
    return c->cload(delta, in_contact, dPdd, c->cuser);
}

static double custom_energy(const struct tt_contact *c, double delta, int in_contact, const double *q)
{
    (void)q;
    return c->cenergy(delta, in_contact, c->cuser);
}

ELASTIC_ROW_FUNCTIONS(static, tt_contact_hertz, hertz)
ELASTIC_ROW_FUNCTIONS(static, custom, custom)

/* The law table: a row per tt_contact_model, then the custom law. A new law is a row
 * here (its force, detail and energy, its state_size), its name in tt_contact_model and
 * its parameters in tt_contact_alloc (docs/architecture.md). */
#define TABLE_ROW tt_contact_table_force, tt_contact_table_detail, tt_contact_table_energy, NULL, NULL
enum { LAW_CUSTOM = TT_CONTACT_JKR + 1, NLAWS };
static const tt_contact_law laws[NLAWS] = {
    [TT_CONTACT_MAUGIS] = {"maugis", 0, TABLE_ROW},
    [TT_CONTACT_HERTZ] = {"hertz", 0, hertz_force, hertz_detail, hertz_energy, NULL, NULL},
    [TT_CONTACT_DMT] = {"dmt", 0, TABLE_ROW},
    [TT_CONTACT_JKR] = {"jkr", 0, TABLE_ROW},
    [LAW_CUSTOM] = {"custom", 0, custom_force, custom_detail, custom_energy, NULL, NULL},
};

const tt_contact_law *tt_contact_law_of(const tt_contact *c) { return c->law; }

tt_contact_forces tt_contact_force(const tt_contact *c, double ci, double delta, double rate,
                                   int in_contact, const double *state)
{
    return c->law->force(c, ci, delta, rate, in_contact, state);
}

void tt_contact_evaluate(const tt_contact *c, double ci, double delta, double rate, int in_contact,
                         const double *state, tt_contact_detail *out)
{
    c->law->detail(c, ci, delta, rate, in_contact, state, out);
}

double tt_contact_load(const tt_contact *c, double delta, int in_contact, double *dPdd, double *a)
{
    if (!dPdd && !a)
        return c->law->force(c, 0.0, delta, 0.0, in_contact, NULL).conservative;
    tt_contact_detail o;
    c->law->detail(c, 0.0, delta, 0.0, in_contact, NULL, &o);
    if (dPdd)
        *dPdd = o.stiffness;
    if (a)
        *a = o.radius;
    return o.f.conservative;
}

double tt_contact_energy(const tt_contact *c, double delta, int in_contact)
{
    return c->law->energy(c, delta, in_contact, NULL);
}

int tt_contact_model_parse(const char *name, tt_contact_model *out)
{
    for (int i = 0; i <= TT_CONTACT_JKR; i++)
        if (strcmp(name, laws[i].name) == 0) {
            *out = (tt_contact_model)i;
            return 0;
        }
    return -1;
}

const char *tt_contact_model_name(tt_contact_model m)
{
    return (unsigned)m <= TT_CONTACT_JKR ? laws[m].name : "?";
}

static int bad(const char *what) { return tt_error(TT_EINVAL, "contact: %s", what); }

int tt_contact_alloc(tt_contact **out, const tt_contact_params *p)
{
    *out = NULL;
    if (!(p->K > 0) || !isfinite(p->K))
        return bad("the reduced modulus K must be positive and finite");
    if (!(p->R > 0) || !isfinite(p->R))
        return bad("the tip radius R must be positive and finite");
    if (!(p->w >= 0) || !isfinite(p->w))
        return bad("the work of adhesion w must be zero or positive and finite");
    if ((unsigned)p->model > TT_CONTACT_JKR)
        return bad("unknown contact model");
    if (!(p->viscosity >= 0) || !isfinite(p->viscosity))
        return bad("the viscosity must be zero or positive and finite");
    if (!(p->film_thickness >= 0) || !isfinite(p->film_thickness))
        return bad("the film thickness must be zero (bulk) or positive and finite");
    if (p->film_thickness > 0 && p->w > 0 && p->model != TT_CONTACT_HERTZ)
        return bad("a film (film_thickness) needs the Hertz law: adhesion_energy 0 or model hertz");
    if (p->arms < 0 || p->arms > TT_CONTACT_ARMS_MAX)
        return bad("the number of relaxation arms must lie from 0 to 4");
    for (int i = 0; i < p->arms; i++)
        if (!(p->arm_modulus[i] >= 0) || !isfinite(p->arm_modulus[i]) || !(p->arm_time[i] > 0))
            return bad("each relaxation arm needs a modulus >= 0 and a relaxation time > 0");
    if (p->arms > 0 && ((p->w > 0 && p->model != TT_CONTACT_HERTZ) || p->viscosity > 0 ||
                        p->film_thickness > 0))
        return bad("relaxation arms need the Hertz law alone: adhesion_energy 0 or model hertz, "
                   "no viscosity, no film_thickness");
    struct tt_contact *c = calloc(1, sizeof *c);
    if (!c)
        return tt_error_nomem("a contact force law");
    c->p = *p;
    if (p->w == 0 || p->model == TT_CONTACT_HERTZ) {
        /* No adhesion: Hertz in physical units exactly (docs/physics.md: w = 0 is singular) */
        c->hertz = 1;
        c->law = &laws[TT_CONTACT_HERTZ];
        c->sum.adhesive = 0;
        c->sum.lambda = 0;
        c->sum.P0 = c->sum.Delta0 = c->sum.pulloff_load = NAN;
        c->sum.jumpout_delta = c->sum.jumpin_delta = 0;
        tt_contact_visco_setup(c, p);
        tt_contact_sls_setup(c, p);
        *out = c;
        return TT_OK;
    }
    c->F = M_PI * p->w * p->R;
    c->d = cbrt(M_PI * M_PI * p->w * p->w * p->R / (p->K * p->K));
    c->a = cbrt(M_PI * p->w * p->R * p->R / p->K);
    double root = cbrt(p->w * p->w * p->R / (M_PI * p->K * p->K));
    double xi0 = p->xi0, lam = p->lambda;
    int have_xi = isfinite(xi0) && xi0 > 0, have_lam = isfinite(lam) && lam > 0;
    if (p->model == TT_CONTACT_MAUGIS) {
        if (!have_lam && !have_xi) {
            free(c);
            return bad("Maugis contact needs the interatomic distance xi0 or lambda");
        }
        if (!have_lam)
            lam = 2.06 / xi0 * root; /* eq. 3, Lennard-Jones */
        if (!have_xi)
            xi0 = 2.06 / lam * root;
        if (lam < 1e-4 || lam > 1e4) {
            free(c);
            return tt_error(TT_EINVAL,
                            "contact: lambda = %.3g is outside 1e-4 to 1e4; use model = dmt or jkr",
                            lam);
        }
        c->kind = CURVE_MAUGIS;
    } else if (p->model == TT_CONTACT_DMT) {
        if (!have_xi && have_lam)
            xi0 = 2.06 / lam * root;
        if (!(isfinite(xi0) && xi0 > 0)) {
            free(c);
            return bad("DMT contact needs the interatomic distance xi0 for its van der Waals branch");
        }
        c->kind = CURVE_DMT;
    } else {
        if (!have_xi)
            xi0 = have_lam ? 2.06 / lam * root : 0.3e-9;
        c->kind = CURVE_JKR;
    }
    c->lambda = lam;
    c->xi = xi0 / c->d;
    if (!(c->xi <= TT_CONTACT_XI0N_MAX)) {
        double xin = c->xi, d = c->d;
        free(c);
        return tt_error(TT_EINVAL,
                        "contact: the interatomic distance xi0 = %.3g m is %.3g depth scales d* "
                        "(%.3g m), beyond the %.0e a force law takes (its van der Waals branch "
                        "squares it)", xi0, xin, d, TT_CONTACT_XI0N_MAX);
    }
    c->law = &laws[p->model];
    int rc = tt_contact_md_build(c);
    if (rc) {
        free(c);
        return rc;
    }
    tt_contact_visco_setup(c, p);
    *out = c;
    return TT_OK;
}

int tt_contact_alloc_normalised(tt_contact **out, tt_contact_model model, double lambda, double xi0n)
{
    *out = NULL;
    if (model == TT_CONTACT_MAUGIS && !(lambda >= 1e-4 && lambda <= 1e4))
        return tt_error(TT_EINVAL, "contact: lambda must lie between 1e-4 and 1e4, got %g", lambda);
    if (!(xi0n > 0 && xi0n <= TT_CONTACT_XI0N_MAX))
        return tt_error(TT_EINVAL, "contact: the normalised xi0 must be positive and at most %.0e, got %g",
                        TT_CONTACT_XI0N_MAX, xi0n);
    struct tt_contact *c = calloc(1, sizeof *c);
    if (!c)
        return tt_error_nomem("a contact force law");
    /* F* = d* = a* = 1: R = 1, w = 1/pi, K = 1 */
    c->p.model = model;
    c->p.K = 1;
    c->p.R = 1;
    c->p.w = 1 / M_PI;
    c->p.xi0 = xi0n;
    c->p.lambda = lambda;
    c->F = c->d = c->a = 1;
    if (model == TT_CONTACT_HERTZ) {
        c->hertz = 1;
        c->law = &laws[TT_CONTACT_HERTZ];
        c->sum.P0 = c->sum.Delta0 = c->sum.pulloff_load = NAN;
        *out = c;
        return TT_OK;
    }
    c->kind = model == TT_CONTACT_MAUGIS ? CURVE_MAUGIS : model == TT_CONTACT_DMT ? CURVE_DMT : CURVE_JKR;
    c->lambda = lambda;
    c->xi = xi0n;
    c->law = &laws[model];
    tt_contact_md_build(c);
    *out = c;
    return TT_OK;
}

int tt_contact_alloc_custom(tt_contact **out,
                            double (*load)(double delta, int in_contact, double *dPdd, void *user),
                            double (*energy)(double delta, int in_contact, void *user), void *user,
                            double jumpin, double jumpout)
{
    *out = NULL;
    if (!load || !energy || !(jumpout <= jumpin))
        return tt_error(TT_EINVAL, "contact: a custom law needs load, energy and jumpout <= jumpin");
    struct tt_contact *c = calloc(1, sizeof *c);
    if (!c)
        return tt_error_nomem("a contact force law");
    c->custom = 1;
    c->law = &laws[LAW_CUSTOM];
    c->cload = load;
    c->cenergy = energy;
    c->cuser = user;
    c->cjin = jumpin;
    c->cjout = jumpout;
    c->sum.hysteresis = jumpout < jumpin;
    *out = c;
    return TT_OK;
}

void tt_contact_free(tt_contact *c) { free(c); }

const tt_contact_summary *tt_contact_summary_of(const tt_contact *c) { return &c->sum; }

double tt_contact_jumpin(const tt_contact *c)
{
    if (c->custom)
        return c->cjin;
    return c->hertz ? 0.0 : c->D0 * c->d;
}

double tt_contact_jumpout(const tt_contact *c)
{
    if (c->custom)
        return c->cjout;
    return c->hertz ? 0.0 : c->dmin * c->d;
}

int tt_contact_beyond_validity(double a, double delta, double R)
{
    return a > TT_CONTACT_MAX_RADIUS_RATIO * R || delta > R;
}

int tt_contact_warn_validity(const char *material, double a, double delta, double R,
                             const char *remedy)
{
    if (!tt_contact_beyond_validity(a, delta, R))
        return 0;
    tt_warn(TT_WARN_VALIDITY,
            "[material %s]: contact radius up to %.3g nm at %.3g nm indentation on a tip of "
            "radius %.3g nm, beyond the contact laws' small contact (radius <= %.1f R, "
            "indentation <= R): their forces are off there; %s keeps within it",
            material, a * 1e9, delta * 1e9, R * 1e9, TT_CONTACT_MAX_RADIUS_RATIO, remedy);
    return 1;
}
