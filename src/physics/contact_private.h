/* The private representation of a tt_contact, shared by the files of the contact laws:
 * contact.c (the law table, allocation, thresholds), contact_md.c (the tabulated
 * Maugis-Dugdale, DMT and JKR curves) and contact_visco.c (the Kelvin-Voigt sample and
 * the bonded film). Private to libtiptap. */
#ifndef TIPTAP_PHYSICS_CONTACT_PRIVATE_H
#define TIPTAP_PHYSICS_CONTACT_PRIVATE_H

#include <math.h>

#include "tiptap/physics/contact.h"

#define S_LO 1e-6  /* one cubic on [0, S_LO] */
#define N0 601      /* nodes uniform in ln s on [ln S_LO, ln S_A] */
#define S_A 0.25
#define N1 1601     /* nodes uniform in s on [S_A, S1] */
#define S1 8.0
#define N2 801      /* nodes uniform in ln s on [ln S1, ln S_MAX] */
#define S_MAX 1e4   /* Delta up to 1e8 normalised units; a Hertz tail beyond */
#define NSEG 4

typedef struct {
    double x0, h;          /* grid start and spacing in the segment's variable */
    double inv_h;          /* 1 / h: look-ups multiply rather than divide */
    int log;               /* variable: 0 = s, 1 = ln s */
    int n;
    double P[N1], dP[N1];  /* values and derivatives in the segment's variable */
    double A[N1], dA[N1];
    double U[N1], dU[N1];  /* integral of P dDelta from s = 0, and dU/ds = 2 s P */
} segment;

typedef enum { CURVE_MAUGIS, CURVE_DMT, CURVE_JKR } curve_kind;

/* A law's load at delta with, when asked, dP/ddelta and the contact radius. */
typedef double load_fn(const struct tt_contact *c, double delta, int in_contact, double *dPdd,
                       double *a);

struct tt_contact {
    const tt_contact_law *law; /* the row it evaluates through */
    /* the Kelvin-Voigt sample (contact_visco.c): the elastic row it adds to, that row's
     * load, the viscosity (Pa s), the film's thickness (m; 0: bulk) and its series'
     * coefficients K sqrt(R) c_k (sqrt(R) / h)^k of delta^((3 + k) / 2) */
    const tt_contact_law *elastic;
    load_fn *elastic_load;
    double eta, film_h, film_k[5], film_rate; /* film_rate: 2 eta / (3 K) */
    /* the relaxation arms (contact_sls.c): their moduli and rates 1 / tau, and the
     * glassy modulus K + sum of the arms' */
    int arms;
    double arm_K[TT_CONTACT_ARMS_MAX], arm_rate[TT_CONTACT_ARMS_MAX], K_glassy;
    tt_contact_params p;
    tt_contact_summary sum;
    int hertz;             /* physical Hertz (w = 0 or model hertz): no table */
    /* custom force law */
    int custom;
    double (*cload)(double, int, double *, void *);
    double (*cenergy)(double, int, void *);
    void *cuser;
    double cjin, cjout;
    /* normalised curve */
    curve_kind kind;
    double lambda;
    double xi;             /* normalised xi0: the van der Waals offset */
    double P0, D0, dmin;
    double s_in;           /* s at the jump-in point Delta0 */
    double Uc_shift;       /* U_contact = I(s) + Uc_shift */
    double vdw_cap;
    double vdw_k2;         /* P0 (Delta0 - xi)^2, the van der Waals law's constant */
    double inv_d, F_per_d; /* 1 / d* and F* / d*: look-ups multiply rather than divide */
    segment seg[NSEG];     /* [0, S_LO], [S_LO, S_A], [S_A, S1], [S1, S_MAX] */
    double Pend, Dend, Aend, Uend;
    /* physical scales F*, d*, a* */
    double F, d, a;
};

/* Hertz, eq. 4 in physical units: P = K a^3 / R, delta = a^2 / R; one law for both
 * contact states. */
static inline double tt_contact_hertz_load(const struct tt_contact *c, double delta, int in_contact,
                                double *dPdd, double *a)
{
    (void)in_contact;
    if (delta <= 0) {
        if (dPdd)
            *dPdd = 0;
        if (a)
            *a = 0;
        return 0;
    }
    double ra = sqrt(c->p.R * delta);
    if (dPdd)
        *dPdd = 1.5 * c->p.K * sqrt(c->p.R * delta);
    if (a)
        *a = ra;
    return c->p.K * ra * delta;
}

/* An elastic law's forces: its load, and the interaction damping in contact only. Inline
 * with the law's own load, so that each row's force is a kernel of its own with no
 * derivative or radius computed (the time loop's). */
static inline tt_contact_forces elastic_force(load_fn *load, const struct tt_contact *c, double ci,
                                              double delta, double rate, int in_contact)
{
    tt_contact_forces f;
    f.conservative = load(c, delta, in_contact, NULL, NULL);
    f.dissipative = in_contact ? ci * rate : 0.0;
    f.viscous = 0.0;
    return f;
}

static inline void elastic_detail(load_fn *load, const struct tt_contact *c, double ci,
                                  double delta, double rate, int in_contact,
                                  tt_contact_detail *out)
{
    out->stiffness = 0; /* a custom law may leave it */
    out->f.conservative = load(c, delta, in_contact, &out->stiffness, &out->radius);
    out->f.dissipative = in_contact ? ci * rate : 0.0;
    out->f.viscous = 0.0;
    out->damping = in_contact ? ci : 0.0;
}

#define ELASTIC_ROW_FUNCTIONS(linkage, law, row)                                                \
    linkage tt_contact_forces row##_force(const tt_contact *c, double ci, double delta,         \
                                          double rate, int in_contact, const double *q)         \
    {                                                                                           \
        (void)q;                                                                                \
        return elastic_force(law##_load, c, ci, delta, rate, in_contact);                       \
    }                                                                                           \
    linkage void row##_detail(const tt_contact *c, double ci, double delta, double rate,        \
                              int in_contact, const double *q, tt_contact_detail *out)          \
    {                                                                                           \
        (void)q;                                                                                \
        elastic_detail(law##_load, c, ci, delta, rate, in_contact, out);                        \
    }

/* contact_md.c: the tabulated laws' row functions and load, and the curve's build. */
tt_contact_forces tt_contact_table_force(const tt_contact *c, double ci, double delta, double rate,
                                         int in_contact, const double *q);
void tt_contact_table_detail(const tt_contact *c, double ci, double delta, double rate,
                             int in_contact, const double *q, tt_contact_detail *out);
double tt_contact_table_energy(const struct tt_contact *c, double delta, int in_contact,
                               const double *q);
double tt_contact_table_load(const struct tt_contact *c, double delta, int in_contact,
                             double *dPdd, double *a);
int tt_contact_md_build(struct tt_contact *c);

/* contact_visco.c: the Kelvin-Voigt row, and its set-up on an elastic law already built
 * (a no-op when the viscosity and the film thickness are 0; tt_contact_alloc checked
 * them). */
extern const tt_contact_law tt_contact_kelvin_voigt;
void tt_contact_visco_setup(struct tt_contact *c, const tt_contact_params *p);

/* contact_sls.c: the generalised Maxwell rows (one per number of arms), set up on the
 * Hertz law (a no-op without arms; tt_contact_alloc checked them). */
void tt_contact_sls_setup(struct tt_contact *c, const tt_contact_params *p);

#endif
