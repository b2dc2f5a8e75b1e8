/* tiptap: a tip and a sample material as the contact parameters of their pair.
 *
 * The reduced modulus of the pair is 1/K = 3/4 [(1 - nu_tip^2)/E_tip +
 * (1 - nu_sample^2)/E_sample] (Burnham et al. section 2.2.1), unless the material gives
 * it directly; the radius is the tip's (a flat sample).
 *
 * Plain structs, no ownership.
 */
#ifndef TIPTAP_MATERIAL_H
#define TIPTAP_MATERIAL_H

#include <stddef.h>

#include "tiptap/export.h"
#include "tiptap/physics/contact.h"

TT_BEGIN_DECLS

typedef struct {
    double radius;         /* m */
    double youngs_modulus; /* Pa */
    double poisson_ratio;
} tt_tip;

/* One sample material, ready to build its force law (tt_contact_alloc). */
typedef struct {
    char name[128];            /* for messages: [material NAME] */
    tt_contact_params contact; /* the tip-sample pair's */
    double Qi;                 /* interaction quality factor; NAN: no interaction damping */
    int map_rgb;               /* colour 0xrrggbb in a PNG material map; -1: none */
    long map_grey;             /* grey level 0-65535 in a PNG material map, at the map's
                                * own depth; -1: none */
} tt_material;

/* 1 when the material has a viscosity or a film (the Kelvin-Voigt law) or relaxation
 * arms (the generalised Maxwell law): the runs then
 * write the tip-sample loss per mechanism (hysteresis, interaction damping, viscous)
 * beside the total, which elastic scenes keep as they were. */
int tt_material_viscous(const tt_material *m);

/* The pair's reduced modulus (Burnham et al. section 2.2.1) from the tip's and the
 * sample's Young's moduli (Pa) and Poisson ratios. */
double tt_material_reduced_modulus(const tt_tip *tip, double E, double nu);

/* The Maugis parameter eq. 3 gives for w, R, K and xi0 (Lennard-Jones):
 * lambda = 2.06 / xi0 (w^2 R / (pi K^2))^(1/3). */
double tt_material_lambda(const tt_contact_params *p);

TT_END_DECLS
#endif
