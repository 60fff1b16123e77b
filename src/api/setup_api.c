/**
 * @file setup_api.c
 * @brief include/spall/setup.h: settings given by C calls, kept as the
 *        option tree of core/options.h that the YAML reader would have
 *        built from the equivalent deck, so that the deck builder
 *        (io/deck_build.c) checks and builds them as it builds a deck.
 *
 * Each node's "line" is the number of the setter call that made it (column
 * 1): the builder's "FILE:LINE:COL:" messages then point at that call.
 */
#include "spall/setup.h"

#include "api/setup_internal.h"
#include "core/options.h"
#include "io/deck.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/** Shown as the file name in the builder's messages. */
#define SETUP_NAME "spall_setup"

struct spall_setup {
    struct deck *deck; /**< root: a mapping; nodes allocated as io/deck.c does */
    int calls;         /**< setter calls so far */
};

static char *dup_text(const char *s)
{
    if (!s)
        return NULL;
    size_t len = strlen(s);
    char *p = malloc(len + 1);
    if (p)
        memcpy(p, s, len + 1);
    return p;
}

static struct deck_node *node_new(const struct spall_setup *s, enum deck_kind kind)
{
    struct deck_node *n = calloc(1, sizeof *n);
    if (!n)
        return NULL;
    n->kind = kind;
    n->line = s->calls;
    n->col = 1;
    n->deck = s->deck;
    return n;
}

/* Append a child (with @p key for a mapping); false when out of memory,
 * @p child then still belongs to the caller. */
static bool node_append(struct deck_node *n, const char *key, struct deck_node *child, int line)
{
    size_t cap = n->n + 1;
    struct deck_node **items = realloc(n->items, cap * sizeof *items);
    if (!items)
        return false;
    n->items = items;
    if (n->kind == DECK_MAPPING) {
        char **keys = realloc(n->keys, cap * sizeof *keys);
        if (keys)
            n->keys = keys;
        int *kl = keys ? realloc(n->key_line, cap * sizeof *kl) : NULL;
        if (kl)
            n->key_line = kl;
        int *kc = kl ? realloc(n->key_col, cap * sizeof *kc) : NULL;
        if (kc)
            n->key_col = kc;
        bool *used = kc ? realloc(n->used, cap * sizeof *used) : NULL;
        if (used)
            n->used = used;
        char *k = used ? dup_text(key) : NULL;
        if (!k)
            return false;
        n->keys[n->n] = k;
        n->key_line[n->n] = line;
        n->key_col[n->n] = 1;
        n->used[n->n] = false;
    }
    n->items[n->n++] = child;
    return true;
}

int spall_setup_create(struct spall_setup **out, struct spall_error *err)
{
    if (!out)
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_setup_create: out is NULL");
    *out = NULL;
    struct spall_setup *s = calloc(1, sizeof *s);
    if (s && (s->deck = calloc(1, sizeof *s->deck)) && (s->deck->path = dup_text(SETUP_NAME)) &&
        (s->deck->root = node_new(s, DECK_MAPPING))) {
        s->deck->root->line = 1;
        *out = s;
        return SPALL_OK;
    }
    spall_setup_destroy(&s);
    return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory creating a setup");
}

void spall_setup_destroy(struct spall_setup **s)
{
    if (!s || !*s)
        return;
    if ((*s)->deck) {
        deck_node_free((*s)->deck->root);
        (*s)->deck->root = NULL;
        deck_destroy(&(*s)->deck);
    }
    free(*s);
    *s = NULL;
}

/* ---------------------------------------------------------------- key paths */

/** One step of a key path: a mapping key or a sequence index. */
struct segment {
    char key[SPALL_ERROR_KEY_LEN];
    long index; /**< >= 0: "[index]"; -1: key */
};

/* Read the segment at *p ("name" up to '.', '[' or the end, or "[k]"),
 * advancing *p past it and a following '.'. */
static bool next_segment(const char **p, struct segment *seg)
{
    const char *c = *p;
    if (*c == '[') {
        char *end = NULL;
        seg->index = strtol(c + 1, &end, 10);
        if (end == c + 1 || *end != ']' || seg->index < 0 || c[1] == '+' || c[1] == '-')
            return false;
        c = end + 1;
        if (*c && *c != '.' && *c != '[')
            return false;
    } else {
        size_t len = strcspn(c, ".[");
        if (len == 0 || len >= sizeof seg->key)
            return false;
        memcpy(seg->key, c, len);
        seg->key[len] = '\0';
        seg->index = -1;
        c += len;
    }
    if (*c == '.') {
        c++;
        if (!*c || *c == '.' || *c == '[')
            return false;
    }
    *p = c;
    return true;
}

