/* Approaches for tests: run a scene's [approach] on its first material. */
#ifndef TT_APPROACH_TEST_H
#define TT_APPROACH_TEST_H

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/setup.h"
#include "tiptap/instrument/approach.h"
#include "tiptap/util/error.h"

/* Every row of the scene's approach into pt (at most cap; more fails the test), a failing
 * row failing it with its message. *alloc_rc: what tt_approach_alloc said (no rows then
 * unless TT_OK); *params: the approach's parameters, when given. The scene stays the
 * caller's. */
static inline size_t tt_run_approach(tt_scene *s, tt_approach_point *pt, size_t cap,
                                     int *alloc_rc, tt_approach_params *params)
{
    tt_setup *su;
    assert_int_equal(tt_setup_alloc(&su, s), TT_OK);
    assert_int_equal(tt_setup_use_material(su, 0), TT_OK);
    tt_approach_params p;
    assert_int_equal(tt_config_approach(s, &p), TT_OK);
    if (params)
        *params = p;
    tt_approach *a = NULL;
    size_t n = 0;
    *alloc_rc = tt_approach_alloc(&a, tt_setup_sim(su), &p);
    while (a && !tt_approach_done(a)) {
        assert_true(n < cap);
        if (tt_approach_iterate(a, &pt[n]) != TT_OK)
            fail_msg("%s", tt_error_message());
        n++;
    }
    tt_approach_free(a);
    tt_setup_free(su);
    return n;
}

#endif
