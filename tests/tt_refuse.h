/* Bad scan input for tests: the scene base plus text must be refused, by the loader or
 * by tt_scan_alloc, with a message containing fragment. */
#ifndef TT_REFUSE_H
#define TT_REFUSE_H

#include "tiptap/error.h"
#include "tiptap/scan.h"

static inline void tt_expect_scan_refused(const char *base, const char *text, const char *fragment)
{
    tt_scene *sc = tt_scene_alloc();
    assert_int_equal(tt_scene_load_string(sc, base, "base"), TT_OK);
    int rc = tt_scene_load_string(sc, text, "bad.ini");
    tt_scan *s = NULL;
    if (rc == TT_OK)
        rc = tt_scan_alloc(&s, sc);
    if (rc == TT_OK)
        fail_msg("accepted: %s", text);
    if (!strstr(tt_error_message(), fragment))
        fail_msg("'%s' lacks '%s'", tt_error_message(), fragment);
    tt_scene_free(sc);
}

#endif
