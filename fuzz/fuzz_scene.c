/* Fuzz target: the scene loader with --set lines.
 *
 * The input is scene text, then optionally a line "--set" and one assignment per
 * following line. Oracles: no sanitizer report; every refusal is one non-empty line; an
 * accepted scene's effective scene (tt_scene_write) loads back and writes the same
 * text again. An accepted scene is then built as the commands build it: every
 * configuration reader, the estimates, and the surface (flat, steps, grating and
 * particles only: a rough grid's FFT or a PNG file would slow every run), each refusal
 * one non-empty line too. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_common.h"
#include "tiptap/config/config.h"
#include "tiptap/config/read_trace.h"
#include "tiptap/config/scene.h"
#include "tiptap/util/error.h"

static char *effective(const tt_scene *s)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f || tt_scene_write(s, f, NULL) != TT_OK)
        fuzz_fail("cannot write the effective scene: %s", tt_error_message());
    fclose(f);
    return buf;
}

/* Apply the --set lines in sets[0, n); 0 when all were accepted. */
static int apply_sets(tt_scene *s, const uint8_t *sets, size_t n)
{
    while (n > 0) {
        const uint8_t *nl = memchr(sets, '\n', n);
        size_t len = nl ? (size_t)(nl - sets) : n;
        char *a = malloc(len + 1);
        if (!a)
            return -1;
        memcpy(a, sets, len);
        a[len] = '\0';
        int rc = strlen(a) == len ? tt_scene_set(s, a) : TT_OK; /* argv holds no NUL */
        free(a);
        if (rc) {
            fuzz_check_refusal("--set");
            return rc;
        }
        sets += nl ? len + 1 : len;
        n -= nl ? len + 1 : len;
    }
    return 0;
}

/* rc from a reader: a refusal must be one non-empty line. */
static int checked(int rc, const char *what)
{
    if (rc)
        fuzz_check_refusal(what);
    return rc;
}

static void build_surface(const tt_scene *s, const tt_scan_params *sp)
{
    const tt_surface_params *p = &sp->surface;
    if (p->type == TT_SURFACE_ROUGH || p->type == TT_SURFACE_PNG || p->type == TT_SURFACE_MEASURED ||
        p->map == TT_MAP_PNG ||
        (p->type == TT_SURFACE_PARTICLES && p->particle_count > 2000))
        return;
    tt_surface *S = NULL;
    if (!checked(tt_config_surface_alloc(&S, s, sp->raster.size_x, sp->raster.size_y), "surface")) {
        (void)tt_surface_height(S, 0.5 * sp->raster.size_x, 0.5 * sp->raster.size_y);
        (void)tt_surface_material(S, 0.25 * sp->raster.size_x, 0.75 * sp->raster.size_y);
    }
    tt_surface_free(S);
}

/* Everything the commands build from an accepted scene, without running it. */
static void build_all(const tt_scene *s)
{
    tt_cantilever c;
    tt_tip tip;
    tt_material *m = NULL;
    size_t n = 0;
    tt_raster r;
    tt_approach_params ap;
    tt_trace_params tp;
    tt_estimate e;
    tt_error_clear();
    int have_c = !checked(tt_config_cantilever(s, &c), "cantilever");
    (void)checked(tt_config_tip(s, &tip), "tip");
    if (!checked(tt_config_materials(s, &m, &n), "materials"))
        free(m);
    (void)checked(tt_config_raster(s, &r), "raster");
    tt_solver solver;
    int have_s = !checked(tt_solver_from_scene(&solver, s), "solver");
    if (!checked(tt_config_approach(s, &ap), "approach") && have_c && have_s && ap.speed > 0)
        tt_config_approach_estimate(&c, &solver, &ap, &e);
    if (!checked(tt_config_trace(s, &tp), "trace") && have_c && have_s)
        tt_config_trace_estimate(&c, &solver, &tp, &e);
    tt_scan_params sp;
    if (!checked(tt_config_scan(s, &sp), "scan")) {
        tt_config_scan_estimate(&sp, &e);
        size_t idx[4];
        (void)tt_config_scan_unused(&sp, idx, 4);
        build_surface(s, &sp);
        tt_config_scan_free(&sp);
    }
    tt_accuracy_subject sub;
    if (!checked(tt_config_accuracy(s, &sub), "accuracy"))
        tt_config_accuracy_free(&sub);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t scene_len = size;
    const uint8_t *sets = NULL;
    for (size_t i = 0; i + 6 <= size; i++)
        if ((i == 0 || data[i - 1] == '\n') && memcmp(data + i, "--set\n", 6) == 0) {
            scene_len = i;
            sets = data + i + 6;
            break;
        }
    tt_scene *s = tt_scene_alloc();
    if (!s)
        return 0;
    tt_error_clear();
    int rc = tt_scene_load(s, fuzz_file(data, scene_len));
    if (rc)
        fuzz_check_refusal("scene");
    else if (sets)
        rc = apply_sets(s, sets, size - (size_t)(sets - data));
    if (rc == TT_OK) {
        char *w1 = effective(s);
        tt_scene *r = tt_scene_alloc();
        if (tt_scene_load_string(r, w1, "effective.ini") != TT_OK)
            fuzz_fail("the effective scene does not load back: %s\n%s", tt_error_message(), w1);
        char *w2 = effective(r);
        if (strcmp(w1, w2) != 0)
            fuzz_fail("the effective scene reads back differently:\n%s\n---\n%s", w1, w2);
        free(w1);
        free(w2);
        tt_scene_free(r);
        build_all(s);
    }
    tt_scene_free(s);
    return 0;
}
