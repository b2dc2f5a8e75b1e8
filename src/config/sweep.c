/* Parameter grids over scene keys (see include/tiptap/config/sweep.h). */
#include "tiptap/config/sweep.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/util/error.h"

typedef struct {
    char *key;              /* as given: section.key or section.NAME.key */
    char unit[16];          /* SI unit of the values; "" for text */
    size_t n;               /* values */
    char **text;            /* as set in the scene */
    double *si;             /* SI values, NAN for text */
    int files;              /* the values are scene files to read, not values of a key */
} axis;

struct tt_sweep {
    const tt_scene *base;
    axis *axes;
    size_t naxes;
};

int tt_sweep_alloc(tt_sweep **out, const tt_scene *base)
{
    *out = calloc(1, sizeof **out);
    if (!*out)
        return tt_error(TT_ENOMEM, "out of memory");
    (*out)->base = base;
    return TT_OK;
}

static void axis_free(axis *a)
{
    for (size_t i = 0; i < a->n; i++)
        free(a->text[i]);
    free(a->text);
    free(a->si);
    free(a->key);
}

void tt_sweep_free(tt_sweep *sw)
{
    if (!sw)
        return;
    for (size_t k = 0; k < sw->naxes; k++)
        axis_free(&sw->axes[k]);
    free(sw->axes);
    free(sw);
}

/* The schema entry of "section.key" or "section.NAME.key". */
static const tt_scene_key *schema_key(const char *key)
{
    size_t nsec;
    const tt_scene_section *sec = tt_scene_schema(&nsec);
    const char *d1 = strchr(key, '.');
    if (!d1)
        return NULL;
    const char *last = strrchr(key, '.');
    size_t sl = (size_t)(d1 - key);
    for (size_t i = 0; i < nsec; i++) {
        if (strlen(sec[i].name) != sl || strncmp(sec[i].name, key, sl) != 0)
            continue;
        if ((sec[i].named != 0) != (last != d1))
            return NULL;
        for (size_t j = 0; j < sec[i].nkeys; j++)
            if (strcmp(sec[i].keys[j].key, last + 1) == 0)
                return &sec[i].keys[j];
    }
    return NULL;
}

static char *trimmed(const char *s, size_t n)
{
    while (n > 0 && isspace((unsigned char)*s))
        s++, n--;
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        n--;
    char *t = malloc(n + 1);
    if (t) {
        memcpy(t, s, n);
        t[n] = '\0';
    }
    return t;
}

