/**
 * @file neighbor_pairs.c
 * @brief The full neighbour list of neighbor.c built with each pair tested
 *        once (a half stencil, as LAMMPS' half lists [Plimpton1995]), and
 *        its pair table (see neighbor.h).
 *
 * neighbor_list_build tests every pair from both ends, twice (a count pass
 * and a fill pass over the 3^dim cells around each particle) and sorts each
 * cell's candidates: on the macro-particle rod (cell edge = list radius,
 * ~ 157 candidates a particle for ~ 17 partners) ~ 8 500 instructions a
 * particle per build.  Here:
 *
 * 1. Sweep: each particle looks only forward, at the later particles of its
 *    own cell and of the next cell along x (one contiguous range of the
 *    cell order), the three cells of the next y-row and the nine of the next
 *    z-layer (three contiguous ranges): 13 of the 26 neighbour cells, so
 *    each pair of adjacent cells is visited from one side and each pair is
 *    tested once (pair_r2, the test of the other builders, symmetric bit
 *    for bit).  Found pairs go to per-thread buffers as (min, max).
 * 2. Order without comparisons: the pairs are scattered into "lower" rows
 *    (per j, its partners i < j, in buffer order), then read j ascending
 *    into "upper" rows (per i, its partners j > i), which therefore ascend;
 *    last, i ascending, each upper row is copied into row i of the full list
 *    after its lower part, and i is appended to the lower part of each of
 *    its partners' rows, which therefore ascend too.  Every step's output
 *    depends only on the set of pairs, not on the buffer order: the list
 *    is the same for any thread count, and is neighbor_list_build's.  The
 *    three steps run over the threads, each thread a block of rows and its
 *    own cursor in every row it writes to (order_pairs).
 *
 * The pair table is the upper rows (pair q = upper slot q) with, per full
 * slot, the pair it holds; it comes out of step 2 at no extra search.
 */
#include "core/neighbor.h"

#include "core/neighbor_grid.h"
#include "spall/error.h"

#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/** One thread's pairs (a, b), a < b, two int32 each. */
struct pair_buf {
    int32_t *ab;
    size_t n, cap; /**< pairs held, pairs allocated */
};

static bool buf_reserve(struct pair_buf *b, size_t more)
{
    if (b->n + more <= b->cap)
        return true;
    size_t cap = 2 * b->cap > b->n + more ? 2 * b->cap : b->n + more + 4096;
    int32_t *ab = realloc(b->ab, 2 * cap * sizeof *ab);
    if (!ab)
        return false;
    b->ab = ab;
    b->cap = cap;
    return true;
}

/* The candidate test of 3D comes in two versions picked once at load time
 * by the CPU (GCC function multi-versioning, as the pair loops of the
 * models): x86-64-v3 (four doubles a vector) and the build's baseline; no
 * FP contraction (ISO C mode), so both round as pair_r2. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) &&     \
    !defined(SPALL_NO_CLONES)
#define NP_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define NP_CLONES
#endif

#if defined(__GNUC__)
typedef double np_v4 __attribute__((vector_size(32)));
typedef long long np_m4 __attribute__((vector_size(32)));
#endif

/** The pairs (a, order[q]) with q in [q0, q1) closer than r2max (3D), as
 *  (min, max) at ab; returns the end of what it wrote.  Four candidates a
 *  vector: r^2 by pair_r2's operations in its order ((dx dx + dy dy) + dz dz,
 *  candidate minus particle), so the same decisions; most candidates fail,
 *  and a group of four with no pair costs no branch per candidate. */
NP_CLONES static int32_t *scan3(const double xi[3], double *const xs[3], const int32_t *order,
                                size_t q0, size_t q1, double r2max, int32_t a, int32_t *ab)
{
    size_t q = q0;
#if defined(__GNUC__)
    const double *x0 = xs[0], *x1 = xs[1], *x2 = xs[2];
    const np_v4 bx = {xi[0], xi[0], xi[0], xi[0]}, by = {xi[1], xi[1], xi[1], xi[1]};
    const np_v4 bz = {xi[2], xi[2], xi[2], xi[2]}, rm = {r2max, r2max, r2max, r2max};
    for (; q + 4 <= q1; q += 4) {
        np_v4 u, v, w;
        memcpy(&u, x0 + q, sizeof u);
        memcpy(&v, x1 + q, sizeof v);
        memcpy(&w, x2 + q, sizeof w);
        const np_v4 dx = u - bx, dy = v - by, dz = w - bz;
        const np_m4 in = (dx * dx + dy * dy) + dz * dz < rm;
        if (!(in[0] | in[1] | in[2] | in[3]))
            continue;
        for (int l = 0; l < 4; l++)
            if (in[l]) {
                const int32_t o = order[q + (size_t)l];
                *ab++ = a < o ? a : o;
                *ab++ = a < o ? o : a;
            }
    }
#endif
    for (; q < q1; q++)
        if (pair_r2(3, xi, xs, q) < r2max) {
            const int32_t o = order[q];
            *ab++ = a < o ? a : o;
            *ab++ = a < o ? o : a;
        }
    return ab;
}

