/* The io layer's files: inputs are regular files only (a pipe is refused without
 * blocking, a link to /dev/zero by what it names); no output replaces an input (also
 * from a program that tracks nothing, once it notes a scene's files), nor anything but
 * a regular file (a pipe, a device, a folder, a link to one); no two outputs of a run
 * name one file; output
 * files never write through a link, and a write error (EFBIG past ulimit -f) fails
 * with the file and the reason and leaves no temporary file; a folder lock is never
 * taken through a link and refuses a second holder, naming its pid. */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tt_test.h"
#include "tiptap/config/config.h"
#include "tiptap/config/sweep.h"
#include "tiptap/io/files.h"
#include "tiptap/io/hdf5.h"
#include "tiptap/io/lock.h"
#include "tiptap/io/outfile.h"
#include "tiptap/util/error.h"

static char dir[] = "/tmp/tt_files_XXXXXX";

static const char *at(const char *name)
{
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}

static void put(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void expect_text(const char *path, const char *text)
{
    char buf[256] = "";
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    assert_string_equal(buf, text);
}

static int names_with(const char *part)
{
    int n = 0;
    DIR *d = opendir(dir);
    for (struct dirent *e; d && (e = readdir(d));)
        n += strstr(e->d_name, part) != NULL;
    closedir(d);
    return n;
}

static void only_regular_inputs(void **st)
{
    (void)st;
    int fd;
    long long size = -1;
    put(at("in.txt"), "twelve bytes");
    assert_int_equal(tt_input_open(at("in.txt"), "scene file", "scene", 100, &fd, &size), TT_OK);
    assert_int_equal(size, 12);
    close(fd);
    /* a pipe without a writer would block an open for reading for ever */
    assert_int_equal(mkfifo(at("fifo"), 0644), 0);
    assert_int_equal(tt_input_open(at("fifo"), "PNG map", "map", 100, &fd, NULL), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "fifo: not a regular file (a device, pipe or socket); a map is a file"));
    assert_int_equal(symlink("/dev/zero", at("zero")), 0);
    assert_int_equal(tt_input_open(at("zero"), "profile CSV", "profile", 100, &fd, NULL), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "zero: not a regular file"));
    assert_int_equal(tt_input_open(dir, "scene file", "scene", 100, &fd, NULL), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), ": is a folder, not a scene file"));
    assert_int_equal(tt_input_open(at("in.txt"), "scene file", "scene", 11, &fd, NULL), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "in.txt: 12 bytes is too large for a scene file (at most 11)"));
    assert_int_equal(tt_input_open(at("none"), "scene file", "scene", 11, &fd, NULL), TT_EIO);
    assert_non_null(strstr(tt_error_message(), "none: cannot open scene file: No such file or directory"));
    unlink(at("fifo"));
    unlink(at("zero"));
    unlink(at("in.txt"));
}

static void outputs_never_replace_inputs(void **st)
{
    (void)st;
    put(at("s.ini"), "[scan]\n");
    /* off (the library's default): a program may write where it read */
    assert_int_equal(tt_output_check(at("s.ini")), TT_OK);
    tt_inputs_track(1);
    int fd;
    assert_int_equal(tt_input_open(at("s.ini"), "scene file", "scene", 100, &fd, NULL), TT_OK);
    close(fd);
    assert_int_equal(tt_output_check(at("s.ini")), TT_EINVAL);
    char want[600];
    snprintf(want, sizeof want, "%s: the same file as the scene file %s that this run reads; "
             "write the output elsewhere", at("s.ini"), at("s.ini"));
    assert_string_equal(tt_error_message(), want);
    /* the same file by another name: a hard link, a symbolic link, a path with ./ */
    assert_int_equal(link(at("s.ini"), at("hard.ini")), 0);
    assert_int_equal(symlink("s.ini", at("soft.ini")), 0);
    assert_int_equal(tt_output_check(at("hard.ini")), TT_EINVAL);
    assert_int_equal(tt_output_check(at("soft.ini")), TT_EINVAL);
    assert_int_equal(tt_output_check(at("./s.ini")), TT_EINVAL);
    assert_int_equal(tt_output_check(at("other.csv")), TT_OK);
    /* and by its path once it is gone: the run read it */
    unlink(at("s.ini"));
    assert_int_equal(tt_output_check(at("s.ini")), TT_EINVAL);
    tt_outfile *o;
    assert_int_equal(tt_outfile_open(&o, at("hard.ini")), TT_EINVAL);
    assert_null(o);
    assert_int_equal(names_with(".tmp."), 0);
    tt_inputs_track(0);
    assert_int_equal(tt_output_check(at("hard.ini")), TT_OK);
    unlink(at("hard.ini"));
    unlink(at("soft.ini"));
}

