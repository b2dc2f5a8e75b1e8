/* The work after a scan's lines as one parallel loop (see src/run/run_scan_private.h):
 * the estimate's companion lines beside the files, so that neither waits for the other
 * (the noisy blend's two companion lines 0.09 s, its scope.png 0.14 s on one thread,
 * the channels' files 0.2 s on two, run one after the other before). */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "tiptap/util/clock.h"
#include "tiptap/util/error.h"

#include "run_scan_private.h"

/* Job j of A's loop: its file (a companion line's status stays in the plan). */
static int after_job(run_after *A, int ne, int j, int *n)
{
    if (j < ne)
        return tt_scan_estimate_job(A->est, j), TT_OK;
    j -= ne;
    return j < A->nfiles ? A->file(A->user, A->scan, j, n) : run_folder_job(A->folder, j - A->nfiles, n);
}

int run_after_files(run_after *A, int *written)
{
    const int ne = A->est ? tt_scan_estimate_jobs(A->est) : 0;
    const int nf = A->folder ? run_folder_jobs(A->folder) : 0;
    const int n = ne + A->nfiles + nf;
    int *jrc = calloc((size_t)n + 1, sizeof *jrc), *jn = calloc((size_t)n + 1, sizeof *jn);
    double *end = calloc((size_t)n + 1, sizeof *end);
    char(*msg)[1024] = calloc((size_t)n + 1, sizeof *msg);
    int rc = jrc && jn && end && msg ? TT_OK : tt_error_nomem("the scan's files");
    int threads = A->threads > 0 ? A->threads : omp_get_max_threads();
    if (ne > 1 && threads < 2)
        threads = 2;
    const int jobs = rc == TT_OK ? n : 0;
    A->files_end = tt_clock(TT_CLOCK_WALL);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (int j = 0; j < jobs; j++) {
        if ((jrc[j] = after_job(A, ne, j, &jn[j])))
            snprintf(msg[j], sizeof msg[j], "%s", tt_error_message()); /* the thread's own */
        end[j] = tt_clock(TT_CLOCK_WALL);
    }
    for (int j = ne; j < jobs; j++) {
        *written += jn[j];
        if (end[j] > A->files_end)
            A->files_end = end[j];
    }
    /* the folder's files first, in their order, then the caller's */
    for (int k = 0; k < A->nfiles + nf && rc == TT_OK; k++) {
        const int j = ne + (k < nf ? A->nfiles + k : k - nf);
        if (j < jobs && jrc[j])
            rc = tt_error(jrc[j], "%s", msg[j]);
    }
    free(jrc);
    free(jn);
    free(end);
    free(msg);
    return rc;
}
