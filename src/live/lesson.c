/* A lesson for the live console (include/tiptap/live/lesson.h): its [lesson] section
 * read and checked, the rest of the file left to the configuration layer. */
#include "tiptap/live/lesson.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/live/controls.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

static char *read_all(const char *path, int *rc)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        *rc = tt_error(TT_EIO, "%s: cannot read the lesson: %s; expected a lesson file (docs/live.md, \"Lessons\")",
                       path, strerror(errno));
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *b = malloc(cap);
    for (size_t k; b && (k = fread(b + n, 1, cap - n - 1, f)) > 0;) {
        n += k;
        if (n + 1 == cap) {
            char *m = cap < ((size_t)1 << 24) ? realloc(b, cap *= 2) : NULL;
            if (!m) {
                free(b);
                b = NULL;
            }
            b = m;
        }
    }
    fclose(f);
    if (!b) {
        *rc = tt_error(TT_EINVAL, "%s: the lesson is over 16 MB or memory ran out", path);
        return NULL;
    }
    b[n] = '\0';
    *rc = TT_OK;
    return b;
}

int tt_live_lesson_is_one(const char *path)
{
    int rc;
    char *t = read_all(path, &rc);
    int yes = 0;
    for (char *p = t; p && *p && !yes;) {
        while (*p == ' ' || *p == '\t')
            p++;
        yes = strncmp(p, "[lesson]", 8) == 0;
        p = strchr(p, '\n');
        p = p ? p + 1 : NULL;
    }
    free(t);
    return yes;
}

/* Control named `name` (n bytes): the message's name, with _ for the dot, or the key alone
 * where one control has it; -1: none. */
static int control_index(const char *name, size_t n)
{
    size_t count;
    const tt_live_control *t = tt_live_control_table(&count);
    int found = -1, keys = 0;
    for (size_t i = 0; i < count; i++) {
        const char *full = t[i].name, *dot = strchr(full, '.');
        int same = strlen(full) == n;
        for (size_t k = 0; same && k < n; k++)
            same = full[k] == name[k] || (full[k] == '.' && name[k] == '_');
        if (same)
            return (int)i;
        if (dot && strlen(dot + 1) == n && strncmp(dot + 1, name, n) == 0) {
            found = (int)i;
            keys++;
        }
    }
    return keys == 1 ? found : -1;
}

static int names_list(const tt_live_lesson *l, long line, const char *key, const char *v,
                      unsigned long *mask)
{
    size_t count;
    const tt_live_control *t = tt_live_control_table(&count);
    for (const char *p = v; *p;) {
        while (*p == ',' || isspace((unsigned char)*p))
            p++;
        const char *e = p;
        while (*e && *e != ',' && !isspace((unsigned char)*e))
            e++;
        if (e == p)
            break;
        int k = control_index(p, (size_t)(e - p));
        if (k < 0) {
            char all[512] = "";
            for (size_t i = 0; i < count; i++)
                snprintf(all + strlen(all), sizeof all - strlen(all), "%s%s", i ? ", " : "", t[i].name);
            return tt_error(TT_EINVAL, "%s:%ld: [lesson] %s: '%.*s' is not a control; expected %s "
                                       "(or with _ for the dot, or the key alone)",
                            l->path, line, key, (int)(e - p), p, all);
        }
        *mask |= 1ul << k;
        p = e;
    }
    return TT_OK;
}

/* scene = paths, resolved against the lesson's folder. */
static int scene_files(tt_live_lesson *l, long line, const char *v)
{
    const char *slash = strrchr(l->path, '/');
    int dirlen = slash ? (int)(slash - l->path) : 0;
    for (const char *p = v; *p;) {
        while (isspace((unsigned char)*p))
            p++;
        const char *e = p;
        while (*e && !isspace((unsigned char)*e))
            e++;
        if (e == p)
            break;
        char path[PATH_MAX];
        if (*p == '/' || !slash)
            snprintf(path, sizeof path, "%.*s", (int)(e - p), p);
        else
            snprintf(path, sizeof path, "%.*s/%.*s", dirlen, l->path, (int)(e - p), p);
        FILE *f = fopen(path, "r");
        if (!f)
            return tt_error(TT_EINVAL, "%s:%ld: [lesson] scene: cannot read %s: %s; expected scene files, "
                                       "relative to the lesson's folder",
                            l->path, line, path, strerror(errno));
        fclose(f);
        char **m = realloc(l->files, (size_t)(l->nfiles + 1) * sizeof *m);
        if (!m)
            return tt_error_nomem("the lesson's scene files");
        l->files = m;
        if (!(l->files[l->nfiles] = tt_strdup(path)))
            return tt_error_nomem("the lesson's scene files");
        l->nfiles++;
        p = e;
    }
    return TT_OK;
}

/* Append text to *dst (a value continued on an indented line: a newline between). */
static int append(char **dst, const char *v, size_t n, int newline)
{
    size_t old = *dst ? strlen(*dst) : 0;
    char *m = realloc(*dst, old + n + 2);
    if (!m)
        return tt_error_nomem("the lesson");
    if (newline && old)
        m[old++] = '\n';
    memcpy(m + old, v, n);
    m[old + n] = '\0';
    *dst = m;
    return TT_OK;
}