/* The node the path @p key leads to, creating the mappings and sequences on
 * the way; *slot is where the leaf node goes (an existing leaf is freed by
 * the caller's replacement).  Kinds: the next segment decides a missing
 * node's kind (a key: mapping, an index: sequence). */
static int walk(struct spall_setup *s, const char *key, bool create, struct deck_node ***slot,
                struct spall_error *err)
{
    if (!key || !key[0])
        return spall_error_set(err, SPALL_ERR_INPUT, "spall_setup: empty key path");
    const char *p = key;
    struct segment seg;
    if (!next_segment(&p, &seg) || seg.index >= 0)
        return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                   "spall_setup: bad key path '%.100s'; expected keys joined by "
                                   "'.', a list item as [k] after its key",
                                   key);
    struct deck_node **at = &s->deck->root;
    for (;;) {
        struct deck_node *cur = *at;
        enum deck_kind want = seg.index >= 0 ? DECK_SEQUENCE : DECK_MAPPING;
        if (cur->kind != want)
            return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                       "spall_setup: key path '%.100s' goes through a value "
                                       "that is not a %s",
                                       key, want == DECK_SEQUENCE ? "list" : "mapping");
        size_t i = 0;
        if (seg.index >= 0) {
            if ((size_t)seg.index > cur->n)
                return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                           "spall_setup: '%.100s': item %ld of a list of %zu "
                                           "(append with index %zu)",
                                           key, seg.index, cur->n, cur->n);
            i = (size_t)seg.index;
        } else {
            while (i < cur->n && strcmp(cur->keys[i], seg.key) != 0)
                i++;
        }
        const char *rest = p;
        struct segment next = {.index = -1};
        bool leaf = !*rest;
        if (!leaf && !next_segment(&rest, &next))
            return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                       "spall_setup: bad key path '%.100s'", key);
        if (i == cur->n && !create) {
            /* a dry run (nothing changes when a path is refused): the rest
             * of the path is new, so its lists are empty */
            while (!leaf) {
                if (next.index > 0)
                    return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                               "spall_setup: '%.100s': item %ld of a new list "
                                               "(append with index 0)",
                                               key, next.index);
                leaf = !*rest;
                if (!leaf && !next_segment(&rest, &next))
                    return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                               "spall_setup: bad key path '%.100s'", key);
            }
            return SPALL_OK;
        }
        if (i == cur->n) {
            /* a new child: an empty scalar for a leaf (the caller
             * replaces it), else the container the next segment needs */
            enum deck_kind kind = leaf                ? DECK_SCALAR
                                  : next.index >= 0 ? DECK_SEQUENCE
                                                    : DECK_MAPPING;
            struct deck_node *child = node_new(s, kind);
            if (child && kind == DECK_SCALAR)
                child->scalar = dup_text("");
            if (!child || (kind == DECK_SCALAR && !child->scalar) ||
                !node_append(cur, seg.key, child, s->calls)) {
                deck_node_free(child);
                return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory setting '%.100s'",
                                       key);
            }
        }
        at = &cur->items[i];
        if (leaf) {
            *slot = at;
            return SPALL_OK;
        }
        p = rest;
        seg = next;
    }
}

/* Put @p value (a new node, owned here from now on) at @p key. */
static int set_node(struct spall_setup *s, const char *key, struct deck_node *value,
                    struct spall_error *err)
{
    struct deck_node **slot = NULL;
    int rc = walk(s, key, false, &slot, err);
    if (!rc)
        rc = walk(s, key, true, &slot, err);
    if (rc) {
        deck_node_free(value);
        return rc;
    }
    deck_node_free(*slot);
    *slot = value;
    return SPALL_OK;
}

static struct deck_node *scalar_new(const struct spall_setup *s, const char *text)
{
    struct deck_node *n = node_new(s, DECK_SCALAR);
    if (n && !(n->scalar = dup_text(text))) {
        free(n);
        n = NULL;
    }
    return n;
}

static int nomem(const char *key, struct spall_error *err)
{
    return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory setting '%.100s'", key);
}

static bool fmt_number(char *buf, size_t cap, double v)
{
    return isfinite(v) && snprintf(buf, cap, "%.17g", v) > 0;
}

static int check_handle(const struct spall_setup *s, const char *who, const char *key,
                        struct spall_error *err)
{
    if (!s)
        return spall_error_set(err, SPALL_ERR_INPUT, "%s: setup is NULL", who);
    if (!key)
        return spall_error_set(err, SPALL_ERR_INPUT, "%s: key is NULL", who);
    return SPALL_OK;
}

int spall_setup_number(struct spall_setup *s, const char *key, double value,
                       struct spall_error *err)
{
    int rc = check_handle(s, "spall_setup_number", key, err);
    if (rc)
        return rc;
    char buf[40];
    if (!fmt_number(buf, sizeof buf, value))
        return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                   "spall_setup_number: '%.100s' = %g is not a finite number",
                                   key, value);
    s->calls++;
    struct deck_node *n = scalar_new(s, buf);
    return n ? set_node(s, key, n, err) : nomem(key, err);
}

