/* tiptap: a lesson for the live console (tiptap live --lesson FILE; docs/live.md,
 * "Lessons").
 *
 * A lesson file is a scene file with a [lesson] section the console reads and takes out
 * before the configuration layer sees the rest (its lines left blank, so that the
 * layer's line numbers stay the file's):
 *     [lesson]
 *     title = Tuning the I gain
 *     instructions = Raise the I gain until the scope rings,
 *         then take the suggestion.     (an indented line continues the value)
 *     scene = ../scans/standard.ini ../surfaces/grating.ini   (relative to the file)
 *     hide = noise, tier                (controls not shown)
 *     lock = scan_size, pixels          (shown, not changeable: the server refuses)
 * A control is named as in the console's messages (scan.size), with _ for the dot
 * (scan_size), or by its key alone where that is one control's (size, tier).
 *
 * Ownership: tt_live_lesson_load allocates; tt_live_lesson_free frees it all.
 */
#ifndef TIPTAP_LIVE_LESSON_H
#define TIPTAP_LIVE_LESSON_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    char *path;         /* the file */
    char *title;        /* required */
    char *instructions; /* "" where none; lines joined by newlines */
    char *scene_text;   /* the file's text with the [lesson] lines blank */
    int has_scene_text; /* the file has sections of its own besides [lesson] */
    char **files;       /* scene = files, resolved against the file's folder */
    int nfiles;
    unsigned long hide, lock; /* bit i: control i of tt_live_control_table */
} tt_live_lesson;

/* Read and check a lesson file: TT_EINVAL (or TT_EIO) with one line naming the file, its
 * line and key, and what is expected. */
int tt_live_lesson_load(tt_live_lesson **out, const char *path);
void tt_live_lesson_free(tt_live_lesson *l);

/* 1 when the file at path has a line "[lesson]" (a scene argument that is a lesson). */
int tt_live_lesson_is_one(const char *path);

/* The [lesson] section of l (NULL: a new lesson titled from nothing) as text, for a saved
 * lesson: title, instructions, hide and lock (not scene: the saved scene follows it). */
int tt_live_lesson_write(const tt_live_lesson *l, FILE *out);

#ifdef __cplusplus
}
#endif
#endif