static int section_line(tt_live_lesson *l, long line, char *p, char ***cur, char **hide, char **lock,
                        char **scene)
{
    int indented = *p == ' ' || *p == '\t';
    while (*p == ' ' || *p == '\t')
        p++;
    size_t n = strlen(p);
    while (n && isspace((unsigned char)p[n - 1]))
        p[--n] = '\0';
    if (n == 0 || *p == '#' || *p == ';')
        return TT_OK;
    if (indented && *cur)
        return append(*cur, p, n, 1);
    char *eq = strchr(p, '=');
    if (!eq)
        return tt_error(TT_EINVAL, "%s:%ld: [lesson]: '%s' is not key = value; expected title, "
                                   "instructions, scene, hide or lock",
                        l->path, line, p);
    char *k = p, *ke = eq, *v = eq + 1;
    while (ke > k && isspace((unsigned char)ke[-1]))
        ke--;
    *ke = '\0';
    while (isspace((unsigned char)*v))
        v++;
    char **dst = strcmp(k, "title") == 0 ? &l->title : strcmp(k, "instructions") == 0 ? &l->instructions
                 : strcmp(k, "hide") == 0 ? hide : strcmp(k, "lock") == 0 ? lock
                 : strcmp(k, "scene") == 0 ? scene : NULL;
    if (!dst)
        return tt_error(TT_EINVAL, "%s:%ld: [lesson] %s: unknown key; expected title, instructions, "
                                   "scene, hide or lock",
                        l->path, line, k);
    free(*dst);
    *dst = NULL;
    *cur = dst; /* an indented line continues it (hide, lock and scene too) */
    return append(dst, v, strlen(v), 0);
}

int tt_live_lesson_load(tt_live_lesson **out, const char *path)
{
    int rc;
    tt_live_lesson *l = calloc(1, sizeof *l);
    if (!l)
        return tt_error_nomem("the lesson");
    l->path = tt_strdup(path);
    l->scene_text = l->path ? read_all(path, &rc) : (rc = tt_error_nomem("the lesson"), NULL);
    char *hide = NULL, *lock = NULL, *scene = NULL, **cur = NULL;
    long hide_at = 0, lock_at = 0, scene_at = 0, line = 0;
    int in = 0, seen = 0;
    for (char *p = l->scene_text; !rc && p && *p;) {
        char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        line++;
        const char *q = p;
        while (*q == ' ' || *q == '\t')
            q++;
        if (*q == '[') {
            in = strncmp(q, "[lesson]", 8) == 0;
            seen |= in;
            cur = NULL;
        } else if (!in && n && !isspace((unsigned char)*q) && *q != '#' && *q != ';') {
            l->has_scene_text = 1;
        }
        if (in) {
            char buf[8192];
            snprintf(buf, sizeof buf, "%.*s", (int)n, p);
            if (*q != '[') {
                char **before = cur;
                rc = section_line(l, line, buf, &cur, &hide, &lock, &scene);
                /* where each list's key is, for its messages */
                if (!rc && cur != before) {
                    if (cur == &hide)
                        hide_at = line;
                    else if (cur == &lock)
                        lock_at = line;
                    else if (cur == &scene)
                        scene_at = line;
                }
            }
            /* blank for the configuration layer, the line numbers kept */
            memset(p, ' ', n);
        }
        p = nl ? nl + 1 : NULL;
    }
    if (!rc && !seen)
        rc = tt_error(TT_EINVAL, "%s: no [lesson] section; expected [lesson] with title = ... "
                                 "(docs/live.md, \"Lessons\")",
                      path);
    if (!rc && (!l->title || !l->title[0]))
        rc = tt_error(TT_EINVAL, "%s: [lesson] title: missing; expected title = the lesson's name", path);
    if (!rc && !l->instructions)
        rc = append(&l->instructions, "", 0, 0);
    if (!rc && hide)
        rc = names_list(l, hide_at, "hide", hide, &l->hide);
    if (!rc && lock)
        rc = names_list(l, lock_at, "lock", lock, &l->lock);
    if (!rc && scene)
        rc = scene_files(l, scene_at, scene);
    if (!rc && !l->nfiles && !l->has_scene_text)
        rc = tt_error(TT_EINVAL, "%s: [lesson] scene: missing, and the file has no scene sections; "
                                 "expected scene = FILE... or the scene's sections in the lesson",
                      path);
    free(hide);
    free(lock);
    free(scene);
    if (rc) {
        tt_live_lesson_free(l);
        return rc;
    }
    *out = l;
    return TT_OK;
}

void tt_live_lesson_free(tt_live_lesson *l)
{
    if (!l)
        return;
    for (int i = 0; i < l->nfiles; i++)
        free(l->files[i]);
    free(l->files);
    free(l->path);
    free(l->title);
    free(l->instructions);
    free(l->scene_text);
    free(l);
}

static int write_names(FILE *out, const char *key, unsigned long mask)
{
    size_t count;
    const tt_live_control *t = tt_live_control_table(&count);
    if (!mask)
        return 0;
    fprintf(out, "%s =", key);
    for (size_t i = 0, k = 0; i < count; i++)
        if (mask & (1ul << i))
            fprintf(out, "%s %s", k++ ? "," : "", t[i].name);
    return fprintf(out, "\n") < 0;
}

int tt_live_lesson_write(const tt_live_lesson *l, FILE *out)
{
    fprintf(out, "[lesson]\ntitle = %s\n", l ? l->title : "A lesson saved from tiptap live");
    if (l && l->instructions[0]) {
        fprintf(out, "instructions =");
        /* each line of the instructions indented: a continuation */
        for (const char *p = l->instructions; *p;) {
            const char *nl = strchr(p, '\n');
            int n = nl ? (int)(nl - p) : (int)strlen(p);
            fprintf(out, "%s%.*s\n", p == l->instructions ? " " : "    ", n, p);
            p = nl ? nl + 1 : p + n;
        }
    }
    if (l && (write_names(out, "hide", l->hide) || write_names(out, "lock", l->lock)))
        return tt_error(TT_EIO, "cannot write the lesson");
    return fprintf(out, "\n") < 0 ? tt_error(TT_EIO, "cannot write the lesson") : TT_OK;
}
