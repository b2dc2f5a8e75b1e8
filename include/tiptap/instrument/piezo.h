/* tiptap: the z piezo between the feedback's command and the sample's actual height.
 *
 * An ideal piezo follows its command at once (the default). A real one has two
 * imperfections a scan shows:
 * - dynamics: a second-order response with resonance f_p and damping ratio zeta,
 *     z'' + 2 zeta w_p z' + w_p^2 z = w_p^2 z_in,   w_p = 2 pi f_p,
 *   so a fast command rings (Devasia, Eleftheriou and Moheimani, IEEE Trans. Control
 *   Syst. Technol. 15 (2007) 802, section II);
 * - creep: after a move dz the piezo keeps moving, logarithmically in time,
 *     creep(t) = gamma dz log10(1 + t / t0),
 *   the form of Jung and Gweon, Rev. Sci. Instrum. 71 (2000) 1896 (with 1 + t / t0 so
 *   that a move starts from no creep), summed over every move of the command
 *   (superposition, as the linear creep models of Croft, Shed and Devasia, J. Dyn. Syst.
 *   Meas. Control 123 (2001) 35 do). The logarithm is carried by a chain of first-order
 *   elements with time constants two per decade, whose weights make their sum match
 *   log10(1 + t / t0) to 6e-4 of a decade from t = 0 to the span given at init.
 * Creep acts on the command; the dynamics then act on the command with its creep.
 *
 * Ownership: plain struct, no allocation.
 */
#ifndef TIPTAP_PIEZO_H
#define TIPTAP_PIEZO_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef struct {
    double resonance;  /* Hz; 0: no dynamics */
    double damping;    /* damping ratio zeta (> 0) */
    double creep;      /* gamma: creep per decade of time, as a fraction of the move; 0: none */
    double creep_time; /* t0, s: when a move's creep begins to grow as log10(t) */
} tt_piezo_params;

enum { TT_PIEZO_CREEP_MAX = 48 };

typedef struct {
    tt_piezo_params p;
    double z, v;        /* actual height and speed */
    double rest;        /* the command the piezo has rested at for ever before init */
    double cmd;         /* the last command */
    int ncreep;
    double tau[TT_PIEZO_CREEP_MAX], w[TT_PIEZO_CREEP_MAX], e[TT_PIEZO_CREEP_MAX];
} tt_piezo;

/* 1 when the piezo follows its command at once. */
int tt_piezo_ideal(const tt_piezo_params *p);

/* At rest at z0 (the command has been z0 for ever). span: the longest time after a
 * move that creep must follow (s). */
void tt_piezo_init(tt_piezo *pz, const tt_piezo_params *p, double z0, double span);

/* The command moves linearly from its last value to z_to over dt seconds; returns the
 * actual height at the end. */
double tt_piezo_advance(tt_piezo *pz, double z_to, double dt);

/* The creep's part of the actual height now (m). */
double tt_piezo_creep(const tt_piezo *pz);

TT_END_DECLS
#endif