/** The forward pairs of the particles of cell @p c; false when out of
 *  memory. */
static inline bool sweep_cell_dim(const struct cell_grid *g, const int dim, size_t c,
                                  double r2max, struct pair_buf *b)
{
    const size_t s0 = g->start[c], s1 = g->start[c + 1];
    if (s0 == s1)
        return true;
    const size_t nx = (size_t)g->nc[0], ny = (size_t)g->nc[1], nz = (size_t)g->nc[2];
    const size_t c0 = c % nx, c1 = (c / nx) % ny, c2 = c / (nx * ny);
    const size_t xa = c0 > 0 ? c0 - 1 : 0, xb = c0 + 1 < nx ? c0 + 1 : c0;
    /* the ranges after the own row: (y+1, z) and (y-1 .. y+1, z+1), each
     * x-1 .. x+1, contiguous in the cell order */
    size_t rk0[4], rk1[4];
    int nr = 0;
    if (dim > 1 && c1 + 1 < ny) {
        const size_t row = (c2 * ny + c1 + 1) * nx;
        rk0[nr] = g->start[row + xa];
        rk1[nr++] = g->start[row + xb + 1];
    }
    if (dim > 2 && c2 + 1 < nz) {
        const size_t ya = c1 > 0 ? c1 - 1 : 0, yb = c1 + 1 < ny ? c1 + 1 : c1;
        for (size_t cy = ya; cy <= yb; cy++) {
            const size_t row = ((c2 + 1) * ny + cy) * nx;
            rk0[nr] = g->start[row + xa];
            rk1[nr++] = g->start[row + xb + 1];
        }
    }
    const size_t own_end = g->start[c - c0 + xb + 1]; /* end of cell (x+1, y, z) */
    size_t cand = own_end - s0;
    for (int r = 0; r < nr; r++)
        cand += rk1[r] - rk0[r];
    if (!buf_reserve(b, (s1 - s0) * cand))
        return false;
    int32_t *ab = b->ab + 2 * b->n;
    const int32_t *order = g->order;
    for (size_t k = s0; k < s1; k++) {
        const int32_t a = order[k];
        double xi[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++)
            xi[d] = g->xs[d][k];
        if (dim == 3) {
            ab = scan3(xi, g->xs, order, k + 1, own_end, r2max, a, ab);
            for (int r = 0; r < nr; r++)
                ab = scan3(xi, g->xs, order, rk0[r], rk1[r], r2max, a, ab);
            continue;
        }
        for (size_t q = k + 1; q < own_end; q++)
            if (pair_r2(dim, xi, g->xs, q) < r2max) {
                const int32_t o = order[q];
                *ab++ = a < o ? a : o;
                *ab++ = a < o ? o : a;
            }
        for (int r = 0; r < nr; r++)
            for (size_t q = rk0[r]; q < rk1[r]; q++)
                if (pair_r2(dim, xi, g->xs, q) < r2max) {
                    const int32_t o = order[q];
                    *ab++ = a < o ? a : o;
                    *ab++ = a < o ? o : a;
                }
    }
    b->n = (size_t)(ab - b->ab) / 2;
    return true;
}

static bool sweep_cell(const struct cell_grid *g, size_t c, double r2max, struct pair_buf *b)
{
    switch (g->dim) {
    case 1:
        return sweep_cell_dim(g, 1, c, r2max, b);
    case 2:
        return sweep_cell_dim(g, 2, c, r2max, b);
    default:
        return sweep_cell_dim(g, 3, c, r2max, b);
    }
}

