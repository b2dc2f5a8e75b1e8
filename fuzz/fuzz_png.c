/* Fuzz target: the PNG map reader, as a height map and as a material map.
 *
 * The input is the PNG file. Oracles: no sanitizer report; every refusal is one
 * non-empty line; an accepted map answers heights and materials inside its range. */
#include <math.h>
#include <stdio.h>

#include "fuzz_common.h"
#include "tiptap/config/config.h"
#include "tiptap/config/scene.h"
#include "tiptap/instrument/surface.h"
#include "tiptap/util/error.h"

static void one_map(const char *path, int material)
{
    char text[512];
    if (material)
        snprintf(text, sizeof text,
                 "[material a]\nmap_value = 0\n[material b]\nmap_value = 128\n"
                 "[material c]\nmap_value = #ff0000\n[surface]\nmap = png\nmap_png = %s\n", path);
    else
        snprintf(text, sizeof text, "[surface]\ntype = png\npng = %s\npng_height_range = 10 nm\n",
                 path);
    tt_scene *s = tt_scene_alloc();
    if (!s)
        return;
    if (tt_scene_load_string(s, text, "fuzz.ini") != TT_OK)
        fuzz_fail("the fixed scene is refused: %s", tt_error_message());
    tt_surface *S = NULL;
    tt_error_clear();
    if (tt_config_surface_alloc(&S, s, 1e-6, 1e-6) != TT_OK) {
        fuzz_check_refusal(material ? "material map" : "height map");
    } else {
        for (int k = 0; k < 5; k++) {
            double x = (0.1 + 0.2 * k) * 1e-6, y = (0.9 - 0.2 * k) * 1e-6;
            double h = tt_surface_height(S, x, y);
            int m = tt_surface_material(S, x, y);
            if (!(h >= 0 && h <= 10e-9))
                fuzz_fail("height %g outside [0, 10 nm]", h);
            if (m < 0 || m > 2)
                fuzz_fail("material %d of 3", m);
        }
        tt_surface_free(S);
    }
    tt_scene_free(s);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fuzz_file(data, size);
    one_map(path, 0);
    one_map(path, 1);
    return 0;
}
