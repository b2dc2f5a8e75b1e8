/* tiptap sweep: finished combinations, their journal, and the threads that compute
 * them (see sweep.h). */
#include <errno.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

#include "commands.h"
#include "journal.h"
#include "sweep.h"
#include "tiptap/io/files.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/cancel.h"
#include "tiptap/util/error.h"
#include "tiptap/version.h"

/* One sweep at a time on a journal: a second one with the same -o would add its records
 * to the first's, and truncate what it took for a record cut short. The lock ends with
 * the process, however it ends. */
static int journal_lock(FILE *f, const char *path)
{
    if (flock(fileno(f), LOCK_EX | LOCK_NB) == 0)
        return TT_OK;
    if (errno == EWOULDBLOCK)
        return tt_error(TT_EIO, "%s is in use by another tiptap sweep", path);
    return tt_error(TT_EIO, "%s: cannot lock: %s", path, strerror(errno));
}

/* Resume an existing journal of the same sweep; -1 when there was none. */
static int resume(sweep_results *r, unsigned long long hash)
{
    FILE *f;
    int rc = tt_file_update(r->journal_path, "sweep journal", TT_INPUT_MAX_BYTES, &f);
    if (rc || !f)
        return rc ? rc : -1;
    if ((rc = journal_lock(f, r->journal_path))) {
        fclose(f);
        return rc;
    }
    char *buf = NULL;
    size_t len = 0, cap = 0, got;
    char chunk[65536];
    while ((got = fread(chunk, 1, sizeof chunk, f)) > 0) {
        if (len + got + 1 > cap) {
            char *nb = realloc(buf, cap = 2 * (len + got + 1));
            if (!nb) {
                free(buf);
                fclose(f);
                return tt_error(TT_ENOMEM, "out of memory");
            }
            buf = nb;
        }
        memcpy(buf + len, chunk, got);
        len += got;
        buf[len] = '\0';
    }
    rc = ferror(f) ? tt_error(TT_EIO, "%s: cannot read: %s", r->journal_path, strerror(errno)) : TT_OK;
    journal_sweep sw = {TIPTAP_VERSION_STRING, hash, r->n};
    size_t good = 0;
    if (!rc)
        rc = journal_read(r->journal_path, buf ? buf : "", len, &sw, r->text, &r->done, &good);
    free(buf);
    if (!rc && (ftruncate(fileno(f), (off_t)good) != 0 || fseek(f, 0, SEEK_END) != 0))
        rc = tt_error(TT_EIO, "%s: cannot continue the journal: %s", r->journal_path, strerror(errno));
    if (rc) {
        fclose(f);
        return rc;
    }
    r->journal = f;
    return TT_OK;
}

int sweep_results_open(sweep_results *r, size_t n, const char *out, unsigned long long hash)
{
    memset(r, 0, sizeof *r);
    r->n = n;
    r->text = calloc(n, sizeof *r->text);
    size_t pl = strlen(out) + sizeof ".partial";
    r->journal_path = malloc(pl);
    if (!r->text || !r->journal_path)
        return tt_error(TT_ENOMEM, "out of memory");
    snprintf(r->journal_path, pl, "%s.partial", out);
    int rc = resume(r, hash);
    r->resumed = r->done;
    if (rc != -1)
        return rc;
    if ((rc = tt_file_create(r->journal_path, "sweep journal", &r->journal)) ||
        (rc = journal_lock(r->journal, r->journal_path)))
        return rc;
    journal_sweep sw = {TIPTAP_VERSION_STRING, hash, n};
    if (journal_write_header(r->journal, &sw) != 0 || fflush(r->journal) != 0)
        return tt_error(TT_EIO, "%s: cannot write: %s", r->journal_path, strerror(errno));
    return TT_OK;
}

int sweep_results_record(sweep_results *r, size_t i, char *text)
{
    if (r->text[i])
        free(r->text[i]);
    else
        r->done++;
    r->text[i] = text;
    /* flushed record by record: a killed sweep keeps every combination it finished */
    if (r->journal && (journal_write_record(r->journal, i, text) != 0 || fflush(r->journal) != 0))
        return tt_error(TT_EIO, "%s: cannot write: %s", r->journal_path, strerror(errno));
    return TT_OK;
}

int sweep_results_write(sweep_results *r, const char *out, const char *header)
{
    tt_outfile *of;
    int rc = tt_outfile_open(&of, out);
    if (rc)
        return rc;
    FILE *f = tt_outfile_stream(of);
    fputs(header, f);
    for (size_t i = 0; i < r->n; i++)
        if (r->text[i])
            fputs(r->text[i], f);
    if ((rc = tt_outfile_close(of, 1)))
        return rc;
    if (r->journal) {
        fclose(r->journal);
        r->journal = NULL;
        remove(r->journal_path);
    }
    return TT_OK;
}

void sweep_results_free(sweep_results *r)
{
    if (r->journal)
        fclose(r->journal);
    for (size_t i = 0; r->text && i < r->n; i++)
        free(r->text[i]);
    free(r->text);
    free(r->journal_path);
    memset(r, 0, sizeof *r);
}

int sweep_run_list(const sweep_job *job, const size_t *todo, size_t m, int threads,
                   int (*deliver)(void *user, size_t i, char *text), void *user)
{
    int err = TT_OK, stop = 0;
    char saved[1024] = "";
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long j = 0; j < (long)m; j++) {
        int halt;
#pragma omp atomic read
        halt = stop;
        if (halt || tt_cancel_requested())
            continue;
        char *t = NULL;
        int rc = sweep_compute(job, todo[j], &t);
#pragma omp critical(tt_sweep_deliver)
        {
            if (!rc && !stop)
                rc = deliver(user, todo[j], t);
            else
                free(t);
            if (rc && !err) {
                err = rc;
                snprintf(saved, sizeof saved, "%s", tt_error_message());
#pragma omp atomic write
                stop = 1;
            }
        }
    }
    if (tt_cancel_requested() && (!err || err == TT_EINTR))
        return tt_error(TT_EINTR, "interrupted");
    return err ? tt_error(err, "%s", saved) : TT_OK;
}

void sweep_progress(cli_progress *p, const sweep_results *r)
{
    if (p)
        cli_progress_show(p, (long)(r->done - r->resumed), (long)(r->n - r->resumed));
}

typedef struct {
    sweep_results *r;
    cli_progress *progress;
} local;

static int record_local(void *user, size_t i, char *text)
{
    local *l = user;
    int rc = sweep_results_record(l->r, i, text);
    sweep_progress(l->progress, l->r);
    return rc;
}

int sweep_run_threads(const sweep_job *job, sweep_results *r, int threads, cli_progress *progress)
{
    size_t *todo = malloc((r->n ? r->n : 1) * sizeof *todo), m = 0;
    if (!todo)
        return tt_error(TT_ENOMEM, "out of memory");
    for (size_t i = 0; i < r->n; i++)
        if (!r->text[i])
            todo[m++] = i;
    local l = {r, progress};
    int rc = sweep_run_list(job, todo, m, threads, record_local, &l);
    free(todo);
    return rc;
}
