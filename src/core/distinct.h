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

#endif
