/* tiptap: the live console's controls (tiptap live; docs/live.md).
 *
 * The console turns the knobs of an instrument: a few scene keys (setpoint, gains, line
 * rate, scan size and fast axis, pixels, lines, free amplitude, noise seed, tier) and two
 * knobs of its own: the sample (one of the bundled surfaces/NAME.ini) and noise on or off.
 * A knob never sets a typed value directly: the console keeps the scene files it was
 * started with and the values the user gave, and each change builds the whole scene again
 * (files, then the sample, then the console's values as scene text from the origin
 * "console") and runs it through the configuration layer's checks, the same as tiptap
 * scan's. A change that fails them changes nothing and is told in the layer's words
 * ("console: [feedback] integral_gain: ...").
 *
 * A message from the page is text, one command a line:
 *     set feedback.integral_gain = 6 kHz
 *     set sample = grating
 *     set noise = off
 *     restart
 * Its lines are applied together or not at all.
 *
 * Ownership: tt_live_controls_alloc copies the file names, --set texts and folder; the
 * controls own them and the scene they last accepted, freed by tt_live_controls_free.
 * tt_live_controls_scene hands out a new scene each call, which the caller frees.
 */
#ifndef TIPTAP_LIVE_CONTROLS_H
#define TIPTAP_LIVE_CONTROLS_H

#include <stddef.h>

#include "tiptap/config/scene.h"
#include "tiptap/instrument/scan.h"
#include "tiptap/live/lesson.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One knob of the console. */
typedef struct {
    const char *name;  /* in messages: "feedback.integral_gain", "sample", "noise" */
    const char *label; /* on the page */
    const char *unit;  /* the unit the page writes after its number ("" for none) */
    int restarts;      /* 1: a change starts a new frame (the raster or the sample
                        * changed); 0: it applies from the next line on */
    const char *panel; /* NULL: the scan's; "force", "tune": that bench's panel on the page
                        * (the engine takes it as any change: its scene is the one exported) */
} tt_live_control;

/* The console's knobs, in the page's order. */
const tt_live_control *tt_live_control_table(size_t *count);

typedef struct tt_live_controls tt_live_controls;

/* files: the scene files (at least one), sets: "section.key=value" as --set; surfaces:
 * the folder of the bundled samples; memory: the bytes the process may still take (the
 * program's: /proc/meminfo's MemAvailable and its limits), asked at each check; NULL:
 * no memory check. Checks the scene as a change would: TT_EINVAL with the layer's
 * message when it fails. A scene whose scans, images and scope records (one point a
 * lock-in block) the console could not hold in that memory is refused, naming
 * [scan] line_rate or pixels. */
int tt_live_controls_alloc(tt_live_controls **out, char *const *files, int nfiles,
                           char *const *sets, int nsets, const char *surfaces,
                           double (*memory)(void));
void tt_live_controls_free(tt_live_controls *c);
/* Another set of controls at c's values, for another instrument (a page of its own): its
 * files, values and scene copied, its lesson c's (borrowed: free the copy before c). */
int tt_live_controls_copy(tt_live_controls **out, const tt_live_controls *c);

/* The same with a lesson (live/lesson.h; taken, freed with the controls, NULL: none): its
 * scene files come before files, its own sections after them and before sets; a change
 * to a control it locks or hides is refused. */
int tt_live_controls_alloc_lesson(tt_live_controls **out, tt_live_lesson *lesson, char *const *files,
                                  int nfiles, char *const *sets, int nsets, const char *surfaces,
                                  double (*memory)(void));
/* The lesson (NULL: none). */
const tt_live_lesson *tt_live_controls_lesson(const tt_live_controls *c);

/* The outcome of a message. */
typedef struct {
    int restart;   /* 1: the frame starts again (a knob that restarts, or "restart") */
    int changed;   /* 1: the scene changed */
    char why[512]; /* a refusal: one line ("" when accepted) */
} tt_live_change;

/* Takes a checked change: the scene and its parameters (both handed over, whatever it
 * returns) and whether it starts a new frame. TT_OK when the change took effect; else
 * the error (tt_error) is the refusal. */
typedef int (*tt_live_take_fn)(void *user, tt_scene *scene, tt_scan_params *p, int restart);

/* Apply a message (text, len bytes, not necessarily NUL-ended, UTF-8): every line or
 * none, at once: once the message passed every check it goes to take (NULL: none), and
 * the controls show it only when take took it. TT_OK, or TT_EINVAL with ch->why set (one
 * line, UTF-8) and the controls as they were. */
int tt_live_controls_apply(tt_live_controls *c, const char *text, size_t len,
                           tt_live_change *ch, tt_live_take_fn take, void *user);

/* The accepted scene, built anew (the caller frees it), and its scan parameters when p
 * is not NULL (free them with tt_config_scan_free). */
int tt_live_controls_scene(const tt_live_controls *c, tt_scene **scene, tt_scan_params *p);

/* The current value of knob i as the page shows it: the text the user gave, else the
 * scene's value in the knob's unit ("3000" Hz for a gain given as "3 kHz"); the
 * sample's name; "on" or "off". */
const char *tt_live_controls_value(const tt_live_controls *c, size_t i, char *buf, size_t len);

/* The bench panel knob i belongs to (NULL: the scan's), and whether the lesson hides
 * every knob of panel (then the page does not show it and the server refuses its run). */
const char *tt_live_control_panel(size_t i);
int tt_live_controls_panel_hidden(const tt_live_controls *c, const char *panel);

/* The bundled samples (surfaces/NAME.ini without the extension), sorted; and which one
 * the scene uses (-1: none of them). */
size_t tt_live_controls_samples(const tt_live_controls *c);
const char *tt_live_controls_sample(const tt_live_controls *c, size_t i);
int tt_live_controls_sample_index(const tt_live_controls *c);

#ifdef __cplusplus
}
#endif
#endif