/** Step 1: the pairs of the grid, into one buffer per thread (*nbuf). */
static struct pair_buf *sweep(const struct cell_grid *g, double r2max, int *nbuf)
{
    int nt = 1;
#ifdef _OPENMP
    nt = omp_get_max_threads();
#endif
    struct pair_buf *bufs = calloc((size_t)nt, sizeof *bufs);
    if (!bufs)
        return NULL;
    const size_t ncell = (size_t)g->nc[0] * (size_t)g->nc[1] * (size_t)g->nc[2];
    int nomem = 0;
#pragma omp parallel num_threads(nt) reduction(| : nomem)
    {
        int t = 0;
#ifdef _OPENMP
        t = omp_get_thread_num();
#endif
#pragma omp for schedule(dynamic, 64)
        for (size_t c = 0; c < ncell; c++)
            if (!nomem && !sweep_cell(g, c, r2max, &bufs[t]))
                nomem = 1;
    }
    if (nomem) {
        for (int t = 0; t < nt; t++)
            free(bufs[t].ab);
        free(bufs);
        return NULL;
    }
    *nbuf = nt;
    return bufs;
}

void neighbor_pairs_free(struct neighbor_pairs *pp)
{
    if (!pp)
        return;
    free(pp->first);
    free(pp->partner);
    free(pp->slot_pair);
    memset(pp, 0, sizeof *pp);
}

/** Block @p t of @p nth of the rows [0, n), cut where the running count
 *  @p cum (a prefix, cum[n] the total) passes t / nth of the total, so that
 *  each block holds about as many entries. */
