/* tiptap sweep: steady points, setpoint points, approach curves or scans over a grid
 * of scene keys, on every core and (in builds with MPI) over MPI ranks. */
#include <getopt.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "sweep.h"
#include "tiptap/io/outfile.h"
#include "tiptap/io/plot.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/version.h"

static void help(void)
{
    printf("Usage: tiptap sweep SCENE... --vary KEY=VALUES [--vary ...] [--run KIND] [-o sweep.csv]\n"
           "                     [-j N] [--plot FILE] [--contrast KEY] [--hdf5] [--set S.K=V]... [-q]\n"
           "Run every combination of the varied keys and write one table.\n\n"
           "      --vary KEY=VALUES  vary a scene key (section.key, material.NAME.key) over\n"
           "                     a list '10 nm,20 nm', a range FROM:TO:N '10nm:30nm:5' (N values,\n"
           "                     ends included) or 'log:FROM:TO:N'; several make a grid, the first\n"
           "                     varying slowest, of at most 10000000 combinations\n"
           "      --run KIND     steady: the steady oscillation at [approach] from (default);\n"
           "                     setpoint: the steady point whose amplitude is [feedback] setpoint\n"
           "                     (a secant search over the rest separation); approach: the\n"
           "                     [approach] curve; scan: a scan into one folder per combination\n"
           "  -o, --output FILE  CSV, one row per point (per material for scans): combination,\n"
           "                     the varied keys in SI units (unit in brackets), then z_nm,\n"
           "                     amplitude_nm, phase_deg, mean_deflection_nm, peak_force_nN,\n"
           "                     max_indentation_nm, contact_fraction, dissipated_aJ, drive_work_aJ,\n"
           "                     energy_residual (the energy balance: a check), regime (free, attractive:\n"
           "                     phase lag above 90 deg, repulsive), direction, settled, cycles,\n"
           "                     found (newton or settled; unreachable: a setpoint not reached,\n"
           "                     the row holds the closest point); with a viscous material or\n"
           "                     a varied viscosity or film_thickness also dissipated_hysteresis_aJ,\n"
           "                     dissipated_damping_aJ, dissipated_viscous_aJ; with mode 2 driven\n"
           "                     ([cantilever] mode2_free_amplitude) also amplitude_2_nm,\n"
           "                     phase_2_deg (mode 2's lock-in). Scans: folder, lines_done,\n"
           "                     energy_balance (a check, not the error), error_estimate_height_nm\n"
           "                     and error_estimate_phase_deg (the largest, as tiptap scan's), material,\n"
           "                     pixels, height and phase mean and\n"
           "                     standard deviation, and their contrast to the first material;\n"
           "                     bimodal scenes ([cantilever] mode2_free_amplitude) also\n"
           "                     amplitude_2_mean_nm, phase_2_mean_deg, phase_2_std_deg,\n"
           "                     phase_2_contrast_deg (mode 2's lock-in, when [scan] channels has them).\n"
           "                     Scan folders go under FILE without its extension (FILE.d\n"
           "                     if it has none).\n"
           "  -j, --threads N    combinations computed in parallel (default: all cores); a scan\n"
           "                     runs one combination at a time on N threads instead\n"
           "      --plot FILE    PNG against the last varied key (approach: against z), one line\n"
           "                     per combination of the others\n"
           "      --hdf5         also FILE with .h5 for its extension: each column a dataset over\n"
           "                     the grid, the varied keys' values as dimension scales, the base\n"
           "                     scene as attributes (docs/hdf5.md); scans also write scan.h5\n"
           "                     into each combination's folder\n"
           "      --contrast KEY plot the differences to KEY's first value instead: apparent\n"
           "                     height (with --run setpoint: this value's rest separation minus\n"
           "                     the first's: the feedback retracts the sample where the setpoint\n"
           "                     needs a larger gap), phase and dissipation\n"
           CLI_HELP_SET
           "  -q, --quiet        no progress or summary on stderr\n\n"
           "Every combination is checked before the first runs. Finished combinations are\n"
           "kept in FILE.partial as they finish; a stopped sweep run again with the same\n"
           "command resumes there and ends with the same table. The table is the same,\n"
           "byte for byte, for any -j and, under 'mpirun -np N tiptap sweep ...' in builds\n"
           "with MPI, for any number of ranks (rank 0 writes it).\n");
}

