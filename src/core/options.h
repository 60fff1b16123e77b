/**
 * @file options.h
 * @brief The options interface models and the core read their settings
 *        through: a tree of mappings, sequences and scalars that remembers
 *        the file, line and column of every node, plus typed getters whose
 *        errors name file:line:column and what was expected.
 *
 * The tree is built by the YAML reader (io/deck.h, libyaml) or by anything
 * else that fills these structs; nothing here knows about YAML.  Every
 * mapping key remembers whether it was read.  After a section is parsed,
 * deck_check_unused() reports the first key nobody asked for as "unknown
 * key", listing the keys that are allowed there.  Error messages have the form
 *     FILE:LINE:COL: <what is wrong>; expected <what>
 * (line and column 1-based).  Status is SPALL_ERR_INPUT for all of them.
 */
#ifndef SPALL_OPTIONS_H
#define SPALL_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>

struct spall_error;

enum deck_kind { DECK_SCALAR, DECK_SEQUENCE, DECK_MAPPING };

struct deck_node {
    enum deck_kind kind;
    int line, col;             /**< 1-based position of the node's start */
    char *scalar;              /**< DECK_SCALAR: the text */
    bool quoted;               /**< scalar was quoted (so "1" is a string) */
    size_t n;                  /**< children (sequence items or mapping pairs) */
    struct deck_node **items;  /**< sequence items / mapping values */
    char **keys;               /**< mapping keys (n of them) */
    int *key_line, *key_col;   /**< position of each key */
    bool *used;                /**< mapping: key was read by a getter */
    const struct deck *deck;   /**< back pointer for file name in messages */
};

/** A whole document: the file it came from and its root node. */
struct deck {
    char *path;                /**< file name used in messages */
    char *text;                /**< the whole file (for the run log echo) */
    struct deck_node *root;    /**< NULL for an empty document */
};

/* Messages are one line (the CLI prints exactly one): a key or value holding
 * a newline or tab must not break that. */
static inline void deck_one_line(char *msg)
{
    for (; *msg; ++msg)
        if ((unsigned char)*msg < 0x20)
            *msg = ' ';
}

/* An unquoted empty value ("key:" with nothing after it). */
static inline bool deck_is_empty_value(const struct deck_node *n)
{
    return n->kind == DECK_SCALAR && !n->quoted && n->scalar[0] == '\0';
}


/** Formats "FILE:LINE:COL: " + message, sets SPALL_ERR_INPUT, returns it. */
int deck_error(struct spall_error *err, const struct deck_node *at, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/** Same, positioned at key @p key of mapping @p map (falls back to the map). */
int deck_error_key(struct spall_error *err, const struct deck_node *map, const char *key,
                   const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/** Lookup without marking (NULL if absent or @p map is not a mapping). */
const struct deck_node *deck_peek(const struct deck_node *map, const char *key);
/** Lookup and mark the key as used. */
const struct deck_node *deck_get(const struct deck_node *map, const char *key);

/** Require @p node to be a mapping / sequence ("expected a mapping"). */
int deck_expect_map(const struct deck_node *node, const char *what, struct spall_error *err);
int deck_expect_seq(const struct deck_node *node, const char *what, struct spall_error *err);
/** The optional list section @p key of @p map (marked used): *out is the
 *  sequence, or NULL when the key is absent; a present key that is not a
 *  sequence is an error naming @p what (e.g. "a list of pre-cracks").  The
 *  front of every "parse a list of mappings" loop. */
int deck_list(const struct deck_node *map, const char *key, const char *what,
              const struct deck_node **out, struct spall_error *err);

/*
 * Typed getters.  `required` true: a missing key is an error
 * ("missing required key 'k' in <map position>"); false: *out keeps its
 * default.  Range checks: value must be within [lo, hi]; pass -INFINITY /
 * INFINITY for no bound.  Messages name the key, the value and the range.
 * A present key is marked used even when its value is bad.
 */
int deck_double(const struct deck_node *map, const char *key, bool required, double lo, double hi,
                double *out, struct spall_error *err);
/** Like deck_double but the bound is exclusive on the low side (e.g. > 0). */
int deck_double_pos(const struct deck_node *map, const char *key, bool required, double *out,
                    struct spall_error *err);
int deck_long(const struct deck_node *map, const char *key, bool required, long lo, long hi,
              long *out, struct spall_error *err);
int deck_bool(const struct deck_node *map, const char *key, bool required, bool *out,
              struct spall_error *err);
/** *out points into the tree (valid while the deck lives). */
int deck_string(const struct deck_node *map, const char *key, bool required, const char **out,
                struct spall_error *err);
/** One of @p choices (NULL-terminated); *index is the position. Error lists them. */
int deck_enum(const struct deck_node *map, const char *key, bool required,
              const char *const *choices, int *index, struct spall_error *err);
/** Fixed-length numeric vector, e.g. a point [x, y] or [x, y, z].  Accepts
 *  between @p min_len and @p max_len numbers; missing trailing components are 0. */
int deck_vector(const struct deck_node *map, const char *key, bool required, size_t min_len,
                size_t max_len, double *out, struct spall_error *err);
/** A velocity [m/s] of @p len components (deck_vector); refused with
 *  SPALL_ERR_PHYSICS when its magnitude is not below the speed of light. */
int deck_velocity(const struct deck_node *map, const char *key, bool required, size_t len,
                  double *out, struct spall_error *err);
/** Point an error raised below the deck at the key it names (err->key, a key
 *  path such as "run.dt" or "bodies[2].lattice.type", see spall/error.h):
 *  the message becomes "file:line:col: message" at that key of the deck under
 *  @p root, code and key kept.  False, @p err untouched, when it names no key
 *  or the deck has no such key. */
bool deck_locate_error(const struct deck_node *root, struct spall_error *err);

/** Scalar node -> double, with the node's position in errors. */
int deck_node_double(const struct deck_node *node, double *out, struct spall_error *err);

/** The `materials: [a, b]` of an entry @p e that joins two different
 *  materials (model.interfaces of the peridynamics and lattice models): the
 *  names into @p a and @p b (@p len bytes each), refused with a position when
 *  missing, not two names, or the same name twice. */
int deck_material_pair(const struct deck_node *e, char *a, char *b, size_t len,
                       struct spall_error *err);

/** Report the first unused key of @p map as
 *  "FILE:L:C: unknown key 'k' in <what>; expected one of: a, b, c"
 *  where @p allowed lists the valid keys (NULL-terminated). */
int deck_check_unused(const struct deck_node *map, const char *what, const char *const *allowed,
                      struct spall_error *err);

#endif
