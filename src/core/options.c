/**
 * @file options.c
 * @brief Option-tree lookups, positioned error messages and the typed
 *        getters ("FILE:LINE:COL: ...; expected ...").  The YAML parser that
 *        builds the tree is io/deck.c.
 */
#include "core/options.h"

#include "spall/error.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/** Longest scalar excerpt quoted back in a message. */
#define DECK_EXCERPT 40

/* ---- small helpers ----------------------------------------------------- */

/* strcasecmp is POSIX, not C11. */
static bool deck_ieq(const char *a, const char *b)
{
    for (; *a && *b; ++a, ++b)
        if (tolower((unsigned char)*a) != tolower((unsigned char)*b))
            return false;
    return *a == *b;
}

static const char *deck_name(const struct deck_node *n)
{
    return (n && n->deck && n->deck->path) ? n->deck->path : "<deck>";
}

/* %g, unless that loses the value (so "0.50000001 > 0.5" never reads "0.5 > 0.5"). */
static void fmt_num(char *buf, size_t cap, double x)
{
    snprintf(buf, cap, "%g", x);
    if (strtod(buf, NULL) != x)
        snprintf(buf, cap, "%.17g", x);
}

/* What the user wrote, for the "; got ..." tail of a message. */
static void describe(const struct deck_node *n, char *buf, size_t cap)
{
    if (n->kind != DECK_SCALAR || deck_is_empty_value(n)) {
        snprintf(buf, cap, "%s", n->kind == DECK_MAPPING    ? "a mapping"
                                 : n->kind == DECK_SEQUENCE ? "a sequence"
                                                            : "an empty value");
        return;
    }
    size_t len = strcspn(n->scalar, "\r\n");
    bool cut = n->scalar[len] != '\0' || len > DECK_EXCERPT;
    if (len > DECK_EXCERPT)
        len = DECK_EXCERPT;
    snprintf(buf, cap, "'%.*s%s'", (int)len, n->scalar, cut ? "..." : "");
}

/* ---- errors and lookup ------------------------------------------------- */

static int vdeck_error_at(struct spall_error *err, const struct deck_node *n, int line, int col,
                          const char *fmt, va_list ap)
{
    char msg[SPALL_ERROR_MSG_LEN];
    vsnprintf(msg, sizeof msg, fmt, ap);
    deck_one_line(msg);
    if (!n)
        return spall_error_set(err, SPALL_ERR_INPUT, "%s", msg);
    return spall_error_set(err, SPALL_ERR_INPUT, "%s:%d:%d: %s", deck_name(n), line, col, msg);
}

int deck_error(struct spall_error *err, const struct deck_node *at, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = vdeck_error_at(err, at, at ? at->line : 0, at ? at->col : 0, fmt, ap);
    va_end(ap);
    return rc;
}

static long key_index(const struct deck_node *map, const char *key)
{
    if (!map || map->kind != DECK_MAPPING || !key)
        return -1;
    for (size_t i = 0; i < map->n; ++i)
        if (strcmp(map->keys[i], key) == 0)
            return (long)i;
    return -1;
}

int deck_error_key(struct spall_error *err, const struct deck_node *map, const char *key,
                   const char *fmt, ...)
{
    long i = key_index(map, key);
    int line = map ? map->line : 0, col = map ? map->col : 0;
    if (i >= 0) {
        line = map->key_line[i];
        col = map->key_col[i];
    }
    va_list ap;
    va_start(ap, fmt);
    int rc = vdeck_error_at(err, map, line, col, fmt, ap);
    va_end(ap);
    return rc;
}

const struct deck_node *deck_peek(const struct deck_node *map, const char *key)
{
    long i = key_index(map, key);
    return i >= 0 ? map->items[i] : NULL;
}

const struct deck_node *deck_get(const struct deck_node *map, const char *key)
{
    long i = key_index(map, key);
    if (i < 0)
        return NULL;
    map->used[i] = true;
    return map->items[i];
}

/* Dotted path of @p target below @p cur ("materials.epoxy", "bodies[0]"). */
static bool node_path(const struct deck_node *cur, const struct deck_node *target, char *buf,
                      size_t cap)
{
    if (cur == target)
        return true;
    if (cur->kind == DECK_SCALAR)
        return false;
    size_t len = strlen(buf);
    for (size_t i = 0; i < cur->n; ++i) {
        if (cur->kind == DECK_MAPPING)
            snprintf(buf + len, cap - len, "%s%s", len ? "." : "", cur->keys[i]);
        else
            snprintf(buf + len, cap - len, "[%zu]", i);
        if (node_path(cur->items[i], target, buf, cap))
            return true;
        buf[len] = '\0';
    }
    return false;
}

