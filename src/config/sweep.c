/* Parameter grids over scene keys (see include/tiptap/config/sweep.h). */
#include "tiptap/config/sweep.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tiptap/config/config.h"
#include "tiptap/util/error.h"

typedef struct {
    char *key;              /* as given: section.key or section.NAME.key */
    char unit[16];          /* SI unit of the values; "" for text */
    size_t n, cap;          /* values, and room for them */
    char **text;            /* as set in the scene */
    double *si;             /* SI values, NAN for text */
    int files;              /* the values are scene files to read, not values of a key */
} axis;

struct tt_sweep {
    const tt_scene *base;
    axis *axes;
    size_t naxes;
};

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && strcmp(s + n - m, tail) == 0;
}

int tt_sweep_viscous(const tt_sweep *sw)
{
    for (size_t k = 0; k < sw->naxes; k++)
        if (ends_with(sw->axes[k].key, ".viscosity") || ends_with(sw->axes[k].key, ".film_thickness") ||
            (ends_with(sw->axes[k].key, "_modulus") && strstr(sw->axes[k].key, ".arm")))
            return 1;
    tt_material *m = NULL;
    size_t n = 0;
    int viscous = 0;
    if (tt_config_materials(sw->base, &m, &n) == TT_OK)
        for (size_t i = 0; i < n; i++)
            viscous |= tt_material_viscous(&m[i]);
    else
        tt_error_clear();
    free(m);
    return viscous;
}

int tt_sweep_bimodal(const tt_sweep *sw)
{
    for (size_t k = 0; k < sw->naxes; k++)
        if (strcmp(sw->axes[k].key, "cantilever.mode2_free_amplitude") == 0)
            return 1;
    return tt_scene_has(sw->base, "cantilever", NULL, "mode2_free_amplitude");
}

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
    /* room doubled as needed: a range of millions of values is not copied per value */
    size_t cap = a->n < a->cap ? a->cap : 2 * a->cap + 8;
    char **t = cap == a->cap ? a->text : realloc(a->text, cap * sizeof *t);
    if (t)
        a->text = t;
    double *v = !t ? NULL : cap == a->cap ? a->si : realloc(a->si, cap * sizeof *v);
    if (!v) {
        free(text);
        return tt_error(TT_ENOMEM, "out of memory");
    }
    a->si = v;
    a->cap = cap;
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
        errno = 0;
        long long v = strtoll(text, &end, 10);
        snprintf(a->unit, sizeof a->unit, "1");
        if (*end || end == text)
            return tt_error(TT_EINVAL, "--vary %s: '%s' is not a whole number", a->key, text);
        /* within 2^53, so that the SI column and the range steps hold it exactly */
        if (errno == ERANGE || llabs(v) > (1LL << 53))
            return tt_error(TT_EINVAL, "--vary %s: '%s' is too large a whole number (at most 2^53 in size)",
                            a->key, text);
        *si = (double)v;
        return TT_OK;
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

/* Why a range FROM:TO:N cannot give N distinct values, or NULL: one value needs
 * FROM = TO (else TO would be dropped), several need FROM != TO, and a whole-number
 * key has only |TO - FROM| + 1 values to give. */
static const char *range_fault(double lo, double hi, long n, int whole, char *buf, size_t len)
{
    if (n == 1 && lo != hi)
        return "FROM:TO:1 is one value, so TO would be dropped; write the one value, or N from 2";
    if (n > 1 && lo == hi)
        return "FROM equals TO, so the N values would all be alike; write the one value";
    if (whole && (double)n > fabs(hi - lo) + 1) {
        snprintf(buf, len, "%ld whole numbers from %.0f to %.0f would repeat values (there are %.0f); "
                 "N at most %.0f", n, lo, hi, fabs(hi - lo) + 1, fabs(hi - lo) + 1);
        return buf;
    }
    return NULL;
}

/* Value i of the n whole numbers evenly spaced from lo to hi (|lo|, |hi| <= 2^53),
 * rounded, exactly: the offset i (hi - lo) / (n - 1) is split into whole steps and a
 * remainder, so that no product overflows. */
static long long whole_value(long long lo, long long hi, long i, long n)
{
    if (n < 2)
        return lo;
    unsigned long long span = (unsigned long long)(hi >= lo ? hi - lo : lo - hi), m = (unsigned long long)(n - 1);
    unsigned long long u = (unsigned long long)i;
    long long off = (long long)(u * (span / m) + (u * (span % m) + m / 2) / m);
    return hi >= lo ? lo + off : lo - off;
}

/* Value i of n evenly spaced from lo to hi (in the logarithm: logscale), TO exactly
 * at the end; halved ends where TO - FROM itself overflows (-1e308 to 1e308). */
