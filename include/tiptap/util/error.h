/* tiptap: status codes and error messages.
 *
 * Every library call that can fail returns an int status (TT_OK on success).
 * On failure it also leaves a one-line message for the calling thread, which
 * tt_error_message() returns; the message names the file, the section and the key
 * where that is known ("scene.ini: [cantilever] spring_constant: ...").
 * The message buffer belongs to the library; copy it if you need it after the
 * next library call on the same thread.
 */
#ifndef TIPTAP_ERROR_H
#define TIPTAP_ERROR_H

#include "tiptap/export.h"

TT_BEGIN_DECLS

enum {
    TT_OK = 0,
    TT_EINVAL = 1,  /* bad input: a scene key, a value, an argument */
    TT_ENOMEM = 2,  /* allocation failed */
    TT_EIO = 3,     /* a file could not be read or written */
    TT_ENUM = 4,    /* numerical failure: no convergence, NaN, step too large */
    TT_EINTR = 5,   /* interrupted by the user; finished work was kept */
    TT_ECAPTURE = 6 /* the run ended in a state the caller asked to treat as an error */
};

/* A short fixed description of a status code. */
const char *tt_strerror(int status);

/* The message of the last failure on this thread ("" if none). */
const char *tt_error_message(void);

/* Set this thread's message (printf format) and return status, so that
 * "return tt_error(TT_EINVAL, "...", ...);" reports and fails in one line. */
int tt_error(int status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* An allocation failed: TT_ENOMEM with "out of memory for WHAT", WHAT (printf format)
 * naming what was being allocated and, where one applies, the file, section or key it
 * was for ("the scan's images, 16384 x 16384 pixels"; "[material glass]'s force law").
 * Every allocation failure reports through it, so that none says only "out of memory". */
int tt_error_nomem(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Clear this thread's message. */
void tt_error_clear(void);

TT_END_DECLS
#endif