/* "'lattice'", "the top level" or "mapping": how a message names a mapping. */
static void map_name(const struct deck_node *map, char *buf, size_t cap)
{
    char path[256] = "";
    const struct deck_node *root = map->deck ? map->deck->root : NULL;
    if (root && node_path(root, map, path, sizeof path)) {
        if (path[0])
            snprintf(buf, cap, "'%s'", path);
        else
            snprintf(buf, cap, "the top level");
    } else
        snprintf(buf, cap, "mapping");
}

/* "<who> must be <want>; got <what was written>" at @p v ("expected ..." without who). */
static int type_error(struct spall_error *err, const struct deck_node *v, const char *who,
                      const char *want)
{
    char got[DECK_EXCERPT + 16];
    describe(v, got, sizeof got);
    if (!who)
        return deck_error(err, v, "expected %s; got %s", want, got);
    return deck_error(err, v, "%s must be %s; got %s", who, want, got);
}

/* "key 'k'" for the front of a message (the key is cut so buffers stay bounded). */
#define DECK_WHO_LEN 256
static void key_who(char *buf, const char *key)
{
    snprintf(buf, DECK_WHO_LEN, "key '%.200s'", key);
}

/* @p what describes the expectation ("a mapping with min and max"); NULL gives
 * plain "a mapping" / "a sequence". */
static int expect_kind(const struct deck_node *node, enum deck_kind kind, const char *what,
                       struct spall_error *err)
{
    if (!what)
        what = kind == DECK_MAPPING ? "a mapping" : "a sequence";
    if (!node)
        return spall_error_set(err, SPALL_ERR_INPUT, "missing value; expected %s", what);
    return node->kind == kind ? SPALL_OK : type_error(err, node, NULL, what);
}

int deck_expect_map(const struct deck_node *node, const char *what, struct spall_error *err)
{
    return expect_kind(node, DECK_MAPPING, what, err);
}

int deck_expect_seq(const struct deck_node *node, const char *what, struct spall_error *err)
{
    return expect_kind(node, DECK_SEQUENCE, what, err);
}

int deck_list(const struct deck_node *map, const char *key, const char *what,
              const struct deck_node **out, struct spall_error *err)
{
    *out = deck_get(map, key);
    return *out ? deck_expect_seq(*out, what, err) : SPALL_OK;
}

/* Common front of every typed getter: find (and mark) @p key and fill @p who
 * ("key 'k'", DECK_WHO_LEN bytes).  *val is NULL with SPALL_OK when the key is
 * absent and optional. */
static int lookup(const struct deck_node *map, const char *key, bool required,
                  const struct deck_node **val, char *who, struct spall_error *err)
{
    *val = NULL;
    key_who(who, key);
    if (!map)
        return required ? spall_error_set(err, SPALL_ERR_INPUT, "missing required key '%s'", key)
                        : SPALL_OK;
    if (map->kind != DECK_MAPPING) {
        char want[DECK_WHO_LEN + 32];
        snprintf(want, sizeof want, "a mapping holding key '%.200s'", key);
        return type_error(err, map, NULL, want);
    }
    *val = deck_get(map, key);
    if (*val || !required)
        return SPALL_OK;
    char name[300];
    map_name(map, name, sizeof name);
    return deck_error(err, map, "missing required key '%s' in %s (mapping at %d:%d)", key, name,
                      map->line, map->col);
}

/* ---- scalar conversion and typed getters ------------------------------- */

static bool only_space(const char *s)
{
    while (isspace((unsigned char)*s))
        ++s;
    return *s == '\0';
}

/* Whole-scalar strtod (surrounding spaces allowed). 0: ok; 1: not a number; 2: not finite. */
static int parse_double(const char *s, double *out)
{
    if (only_space(s))
        return 1;
    char *end;
    double x = strtod(s, &end);
    if (end == s || !only_space(end)) {
        /* YAML spells them .inf / -.inf / .nan: say "finite", not "number". */
        const char *t = s + strspn(s, " \t\r\n\f\v");
        t += (*t == '+' || *t == '-');
        char low[5] = {0};
        for (int i = 0; i < 4 && t[i]; ++i)
            low[i] = (char)tolower((unsigned char)t[i]);
        bool yaml_nonfinite = (!strcmp(low, ".inf") || !strcmp(low, ".nan")) && only_space(t + 4);
        return yaml_nonfinite ? 2 : 1;
    }
    if (!isfinite(x)) /* nan, inf, and overflow such as 1e999 */
        return 2;
    *out = x;
    return 0;
}