static int add_value(axis *a, char *text, double si)
{
    char **t = realloc(a->text, (a->n + 1) * sizeof *t);
    if (t)
        a->text = t;
    double *v = t ? realloc(a->si, (a->n + 1) * sizeof *v) : NULL;
    if (!v) {
        free(text);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    a->si = v;
    a->text[a->n] = text;
    a->si[a->n++] = si;
    return TT_OK;
}

/* One value's SI number and dimension; the unit of an axis is that of its first value,
 * and the others must share it (one column, one unit). */
static int parse_one(axis *a, const tt_scene_key *k, const char *text, double *si)
{
    char why[256];
    *si = NAN;
    if (k->kind == TT_KEY_INT) {
        char *end;
        *si = (double)strtol(text, &end, 10);
        snprintf(a->unit, sizeof a->unit, "1");
        return (*end || end == text) ? tt_error(TT_EINVAL, "--vary %s: '%s' is not a whole number", a->key, text) : TT_OK;
    }
    if (k->kind != TT_KEY_QUANTITY)
        return TT_OK;
    tt_dim dim;
    if (tt_units_parse(text, k->dims, si, &dim, why, sizeof why) != 0)
        return tt_error(TT_EINVAL, "--vary %s: '%s': %s", a->key, text, why);
    const char *u = (dim == TT_DIM_NONE || dim == TT_DIM_FRACTION) ? "1" : tt_units_symbol(dim);
    if (a->n > 0 && strcmp(a->unit, u) != 0)
        return tt_error(TT_EINVAL, "--vary %s: '%s' has another unit than the first value", a->key, text);
    snprintf(a->unit, sizeof a->unit, "%s", u);
    return TT_OK;
}

/* FROM:TO:N (log: evenly in the logarithm), each value written back in SI so that the
 * scene reads exactly the number computed here. */
static int add_range(axis *a, const tt_scene_key *k, const char *spec, int logscale)
{
    const char *c1 = strchr(spec, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c2 || strchr(c2 + 1, ':') || (k->kind != TT_KEY_QUANTITY && k->kind != TT_KEY_INT))
        return tt_error(TT_EINVAL, "--vary %s: a range is FROM:TO:N of a number-valued key", a->key);
    char *from = trimmed(spec, (size_t)(c1 - spec)), *to = trimmed(c1 + 1, (size_t)(c2 - c1 - 1));
    char *end;
    long n = strtol(c2 + 1, &end, 10);
    double lo, hi;
    int rc = (!from || !to) ? tt_error(TT_ENOMEM, "out of memory") : TT_OK;
    if (!rc && (*end || n < 1 || n > 10000000))
        rc = tt_error(TT_EINVAL, "--vary %s: N in FROM:TO:N must be a whole number from 1", a->key);
    if (!rc && !(rc = parse_one(a, k, from, &lo)))
        rc = parse_one(a, k, to, &hi);
    if (!rc && logscale && !(lo > 0 && hi > 0))
        rc = tt_error(TT_EINVAL, "--vary %s: a log range needs positive ends", a->key);
    tt_dim dim = TT_DIM_NONE;
    char why[256];
    if (!rc && k->kind == TT_KEY_QUANTITY)
        tt_units_parse(from, k->dims, &lo, &dim, why, sizeof why);
    for (long i = 0; i < n && !rc; i++) {
        double f = n > 1 ? (double)i / (double)(n - 1) : 0;
        double v = logscale ? exp(log(lo) + f * (log(hi) - log(lo))) : lo + f * (hi - lo);
        if (i == n - 1 && n > 1)
            v = hi;
        char buf[64];
        if (k->kind == TT_KEY_INT)
            snprintf(buf, sizeof buf, "%ld", lround(v));
        else if (dim == TT_DIM_FRACTION)
            snprintf(buf, sizeof buf, "%.15g %%", v * 100);
        else
            snprintf(buf, sizeof buf, "%.15g%s%s", v, dim == TT_DIM_NONE ? "" : " ", tt_units_symbol(dim));
        char *t = trimmed(buf, strlen(buf));
        rc = t ? add_value(a, t, k->kind == TT_KEY_INT ? (double)lround(v) : v)
               : tt_error(TT_ENOMEM, "out of memory");
    }
    free(from);
    free(to);
    return rc;
}

static int add_list(axis *a, const tt_scene_key *k, const char *spec)
{
    int rc = TT_OK;
    for (const char *p = spec; !rc;) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        char *t = trimmed(p, len);
        double si;
        if (!t)
            return tt_error(TT_ENOMEM, "out of memory");
        if (!t[0]) {
            free(t);
            return tt_error(TT_EINVAL, "--vary %s: an empty value in the list", a->key);
        }
        if ((rc = parse_one(a, k, t, &si)) || (rc = add_value(a, t, si))) {
            if (rc != TT_ENOMEM)
                free(t);
            break;
        }
        if (!comma)
            break;
        p = comma + 1;
    }
    return rc;
}

int tt_sweep_vary(tt_sweep *sw, const char *spec)
{
    const char *eq = strchr(spec, '=');
    if (!eq)
        return tt_error(TT_EINVAL, "--vary %s: expected KEY=LIST or KEY=FROM:TO:N", spec);
    axis a = {0};
    if (!(a.key = trimmed(spec, (size_t)(eq - spec))))
        return tt_error(TT_ENOMEM, "out of memory");
    /* "scene": whole scene files read over the base, for what no single key says
     * (a cantilever is its stiffness, frequency and Q together) */
    a.files = strcmp(a.key, "scene") == 0;
    static const tt_scene_key file_key = {"scene", TT_KEY_STRING, 0, NULL, 0, 0, 0, NULL, "scene files"};
    const tt_scene_key *k = a.files ? &file_key : schema_key(a.key);
    int rc = TT_OK;
    for (size_t i = 0; i < sw->naxes && !rc; i++)
        if (strcmp(sw->axes[i].key, a.key) == 0)
            rc = tt_error(TT_EINVAL, "--vary %s: the key is varied twice", a.key);
    if (!rc && !k)
        rc = tt_error(TT_EINVAL, "--vary %s: unknown key (see 'tiptap keys'; named sections: "
                                 "material.NAME.key)", a.key);
    const char *v = eq + 1;
    while (isspace((unsigned char)*v))
        v++;
    int logscale = strncmp(v, "log:", 4) == 0;
    if (!rc)
        rc = (logscale || (strchr(v, ':') && !strchr(v, ','))) ? add_range(&a, k, v + (logscale ? 4 : 0), logscale)
                                                                : add_list(&a, k, v);
    axis *axes = rc ? NULL : realloc(sw->axes, (sw->naxes + 1) * sizeof *axes);
    if (!rc && !axes)
        rc = tt_error(TT_ENOMEM, "out of memory");
    if (rc) {
        axis_free(&a);
        return rc;
    }
    sw->axes = axes;
    sw->axes[sw->naxes++] = a;
    return TT_OK;
}