/* The index of a varied key, or -1. */
static long find_key(const tt_sweep *g, const char *key)
{
    for (size_t k = 0; key && k < tt_sweep_keys(g); k++)
        if (strcmp(tt_sweep_key(g, k), key) == 0)
            return (long)k;
    return -1;
}

#ifndef TT_HAVE_MPI
/* Ranks under mpirun: Open MPI, MPICH and PMIx all say how many. */
static long launched_ranks(void)
{
    static const char *vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"};
    for (size_t i = 0; i < sizeof vars / sizeof vars[0]; i++)
        if (getenv(vars[i]))
            return strtol(getenv(vars[i]), NULL, 10);
    return 1;
}
#endif

/* What a journal must match: the program's version (another may compute other rows),
 * the run, the header, the grid and the whole base scene. */
static unsigned long long fingerprint(const tt_scene *scene, const sweep_job *job, const char *header)
{
    unsigned long long h = 1469598103934665603ULL;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (f) {
        fprintf(f, "tiptap %s\nrun %d\n%s", TIPTAP_VERSION_STRING, (int)job->kind, header);
        tt_scene_write(scene, f, NULL);
        fclose(f);
    }
    for (size_t i = 0; buf && i < len; i++)
        h = (h ^ (unsigned char)buf[i]) * 1099511628211ULL;
    free(buf);
    return tt_sweep_hash(job->grid, h);
}

/* The grid from the --vary list, every combination checked, before anything runs. */
static int build_grid(tt_scene *scene, char **vary, int nvary, sweep_job *job, const char *contrast)
{
    /* an astronomical grid is refused from its --vary forms alone, before any value */
    int rc = tt_sweep_check_size((const char *const *)vary, (size_t)nvary);
    if (rc)
        return rc;
    tt_sweep *g = NULL;
    rc = tt_sweep_alloc(&g, scene);
    for (int i = 0; i < nvary && !rc; i++)
        rc = tt_sweep_vary(g, vary[i]);
    job->grid = g;
    if (!rc && contrast && find_key(g, contrast) < 0)
        rc = tt_error(TT_EINVAL, "--contrast %s: not a varied key", contrast);
    for (size_t i = 0; i < tt_sweep_count(g) && !rc; i++)
        rc = sweep_check(job, i);
    return rc;
}

/* A file the sweep writes at its end, checked before the first combination runs: a
 * file can be made beside it (made and removed again). */
static int check_output(const char *path)
{
    tt_outfile *of;
    int rc = tt_outfile_open(&of, path);
    return rc ? rc : tt_outfile_close(of, 0);
}

/* Every path the sweep writes, before anything runs: the table, the plot (and whether
 * it can be drawn at all), and a scan's folder of combination folders. */
static int check_outputs(const sweep_job *job, const cli_args *a, long contrast, const char *h5)
{
    int rc = check_output(a->output);
    if (!rc && a->plot && !(rc = sweep_plot_check(job, contrast)))
        rc = check_output(a->plot);
    if (!rc && h5)
        rc = check_output(h5);
    if (!rc && job->kind == TT_SWEEP_SCAN)
        rc = tt_mkdirs(job->dir);
    return rc;
}

/* Which setpoint rows say found=unreachable (tt_run_warn_unreached), so that no one takes
 * them for points at the setpoint (with -q too: it is about the table, not progress). */
static void warn_unreached(const sweep_job *job, const sweep_results *r)
{
    tt_table *t;
    if (sweep_table(job, r, &t) == TT_OK)
        tt_run_warn_unreached(t);
    tt_table_free(t);
}

/* The sweep's table as FILE.h5 (docs/hdf5.md), read back from the texts of its
 * combinations, resumed ones included. */
static int write_hdf5(const char *path, const sweep_job *job, const sweep_results *r,
                      const tt_scene *scene)
{
    tt_table *t;
    int rc = sweep_table(job, r, &t);
    if (!rc)
        rc = tt_run_sweep_hdf5(path, job->grid, job->kind, scene, t);
    tt_table_free(t);
    return rc;
}