/* @p who: "key 'k'" or NULL for a bare node. */
static int node_to_double(const struct deck_node *n, const char *who, double *out,
                          struct spall_error *err)
{
    int bad = (n->kind != DECK_SCALAR || deck_is_empty_value(n)) ? 1 : parse_double(n->scalar, out);
    if (!bad)
        return SPALL_OK;
    return type_error(err, n, who, bad == 2 ? "a finite number" : "a number");
}

int deck_node_double(const struct deck_node *node, double *out, struct spall_error *err)
{
    if (!node)
        return spall_error_set(err, SPALL_ERR_INPUT, "missing value; expected a number");
    double x;
    int rc = node_to_double(node, NULL, &x, err);
    if (!rc)
        *out = x;
    return rc;
}

/* "in [a, b]", "> a", ">= a", "<= b" (infinite bounds left out). */
static void range_text(char *buf, size_t cap, const char *lo, const char *hi, bool lo_open,
                       bool has_lo, bool has_hi)
{
    if (has_lo && has_hi)
        snprintf(buf, cap, "in %s%s, %s]", lo_open ? "(" : "[", lo, hi);
    else if (has_lo)
        snprintf(buf, cap, "%s %s", lo_open ? ">" : ">=", lo);
    else
        snprintf(buf, cap, "<= %s", hi);
}

static int get_double(const struct deck_node *map, const char *key, bool required, double lo,
                      double hi, bool lo_open, double *out, struct spall_error *err)
{
    const struct deck_node *v;
    char who[DECK_WHO_LEN];
    int rc = lookup(map, key, required, &v, who, err);
    if (rc || !v)
        return rc;
    double x;
    if ((rc = node_to_double(v, who, &x, err)))
        return rc;
    bool has_lo = lo > -INFINITY, has_hi = hi < INFINITY;
    if ((has_lo && (lo_open ? !(x > lo) : !(x >= lo))) || (has_hi && !(x <= hi))) {
        char xs[32], los[32], his[32], rng[96];
        fmt_num(xs, sizeof xs, x);
        fmt_num(los, sizeof los, lo);
        fmt_num(his, sizeof his, hi);
        range_text(rng, sizeof rng, los, his, lo_open, has_lo, has_hi);
        return deck_error(err, v, "%s = %s is out of range; expected a value %s", who, xs, rng);
    }
    *out = x;
    return SPALL_OK;
}

int deck_double(const struct deck_node *map, const char *key, bool required, double lo, double hi,
                double *out, struct spall_error *err)
{
    return get_double(map, key, required, lo, hi, false, out, err);
}

int deck_double_pos(const struct deck_node *map, const char *key, bool required, double *out,
                    struct spall_error *err)
{
    return get_double(map, key, required, 0.0, INFINITY, true, out, err);
}

/* Integers: plain decimal via strtol; also "1e6" or "2.0" when exactly integral
 * (decks often write step counts that way). */
static bool parse_long(const char *s, long *out)
{
    if (only_space(s))
        return false;
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end != s && only_space(end) && errno == 0) {
        *out = v;
        return true;
    }
    double x;
    /* -(double)LONG_MIN is 2^63 exactly, the first value that does not fit. */
    if (parse_double(s, &x) == 0 && x == floor(x) && x >= (double)LONG_MIN &&
        x < -(double)LONG_MIN) {
        *out = (long)x;
        return true;
    }
    return false;
}

int deck_long(const struct deck_node *map, const char *key, bool required, long lo, long hi,
              long *out, struct spall_error *err)
{
    const struct deck_node *v;
    char who[DECK_WHO_LEN];
    int rc = lookup(map, key, required, &v, who, err);
    if (rc || !v)
        return rc;
    long x = 0;
    if (v->kind != DECK_SCALAR || deck_is_empty_value(v) || !parse_long(v->scalar, &x))
        return type_error(err, v, who, "an integer");
    bool has_lo = lo != LONG_MIN, has_hi = hi != LONG_MAX;
    if ((has_lo && x < lo) || (has_hi && x > hi)) {
        char los[32], his[32], rng[96];
        snprintf(los, sizeof los, "%ld", lo);
        snprintf(his, sizeof his, "%ld", hi);
        range_text(rng, sizeof rng, los, his, false, has_lo, has_hi);
        return deck_error(err, v, "%s = %ld is out of range; expected a value %s", who, x, rng);
    }
    *out = x;
    return SPALL_OK;
}

