/* tiptap sweep over MPI ranks (compiled only when CMake's TT_MPI finds MPI; see
 * sweep.h). The combinations left to run are dealt out to the ranks in turn (cyclic:
 * neighbouring grid points cost about the same, so every rank gets a fair share
 * without a scheduler), each rank spreads its share over its threads dynamically, and
 * every finished text goes to rank 0, which records it in the journal at once and
 * writes the table in combination order at the end. */
#include <mpi.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "sweep.h"
#include "tiptap/util/error.h"

enum { TAG_RESULT = 1, TAG_DONE = 2 };

static int started;

int sweep_mpi_start(int *rank, int *size)
{
    static const char *vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"};
    long ranks = 1;
    for (size_t i = 0; i < sizeof vars / sizeof vars[0]; i++)
        if (getenv(vars[i])) {
            ranks = strtol(getenv(vars[i]), NULL, 10);
            break;
        }
    /* a plain run never starts MPI: no launcher, no singleton start-up cost */
    if (ranks < 2)
        return 0;
    int provided = 0;
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
        return 0;
    started = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
    return *size > 1;
}

void sweep_mpi_stop(void)
{
    if (started)
        MPI_Finalize();
    started = 0;
}

int sweep_mpi_agree(int rc)
{
    int worst = rc;
    MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (rc || !worst)
        return rc;
    return tt_error(worst, "another MPI rank failed before the sweep started");
}

/* A result: the combination index (8 bytes) then its text. */
static int send_result(void *user, size_t i, char *text)
{
    (void)user;
    size_t len = strlen(text);
    char *buf = malloc(len + 8);
    if (!buf) {
        free(text);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    uint64_t idx = i;
    memcpy(buf, &idx, 8);
    memcpy(buf + 8, text, len);
    free(text);
    int rc = MPI_Send(buf, (int)(len + 8), MPI_CHAR, 0, TAG_RESULT, MPI_COMM_WORLD);
    free(buf);
    return rc == MPI_SUCCESS ? TT_OK : tt_error(TT_EIO, "MPI: cannot send a result to rank 0");
}

typedef struct {
    sweep_results *r;
    cli_progress *progress;
    int pending; /* ranks not yet done */
    int rc;                /* the first error another rank reported */
    char why[1024];
} root;

/* Receive one message if there is one (or wait for it when block). 1 if received. */
static int receive(root *R, int block)
{
    MPI_Status st;
    int flag = 1, count = 0;
    if (block)
        MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
    else
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (!flag)
        return 0;
    MPI_Get_count(&st, MPI_CHAR, &count);
    char *buf = malloc((size_t)count + 1);
    MPI_Recv(buf, count, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (!buf)
        return 1;
    buf[count] = '\0';
    if (st.MPI_TAG == TAG_DONE) {
        int rc;
        memcpy(&rc, buf, sizeof rc);
        if (rc && !R->rc) {
            R->rc = rc;
            snprintf(R->why, sizeof R->why, "rank %d: %s", st.MPI_SOURCE, buf + sizeof rc);
        }
        R->pending--;
        free(buf);
        return 1;
    }
    uint64_t idx;
    memcpy(&idx, buf, 8);
    char *text = strdup(buf + 8);
    free(buf);
    if (text && idx < R->r->n && !R->r->text[idx]) {
        sweep_results_record(R->r, (size_t)idx, text);
        sweep_progress(R->progress, R->r);
    } else
        free(text);
    return 1;
}

/* Rank 0's own results, and whatever the others sent meanwhile. */
static int record_root(void *user, size_t i, char *text)
{
    root *R = user;
    int rc = sweep_results_record(R->r, i, text);
    sweep_progress(R->progress, R->r);
    while (receive(R, 0))
        ;
    return rc;
}

int sweep_mpi_run(const sweep_job *job, sweep_results *r, int threads, cli_progress *progress)
{
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    size_t n = r->n, m = 0, k = 0;
    unsigned char *done = calloc(n ? n : 1, 1);
    size_t *mine = malloc((n ? n : 1) * sizeof *mine);
    if (!done || !mine) {
        free(done);
        free(mine);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    for (size_t i = 0; rank == 0 && i < n; i++)
        done[i] = r->text[i] != NULL;
    MPI_Bcast(done, (int)n, MPI_UNSIGNED_CHAR, 0, MPI_COMM_WORLD);
    for (size_t i = 0; i < n; i++)
        if (!done[i] && k++ % (size_t)size == (size_t)rank)
            mine[m++] = i;
    free(done);
    int rc;
    if (rank != 0) {
        rc = sweep_run_list(job, mine, m, threads, send_result, NULL);
        char msg[1024 + sizeof rc];
        memcpy(msg, &rc, sizeof rc);
        snprintf(msg + sizeof rc, 1024, "%s", rc ? tt_error_message() : "");
        MPI_Send(msg, (int)(sizeof rc + strlen(msg + sizeof rc) + 1), MPI_CHAR, 0, TAG_DONE, MPI_COMM_WORLD);
        free(mine);
        return rc;
    }
    root R = {r, progress, size - 1, TT_OK, ""};
    rc = sweep_run_list(job, mine, m, threads, record_root, &R);
    while (R.pending > 0)
        receive(&R, 1);
    free(mine);
    if (!rc && R.rc)
        rc = tt_error(R.rc, "%s", R.why);
    return rc;
}