/* An output replaces only a regular file (or a link, by rename): a pipe, a device, a
 * folder or a link to one of those at its name is refused and left as it was, which
 * rename() would have replaced by a regular file (as root, /dev/null itself). */
static void outputs_replace_only_regular_files(void **st)
{
    (void)st;
    assert_int_equal(mkfifo(at("pipe.csv"), 0644), 0);
    assert_int_equal(mkdir(at("folder.csv"), 0755), 0);
    assert_int_equal(symlink("pipe.csv", at("to_pipe.csv")), 0);
    /* never /dev/null: code without the check would replace it, as root */
    const char *names[] = {"pipe.csv", "folder.csv", "to_pipe.csv"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *path = at(names[i]);
        tt_outfile *o = NULL;
        assert_int_equal(tt_output_check(path), TT_EINVAL);
        assert_int_equal(tt_outfile_open(&o, path), TT_EINVAL);
        assert_null(o);
        char want[600];
        snprintf(want, sizeof want, i == 1 ? "%s: is a folder; the output is a file: name another"
                                           : "%s: not a regular file (a device, pipe or socket); an "
                                             "output replaces only a regular file: name another",
                 path);
        assert_string_equal(tt_error_message(), want);
    }
    struct stat st_;
    assert_true(lstat(at("pipe.csv"), &st_) == 0 && S_ISFIFO(st_.st_mode));
    assert_true(lstat(at("folder.csv"), &st_) == 0 && S_ISDIR(st_.st_mode));
    assert_true(lstat(at("to_pipe.csv"), &st_) == 0 && S_ISLNK(st_.st_mode));
    assert_int_equal(names_with(".tmp."), 0);
    /* the HDF5 writer opens its file the same way */
    tt_h5 *h = NULL;
    assert_int_equal(tt_h5_create(&h, at("pipe.csv")), TT_EINVAL);
    assert_null(h);
    /* nothing there, a regular file, a link to one: written */
    put(at("plain.csv"), "old");
    assert_int_equal(symlink("plain.csv", at("to_plain.csv")), 0);
    assert_int_equal(tt_output_check(at("new.csv")), TT_OK);
    assert_int_equal(tt_output_check(at("plain.csv")), TT_OK);
    assert_int_equal(tt_output_check(at("to_plain.csv")), TT_OK);
    unlink(at("pipe.csv"));
    rmdir(at("folder.csv"));
    unlink(at("to_pipe.csv"));
    unlink(at("plain.csv"));
    unlink(at("to_plain.csv"));
}

/* No two outputs of one run name one file, by any name (sweep -o t.csv --plot t.h5
 * --hdf5 wrote the plot over the HDF5 table). */
static void outputs_of_a_run_are_distinct(void **st)
{
    (void)st;
    char dot[600];
    snprintf(dot, sizeof dot, "%s/../%s/./t.h5", dir, strrchr(dir, '/') + 1);
    tt_output outs[] = {{at("t.csv"), "-o"}, {at("t.h5"), "--plot"}, {dot, "--hdf5"}};
    assert_int_equal(tt_outputs_distinct(outs, 3), TT_EINVAL);
    char want[1400];
    snprintf(want, sizeof want, "--hdf5 %s: the same file as --plot %s; give each its own name", dot,
             at("t.h5"));
    assert_string_equal(tt_error_message(), want);
    outs[2].path = at("u.h5");
    assert_int_equal(tt_outputs_distinct(outs, 3), TT_OK);
    outs[1].path = NULL; /* no --plot */
    outs[2].path = at("t.csv");
    assert_int_equal(tt_outputs_distinct(outs, 3), TT_EINVAL);
    /* files that exist: the same inode by a hard link */
    put(at("a.csv"), "a");
    assert_int_equal(link(at("a.csv"), at("b.csv")), 0);
    tt_output two[] = {{at("a.csv"), "-o"}, {at("b.csv"), "--plot"}};
    assert_int_equal(tt_outputs_distinct(two, 2), TT_EINVAL);
    unlink(at("a.csv"));
    unlink(at("b.csv"));
}

