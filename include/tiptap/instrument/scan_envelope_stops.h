/* tiptap: why the envelope tier integrates a cycle (docs/dynamics.md, Tiers): counts
 * of its controller's decisions, kept per thread, for the bench's lesson figure and for
 * anyone asking why a scene runs slowly. A line stepped with tt_scan_step runs on the
 * calling thread, so its counts are that thread's. */
#ifndef TIPTAP_SCAN_ENVELOPE_STOPS_H
#define TIPTAP_SCAN_ENVELOPE_STOPS_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

typedef enum {
    TT_ENV_MODEL = 0,      /* cycles the model ran */
    TT_ENV_CHECK_PASS,     /* checks (each an integrated cycle) that passed */
    TT_ENV_CHECK_ERROR,    /* checks failed: the model's error beyond the tolerance */
    TT_ENV_CHECK_CONTACT,  /* checks failed: the end's contact flag not the anchor's */
    TT_ENV_CHECK_TOUCH,    /* checks failed: touched where the anchor did not, or not */
    TT_ENV_CHECK_CYCLE,    /* checks failed: the cycle could not be integrated */
    TT_ENV_SHORTEST,       /* failures on the shortest stretch: every cycle through it */
    TT_ENV_FULL,           /* cycles integrated with the model off, of which: */
    TT_ENV_FULL_EDGE,      /*   at an edge (height or material) */
    TT_ENV_FULL_CHANGE,    /*   contact or touch changed from the last cycle */
    TT_ENV_FULL_REDO,      /*   through a stretch that failed as the shortest */
    TT_ENV_FULL_WAIT,      /*   waiting for quiet cycles before a build */
    TT_ENV_FULL_GRAZE,     /*   in the grazing mode */
    TT_ENV_END_SAMPLE,     /* stretches ended early: the sample's smooth course moved
                            * past the bound from the anchor (1e-3 of A0) */
    TT_ENV_END_REACH,      /* stretches ended early: the inputs past the second-order
                            * model's reach, no kept model near */
    TT_ENV_BUILD,          /* models built (each 7 to 22 more cycles, not the run's) */
    TT_ENV_STOPS
} tt_envelope_stop;

/* The calling thread's counts since its start or the last reset. */
void tt_scan_envelope_stops(long counts[TT_ENV_STOPS]);
void tt_scan_envelope_stops_reset(void);
/* A short name of each count ("model", "check_pass", ...). */
const char *tt_scan_envelope_stop_name(int i);

TT_END_DECLS
#endif
