/* Fuzz target: the --vary grammar of tiptap sweep (tt_sweep_check_size, tt_sweep_vary).
 *
 * The input is one specification KEY=VALUES per line, as tiptap sweep gets them, over a
 * fixed scene of two materials. Oracles: no sanitizer report; every refusal is one
 * non-empty line; an accepted grid has as many combinations as the product of its
 * keys' values and no more than TT_SWEEP_MAX_COMBINATIONS, finite SI values (NaN only
 * for text), values without control characters, and the first and last combinations'
 * scenes are built or refused in one line (not when whole scene files vary: their
 * names would be read from the disk). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_common.h"
#include "tiptap/config/sweep.h"
#include "tiptap/util/error.h"

enum { MAX_SPECS = 6 };

static const char base_text[] = "[material soft]\nyoungs_modulus = 100 MPa\n"
                                "[material hard]\nyoungs_modulus = 3 GPa\n";

/* Split data into at most MAX_SPECS lines (a NUL ends a line's text, as in argv). */
static size_t split(const uint8_t *data, size_t size, char **specs)
{
    size_t n = 0;
    while (size > 0 && n < MAX_SPECS) {
        const uint8_t *nl = memchr(data, '\n', size);
        size_t len = nl ? (size_t)(nl - data) : size;
        if (!(specs[n] = malloc(len + 1)))
            break;
        memcpy(specs[n], data, len);
        specs[n++][len] = '\0';
        data += nl ? len + 1 : len;
        size -= nl ? len + 1 : len;
    }
    return n;
}

static void check_grid(const tt_sweep *g)
{
    size_t count = 1;
    int files = 0;
    for (size_t k = 0; k < tt_sweep_keys(g); k++) {
        files |= strcmp(tt_sweep_key(g, k), "scene") == 0;
        size_t levels = tt_sweep_levels(g, k);
        if (levels == 0)
            fuzz_fail("key %zu has no values", k);
        count *= levels;
    }
    if (count != tt_sweep_count(g) || count > TT_SWEEP_MAX_COMBINATIONS)
        fuzz_fail("%zu combinations, the keys' product is %zu", tt_sweep_count(g), count);
    size_t ends[2] = {0, count - 1};
    for (int e = 0; e < 2; e++) {
        for (size_t k = 0; k < tt_sweep_keys(g); k++) {
            const char *t = tt_sweep_text(g, ends[e], k);
            double v = tt_sweep_value(g, ends[e], k);
            if (isinf(v) || (isnan(v) && tt_sweep_unit(g, k)[0]))
                fuzz_fail("key %s: value '%s' is %g", tt_sweep_key(g, k), t, v);
            for (const char *p = t; *p; p++)
                if ((unsigned char)*p < 0x20)
                    fuzz_fail("key %s: a control character in a value", tt_sweep_key(g, k));
        }
        char label[512];
        tt_sweep_label(g, ends[e], label, sizeof label);
        tt_scene *s = NULL;
        tt_error_clear();
        if (!files && tt_sweep_scene(g, ends[e], &s) != TT_OK)
            fuzz_check_refusal("combination");
        tt_scene_free(s);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *owned[MAX_SPECS];
    size_t n = split(data, size, owned);
    /* a first key of 1000 values brings the maximum down to 1e4 for the fuzzed ones,
     * so that no run spends seconds storing millions of values */
    const char *specs[MAX_SPECS + 1] = {"cantilever.quality_factor=1:1000:1000"};
    for (size_t i = 0; i < n; i++)
        specs[i + 1] = owned[i];
    tt_error_clear();
    int small = tt_sweep_check_size(specs, n + 1) == TT_OK;
    if (!small)
        fuzz_check_refusal("grid size");
    tt_scene *base = tt_scene_alloc();
    tt_sweep *g = NULL;
    if (!base || tt_scene_load_string(base, base_text, "base.ini") != TT_OK || tt_sweep_alloc(&g, base) != TT_OK)
        fuzz_fail("the fixed scene is refused: %s", tt_error_message());
    for (size_t i = 0; i < n && small; i++) {
        tt_error_clear();
        if (tt_sweep_vary(g, owned[i]) != TT_OK)
            fuzz_check_refusal("--vary");
    }
    if (tt_sweep_keys(g) > 0)
        check_grid(g);
    tt_sweep_free(g);
    tt_scene_free(base);
    for (size_t i = 0; i < n; i++)
        free(owned[i]);
    return 0;
}