int deck_bool(const struct deck_node *map, const char *key, bool required, bool *out,
              struct spall_error *err)
{
    static const char *const words[] = {"false", "true", "no", "yes", "off", "on"};
    const struct deck_node *v;
    char who[DECK_WHO_LEN];
    int rc = lookup(map, key, required, &v, who, err);
    if (rc || !v)
        return rc;
    for (size_t i = 0; v->kind == DECK_SCALAR && i < 6; ++i) {
        if (deck_ieq(v->scalar, words[i])) {
            *out = (i % 2) == 1;
            return SPALL_OK;
        }
    }
    return type_error(err, v, who, "true or false (also yes/no, on/off)");
}

int deck_string(const struct deck_node *map, const char *key, bool required, const char **out,
                struct spall_error *err)
{
    const struct deck_node *v;
    char who[DECK_WHO_LEN];
    int rc = lookup(map, key, required, &v, who, err);
    if (rc || !v)
        return rc;
    if (v->kind == DECK_SCALAR && !deck_is_empty_value(v)) {
        *out = v->scalar;
        return SPALL_OK;
    }
    return type_error(err, v, who, "a string");
}

/* "a, b, c" */
static void join_list(char *buf, size_t cap, const char *const *list)
{
    size_t len = 0;
    buf[0] = '\0';
    for (size_t i = 0; list && list[i] && len < cap; ++i) {
        int w = snprintf(buf + len, cap - len, "%s%s", i ? ", " : "", list[i]);
        if (w < 0)
            break;
        len += (size_t)w;
    }
}

int deck_enum(const struct deck_node *map, const char *key, bool required,
              const char *const *choices, int *index, struct spall_error *err)
{
    const struct deck_node *v;
    char who[DECK_WHO_LEN];
    int rc = lookup(map, key, required, &v, who, err);
    if (rc || !v)
        return rc;
    char list[512], want[540];
    join_list(list, sizeof list, choices);
    if (v->kind != DECK_SCALAR || deck_is_empty_value(v)) {
        snprintf(want, sizeof want, "one of: %s", list);
        return type_error(err, v, who, want);
    }
    for (int i = 0; choices && choices[i]; ++i) {
        if (strcmp(v->scalar, choices[i]) == 0) {
            *index = i;
            return SPALL_OK;
        }
    }
    char got[DECK_EXCERPT + 16];
    describe(v, got, sizeof got);
    return deck_error(err, v, "%s = %s is not valid; expected one of: %s", who, got, list);
}

int deck_vector(const struct deck_node *map, const char *key, bool required, size_t min_len,
                size_t max_len, double *out, struct spall_error *err)
{
    const struct deck_node *v;
    char who[DECK_WHO_LEN];
    int rc = lookup(map, key, required, &v, who, err);
    if (rc || !v)
        return rc;
    char want[80];
    if (min_len == max_len)
        snprintf(want, sizeof want, "a sequence of %zu number%s", max_len, max_len == 1 ? "" : "s");
    else
        snprintf(want, sizeof want, "a sequence of %zu to %zu numbers", min_len, max_len);
    if (v->kind != DECK_SEQUENCE)
        return type_error(err, v, who, want);
    if (v->n < min_len || v->n > max_len)
        return deck_error(err, v, "%s must be %s; got %zu item%s", who, want, v->n,
                          v->n == 1 ? "" : "s");
    /* Parse every item before writing, so *out is untouched on error. */
    for (size_t i = 0; i < v->n; ++i) {
        double x;
        snprintf(who, sizeof who, "key '%.200s[%zu]'", key, i);
        if ((rc = node_to_double(v->items[i], who, &x, err)))
            return rc;
    }
    for (size_t i = 0; i < max_len; ++i) {
        out[i] = 0.0; /* missing trailing components are 0 */
        if (i < v->n)
            (void)parse_double(v->items[i]->scalar, &out[i]); /* checked above */
    }
    return SPALL_OK;
}

int deck_check_unused(const struct deck_node *map, const char *what, const char *const *allowed,
                      struct spall_error *err)
{
    if (!map || map->kind != DECK_MAPPING)
        return SPALL_OK;
    for (size_t i = 0; i < map->n; ++i) {
        /* An allowed key that this mode simply did not read is not "unknown". */
        bool known = map->used[i];
        for (size_t j = 0; allowed && allowed[j] && !known; ++j)
            known = strcmp(allowed[j], map->keys[i]) == 0;
        if (known)
            continue;
        char where[DECK_WHO_LEN] = "", list[512], tail[540] = "";
        if (what)
            snprintf(where, sizeof where, " in '%.200s'", what);
        join_list(list, sizeof list, allowed);
        if (allowed && allowed[0])
            snprintf(tail, sizeof tail, "; expected one of: %s", list);
        else if (allowed)
            snprintf(tail, sizeof tail, "; expected no keys here");
        return deck_error_key(err, map, map->keys[i], "unknown key '%s'%s%s", map->keys[i],
                              where, tail);
    }
    return SPALL_OK;
}

