/* Warnings through a per-thread handler (see include/tiptap/util/warning.h). */
#include "tiptap/util/warning.h"

#include <stdarg.h>
#include <stdio.h>

/* Per thread, so that a Python thread's run does not hear another's warnings. */
static _Thread_local tt_warning_sink tt_sink;
static _Thread_local unsigned long tt_raised;

tt_warning_sink tt_warning_push(tt_warning_fn fn, void *data)
{
    tt_warning_sink old = tt_sink;
    tt_sink.fn = fn;
    tt_sink.data = fn ? data : NULL;
    return old;
}

void tt_warning_pop(tt_warning_sink previous) { tt_sink = previous; }

unsigned long tt_warning_count(void) { return tt_raised; }

void tt_warn(const char *category, const char *fmt, ...)
{
    char message[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    tt_raised++;
    if (tt_sink.fn)
        tt_sink.fn(category ? category : TT_WARN_RUN, message, tt_sink.data);
    else
        fprintf(stderr, "tiptap: warning: %s\n", message);
}
