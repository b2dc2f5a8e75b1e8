/* Status codes and the per-thread error message (see include/tiptap/util/error.h). */
#include "tiptap/util/error.h"

#include <stdarg.h>
#include <stdio.h>

/* One message per thread, so that OpenMP scan lines cannot garble each other's. */
static _Thread_local char tt_message[1024];

const char *tt_strerror(int status)
{
    switch (status) {
    case TT_OK: return "success";
    case TT_EINVAL: return "invalid input";
    case TT_ENOMEM: return "out of memory";
    case TT_EIO: return "input/output error";
    case TT_ENUM: return "numerical failure";
    case TT_EINTR: return "interrupted";
    case TT_ECAPTURE: return "tip captured";
    default: return "unknown error";
    }
}

const char *tt_error_message(void) { return tt_message; }

void tt_error_clear(void) { tt_message[0] = '\0'; }

int tt_error(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(tt_message, sizeof tt_message, fmt, ap);
    va_end(ap);
    return status;
}

int tt_error_nomem(const char *fmt, ...)
{
    char what[768];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return tt_error(TT_ENOMEM, "out of memory for %s", what);
}
