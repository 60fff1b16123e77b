/**
 * @file neighbor.h
 * @brief O(N) cell-list neighbour search (and its brute-force twin for tests).
 *
 * Knows nothing about physics: given positions and a radius it returns, in CSR
 * form, for every particle i the sorted list of particles j != i with
 * |x_i - x_j| < radius.  Both i->j and j->i are listed (full list), which is
 * what race-free "gather" force loops need.
 */
#ifndef SPALL_NEIGHBOR_H
#define SPALL_NEIGHBOR_H

#include <stddef.h>
#include <stdint.h>

struct spall_error;

/** Full neighbour list in CSR form. */
struct neighbor_list {
    size_t n;        /**< number of particles */
    size_t *offset;  /**< n+1 entries; neighbours of i are idx[offset[i] .. offset[i+1]) */
    int32_t *idx;    /**< partner indices, ascending per particle */
};

/** Build with a cell list, O(N) for bounded density.  x[d] are the position
 *  arrays of particles [0, n); dim in 1..3. */
int neighbor_list_build(struct neighbor_list **out, int dim, size_t n, double *const x[3],
                        double radius, struct spall_error *err);
/** Same result by the O(N^2) double loop (tests only). */
int neighbor_list_build_brute(struct neighbor_list **out, int dim, size_t n, double *const x[3],
                              double radius, struct spall_error *err);
void neighbor_list_destroy(struct neighbor_list **nl);

/** The pairs of a full list, each once: pair q = (i, j) with i < j, numbered
 *  by i, then by j ascending (so the pairs of i are the upper part of its
 *  row, in the row's order); at most UINT32_MAX pairs (4 B a slot). */
struct neighbor_pairs {
    size_t n_pairs;
    size_t *first;     /**< n+1: the pairs of i are [first[i], first[i+1]) */
    int32_t *partner;  /**< per pair: its j (> i) */
    uint32_t *slot_pair; /**< per slot of the full list: the pair it holds */
};

/** The list of neighbor_list_build (the same CSR, bit for bit) by a half
 *  stencil: each pair is tested once, the rows are put in order by two
 *  counting-sort passes instead of sorts (neighbor_pairs.c).  With @p pairs
 *  not NULL its arrays are allocated and filled (free with
 *  neighbor_pairs_free).  Positions must be finite. */
int neighbor_list_build_pairs(struct neighbor_list **out, struct neighbor_pairs *pairs, int dim,
                              size_t n, double *const x[3], double radius,
                              struct spall_error *err);
void neighbor_pairs_free(struct neighbor_pairs *pp);

#endif
