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

#endif