int spall_setup_text(struct spall_setup *s, const char *key, const char *value,
                     struct spall_error *err)
{
    int rc = check_handle(s, "spall_setup_text", key, err);
    if (rc)
        return rc;
    if (!value)
        return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                   "spall_setup_text: value of '%.100s' is NULL", key);
    s->calls++;
    struct deck_node *n = scalar_new(s, value);
    return n ? set_node(s, key, n, err) : nomem(key, err);
}

/* A list of @p n scalars: numbers from @p nums, else words from @p words. */
static int set_list(struct spall_setup *s, const char *key, const double *nums,
                    const char *const *words, size_t n, struct spall_error *err)
{
    if (n > 0 && !nums && !words)
        return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                   "spall_setup: values of '%.100s' are NULL", key);
    s->calls++;
    struct deck_node *seq = node_new(s, DECK_SEQUENCE);
    if (!seq)
        return nomem(key, err);
    for (size_t k = 0; k < n; k++) {
        char buf[40];
        const char *text = buf;
        if (nums && !fmt_number(buf, sizeof buf, nums[k])) {
            deck_node_free(seq);
            return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                       "spall_setup_numbers: '%.100s' item %zu is not finite",
                                       key, k);
        }
        if (!nums)
            text = words[k];
        if (!text) {
            deck_node_free(seq);
            return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                       "spall_setup_texts: '%.100s' item %zu is NULL", key, k);
        }
        struct deck_node *item = scalar_new(s, text);
        if (!item || !node_append(seq, NULL, item, s->calls)) {
            deck_node_free(item);
            deck_node_free(seq);
            return nomem(key, err);
        }
    }
    return set_node(s, key, seq, err);
}

int spall_setup_numbers(struct spall_setup *s, const char *key, const double *values, size_t n,
                        struct spall_error *err)
{
    int rc = check_handle(s, "spall_setup_numbers", key, err);
    return rc ? rc : set_list(s, key, values, NULL, n, err);
}

int spall_setup_texts(struct spall_setup *s, const char *key, const char *const *values,
                      size_t n, struct spall_error *err)
{
    int rc = check_handle(s, "spall_setup_texts", key, err);
    if (!rc && n > 0 && !values)
        return spall_error_set_key(err, SPALL_ERR_INPUT, key,
                                   "spall_setup_texts: values of '%.100s' are NULL", key);
    return rc ? rc : set_list(s, key, NULL, values, n, err);
}

size_t spall_setup_length(const struct spall_setup *s, const char *key)
{
    if (!s || !key)
        return 0;
    const struct deck_node *cur = s->deck->root;
    const char *p = key;
    struct segment seg;
    while (*p) {
        if (!next_segment(&p, &seg) || cur->kind == DECK_SCALAR)
            return 0;
        size_t i = 0;
        if (seg.index >= 0) {
            if (cur->kind != DECK_SEQUENCE || (size_t)seg.index >= cur->n)
                return 0;
            i = (size_t)seg.index;
        } else {
            if (cur->kind != DECK_MAPPING)
                return 0;
            while (i < cur->n && strcmp(cur->keys[i], seg.key) != 0)
                i++;
            if (i == cur->n)
                return 0;
        }
        cur = cur->items[i];
    }
    return cur->kind == DECK_SCALAR ? 0 : cur->n;
}

/* ---------------------------------------------------------------- copies */

static struct deck_node *node_copy(const struct deck_node *n, const struct deck *d)
{
    struct deck_node *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->kind = n->kind;
    c->line = n->line;
    c->col = n->col;
    c->quoted = n->quoted;
    c->deck = d;
    if (n->scalar && !(c->scalar = dup_text(n->scalar))) {
        free(c);
        return NULL;
    }
    for (size_t i = 0; i < n->n; i++) {
        struct deck_node *item = node_copy(n->items[i], d);
        if (!item || !node_append(c, n->keys ? n->keys[i] : NULL, item,
                                  n->key_line ? n->key_line[i] : n->line)) {
            deck_node_free(item);
            deck_node_free(c);
            return NULL;
        }
    }
    return c;
}

int setup_deck_copy(const struct spall_setup *s, struct deck **out, struct spall_error *err)
{
    *out = NULL;
    struct deck *d = calloc(1, sizeof *d);
    if (d && (d->path = dup_text(SETUP_NAME)) && (d->root = node_copy(s->deck->root, d))) {
        *out = d;
        return SPALL_OK;
    }
    deck_destroy(&d);
    return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory copying a setup");
}