static size_t row_cut(const size_t *cum, size_t n, int t, int nth)
{
    if (t <= 0)
        return 0;
    if (t >= nth)
        return n;
    const size_t want = (size_t)((double)cum[n] * t / nth);
    size_t lo = 0, hi = n; /* the first row r with cum[r] >= want */
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (cum[mid] < want)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/** Step 2 (O(pairs), no comparisons, over the threads): the full list's
 *  offsets and rows and the pair table from the buffers; false when out of
 *  memory.  Each placing step gives every thread a block of rows and a
 *  start inside each row it writes to (the counts of the threads before
 *  it, per row: cur, a column of n a thread), so a row's entries land in
 *  the order of the serial loop whatever the number of threads.  Only the
 *  lower rows, which nothing reads in order, take the buffers' order. */
static bool order_pairs(const struct pair_buf *bufs, int nbuf, size_t n, size_t *off,
                        int32_t **idx_out, size_t **first_out, int32_t **partner_out,
                        uint32_t **slot_out)
{
    int nt = 1;
#ifdef _OPENMP
    nt = omp_get_max_threads();
#endif
    size_t np = 0;
    for (int t = 0; t < nbuf; t++)
        np += bufs[t].n;
    size_t *lo = calloc(n + 1, sizeof *lo), *first = calloc(n + 1, sizeof *first);
    size_t *bsum = calloc((size_t)nt + 1, sizeof *bsum);
    int32_t *low = malloc((np ? np : 1) * sizeof *low);
    int32_t *up = malloc((np ? np : 1) * sizeof *up);
    int32_t *idx = malloc((np ? 2 * np : 1) * sizeof *idx);
    uint32_t *sp = slot_out ? malloc((np ? 2 * np : 1) * sizeof *sp) : NULL;
    size_t *cur = malloc((n ? n : 1) * (size_t)nt * sizeof *cur); /* row cursors */
    if (!lo || !first || !bsum || !low || !up || !idx || (slot_out && !sp) || !cur) {
        free(lo);
        free(first);
        free(bsum);
        free(low);
        free(up);
        free(idx);
        free(sp);
        free(cur);
        return false;
    }
#pragma omp parallel num_threads(nt)
    {
        int tid, nth;
        neighbor_team(&tid, &nth);
        size_t *my = cur + (size_t)tid * n;
        const size_t x0 = neighbor_block(n, tid, nth), x1 = neighbor_block(n, tid + 1, nth);
        /* the lower rows (per b, its partners a < b): this thread's counts
         * of its buffers, then its starts inside each row */
        memset(my, 0, n * sizeof *my);
        for (int t = tid; t < nbuf; t += nth)
            for (size_t k = 0; k < bufs[t].n; k++)
                my[(size_t)bufs[t].ab[2 * k + 1]]++;
#pragma omp barrier
        neighbor_row_starts(cur, nth, n, x0, x1, lo, bsum, tid);
        for (int t = tid; t < nbuf; t += nth)
            for (size_t k = 0; k < bufs[t].n; k++) {
                const size_t b = (size_t)bufs[t].ab[2 * k + 1];
                low[my[b]++] = bufs[t].ab[2 * k];
            }
#pragma omp barrier
        /* the upper rows (per a, its partners b > a) read from the lower
         * rows j ascending: this thread's block of j, its counts per a,
         * then the upper rows' offsets (first) and the full rows' (off) */
        const size_t j0 = row_cut(lo, n, tid, nth), j1 = row_cut(lo, n, tid + 1, nth);
        memset(my, 0, n * sizeof *my);
        for (size_t t = lo[j0]; t < lo[j1]; t++)
            my[(size_t)low[t]]++;
#pragma omp barrier
        neighbor_row_starts(cur, nth, n, x0, x1, first, bsum, tid);
        for (size_t x = x0; x < x1; x++) /* row x: its lower, then its upper part */
            off[x + 1] = lo[x + 1] + first[x + 1];
        for (size_t j = j0; j < j1; j++)
            for (size_t t = lo[j]; t < lo[j + 1]; t++) {
                const size_t a = (size_t)low[t];
                up[my[a]++] = (int32_t)j;
            }
#pragma omp barrier
        /* the full rows, this thread's block of i ascending: the upper row
         * after the lower part, i appended to each partner's lower part at
         * the partner's cursor (off[j], then the entries of the threads
         * before) */
        const size_t i0 = row_cut(first, n, tid, nth), i1 = row_cut(first, n, tid + 1, nth);
        if (nth > 1) {
            memset(my, 0, n * sizeof *my);
            for (size_t q = first[i0]; q < first[i1]; q++)
                my[(size_t)up[q]]++;
#pragma omp barrier
            for (size_t x = x0; x < x1; x++) {
                size_t c0 = off[x];
                for (int t = 0; t < nth; t++) {
                    const size_t c = cur[(size_t)t * n + x];
                    cur[(size_t)t * n + x] = c0;
                    c0 += c;
                }
            }
        } else
            memcpy(my, off, n * sizeof *my);
#pragma omp barrier
        for (size_t i = i0; i < i1; i++) {
            const size_t q0 = first[i], q1 = first[i + 1], h = off[i + 1] - (q1 - q0);
            for (size_t q = q0; q < q1; q++) {
                const size_t j = (size_t)up[q], s = h + (q - q0), t = my[j]++;
                idx[s] = up[q];
                idx[t] = (int32_t)i;
                if (sp) {
                    sp[s] = (uint32_t)q;
                    sp[t] = (uint32_t)q;
                }
            }
        }
    }
    free(cur);
    free(bsum);
    free(lo);
    free(low);
    *idx_out = idx;
    if (first_out) {
        *first_out = first;
        *partner_out = up;
        *slot_out = sp;
    } else {
        free(first);
        free(up);
    }
    return true;
}

int neighbor_list_build_pairs(struct neighbor_list **out, struct neighbor_pairs *pairs, int dim,
                              size_t n, double *const x[3], double radius,
                              struct spall_error *err)
{
    *out = NULL;
    if (pairs)
        memset(pairs, 0, sizeof *pairs);
    int rc = neighbor_check_input(dim, n, x, radius, err);
    if (rc)
        return rc;
    struct neighbor_list *nl = NULL;
    if ((rc = neighbor_list_alloc(&nl, n, err)))
        return rc;
    struct cell_grid g;
    memset(&g, 0, sizeof g);
    if (n > 0 && (rc = grid_build(&g, dim, n, x, radius, err))) {
        neighbor_list_destroy(&nl);
        return rc;
    }
    int nbuf = 0;
    struct pair_buf *bufs = NULL, none = {0};
    if (n > 0)
        bufs = sweep(&g, radius * radius, &nbuf);
    else {
        bufs = &none;
        nbuf = 1;
    }
    grid_free(&g);
    bool ok = bufs != NULL;
    size_t np = 0;
    for (int t = 0; ok && t < nbuf; t++)
        np += bufs[t].n;
    if (ok && pairs && np > UINT32_MAX) {
        for (int t = 0; t < nbuf && bufs != &none; t++)
            free(bufs[t].ab);
        if (bufs != &none)
            free(bufs);
        neighbor_list_destroy(&nl);
        return spall_error_set(err, SPALL_ERR_INPUT, "neighbour search: %zu pairs exceed the "
                               "32-bit pair index of the pair table", np);
    }
    if (ok)
        ok = order_pairs(bufs, nbuf, n, nl->offset, &nl->idx, pairs ? &pairs->first : NULL,
                         pairs ? &pairs->partner : NULL, pairs ? &pairs->slot_pair : NULL);
    if (bufs && bufs != &none) {
        for (int t = 0; t < nbuf; t++)
            free(bufs[t].ab);
        free(bufs);
    }
    if (!ok) {
        neighbor_list_destroy(&nl);
        return spall_error_set(err, SPALL_ERR_NOMEM,
                               "out of memory for the neighbour pairs of %zu particles", n);
    }
    if (pairs)
        pairs->n_pairs = pairs->first[n];
    *out = nl;
    return SPALL_OK;
}