/* A program that tracks nothing (Python) notes the scene's files before it writes:
 * hdf5="s.ini" replaced the scene. The scene knows the files it was read from, and so
 * does its copy; a sweep notes the scene files it varies. */
static void scene_files_noted_without_tracking(void **st)
{
    (void)st;
    tt_inputs_track(0);
    put(at("n.ini"), "[trace]\ncycles = 3\n");
    tt_scene *s = tt_scene_alloc();
    assert_int_equal(tt_scene_load(s, at("n.ini")), TT_OK);
    assert_int_equal(tt_output_check(at("n.ini")), TT_OK); /* not tracked, not noted */
    tt_config_note_inputs(s);
    tt_h5 *h = NULL;
    assert_int_equal(tt_h5_create(&h, at("n.ini")), TT_EINVAL);
    assert_null(h);
    assert_int_equal(tt_h5_create(&h, at("./n.ini")), TT_EINVAL);
    expect_text(at("n.ini"), "[trace]\ncycles = 3\n");
    assert_int_equal(names_with(".tmp."), 0);
    tt_inputs_track(0); /* forgets what was noted */
    assert_int_equal(tt_output_check(at("n.ini")), TT_OK);
    tt_scene *c = tt_scene_copy(s);
    assert_non_null(c);
    tt_config_note_inputs(c);
    assert_int_equal(tt_output_check(at("n.ini")), TT_EINVAL);
    tt_inputs_track(0);
    /* the scene files a sweep varies, noted as the axis is added, before it runs */
    put(at("v.ini"), "[trace]\ncycles = 4\n");
    tt_sweep *g = NULL;
    char spec[600];
    snprintf(spec, sizeof spec, "scene=%s", at("v.ini"));
    assert_int_equal(tt_sweep_alloc(&g, s), TT_OK);
    assert_int_equal(tt_output_check(at("v.ini")), TT_OK);
    assert_int_equal(tt_sweep_vary(g, spec), TT_OK);
    assert_int_equal(tt_output_check(at("v.ini")), TT_EINVAL);
    tt_sweep_free(g);
    tt_inputs_track(0);
    tt_scene_free(c);
    tt_scene_free(s);
    unlink(at("n.ini"));
    unlink(at("v.ini"));
}

static void rename_replaces_a_link(void **st)
{
    (void)st;
    put(at("precious.txt"), "precious");
    assert_int_equal(symlink("precious.txt", at("out.csv")), 0);
    tt_outfile *o;
    assert_int_equal(tt_outfile_open(&o, at("out.csv")), TT_OK);
    fputs("result", tt_outfile_stream(o));
    assert_int_equal(tt_outfile_close(o, 1), TT_OK);
    struct stat sb;
    assert_int_equal(lstat(at("out.csv"), &sb), 0);
    assert_true(S_ISREG(sb.st_mode));
    expect_text(at("out.csv"), "result");
    expect_text(at("precious.txt"), "precious");
    unlink(at("out.csv"));
    unlink(at("precious.txt"));
}

