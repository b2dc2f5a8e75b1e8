/* The run layer's scan internals: the folder's files as jobs (src/run/run_scan.c) and
 * the work after a scan's lines as one parallel loop (src/run/run_scan_after.c). */
#ifndef TIPTAP_RUN_SCAN_PRIVATE_H
#define TIPTAP_RUN_SCAN_PRIVATE_H

#include "tiptap/config/config.h"
#include "tiptap/instrument/scan.h"

/* `tiptap scan -o DIR`'s files (tt_run_scan_write_outputs) as jobs: each channel's GSF
 * and PNG, then scan.gwy, scan.h5 and profile.csv; job j on any thread, each j once
 * (scan.h5 the only HDF5 user); *n counts the files it wrote. */
typedef struct run_folder run_folder;
int run_folder_open(run_folder **F, const tt_scan *scan, const tt_scene *scene, const char *dir,
                    int hdf5);
int run_folder_jobs(const run_folder *F);
int run_folder_job(const run_folder *F, int j, int *n);
void run_folder_free(run_folder *F);

/* What runs once the lines finished, each part optional: the error estimate's companion
 * lines (est, tt_scan_estimate_plan), the caller's own files (nfiles of file: the
 * program's scope.csv and scope.png) and the folder's, as jobs of one loop on threads
 * threads (0: all cores; two at least for two companion lines, as
 * tt_scan_estimate_error runs them), the longest first: the companion lines, then the
 * caller's files, then the folder's. */
typedef struct {
    int threads;
    tt_scan_estimate *est;
    int nfiles;
    int (*file)(void *user, const tt_scan *scan, int j, int *written);
    void *user;
    const tt_scan *scan;
    run_folder *folder;
    double files_end; /* out: the wall clock when the last file was done (the loop's start
                       * without files) */
} run_after;
/* Every job runs, also after one failed: the files written are kept, *written counts
 * them, and the first failure among the folder's files in their order, else among the
 * caller's, is returned with its own thread's message, on any number of threads. The
 * companion lines' statuses stay in est (tt_scan_estimate_finish). */
int run_after_files(run_after *A, int *written);

#endif
