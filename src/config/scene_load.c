/* Loading a scene: scene files (only regular files, at most 256 MiB) and scene text read
 * through the INI reader, section headers split into section and name, and --set
 * assignments "section.key=value" or "section.name.key=value"; every key goes through
 * scene_put's checks (see include/tiptap/config/scene.h). */
#include "scene_private.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tiptap/config/ini.h"
#include "tiptap/io/files.h"
#include "tiptap/util/error.h"
#include "tiptap/util/str.h"

/* Split an INI section header "material glass" into schema section and name (NULL when
 * there is none); both are allocated together in *buf, which the caller frees. */
static int split_header(const char *header, char **buf, const char **section, const char **name)
{
    size_t n = strlen(header);
    char *b = malloc(n + 1);
    if (!b)
        return tt_error_nomem("the section header [%.64s]", header);
    memcpy(b, header, n + 1);
    char *p = b;
    while (*p && !isspace((unsigned char)*p))
        p++;
    char *rest = p;
    while (isspace((unsigned char)*rest))
        rest++;
    *p = '\0';
    *buf = b;
    *section = b;
    *name = *rest ? rest : NULL;
    return TT_OK;
}

typedef struct {
    tt_scene *s;
    const char *origin;
    unsigned load;
} load_ctx;

static int on_item(void *user, const tt_ini_item *it)
{
    load_ctx *c = user;
    char *buf = NULL;
    const char *section = NULL, *name = NULL;
    char shown[160];
    if (!it->key && !it->section[0])
        return tt_error(TT_EINVAL, "%s: line %ld: empty section header '[]'", c->origin, it->line);
    if (!it->section[0])
        return tt_error(TT_EINVAL, "%s: %s: key outside any section; put it under a [section]",
                        c->origin, tt_ini_escape(it->key, shown, sizeof shown));
    int rc = split_header(it->section, &buf, &section, &name);
    if (rc)
        return rc;
    if (!it->key) {
        /* a section without keys still exists: [material glass] with all defaults */
        rc = scene_check_section(c->origin, section, name);
        if (!rc)
            rc = scene_note_section(c->s, section, name, c->origin);
    } else {
        rc = scene_put(c->s, c->origin, c->load, section, name, it->key, it->value);
    }
    free(buf);
    return rc;
}

static int load_text(tt_scene *s, const char *text, size_t len, const char *origin)
{
    load_ctx c = {s, origin, ++s->loads};
    int rc = tt_ini_parse(text, len, origin, on_item, &c);
    if (rc)
        return rc;
    if (!s->origin && !(s->origin = tt_strdup(origin)))
        return tt_error_nomem("the scene read from %s", origin);
    return TT_OK;
}

int tt_scene_load(tt_scene *s, const char *path)
{
    /* a folder reads as empty and /dev/zero never ends: only regular files are scenes,
     * of at most TT_INPUT_MAX_BYTES (50,000 materials take 5 MB) */
    int fd;
    long long size = 0;
    int rc = tt_input_open(path, "scene file", "scene", TT_INPUT_MAX_BYTES, &fd, &size);
    if (rc)
        return rc;
    char *text = NULL;
    size_t len = 0;
    if (!(text = malloc((size_t)size + 1)))
        rc = tt_error_nomem("the text of %s (%lld bytes)", path, (long long)size);
    while (!rc && len <= (size_t)size) {
        ssize_t got = read(fd, text + len, (size_t)size + 1 - len);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0)
            rc = tt_error(TT_EIO, "%s: cannot read scene file: %s", path, strerror(errno));
        else if (got == 0)
            break;
        else
            len += (size_t)got;
    }
    close(fd);
    if (!rc && len > (size_t)size)
        rc = tt_error(TT_EIO, "%s: the file grew while it was read", path);
    if (!rc)
        rc = load_text(s, text, len, path);
    if (!rc)
        rc = scene_note_file(s, path);
    free(text);
    return rc;
}

int tt_scene_load_string(tt_scene *s, const char *text, const char *origin)
{
    return load_text(s, text, strlen(text), origin);
}

/* A --set into a named section the scene lacks would make a new one that nothing uses
 * (material.silicone.KEY when the scene has [material silicon]): refused with the names
 * it has. A scene without any has the default material, "sample". Unnamed sections
 * ([approach], [trace], ...) are made by a --set as by a file. */
static int check_set_names(const tt_scene *s, const char *shown, const char *section,
                           const char *name)
{
    const tt_scene_section *sec = scene_find_section(section);
    if (!sec || !sec->named || !name || scene_find_use(s, section, name))
        return TT_OK;
    size_t n = tt_scene_count_named(s, section);
    if (n == 0 && strcmp(section, "material") == 0 && strcmp(name, "sample") == 0)
        return TT_OK;
    char have[512] = "", nm[160];
    size_t used = 0;
    for (size_t i = 0; i < n; i++) {
        tt_ini_escape(tt_scene_named(s, section, i), nm, sizeof nm);
        /* room is kept for the ", ..." of a list cut short */
        if (scene_list_add(have, sizeof have - 5, &used, nm)) {
            snprintf(have + used, sizeof have - used, ", ...");
            break;
        }
    }
    tt_ini_escape(name, nm, sizeof nm);
    return tt_error(TT_EINVAL, "--set %s: no [%s %s] in the scene; it has: %s", shown, section, nm,
                    n ? have : strcmp(section, "material") == 0 ? "none but the default, sample"
                                                                : "none");
}

int tt_scene_set(tt_scene *s, const char *assignment)
{
    char shown[160];
    const char *eq = strchr(assignment, '=');
    tt_ini_escape(assignment, shown, sizeof shown);
    if (!eq)
        return tt_error(TT_EINVAL, "--set %s: expected section.key=value", shown);
    size_t n = (size_t)(eq - assignment);
    char *lhs = malloc(n + 1);
    if (!lhs)
        return tt_error_nomem("--set %s", shown);
    memcpy(lhs, assignment, n);
    lhs[n] = '\0';
    while (n > 0 && isspace((unsigned char)lhs[n - 1]))
        lhs[--n] = '\0';
    const char *value = eq + 1;
    while (isspace((unsigned char)*value) && *value != '\n' && *value != '\r')
        value++;
    size_t vl = strlen(value);
    while (vl > 0 && (value[vl - 1] == ' ' || value[vl - 1] == '\t'))
        vl--;
    char *val = malloc(vl + 1);
    char *d1 = strchr(lhs, '.');
    int rc = TT_OK;
    if (!val)
        rc = tt_error_nomem("--set %s", shown);
    else if (!d1)
        rc = tt_error(TT_EINVAL, "--set %s: expected section.key=value", shown);
    if (!rc) {
        memcpy(val, value, vl);
        val[vl] = '\0';
        *d1 = '\0';
        const char *section = lhs, *name = NULL, *key = d1 + 1;
        /* "material.glass.youngs_modulus": the last dot separates the key. */
        char *d2 = strrchr(d1 + 1, '.');
        if (d2) {
            *d2 = '\0';
            name = d1 + 1;
            key = d2 + 1;
        }
        if (!section[0] || !key[0] || (name && !name[0]))
            rc = tt_error(TT_EINVAL, "--set %s: empty %s; expected section.key=value or "
                          "section.name.key=value", shown,
                          !section[0] ? "section" : !key[0] ? "key" : "name");
        else if (!(rc = check_set_names(s, shown, section, name)))
            rc = scene_put(s, "--set", 0, section, name, key, val);
    }
    free(val);
    free(lhs);
    return rc;
}
