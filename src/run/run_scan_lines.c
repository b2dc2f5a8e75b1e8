/* tiptap scan's sequence a line at a time, for the console (tt_run_scan_begin, _step,
 * _end; see include/tiptap/run/run.h): the same checks and warnings as tt_run_scan. */
#include <string.h>

#include "tiptap/run/run.h"

int tt_run_scan_begin(const tt_scene *s, tt_run_scan_lines *r)
{
    memset(r, 0, sizeof *r);
    return tt_run_scan_alloc(s, 1, &r->scan, &r->cost);
}

int tt_run_scan_step(tt_run_scan_lines *r, const tt_scene *s, long line, tt_scan_scope *scope)
{
    /* on the stepping thread, whose handler hears them, not the one that made the scan */
    if (!r->warned) {
        tt_run_scan_warn_inputs(s, &r->cost);
        r->warned = 1;
    }
    int rc = tt_scan_step(r->scan, line, scope);
    r->lines_run += rc == 0;
    return rc;
}

int tt_run_scan_end(tt_run_scan_lines *r, const tt_scan_scope *scope, const char *files)
{
    int n = 0;
    if (r->lines_run > 0) {
        n += tt_run_scan_warn_result(r->scan);
        /* the averaged tier's collapsed pixels are counted per end, as the lines are */
        tt_scan_averaged_marks_clear(r->scan);
    }
    if (scope)
        n += tt_run_scan_warn_oscillation(r->scan, scope, files);
    r->lines_run = 0;
    return n;
}
