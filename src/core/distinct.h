/**
 * @file distinct.h
 * @brief A 16-bit index of n keys into the table of their distinct values:
 *        the compact storage of rest lengths (core/bond_list.c) and of the
 *        peridynamic families (models/peridynamics/pd_compact.c).  Keys are
 *        compared as bytes (bit patterns: -0.0 and 0.0 differ, as they would
 *        in the arrays they replace), so the table holds the very values.
 */
#ifndef SPALL_CORE_DISTINCT_H
#define SPALL_CORE_DISTINCT_H

#include <stddef.h>
#include <stdint.h>

struct spall_error;

/** Longest key, in bytes. */
#define DISTINCT_MAX_KEY 64

/** Writes key @p k (key_size bytes) into @p out. */
typedef void (*distinct_key_fn)(const void *ctx, size_t k, unsigned char *out);

/** Index keys 0..n-1 (each written by @p key) into their distinct values in
 *  first-seen order: idx[k] names the row of key k in *table (malloc'd,
 *  *n_distinct rows of key_size bytes).  More than @p max_distinct
 *  (<= 65536) distinct keys: *table is NULL and idx is undefined (the caller
 *  keeps its arrays).  SPALL_ERR_NOMEM when out of memory. */
int distinct_index16(distinct_key_fn key, const void *ctx, size_t n, size_t key_size,
                     size_t max_distinct, uint16_t *idx, void **table, size_t *n_distinct,
                     struct spall_error *err);

/** The same index built one key at a time, for callers that compute their
 *  keys on the fly instead of holding them in arrays (the set-up's compact
 *  bond storage, core/bond_list.c and peridynamics' pd_compact.c): adding
 *  keys 0..n-1 in order gives the rows distinct_index16 gives. */
struct distinct16;
int distinct16_create(struct distinct16 **out, size_t key_size, size_t max_distinct,
                      struct spall_error *err);
/** Row of @p key (key_size bytes), added when new; -1 when it is new and the
 *  table already holds max_distinct rows (nothing is added). */
int32_t distinct16_add(struct distinct16 *d, const unsigned char *key);
/** The table (malloc'd, *n_distinct rows; the caller frees it) taken from
 *  @p d; NULL when out of memory (the table stays with @p d). */
void *distinct16_take_table(struct distinct16 *d, size_t *n_distinct);
void distinct16_destroy(struct distinct16 **d);

#endif