/* The names the sweep derives from its table's, out: the folder of a scan sweep's
 * combinations (the name without its extension, else with .d) and FILE.h5 (the
 * extension replaced by .h5). */
static void sweep_names(const char *out, char dir[4096], char h5[4100])
{
    snprintf(dir, 4096, "%s", out);
    char *dot = strrchr(dir, '.');
    if (dot && !strchr(dot, '/') && dot != dir)
        *dot = '\0';
    else /* no extension: the folder cannot take the table's own name */
        strncat(dir, ".d", 4096 - strlen(dir) - 1);
    snprintf(h5, 4100, "%s", out);
    dot = strrchr(h5, '.');
    if (dot && !strchr(dot, '/') && dot != h5)
        *dot = '\0';
    strncat(h5, ".h5", 4100 - strlen(h5) - 1);
}

static int sweep_main(tt_scene *scene, char **vary, int nvary, tt_sweep_kind kind, const cli_args *a,
                      int threads, const char *contrast, int hdf5)
{
    int rank = 0, size = 1, mpi = 0, rc;
#ifdef TT_HAVE_MPI
    mpi = sweep_mpi_start(&rank, &size);
#else
    if (launched_ranks() > 1) {
        fprintf(stderr, "tiptap sweep: started by mpirun, but this tiptap was built without MPI "
                        "(cmake -DTT_MPI=ON with Open MPI installed)\n");
        return CLI_FAIL;
    }
#endif
    char dir[4096], header[8192], h5[4100];
    sweep_names(a->output, dir, h5);
    if (!threads)
        threads = omp_get_max_threads();
    sweep_job job = {NULL, kind, dir, threads, hdf5};
    double t0 = cli_now();
    sweep_results r = {0};
    rc = build_grid(scene, vary, nvary, &job, contrast);
    header[0] = '\0';
    if (job.grid)
        sweep_header(&job, header, sizeof header);
    size_t n = job.grid ? tt_sweep_count(job.grid) : 0;
    cli_progress prog;
    cli_progress_begin(&prog, "sweep", "combinations", a->quiet || rank != 0);
    cli_progress *progress = &prog;
    cli_catch_interrupt(); /* from the journal on a signal keeps the combinations finished */
    if (!rc && rank == 0)
        rc = check_outputs(&job, a, find_key(job.grid, contrast), hdf5 ? h5 : NULL);
    if (!rc && rank == 0)
        rc = sweep_results_open(&r, n, a->output, fingerprint(scene, &job, header));
    else if (!rc && !(r.text = calloc(n, sizeof *r.text)))
        rc = tt_error(TT_ENOMEM, "out of memory");
    r.n = n;
    size_t resumed = r.done;
    if (!rc && !a->quiet && rank == 0 && resumed)
        fprintf(stderr, "sweep: resuming %s: %zu of %zu combinations already done\n", r.journal_path,
                resumed, n);
#ifdef TT_HAVE_MPI
    if (mpi)
        rc = sweep_mpi_agree(rc);
    if (!rc)
        rc = mpi ? sweep_mpi_run(&job, &r, kind == TT_SWEEP_SCAN ? 1 : threads, progress)
                 : sweep_run_threads(&job, &r, kind == TT_SWEEP_SCAN ? 1 : threads, progress);
#else
    if (!rc)
        rc = sweep_run_threads(&job, &r, kind == TT_SWEEP_SCAN ? 1 : threads, progress);
#endif
    cli_progress_end(&prog);
    if (rank == 0 && rc == TT_EINTR)
        rc = tt_error(TT_EINTR, "interrupted: %zu of %zu combinations kept in %s; the same command "
                                "resumes there", r.done, n, r.journal_path);
    if (rank == 0 && !rc)
        rc = sweep_results_write(&r, a->output, header);
    if (rank == 0 && !rc && hdf5)
        rc = write_hdf5(h5, &job, &r, scene);
    if (rank == 0 && !rc && a->plot)
        rc = sweep_plot(&job, &r, a->plot, find_key(job.grid, contrast));
    if (rank == 0 && !rc && kind == TT_SWEEP_SETPOINT)
        warn_unreached(&job, &r);
    if (rank == 0 && !rc && kind != TT_SWEEP_SCAN) {
        tt_table *t = NULL; /* the library's warnings of periodic and unsettled points */
        if (sweep_table(&job, &r, &t) == TT_OK)
            tt_run_sweep_warn(t);
        tt_table_free(t);
    }
    double wall = cli_now() - t0;
    if (rank == 0 && !rc && !a->quiet)
        fprintf(stderr, "combinations = %zu (%zu resumed)\nranks = %d\nthreads = %d\nrun_time_s = %.3f\n"
                        "combinations_per_s = %.4g\n", n, resumed, size, threads, wall,
                wall > 0 ? (double)(n - resumed) / wall : 0.0);
    if (rc && rank == 0)
        cli_fail(rc, NULL);
    sweep_results_free(&r);
    tt_sweep_free((tt_sweep *)job.grid);
#ifdef TT_HAVE_MPI
    if (mpi)
        sweep_mpi_stop();
#endif
    (void)size;
    (void)mpi;
    return rc == TT_OK ? CLI_OK : rc == TT_EINTR ? CLI_INTERRUPTED : CLI_FAIL;
}