/* Speed of light in vacuum [m/s] (exact, SI). */
#define DECK_SPEED_OF_LIGHT 299792458.0

int deck_velocity(const struct deck_node *map, const char *key, bool required, size_t len,
                  double *out, struct spall_error *err)
{
    double v[3] = {0, 0, 0};
    if (len > 3)
        return spall_error_set(err, SPALL_ERR_INTERNAL, "deck_velocity: %zu components", len);
    int rc = deck_vector(map, key, required, len, len, v, err);
    if (rc || !deck_peek(map, key))
        return rc;
    double vmax = 0.0, s2 = 0.0; /* |v| = vmax |v / vmax|, without overflow */
    for (size_t d = 0; d < len; d++)
        vmax = fmax(vmax, fabs(v[d]));
    for (size_t d = 0; vmax > 0.0 && d < len; d++)
        s2 += (v[d] / vmax) * (v[d] / vmax);
    double speed = vmax * sqrt(s2);
    if (!(speed < DECK_SPEED_OF_LIGHT)) {
        deck_error_key(err, map, key,
                       "key '%.200s': speed %g m/s is not below the speed of light (%.9g m/s)", key,
                       speed, DECK_SPEED_OF_LIGHT);
        err->code = SPALL_ERR_PHYSICS;
        return SPALL_ERR_PHYSICS;
    }
    memcpy(out, v, len * sizeof(double));
    return SPALL_OK;
}

/* Position of the key path @p path below @p root (syntax in spall/error.h):
 * the last key's own position, or a sequence item's.  False when the deck
 * has no such key. */
static bool key_path_position(const struct deck_node *root, const char *path, int *line,
                              int *col)
{
    const struct deck_node *n = root;
    bool found = false;
    for (const char *s = path; n && *s;) {
        if (*s == '[') { /* "[k]": a sequence item */
            char *end;
            unsigned long k = strtoul(s + 1, &end, 10);
            if (end == s + 1 || *end != ']' || n->kind != DECK_SEQUENCE || k >= n->n)
                return false;
            n = n->items[k];
            *line = n->line;
            *col = n->col;
            s = end + 1;
        } else {
            size_t w = strcspn(s, ".[");
            long i = -1;
            for (size_t j = 0; n->kind == DECK_MAPPING && j < n->n && i < 0; ++j)
                if (strncmp(n->keys[j], s, w) == 0 && n->keys[j][w] == '\0')
                    i = (long)j;
            if (w == 0 || i < 0)
                return false;
            *line = n->key_line[i];
            *col = n->key_col[i];
            n = n->items[i];
            s += w;
        }
        found = true;
        if (*s == '.')
            ++s;
    }
    return found && n;
}

bool deck_locate_error(const struct deck_node *root, struct spall_error *err)
{
    int line = 0, col = 0;
    if (!root || !err || !memchr(err->key, '\0', sizeof err->key) || !err->key[0] ||
        !key_path_position(root, err->key, &line, &col))
        return false;
    const int code = err->code;
    char msg[SPALL_ERROR_MSG_LEN], key[SPALL_ERROR_KEY_LEN];
    memcpy(msg, err->msg, sizeof msg);
    msg[sizeof msg - 1] = '\0';
    memcpy(key, err->key, sizeof key);
    deck_one_line(msg);
    spall_error_set_key(err, code, key, "%s:%d:%d: %s", deck_name(root), line, col, msg);
    return true;
}

int deck_material_pair(const struct deck_node *e, char *a, char *b, size_t len,
                       struct spall_error *err)
{
    const struct deck_node *mats = deck_get(e, "materials");
    if (!mats)
        return deck_error(err, e, "interface: missing required key 'materials' ([a, b])");
    if (mats->kind != DECK_SEQUENCE || mats->n != 2 || mats->items[0]->kind != DECK_SCALAR ||
        mats->items[1]->kind != DECK_SCALAR)
        return deck_error(err, mats, "interface materials: expected two material names [a, b]");
    snprintf(a, len, "%s", mats->items[0]->scalar);
    snprintf(b, len, "%s", mats->items[1]->scalar);
    if (strcmp(a, b) == 0)
        return deck_error(err, mats, "interface materials: '%s' twice (an interface joins two "
                          "different materials)", a);
    return SPALL_OK;
}
