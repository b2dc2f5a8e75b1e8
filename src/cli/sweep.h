/* tiptap sweep: one combination's run, the results journal, and their spread over
 * threads (sweep_run.c) and MPI ranks (sweep_mpi.c, only in builds with TT_MPI).
 *
 * Each combination is computed from its own fresh scene, setup and simulation into a
 * block of CSV text, so that the table depends on nothing but the combination: the same
 * bytes for any number of threads or ranks, and for a run resumed from its journal.
 *
 * Ownership: a sweep_results owns the texts it was given (sweep_results_free) and its
 * journal file; a sweep_job borrows the grid. */
#ifndef TIPTAP_CLI_SWEEP_H
#define TIPTAP_CLI_SWEEP_H

#include <stddef.h>
#include <stdio.h>

#include "tiptap/config/sweep.h"
#include "tiptap/run/sweep.h"

typedef struct {
    const tt_sweep *grid;
    tt_sweep_kind kind;
    const char *dir;  /* scan: the folder holding one folder per combination */
    int scan_threads; /* scan: threads of each scan's lines */
    int hdf5;         /* scan: each combination's folder also gets scan.h5 */
} sweep_job;

/* The CSV header of a job's table (static storage reused per call; ends with \n). */
void sweep_header(const sweep_job *job, char *buf, size_t len);

/* Check combination i before anything runs: its scene and every configuration the run
 * reads. One line naming the combination on failure. */
int sweep_check(const sweep_job *job, size_t i);

/* Compute combination i into *text (malloc'd rows ending with \n). A combination whose
 * solver fails gives a row saying so, not an error: the sweep goes on. TT_EINTR when
 * cancelled part way; TT_ENOMEM. */
int sweep_compute(const sweep_job *job, size_t i, char **text);

typedef struct {
    size_t n;         /* combinations */
    char **text;      /* finished ones, NULL otherwise */
    size_t done;
    FILE *journal;    /* OUT.partial, appended as combinations finish */
    char *journal_path;
    size_t resumed;   /* done when the journal was opened (a resumed sweep) */
} sweep_results;

/* The finished combinations' rows read back from their CSV texts into one table of
 * the library's columns (tt_run_sweep_columns), in SI, at the CSV's precision: for
 * sweep --hdf5, whose journal holds the texts of a resumed sweep's combinations. */
int sweep_table(const sweep_job *job, const sweep_results *r, tt_table **out);

struct cli_progress;
/* Show r's progress (the combinations this run computes) on p; NULL: none. */
void sweep_progress(struct cli_progress *p, const sweep_results *r);

/* Open (or resume) the journal OUT.partial of a sweep with fingerprint hash: its
 * finished combinations are loaded into r and not run again. */
int sweep_results_open(sweep_results *r, size_t n, const char *out, unsigned long long hash);
/* Keep combination i's text (taking it) and append it to the journal. */
int sweep_results_record(sweep_results *r, size_t i, char *text);
/* Write header and every text in order to out; the journal is removed. */
int sweep_results_write(sweep_results *r, const char *out, const char *header);
/* Close the journal (kept when the sweep did not finish) and free the texts. */
void sweep_results_free(sweep_results *r);

/* Compute the combinations not yet in r on threads threads (dynamic load balance),
 * recording each as it finishes; progress on stderr when shown. Stops at cancellation
 * with TT_EINTR. */
int sweep_run_threads(const sweep_job *job, sweep_results *r, int threads,
                      struct cli_progress *progress);

/* The loop under both: compute the combinations todo[0..m) on threads threads
 * (dynamic, one at a time), handing each finished text to deliver (which takes it) one
 * at a time. Stops at the first error or at cancellation (TT_EINTR). */
int sweep_run_list(const sweep_job *job, const size_t *todo, size_t m, int threads,
                   int (*deliver)(void *user, size_t i, char *text), void *user);

/* Whether sweep_plot can draw job's table (not a scan's; points need a key to plot
 * against besides the contrast key), before anything runs. */
int sweep_plot_check(const sweep_job *job, long contrast);
/* A PNG of the finished table: against the last varied key other than contrast (an
 * index, -1 for none), or against z for approach curves. */
int sweep_plot(const sweep_job *job, const sweep_results *r, const char *path, long contrast);

#ifdef TT_HAVE_MPI
/* Whether this process was started by mpirun with more than one rank; then MPI is
 * initialised and rank and size set. */
int sweep_mpi_start(int *rank, int *size);
/* The combinations not in r spread over the ranks (cyclic), threads threads each;
 * rank 0 receives and records every result. r must be the same on every rank (rank 0
 * sends its finished flags to the others first). */
int sweep_mpi_run(const sweep_job *job, sweep_results *r, int threads, struct cli_progress *progress);
/* All ranks agree on rc (the worst); broadcast from rank 0. */
int sweep_mpi_agree(int rc);
void sweep_mpi_stop(void);
#endif

#endif