int cmd_sweep(int argc, char **argv)
{
    static const struct option opts[] = {{"vary", required_argument, NULL, 'V'},
                                         {"run", required_argument, NULL, 'R'},
                                         {"threads", required_argument, NULL, 'j'},
                                         {"contrast", required_argument, NULL, 'C'},
                                         {"hdf5", no_argument, NULL, 'H'},
                                         {NULL, 0, NULL, 0}};
    static const cli_spec spec = {"sweep", CLI_OPT_OUTPUT | CLI_OPT_PLOT | CLI_OPT_SET | CLI_OPT_QUIET,
                                  opts, "j:", help};
    cli_args args = {.output = "sweep.csv"};
    char **vary = calloc((size_t)argc + 1, sizeof *vary);
    const char *contrast = NULL;
    int nvary = 0, threads = 0, hdf5 = 0, c;
    tt_sweep_kind kind = TT_SWEEP_STEADY;
    if (!vary)
        return cli_fail(TT_ENOMEM, "out of memory");
    while ((c = cli_getopt(&spec, &args, argc, argv)) > 0) {
        long j;
        switch (c) {
        case 'V': vary[nvary++] = optarg; break;
        case 'C': contrast = optarg; break;
        case 'H': hdf5 = 1; break;
        case 'R':
            if (tt_sweep_kind_parse(optarg, &kind) == 0)
                break;
            fprintf(stderr, "tiptap sweep: --run: '%s' is not steady, setpoint, approach or scan\n", optarg);
            cli_args_free(&args);
            free(vary);
            return CLI_USAGE;
        case 'j':
            if (cli_whole("sweep", "-j", optarg, 1, 4096, "a number of threads", &j) == CLI_OK) {
                threads = (int)j;
                break;
            }
            cli_args_free(&args);
            free(vary);
            return CLI_USAGE;
        }
    }
    if (c == CLI_EXIT) {
        free(vary);
        return args.exit;
    }
    /* every file the sweep writes, checked together before anything runs */
    char dir[4096], h5[4100], journal[4200];
    sweep_names(args.output, dir, h5);
    snprintf(journal, sizeof journal, "%s.partial", args.output);
    cli_args_more(&args, hdf5 ? h5 : NULL, "--hdf5", CLI_OUT_FILE);
    cli_args_more(&args, journal, "the journal", CLI_OUT_DISTINCT);
    cli_args_more(&args, kind == TT_SWEEP_SCAN ? dir : NULL, "the combinations' folder", CLI_OUT_FOLDER);
    int code;
    tt_scene *scene = cli_args_scene(&spec, &args, argc, argv, &code);
    if (!scene) {
        free(vary);
        return code;
    }
    code = sweep_main(scene, vary, nvary, kind, &args, threads, contrast, hdf5);
    free(vary);
    tt_scene_free(scene);
    return code;
}
