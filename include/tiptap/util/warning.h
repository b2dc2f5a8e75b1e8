/* tiptap: warnings, for results that were computed but may mislead.
 *
 * A result outside the model's validity (a contact radius past 0.5 R), a loop that
 * oscillates, a setpoint not reached, points not settled, an error estimate above the
 * tolerance: the run still returns its numbers, and the library says what to doubt
 * through tt_warn(). Every surface hears the same warnings: the command line prints
 * them, Python raises them with warnings.warn and keeps them on the result.
 *
 * A warning goes to the handler installed on the calling thread by tt_warning_push(),
 * or, where none is, to the default, which prints "tiptap: warning: MESSAGE" on stderr.
 * Warnings raised on other threads (a scan's worker threads) go to the default: raise
 * them on the thread that called the run. The category and message strings belong to
 * the library and live until the handler returns: copy them to keep them.
 */
#ifndef TIPTAP_WARNING_H
#define TIPTAP_WARNING_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

/* Categories: short stable names a caller may sort warnings by. */
#define TT_WARN_VALIDITY "validity"       /* past the force laws' or model's validity */
#define TT_WARN_OSCILLATION "oscillation" /* the feedback loop oscillates */
#define TT_WARN_SETPOINT "setpoint"       /* a setpoint or amplitude not reached */
#define TT_WARN_SETTLE "settle"           /* points not settled, periodic orbits */
#define TT_WARN_ESTIMATE "estimate"       /* the error estimate above the tolerance */
#define TT_WARN_INPUT "input"             /* a scene part given but not used */
#define TT_WARN_RUN "run"                 /* anything else about how the run went */

/* Receives one warning: its category (one of TT_WARN_*) and its one-line message,
 * without "warning:" and without a newline. */
typedef void (*tt_warning_fn)(const char *category, const char *message, void *data);

/* A handler and its data, as tt_warning_push() returns the one it replaced. */
typedef struct {
    tt_warning_fn fn;
    void *data;
} tt_warning_sink;

/* Install fn (with data) for the calling thread and return the handler it replaces, to
 * be given back to tt_warning_pop(). fn NULL restores the default. */
tt_warning_sink tt_warning_push(tt_warning_fn fn, void *data);

/* Reinstall the handler tt_warning_push() returned. */
void tt_warning_pop(tt_warning_sink previous);

/* Raise a warning of a category (printf format for the message). */
void tt_warn(const char *category, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* How many warnings the calling thread has raised since the process started: a caller
 * compares two readings to learn whether a call warned. */
unsigned long tt_warning_count(void);

TT_END_DECLS
#endif
