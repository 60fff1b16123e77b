/**
 * @file neighbor_grid.h
 * @brief The cell grid shared by the two cell-list builders of src/core
 *        (neighbor.c: full rows by cells of candidates; neighbor_pairs.c:
 *        each pair tested once by a half stencil).  Internal to src/core.
 */
#ifndef SPALL_NEIGHBOR_GRID_H
#define SPALL_NEIGHBOR_GRID_H

#include <stddef.h>
#include <stdint.h>
#ifdef _OPENMP
#include <omp.h>
#endif

struct spall_error;

/** The binned particles: cells of edge >= the radius, numbered x fastest;
 *  inside a cell the particles ascend in index (stable counting sort). */
struct cell_grid {
    int dim;
    double lo[3];
    double inv_edge;
    long nc[3];       /**< cells per axis (1 for unused axes) */
    size_t *start;    /**< ncell+1: particles of cell c are [start[c], start[c+1]) */
    int32_t *order;   /**< sorted slot -> particle index */
    double *xs[3];    /**< positions in sorted order */
};

/** Bin particles [0, n) (positions finite, checked). */
int grid_build(struct cell_grid *g, int dim, size_t n, double *const x[3], double radius,
               struct spall_error *err);
void grid_free(struct cell_grid *g);
/** Inside a parallel region: this thread's number and the team's size
 *  (0 and 1 without OpenMP). */
static inline void neighbor_team(int *tid, int *nth)
{
    *tid = 0;
    *nth = 1;
#ifdef _OPENMP
    *tid = omp_get_thread_num();
    *nth = omp_get_num_threads();
#endif
}

/** The start of block @p t of @p nth equal blocks of [0, n). */
static inline size_t neighbor_block(size_t n, int t, int nth)
{
    return n * (size_t)t / (size_t)nth;
}

/** Inside a parallel region of nth threads, all of which call it, each
 *  with its own block [x0, x1) of the n rows: the per-thread counts
 *  cnt[t * n + x] (t < nth) of the entries each thread puts in row x
 *  become the rows' offsets v (v[0] = 0, v[x + 1] the end of row x) and
 *  each thread's cursor in row x (v[x] plus the counts of the threads
 *  before it), so that the threads fill every row in thread order.
 *  @p bsum holds nth + 1 block sums.  Integer sums: the same for any split.
 *  Ends at a barrier. */
void neighbor_row_starts(size_t *cnt, int nth, size_t n, size_t x0, size_t x1, size_t *v,
                         size_t *bsum, int tid);
/** The argument checks of every builder (dimension, radius, sizes). */
int neighbor_check_input(int dim, size_t n, double *const x[3], double radius,
                         struct spall_error *err);

/** Squared distance, written once so that every builder (and the brute
 *  force) takes exactly the same decision for every pair; it is symmetric
 *  bit for bit (x_i - x_j is exactly -(x_j - x_i)). */
static inline double pair_r2(int dim, const double *xi, double *const xs[3], size_t k)
{
    double dx = xs[0][k] - xi[0];
    double r2 = dx * dx;
    if (dim > 1) {
        double dy = xs[1][k] - xi[1];
        r2 += dy * dy;
    }
    if (dim > 2) {
        double dz = xs[2][k] - xi[2];
        r2 += dz * dz;
    }
    return r2;
}

struct neighbor_list;
/** An empty list of @p n rows (offsets zeroed) for the builders. */
int neighbor_list_alloc(struct neighbor_list **out, size_t n, struct spall_error *err);

#endif