static double range_value(double lo, double hi, long i, long n, int logscale)
{
    if (i == n - 1 && n > 1)
        return hi;
    double f = n > 1 ? (double)i / (double)(n - 1) : 0;
    if (logscale)
        return exp(log(lo) + f * (log(hi) - log(lo)));
    return isfinite(hi - lo) ? lo + f * (hi - lo) : 2 * (lo / 2 + f * (hi / 2 - lo / 2));
}

/* FROM:TO:N (log: evenly in the logarithm), each value written back in SI so that the
 * scene reads exactly the number computed here. A range gives N distinct finite values
 * or is refused (range_fault; two values alike once written at 15 digits). */
static int add_range(axis *a, const tt_scene_key *k, const char *spec, int logscale)
{
    const char *c1 = strchr(spec, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c2 || strchr(c2 + 1, ':') || (k->kind != TT_KEY_QUANTITY && k->kind != TT_KEY_INT))
        return tt_error(TT_EINVAL, "--vary %s: a range is FROM:TO:N of a number-valued key", a->key);
    char *from = trimmed(spec, (size_t)(c1 - spec)), *to = trimmed(c1 + 1, (size_t)(c2 - c1 - 1));
    char *count = trimmed(c2 + 1, strlen(c2 + 1)), *end = NULL, why[256];
    errno = 0;
    /* digits only, as spec_levels counts them ("+5" would pass it as one value) */
    long n = count && isdigit((unsigned char)count[0]) ? strtol(count, &end, 10) : 0;
    double lo, hi;
    int whole = k->kind == TT_KEY_INT;
    int rc = (!from || !to || !count) ? tt_error(TT_ENOMEM, "out of memory") : TT_OK;
    if (!rc && (!end || *end || errno == ERANGE || n < 1 || n > TT_SWEEP_MAX_COMBINATIONS))
        rc = tt_error(TT_EINVAL, "--vary %s: N in FROM:TO:N must be a whole number from 1 to %d", a->key,
                      TT_SWEEP_MAX_COMBINATIONS);
    if (!rc && !(rc = parse_one(a, k, from, &lo)))
        rc = parse_one(a, k, to, &hi);
    if (!rc && logscale && !(lo > 0 && hi > 0))
        rc = tt_error(TT_EINVAL, "--vary %s: a log range needs positive ends", a->key);
    const char *fault = rc ? NULL : range_fault(lo, hi, n, whole, why, sizeof why);
    if (fault)
        rc = tt_error(TT_EINVAL, "--vary %s=%s%s: %s", a->key, logscale ? "log:" : "", spec, fault);
    tt_dim dim = TT_DIM_NONE;
    if (!rc && k->kind == TT_KEY_QUANTITY)
        tt_units_parse(from, k->dims, &lo, &dim, why, sizeof why);
    for (long i = 0; i < n && !rc; i++) {
        double v = whole ? (double)whole_value((long long)lo, (long long)hi, i, n) : range_value(lo, hi, i, n, logscale);
        char buf[64];
        if (!isfinite(v))
            rc = tt_error(TT_EINVAL, "--vary %s=%s%s: value %ld is not a finite number", a->key,
                          logscale ? "log:" : "", spec, i + 1);
        else if (whole)
            snprintf(buf, sizeof buf, "%.0f", v);
        else if (dim == TT_DIM_FRACTION)
            snprintf(buf, sizeof buf, "%.15g %%", v * 100);
        else
            snprintf(buf, sizeof buf, "%.15g%s%s", v, dim == TT_DIM_NONE ? "" : " ", tt_units_symbol(dim));
        char *t = rc ? NULL : trimmed(buf, strlen(buf));
        if (!rc && t && a->n > 0 && strcmp(t, a->text[a->n - 1]) == 0) {
            rc = tt_error(TT_EINVAL, "--vary %s=%s%s: values %ld and %ld are both '%s': the range holds "
                          "fewer than N distinct values at 15 significant digits", a->key,
                          logscale ? "log:" : "", spec, i, i + 1, t);
            free(t);
        } else if (!rc)
            rc = t ? add_value(a, t, v) : tt_error(TT_ENOMEM, "out of memory");
    }
    free(from);
    free(to);
    free(count);
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

/* spec as messages show it: control characters escaped (\x0a), no more than about 60
 * bytes of it, so that a refusal stays one short line. */
static void shown(const char *spec, char *buf, size_t len)
{
    size_t used = 0, in = 0;
    for (; spec[in] && used + 8 < len && in < 60; in++) {
        unsigned char c = (unsigned char)spec[in];
        used += (size_t)snprintf(buf + used, len - used, c < 0x20 || c == 0x7f ? "\\x%02x" : "%c", c);
    }
    snprintf(buf + used, len - used, "%s", spec[in] ? "..." : "");
}

/* The values a specification gives, from its form alone, as an exact count (0 when
 * beyond 64 bits) and its decimal logarithm: a range's N of any length, a list's items.
 * A malformed form counts 1: tt_sweep_vary refuses it with its own reason. */
static unsigned long long spec_levels(const char *spec, double *lg)
{
    const char *v = strchr(spec, '=');
    *lg = 0;
    if (!v)
        return 1;
    for (v++; isspace((unsigned char)*v);)
        v++;
    if (strncmp(v, "log:", 4) != 0 && !(strchr(v, ':') && !strchr(v, ','))) {
        unsigned long long items = 1;
        for (const char *p = v; (p = strchr(p, ',')); p++)
            items++;
        *lg = log10((double)items);
        return items;
    }
    const char *d = strrchr(v, ':') + 1, *e;
    while (isspace((unsigned char)*d) || *d == '0')
        d++;
    for (e = d; isdigit((unsigned char)*e);)
        e++;
    size_t nd = (size_t)(e - d), lead = nd < 15 ? nd : 15;
    while (isspace((unsigned char)*e))
        e++;
    if (*e || nd == 0)
        return 1;
    char head[16];
    memcpy(head, d, lead);
    head[lead] = '\0';
    *lg = log10(strtod(head, NULL)) + (double)(nd - lead);
    errno = 0;
    unsigned long long n = strtoull(d, NULL, 10);
    return errno == ERANGE ? 0 : n;
}

/* A grid's count for messages: exact when it fits in 64 bits (exact != 0), else from
 * its decimal logarithm lg as a power of ten and of two. */
static void count_text(unsigned long long exact, double lg, char *buf, size_t len)
{
    if (exact)
        snprintf(buf, len, "%llu", exact);
    else if (lg < 300)
        snprintf(buf, len, "%.2g (about 2^%.0f)", pow(10, lg), lg / log10(2));
    else
        snprintf(buf, len, "about 10^%.0f", lg);
}

int tt_sweep_check_size(const char *const *specs, size_t n)
{
    unsigned long long exact = 1;
    double lg = 0;
    int over = 0;
    for (size_t i = 0; i < n; i++) {
        double l;
        unsigned long long c = spec_levels(specs[i], &l);
        lg += l;
        if (!c || __builtin_mul_overflow(exact, c, &exact))
            over = 1;
    }
    if (!over && exact <= TT_SWEEP_MAX_COMBINATIONS)
        return TT_OK;
    char msg[768], one[80], count[64];
    size_t used = 0;
    for (size_t i = 0; i < n && used < sizeof msg; i++) {
        shown(specs[i], one, sizeof one);
        used += (size_t)snprintf(msg + used, sizeof msg - used, "%s--vary %s", i ? " " : "", one);
    }
    count_text(over ? 0 : exact, lg, count, sizeof count);
    return tt_error(TT_EINVAL, "%s: %s combinations, more than the %d a sweep may have; vary fewer "
                               "keys or fewer values", msg, count, TT_SWEEP_MAX_COMBINATIONS);
}

static int set_key(const tt_sweep *sw, size_t i, size_t k, tt_scene *s);

/* The files axis k makes the sweep read, noted as inputs (tt_config_note_inputs) when
 * it is added, before anything runs: each scene file varied, and the maps a varied
 * path key names, so that no output of the run (Python's hdf5= included) replaces one.
 * The axis is the last one, so its level l is combination l. */
static void note_inputs(const tt_sweep *sw, size_t k, const tt_scene_key *key)
{
    if (!sw->axes[k].files && !(key->flags & TT_KEY_PATH))
        return;
    for (size_t l = 0; l < sw->axes[k].n; l++) {
        tt_scene *c = tt_scene_copy(sw->base);
        if (c && (sw->axes[k].files ? tt_scene_load(c, tt_sweep_text(sw, l, k)) : set_key(sw, l, k, c)) == TT_OK)
            tt_config_note_inputs(c);
        tt_scene_free(c);
    }
}

int tt_sweep_vary(tt_sweep *sw, const char *spec)
{
    char show[80];
    for (const char *p = spec; *p; p++)
        if ((unsigned char)*p < 0x20 || *p == 0x7f) {
            shown(spec, show, sizeof show);
            return tt_error(TT_EINVAL, "--vary %s: control character \\x%02x; expected KEY=VALUES on one line",
                            show, (unsigned char)*p);
        }
    double lg;
    unsigned long long more = spec_levels(spec, &lg), now = tt_sweep_count(sw), total = 0;
    int over = !more || __builtin_mul_overflow(now, more, &total);
    if (over || total > TT_SWEEP_MAX_COMBINATIONS) {
        char count[64];
        shown(spec, show, sizeof show);
        count_text(over ? 0 : total, lg + log10((double)now), count, sizeof count);
        return tt_error(TT_EINVAL, "--vary %s: the grid would have %s combinations, more than the %d a "
                                   "sweep may have", show, count, TT_SWEEP_MAX_COMBINATIONS);
    }
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
    note_inputs(sw, sw->naxes - 1, k);
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