static void write_errors_name_the_file(void **st)
{
    (void)st;
    put(at("big.bin"), "earlier");
    struct rlimit old, lim;
    getrlimit(RLIMIT_FSIZE, &old);
    lim = old;
    lim.rlim_cur = 8192;
    void (*was)(int) = signal(SIGXFSZ, SIG_IGN);
    assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
    tt_outfile *o;
    assert_int_equal(tt_outfile_open(&o, at("big.bin")), TT_OK);
    for (int i = 0; i < 10000; i++)
        fputs("0123456789", tt_outfile_stream(o));
    int rc = tt_outfile_close(o, 1);
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, was);
    assert_int_equal(rc, TT_EIO);
    char want[600];
    snprintf(want, sizeof want, "%s: cannot write: %s", at("big.bin"), strerror(EFBIG));
    assert_string_equal(tt_error_message(), want);
    expect_text(at("big.bin"), "earlier");
    assert_int_equal(names_with(".tmp."), 0);
    unlink(at("big.bin"));
}

static void locks(void **st)
{
    (void)st;
    int fd = -1, second = -1;
    put(at("precious.txt"), "precious");
    assert_int_equal(symlink("precious.txt", at(".tiptap.lock")), 0);
    assert_int_equal(tt_folder_lock(dir, "scan", &fd), TT_EIO);
    assert_non_null(strstr(tt_error_message(), ".tiptap.lock: is a symbolic link; tiptap never writes through a link"));
    expect_text(at("precious.txt"), "precious");
    unlink(at(".tiptap.lock"));
    /* a hard link would have its other name truncated */
    assert_int_equal(link(at("precious.txt"), at(".tiptap.lock")), 0);
    assert_int_equal(tt_folder_lock(dir, "scan", &fd), TT_EIO);
    expect_text(at("precious.txt"), "precious");
    unlink(at(".tiptap.lock"));
    /* a lock left by a dead run is taken over; a held one is refused with its pid */
    put(at(".tiptap.lock"), "999999999 scan\n");
    assert_int_equal(tt_folder_lock(dir, "sweep", &fd), TT_OK);
    assert_int_equal(tt_folder_lock(dir, "scan", &second), TT_EIO);
    char want[600];
    snprintf(want, sizeof want, "%s is in use by another tiptap sweep (pid %ld)", dir, (long)getpid());
    assert_string_equal(tt_error_message(), want);
    assert_int_equal(second, -1);
    tt_folder_unlock(dir, fd);
    assert_int_equal(access(at(".tiptap.lock"), F_OK), -1);
    assert_int_equal(tt_folder_lock(dir, "scan", &fd), TT_OK);
    tt_folder_unlock(dir, fd);
    unlink(at("precious.txt"));
}

static void journals_never_through_links(void **st)
{
    (void)st;
    FILE *f = NULL;
    put(at("precious.txt"), "precious");
    assert_int_equal(symlink("precious.txt", at("j.partial")), 0);
    assert_int_equal(tt_file_update(at("j.partial"), "sweep journal", 100, &f), TT_EINVAL);
    assert_int_equal(tt_file_create(at("j.partial"), "sweep journal", &f), TT_EINVAL);
    assert_non_null(strstr(tt_error_message(), "the sweep journal is a symbolic link"));
    expect_text(at("precious.txt"), "precious");
    unlink(at("j.partial"));
    assert_int_equal(tt_file_update(at("j.partial"), "sweep journal", 100, &f), TT_OK);
    assert_null(f);
    assert_int_equal(tt_file_create(at("j.partial"), "sweep journal", &f), TT_OK);
    fputs("journal", f);
    fclose(f);
    assert_int_equal(tt_file_update(at("j.partial"), "sweep journal", 100, &f), TT_OK);
    assert_non_null(f);
    fclose(f);
    unlink(at("j.partial"));
    unlink(at("precious.txt"));
}

static int setup(void **st)
{
    (void)st;
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **st)
{
    (void)st;
    return rmdir(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(only_regular_inputs),
        cmocka_unit_test(outputs_never_replace_inputs),
        cmocka_unit_test(rename_replaces_a_link),
        cmocka_unit_test(outputs_replace_only_regular_files),
        cmocka_unit_test(outputs_of_a_run_are_distinct),
        cmocka_unit_test(scene_files_noted_without_tracking),
        cmocka_unit_test(write_errors_name_the_file),
        cmocka_unit_test(locks),
        cmocka_unit_test(journals_never_through_links),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
