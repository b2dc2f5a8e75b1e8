/* The contact law's local geometry in a scan ([tip] contact_geometry = local): the
 * geometry where the tip touches, quantised into a key, and each thread's laws built
 * for the keys it meets (see scan_private.h, docs/surfaces.md). */
#include "scan_private.h"

#include <math.h>
#include <stdlib.h>

#include "tiptap/util/error.h"

/* The quantisation: -ln cos a in steps of GEO_DC and ln (R_eff / R) in steps of GEO_DR,
 * each law built at its step's centre, half a step at most from the geometry: Hertz's
 * cos^2.5 a within 0.5 % and sqrt(R_eff) within 0.25 %, an adhesive law's ~R_eff within
 * 0.5 %, together within 1 % (measured: docs/surfaces.md). Bin (0, 0) is the
 * material's flat law itself. */
#define GEO_DC 0.004
#define GEO_DR 0.01
/* cos a at least 0.1 (84 deg) and R_eff at least R / 100: a wall or a corner inside the
 * stencil reads a slope and a curvature no law describes (docs/surfaces.md), and
 * these bound its thresholds to ten times the flat's */
#define GEO_COS_MIN 0.1
#define GEO_R_MIN 0.01

/* Laws kept per thread, least recently used replaced: a law is 307 kB with its tables,
 * so 32 laws and 64 tables at their R_eff (from which a slope's law is a copy, not a
 * rebuild: tt_contact_alloc_tilted) hold 29 MB a thread; on geometry.ini's spheres
 * (examples/instrument) 128 and 16 rebuilt 2485 tables and took 1.31 times axis's CPU,
 * 32 and 64 rebuilt 1130 (copying 21177 laws) and took 1.19 times. */
enum { GEO_KEPT = 32, GEO_TABLES = 64 };

typedef struct {
    size_t mat;
    uint32_t key;
    unsigned long used; /* the look-up that last chose it (0: empty) */
    tt_contact *law;
} geo_law;

struct tt_scan_laws {
    geo_law law[GEO_KEPT];
    geo_law table[GEO_TABLES]; /* keyed by the R_eff part of the key alone */
    unsigned long clock;
    long built, tables;
};

/* A corner: the surface's slope turns by more than GEO_KINK (14 deg) across the stencil
 * (a surface of radius r turns R / (20 r cos a): one sharper than R / 5 along its slope),
 * where its differences read the wall; there the tip's own normal at the contact point
 * is the contact's (a smooth surface touches the tip tangentially: the two agree), and
 * R_eff is GEO_CORNER_R of R (docs/surfaces.md). */
#define GEO_KINK 0.25
#define GEO_CORNER_R 1.0

uint32_t tt_scan_geometry_key(const tt_scan *S, double x, double y, double rho, size_t mat)
{
    const double R = S->contact_R[mat], h = S->geo_step * R;
    tt_contact_geometry g;
    if (S->dilation && S->tip.kind != TT_TIP_POINT && tt_surface_turn(S->surface, x, y, h) > GEO_KINK)
        g = (tt_contact_geometry){tt_tip_shape_normal_cos(&S->tip, rho), GEO_CORNER_R * R};
    else
        g = tt_surface_contact_geometry(S->surface, x, y, h, R);
    if (g.cos_slope == 1.0 && g.R_eff == R)
        return 0;
    double c = -log(fmax(g.cos_slope, GEO_COS_MIN)), r = log(fmax(g.R_eff / R, GEO_R_MIN));
    long kc = lround(c / GEO_DC), kr = lround(r / GEO_DR);
    return (uint32_t)kc | (uint32_t)(uint16_t)(int16_t)kr << 16;
}

/* The geometry at a key's bin centre: the same law whichever thread builds it. */
tt_contact_geometry tt_scan_geometry_of_key(uint32_t key, double R)
{
    const int kc = (int)(key & 0xffffu), kr = (int16_t)(uint16_t)(key >> 16);
    return (tt_contact_geometry){exp(-kc * GEO_DC), R * exp(kr * GEO_DR)};
}

/* The kept law for (mat, key) among n, or a slot to build it in (the empty or least
 * recently used one, never the law on the sim: it was the last chosen). */
static geo_law *find(geo_law *kept, int n, size_t mat, uint32_t key)
{
    geo_law *old = &kept[0];
    for (int i = 0; i < n; i++) {
        geo_law *e = &kept[i];
        if (e->law && e->mat == mat && e->key == key)
            return e;
        if (e->used < old->used)
            old = e;
    }
    return old;
}

/* Material mat's law for a flat at the key's R_eff (the material's own at R), kept
 * among the last GEO_TABLES used. */
static int flat_at(const tt_scan *S, struct tt_scan_laws *C, size_t mat, uint32_t key,
                   const tt_contact **out)
{
    const uint32_t rkey = key & 0xffff0000u;
    if (rkey == 0) {
        *out = S->contacts[mat];
        return TT_OK;
    }
    geo_law *e = find(C->table, GEO_TABLES, mat, rkey);
    if (!(e->law && e->mat == mat && e->key == rkey)) {
        const tt_contact_geometry g = tt_scan_geometry_of_key(rkey, S->contact_R[mat]);
        tt_contact *law;
        int rc = tt_contact_alloc_local(&law, &S->contact_p[mat], &g);
        if (rc)
            return tt_error(rc, "[material %s] at R_eff %g nm: %s", S->names[mat], g.R_eff * 1e9,
                            tt_error_message());
        tt_contact_free(e->law);
        *e = (geo_law){mat, rkey, 0, law};
        C->tables++;
    }
    e->used = ++C->clock;
    *out = e->law;
    return TT_OK;
}

int tt_scan_geometry_use(const tt_scan *S, worker *W, size_t mat, uint32_t key)
{
    if (key == 0) {
        tt_scan_worker_contact(S, W, mat);
        return TT_OK;
    }
    if (!W->laws && !(W->laws = calloc(1, sizeof *W->laws)))
        return tt_error_nomem("a scan thread's contact laws");
    struct tt_scan_laws *C = W->laws;
    geo_law *e = find(C->law, GEO_KEPT, mat, key);
    if (!(e->law && e->mat == mat && e->key == key)) {
        const tt_contact *flat = NULL;
        tt_contact *law = NULL;
        int rc = flat_at(S, C, mat, key, &flat);
        if (!rc && (rc = tt_contact_alloc_tilted(&law, flat, tt_scan_geometry_of_key(key, 1).cos_slope)))
            tt_error(rc, "[material %s]: %s", S->names[mat], tt_error_message());
        if (rc)
            return rc;
        tt_contact_free(e->law);
        *e = (geo_law){mat, key, 0, law};
        C->built++;
    }
    e->used = ++C->clock;
    tt_sim_set_contact(W->sim, e->law, S->Qi[mat]);
    return TT_OK;
}

long tt_scan_geometry_built(const worker *W, long *tables)
{
    if (tables)
        *tables = W->laws ? W->laws->tables : 0;
    return W->laws ? W->laws->built : 0;
}

void tt_scan_geometry_free(worker *W)
{
    for (int i = 0; W->laws && i < GEO_KEPT; i++)
        tt_contact_free(W->laws->law[i].law);
    for (int i = 0; W->laws && i < GEO_TABLES; i++)
        tt_contact_free(W->laws->table[i].law);
    free(W->laws);
    W->laws = NULL;
}
