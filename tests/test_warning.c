/* Warnings (util/warning.h): a thread's handler hears its own thread's warnings with
 * their category, a pushed handler is undone by pop, and other threads keep theirs. */
#include "tt_test.h"
#include "tiptap/util/warning.h"

#include <pthread.h>

typedef struct {
    int n;
    char category[32];
    char message[256];
} heard;

static void hear(const char *category, const char *message, void *data)
{
    heard *h = data;
    h->n++;
    snprintf(h->category, sizeof h->category, "%s", category);
    snprintf(h->message, sizeof h->message, "%s", message);
}

static void handler_hears_category_and_message(void **st)
{
    (void)st;
    heard h = {0};
    unsigned long before = tt_warning_count();
    tt_warning_sink old = tt_warning_push(hear, &h);
    tt_warn(TT_WARN_VALIDITY, "contact radius %.2f R", 0.73);
    assert_int_equal(h.n, 1);
    assert_string_equal(h.category, "validity");
    assert_string_equal(h.message, "contact radius 0.73 R");
    assert_true(tt_warning_count() == before + 1);
    tt_warning_pop(old);
}

static void pop_restores_the_outer_handler(void **st)
{
    (void)st;
    heard outer = {0}, inner = {0};
    tt_warning_sink o = tt_warning_push(hear, &outer);
    tt_warning_sink i = tt_warning_push(hear, &inner);
    tt_warn(TT_WARN_SETTLE, "inner");
    tt_warning_pop(i);
    tt_warn(TT_WARN_SETTLE, "outer");
    tt_warning_pop(o);
    assert_int_equal(inner.n, 1);
    assert_int_equal(outer.n, 1);
    assert_string_equal(inner.message, "inner");
    assert_string_equal(outer.message, "outer");
}

static void *other_thread(void *arg)
{
    heard *h = arg;
    tt_warning_sink old = tt_warning_push(hear, h);
    tt_warn(TT_WARN_RUN, "from the other thread");
    tt_warning_pop(old);
    return NULL;
}

static void threads_hear_their_own(void **st)
{
    (void)st;
    heard mine = {0}, theirs = {0};
    tt_warning_sink old = tt_warning_push(hear, &mine);
    pthread_t t;
    assert_int_equal(pthread_create(&t, NULL, other_thread, &theirs), 0);
    pthread_join(t, NULL);
    assert_int_equal(mine.n, 0);
    assert_int_equal(theirs.n, 1);
    assert_string_equal(theirs.message, "from the other thread");
    tt_warning_pop(old);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(handler_hears_category_and_message),
        cmocka_unit_test(pop_restores_the_outer_handler),
        cmocka_unit_test(threads_hear_their_own),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