size_t tt_sweep_keys(const tt_sweep *sw) { return sw->naxes; }

size_t tt_sweep_count(const tt_sweep *sw)
{
    size_t n = 1;
    for (size_t k = 0; k < sw->naxes; k++)
        n *= sw->axes[k].n;
    return n;
}

const char *tt_sweep_key(const tt_sweep *sw, size_t k) { return sw->axes[k].key; }
const char *tt_sweep_unit(const tt_sweep *sw, size_t k) { return sw->axes[k].unit; }
size_t tt_sweep_levels(const tt_sweep *sw, size_t k) { return sw->axes[k].n; }

/* Nested loops, the first key outermost. */
size_t tt_sweep_level(const tt_sweep *sw, size_t i, size_t k)
{
    for (size_t j = sw->naxes; j-- > k + 1;)
        i /= sw->axes[j].n;
    return i % sw->axes[k].n;
}

const char *tt_sweep_text(const tt_sweep *sw, size_t i, size_t k)
{
    return sw->axes[k].text[tt_sweep_level(sw, i, k)];
}

double tt_sweep_value(const tt_sweep *sw, size_t i, size_t k)
{
    return sw->axes[k].si[tt_sweep_level(sw, i, k)];
}

void tt_sweep_label(const tt_sweep *sw, size_t i, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < sw->naxes && used < len; k++) {
        int w = snprintf(buf + used, len - used, "%s%s=%s", k ? ", " : "", sw->axes[k].key,
                         tt_sweep_text(sw, i, k));
        if (w < 0)
            break;
        used += (size_t)w;
    }
}

/* rc with the combination named in front of the message; the scene is freed. */
static int combination_error(const tt_sweep *sw, size_t i, tt_scene *s, int rc)
{
    char label[512], msg[1024];
    tt_sweep_label(sw, i, label, sizeof label);
    snprintf(msg, sizeof msg, "%s", tt_error_message());
    tt_scene_free(s);
    return tt_error(rc, "combination %zu (%s): %s", i + 1, label, msg);
}

/* Set key axis k of combination i as --set would. */
static int set_key(const tt_sweep *sw, size_t i, size_t k, tt_scene *s)
{
    const char *key = sw->axes[k].key, *value = tt_sweep_text(sw, i, k);
    size_t len = strlen(key) + strlen(value) + 2;
    char *set = malloc(len);
    if (!set)
        return tt_error(TT_ENOMEM, "out of memory");
    snprintf(set, len, "%s=%s", key, value);
    int rc = tt_scene_set(s, set);
    free(set);
    return rc;
}

int tt_sweep_scene(const tt_sweep *sw, size_t i, tt_scene **out)
{
    tt_scene *s = tt_scene_copy(sw->base);
    if (!s)
        return tt_error(TT_ENOMEM, "out of memory");
    /* scene files first, so that the varied keys override what they set */
    for (size_t k = 0; k < sw->naxes; k++) {
        int rc = sw->axes[k].files ? tt_scene_load(s, tt_sweep_text(sw, i, k)) : TT_OK;
        if (rc)
            return combination_error(sw, i, s, rc);
    }
    for (size_t k = 0; k < sw->naxes; k++) {
        int rc = sw->axes[k].files ? TT_OK : set_key(sw, i, k, s);
        if (rc)
            return combination_error(sw, i, s, rc);
    }
    *out = s;
    return TT_OK;
}

static unsigned long long mix(unsigned long long h, const char *s)
{
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211ULL;
    return (h ^ 0xff) * 1099511628211ULL;
}

unsigned long long tt_sweep_hash(const tt_sweep *sw, unsigned long long h)
{
    for (size_t k = 0; k < sw->naxes; k++) {
        h = mix(h, sw->axes[k].key);
        for (size_t j = 0; j < sw->axes[k].n; j++)
            h = mix(h, sw->axes[k].text[j]);
    }
    return h;
}
