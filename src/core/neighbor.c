/**
 * @file neighbor.c
 * @brief Cell-list neighbour search (see neighbor.h).
 *
 * Particles are binned into a uniform grid of cells with edge >= radius by a
 * counting sort (stable: ascending index inside a cell; over the threads,
 * each a block of particles placed after the blocks before it), and their
 * positions are copied in cell order so the scan reads contiguous memory.
 * The query for particle i visits the 3^dim cells around its own; because
 * cells are numbered x-fastest, the three cells of one x-row are a single
 * contiguous range, so only 3^(dim-1) ranges are scanned.
 *
 * Determinism: each row is built independently by two passes (count, then
 * fill into the slot given by the serial prefix sum) and sorted ascending, so
 * the CSR is bitwise identical for any thread count, and identical to the
 * brute-force twin because both use pair_r2() for the distance test.
 *
 * The fill goes cell by cell: the candidates of a cell (the particles of
 * the 3^dim cells around it) are sorted by index once, and each particle of
 * the cell keeps the candidates within the radius in that order, so its
 * row comes out ascending without a sort of its own.  Sorting the rows one
 * by one was ~ 40 % of a build in 3D SPH (~ 45 particles a cell, rows of
 * 140-200 partners: the cell's ~ 1 200 candidates once instead of 45 rows).
 */
#include "core/neighbor.h"

#include "core/neighbor_grid.h"
#include "spall/error.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/** Rows up to this length are sorted by plain insertion sort. */
#define NEIGHBOR_INSERTION_MAX 48

/* Shell sort (Ciura's gaps) for long rows: glibc's qsort is a merge sort
 * through a comparison function pointer and memcpy per element, which
 * cost 6-10 % of an SPH run whose rows hold 150-300 partners (perf). */
static void sort_row(int32_t *v, size_t m)
{
    static const size_t gaps[] = {701, 301, 132, 57, 23, 10, 4, 1};
    for (size_t g = 0; g < sizeof gaps / sizeof gaps[0]; g++) {
        const size_t gap = gaps[g];
        if (gap >= m || (gap > 1 && m <= NEIGHBOR_INSERTION_MAX))
            continue;
        for (size_t a = gap; a < m; a++) {
            int32_t key = v[a];
            size_t b = a;
            while (b >= gap && v[b - gap] > key) {
                v[b] = v[b - gap];
                b -= gap;
            }
            v[b] = key;
        }
    }
}

int neighbor_list_alloc(struct neighbor_list **out, size_t n, struct spall_error *err)
{
    struct neighbor_list *nl = calloc(1, sizeof *nl);
    if (nl)
        nl->offset = calloc(n + 1, sizeof *nl->offset);
    if (!nl || !nl->offset) {
        free(nl);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the neighbour list of %zu",
                               n);
    }
    nl->n = n;
    *out = nl;
    return SPALL_OK;
}

/** offset[i+1] holds row i's count on entry; turn into offsets and allocate. */
static int list_finish_offsets(struct neighbor_list *nl, struct spall_error *err)
{
    size_t n = nl->n;
    nl->offset[0] = 0;
    for (size_t i = 0; i < n; i++)
        nl->offset[i + 1] += nl->offset[i];
    size_t total = nl->offset[n];
    nl->idx = malloc((total ? total : 1) * sizeof *nl->idx);
    if (!nl->idx)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu neighbour pairs", total);
    return SPALL_OK;
}

int neighbor_check_input(int dim, size_t n, double *const x[3], double radius,
                         struct spall_error *err)
{
    if (dim < 1 || dim > 3)
        return spall_error_set(err, SPALL_ERR_INPUT, "neighbour search: dimension %d not in 1..3",
                               dim);
    if (!(radius > 0.0) || !isfinite(radius))
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "neighbour search: radius must be positive and finite (got %g)",
                               radius);
    if (n > (size_t)INT32_MAX)
        return spall_error_set(err, SPALL_ERR_INPUT,
                               "neighbour search: %zu particles exceed the int32 index range", n);
    for (int d = 0; d < dim && n > 0; d++)
        if (!x[d])
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "neighbour search: position component %d missing", d);
    return SPALL_OK;
}

void grid_free(struct cell_grid *g)
{
    free(g->start);
    free(g->order);
    for (int d = 0; d < 3; d++)
        free(g->xs[d]);
}

static inline long cell_coord(const struct cell_grid *g, int d, double xd)
{
    long c = (long)((xd - g->lo[d]) * g->inv_edge);
    return c < 0 ? 0 : (c >= g->nc[d] ? g->nc[d] - 1 : c);
}

/** Linear cell index of particle i (x fastest). */
static inline size_t cell_index(const struct cell_grid *g, double *const x[3], size_t i)
{
    size_t c = 0;
    for (int d = g->dim - 1; d >= 0; d--)
        c = c * (size_t)g->nc[d] + (size_t)cell_coord(g, d, x[d][i]);
    return c;
}

void neighbor_row_starts(size_t *cnt, int nth, size_t n, size_t x0, size_t x1, size_t *v,
                         size_t *bsum, int tid)
{
    size_t s = 0;
    if (nth == 1)
        for (size_t x = x0; x < x1; x++)
            s += cnt[x];
    else
        for (size_t x = x0; x < x1; x++)
            for (int t = 0; t < nth; t++)
                s += cnt[(size_t)t * n + x];
    bsum[tid + 1] = s;
#pragma omp barrier
#pragma omp single
    {
        v[0] = 0;
        bsum[0] = 0;
        for (int t = 0; t < nth; t++)
            bsum[t + 1] += bsum[t];
    }
    s = bsum[tid];
    if (nth == 1)
        for (size_t x = x0; x < x1; x++) {
            const size_t c = cnt[x];
            cnt[x] = s;
            s += c;
            v[x + 1] = s;
        }
    else
        for (size_t x = x0; x < x1; x++) {
            for (int t = 0; t < nth; t++) {
                const size_t c = cnt[(size_t)t * n + x];
                cnt[(size_t)t * n + x] = s;
                s += c;
            }
            v[x + 1] = s;
        }
#pragma omp barrier
}

/** One thread's share of the bounds: its particles' extremes per axis and
 *  the first of them with a non-finite coordinate per axis (n when none). */
struct grid_share {
    double lo[3], hi[3];
    size_t bad[3];
    bool has; /**< the share holds particles */
};

/** The bounds of particles [0, n) per axis over the threads, each a block
 *  of particles, joined block by block in index order with the comparisons
 *  of one loop (v < lo, v > hi: the first of equal extremes, +0 or -0,
 *  wins), so the same bits as one thread; then the serial loop's errors in
 *  its order (per axis: the first non-finite particle, then the span). */
static int grid_bounds(int dim, size_t n, double *const x[3], int nt, double lo[3],
                       double hi[3], struct spall_error *err)
{
    struct grid_share *sh = calloc((size_t)nt, sizeof *sh);
    if (!sh)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the neighbour grid");
#pragma omp parallel num_threads(nt)
    {
        int tid, nth;
        neighbor_team(&tid, &nth);
        const size_t i0 = neighbor_block(n, tid, nth), i1 = neighbor_block(n, tid + 1, nth);
        struct grid_share *m = &sh[tid];
        m->has = i0 < i1;
        for (int d = 0; d < dim && m->has; d++) {
            double l = x[d][i0], h = x[d][i0];
            m->bad[d] = n;
            for (size_t i = i0; i < i1; i++) {
                const double v = x[d][i];
                if (!isfinite(v)) {
                    m->bad[d] = i;
                    break;
                }
                l = v < l ? v : l;
                h = v > h ? v : h;
            }
            m->lo[d] = l;
            m->hi[d] = h;
        }
    }
    int rc = SPALL_OK;
    for (int d = 0; d < dim && !rc; d++) {
        bool any = false;
        for (int t = 0; t < nt && !rc; t++) {
            if (!sh[t].has)
                continue;
            if (sh[t].bad[d] < n)
                rc = spall_error_set(err, SPALL_ERR_INPUT,
                                     "neighbour search: particle %zu has a non-finite position",
                                     sh[t].bad[d]);
            else if (!any) {
                lo[d] = sh[t].lo[d];
                hi[d] = sh[t].hi[d];
                any = true;
            } else {
                lo[d] = sh[t].lo[d] < lo[d] ? sh[t].lo[d] : lo[d];
                hi[d] = sh[t].hi[d] > hi[d] ? sh[t].hi[d] : hi[d];
            }
        }
        if (!rc && !isfinite(hi[d] - lo[d]))
            rc = spall_error_set(err, SPALL_ERR_INPUT,
                                 "neighbour search: positions span more than a double holds");
    }
    free(sh);
    return rc;
}

int grid_build(struct cell_grid *g, int dim, size_t n, double *const x[3], double radius,
               struct spall_error *err)
{
    memset(g, 0, sizeof *g);
    g->dim = dim;
    int nt = 1;
#ifdef _OPENMP
    nt = omp_get_max_threads();
#endif
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int rc = grid_bounds(dim, n, x, nt, lo, hi, err);
    if (rc)
        return rc;
    for (int d = 0; d < dim; d++)
        g->lo[d] = lo[d];
    /* Cell edge >= radius keeps every partner within the 3^dim block; cap the
     * number of cells at ~4n + 1000 (widely spread points) by enlarging it. */
    double edge = radius;
    double limit = 4.0 * (double)n + 1000.0;
    for (;;) {
        double total = 1.0;
        for (int d = 0; d < dim; d++)
            total *= floor((hi[d] - lo[d]) / edge) + 1.0;
        if (total <= limit)
            break;
        edge *= fmax(pow(total / limit, 1.0 / dim), 1.01);
    }
    g->inv_edge = 1.0 / edge;
    size_t ncell = 1;
    for (int d = 0; d < 3; d++) {
        g->nc[d] = d < dim ? (long)floor((hi[d] - lo[d]) / edge) + 1 : 1;
        ncell *= (size_t)g->nc[d];
    }

    g->start = calloc(ncell + 1, sizeof *g->start);
    g->order = malloc(n * sizeof *g->order);
    size_t *bsum = calloc((size_t)nt + 1, sizeof *bsum);
    size_t *cnt = malloc(ncell * (size_t)nt * sizeof *cnt); /* per thread and cell */
    bool bad = !g->start || !g->order || !bsum || !cnt;
    for (int d = 0; d < dim; d++) {
        g->xs[d] = malloc(n * sizeof(double));
        bad = bad || !g->xs[d];
    }
    if (bad) {
        free(bsum);
        free(cnt);
        grid_free(g);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for %zu cells", ncell);
    }
    /* Counting sort over the threads, each a block of particles: its counts
     * per cell, then its start inside each cell (the counts of the blocks
     * before), so a cell's particles ascend in index whatever the number of
     * threads.  The cell of a particle is recomputed in the scatter rather
     * than stored: cheaper than touching another n-sized array. */
#pragma omp parallel num_threads(nt)
    {
        int tid, nth;
        neighbor_team(&tid, &nth);
        const size_t i0 = neighbor_block(n, tid, nth), i1 = neighbor_block(n, tid + 1, nth);
        const size_t c0 = neighbor_block(ncell, tid, nth), c1 = neighbor_block(ncell, tid + 1, nth);
        size_t *my = cnt + (size_t)tid * ncell;
        memset(my, 0, ncell * sizeof *my);
        for (size_t i = i0; i < i1; i++)
            my[cell_index(g, x, i)]++;
#pragma omp barrier
        neighbor_row_starts(cnt, nth, ncell, c0, c1, g->start, bsum, tid);
        for (size_t i = i0; i < i1; i++) {
            const size_t c = cell_index(g, x, i), k = my[c]++;
            g->order[k] = (int32_t)i;
            for (int d = 0; d < dim; d++)
                g->xs[d][k] = x[d][i];
        }
    }
    free(bsum);
    free(cnt);
    return SPALL_OK;
}

/** Scan the cells around particle i; write partners to @p outv when not NULL.
 *  Returns the number of partners. */
static inline size_t grid_query_dim(const struct cell_grid *g, const int dim, size_t i,
                                    double *const x[3], double r2max, int32_t *outv)
{
    double xi[3] = {0, 0, 0};
    long c[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) {
        xi[d] = x[d][i];
        c[d] = cell_coord(g, d, xi[d]);
    }
    long x0 = c[0] > 0 ? c[0] - 1 : 0;
    long x1 = c[0] + 1 < g->nc[0] ? c[0] + 1 : g->nc[0] - 1;
    long z0 = dim > 2 ? (c[2] > 0 ? c[2] - 1 : 0) : 0;
    long z1 = dim > 2 ? (c[2] + 1 < g->nc[2] ? c[2] + 1 : g->nc[2] - 1) : 0;
    long y0 = dim > 1 ? (c[1] > 0 ? c[1] - 1 : 0) : 0;
    long y1 = dim > 1 ? (c[1] + 1 < g->nc[1] ? c[1] + 1 : g->nc[1] - 1) : 0;
    int32_t self = (int32_t)i;
    size_t m = 0;
    for (long cz = z0; cz <= z1; cz++) {
        for (long cy = y0; cy <= y1; cy++) {
            size_t row = ((size_t)cz * (size_t)g->nc[1] + (size_t)cy) * (size_t)g->nc[0];
            size_t k0 = g->start[row + (size_t)x0], k1 = g->start[row + (size_t)x1 + 1];
            for (size_t k = k0; k < k1; k++) {
                if (pair_r2(dim, xi, g->xs, k) < r2max && g->order[k] != self) {
                    if (outv)
                        outv[m] = g->order[k];
                    m++;
                }
            }
        }
    }
    return m;
}

/** Dispatch once per particle so each dimension gets its own unrolled loop. */
static size_t grid_query(const struct cell_grid *g, size_t i, double *const x[3], double r2max,
                         int32_t *outv)
{
    switch (g->dim) {
    case 1:
        return grid_query_dim(g, 1, i, x, r2max, outv);
    case 2:
        return grid_query_dim(g, 2, i, x, r2max, outv);
    default:
        return grid_query_dim(g, 3, i, x, r2max, outv);
    }
}

/** The candidates of one cell: particle indices ascending and their
 *  positions in that order. */
struct cell_cands {
    int32_t *id;
    double *xs[3];
    size_t cap;
};

static void cands_free(struct cell_cands *cc)
{
    free(cc->id);
    for (int d = 0; d < 3; d++)
        free(cc->xs[d]);
    memset(cc, 0, sizeof *cc);
}

static int cands_reserve(struct cell_cands *cc, int dim, size_t m)
{
    if (m <= cc->cap)
        return 0;
    size_t cap = m + m / 2 + 64;
    int32_t *id = realloc(cc->id, cap * sizeof *id);
    if (!id)
        return -1;
    cc->id = id;
    for (int d = 0; d < dim; d++) {
        double *v = realloc(cc->xs[d], cap * sizeof *v);
        if (!v)
            return -1;
        cc->xs[d] = v;
    }
    cc->cap = cap;
    return 0;
}

/** Fill the rows of the particles of cell @p c (offsets known) from the
 *  cell's sorted candidates; -1 when out of memory. */
static inline int grid_fill_cell_dim(const struct cell_grid *g, const int dim, size_t c,
                                     double *const x[3], double r2max, const size_t *off,
                                     int32_t *idx, struct cell_cands *cc)
{
    const size_t s0 = g->start[c], s1 = g->start[c + 1];
    if (s0 == s1)
        return 0;
    const size_t nx = (size_t)g->nc[0], ny = (size_t)g->nc[1];
    const long c0 = (long)(c % nx), c1 = (long)((c / nx) % ny), c2 = (long)(c / (nx * ny));
    const long x0 = c0 > 0 ? c0 - 1 : 0, x1 = c0 + 1 < g->nc[0] ? c0 + 1 : g->nc[0] - 1;
    const long y0 = dim > 1 && c1 > 0 ? c1 - 1 : c1;
    const long y1 = dim > 1 && c1 + 1 < g->nc[1] ? c1 + 1 : c1;
    const long z0 = dim > 2 && c2 > 0 ? c2 - 1 : c2;
    const long z1 = dim > 2 && c2 + 1 < g->nc[2] ? c2 + 1 : c2;
    size_t m = 0;
    for (int pass = 0; pass < 2; pass++) {
        if (pass && cands_reserve(cc, dim, m))
            return -1;
        m = 0;
        for (long cz = z0; cz <= z1; cz++)
            for (long cy = y0; cy <= y1; cy++) {
                size_t row = ((size_t)cz * ny + (size_t)cy) * nx;
                size_t k0 = g->start[row + (size_t)x0], k1 = g->start[row + (size_t)x1 + 1];
                if (pass)
                    memcpy(cc->id + m, g->order + k0, (k1 - k0) * sizeof *cc->id);
                m += k1 - k0;
            }
    }
    sort_row(cc->id, m);
    for (int d = 0; d < dim; d++)
        for (size_t q = 0; q < m; q++)
            cc->xs[d][q] = x[d][cc->id[q]];
    for (size_t k = s0; k < s1; k++) {
        const int32_t self = g->order[k];
        double xi[3] = {0, 0, 0};
        for (int d = 0; d < dim; d++)
            xi[d] = g->xs[d][k];
        int32_t *outv = idx + off[self];
        size_t w = 0;
        for (size_t q = 0; q < m; q++)
            if (pair_r2(dim, xi, cc->xs, q) < r2max && cc->id[q] != self)
                outv[w++] = cc->id[q];
    }
    return 0;
}

static int grid_fill_cell(const struct cell_grid *g, size_t c, double *const x[3], double r2max,
                          const size_t *off, int32_t *idx, struct cell_cands *cc)
{
    switch (g->dim) {
    case 1:
        return grid_fill_cell_dim(g, 1, c, x, r2max, off, idx, cc);
    case 2:
        return grid_fill_cell_dim(g, 2, c, x, r2max, off, idx, cc);
    default:
        return grid_fill_cell_dim(g, 3, c, x, r2max, off, idx, cc);
    }
}

int neighbor_list_build(struct neighbor_list **out, int dim, size_t n, double *const x[3],
                        double radius, struct spall_error *err)
{
    *out = NULL;
    int rc = neighbor_check_input(dim, n, x, radius, err);
    if (rc)
        return rc;
    struct neighbor_list *nl = NULL;
    rc = neighbor_list_alloc(&nl, n, err);
    if (rc)
        return rc;
    if (n == 0) {
        rc = list_finish_offsets(nl, err);
        if (rc)
            neighbor_list_destroy(&nl);
        *out = nl;
        return rc;
    }
    struct cell_grid g;
    rc = grid_build(&g, dim, n, x, radius, err);
    if (rc) {
        neighbor_list_destroy(&nl);
        return rc;
    }
    double r2max = radius * radius;
    size_t *off = nl->offset;
    /* Pass 1: count per row.  Pass 2: fill at the prefix-sum offsets. */
#pragma omp parallel for schedule(dynamic, 2048)
    for (size_t i = 0; i < n; i++)
        off[i + 1] = grid_query(&g, i, x, r2max, NULL);
    rc = list_finish_offsets(nl, err);
    if (!rc) {
        int32_t *idx = nl->idx;
        const size_t ncell = (size_t)g.nc[0] * (size_t)g.nc[1] * (size_t)g.nc[2];
        int nomem = 0;
#pragma omp parallel reduction(| : nomem)
        {
            struct cell_cands cc = {0};
#pragma omp for schedule(dynamic, 16)
            for (size_t c = 0; c < ncell; c++)
                if (!nomem && grid_fill_cell(&g, c, x, r2max, off, idx, &cc))
                    nomem = 1;
            cands_free(&cc);
        }
        if (nomem)
            rc = spall_error_set(err, SPALL_ERR_NOMEM,
                                 "out of memory for the neighbour candidates of a cell");
    }
    grid_free(&g);
    if (rc) {
        neighbor_list_destroy(&nl);
        return rc;
    }
    *out = nl;
    return SPALL_OK;
}

/** Brute-force row i: every j != i in ascending order. */
static size_t brute_row(int dim, size_t n, double *const x[3], size_t i, double r2max,
                        int32_t *outv)
{
    double xi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++)
        xi[d] = x[d][i];
    size_t m = 0;
    for (size_t j = 0; j < n; j++) {
        if (j != i && pair_r2(dim, xi, x, j) < r2max) {
            if (outv)
                outv[m] = (int32_t)j;
            m++;
        }
    }
    return m;
}

int neighbor_list_build_brute(struct neighbor_list **out, int dim, size_t n, double *const x[3],
                              double radius, struct spall_error *err)
{
    *out = NULL;
    int rc = neighbor_check_input(dim, n, x, radius, err);
    if (rc)
        return rc;
    struct neighbor_list *nl = NULL;
    rc = neighbor_list_alloc(&nl, n, err);
    if (rc)
        return rc;
    double r2max = radius * radius;
    size_t *off = nl->offset;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; i++)
        off[i + 1] = brute_row(dim, n, x, i, r2max, NULL);
    rc = list_finish_offsets(nl, err);
    if (rc) {
        neighbor_list_destroy(&nl);
        return rc;
    }
    int32_t *idx = nl->idx;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; i++)
        brute_row(dim, n, x, i, r2max, idx + off[i]);
    *out = nl;
    return SPALL_OK;
}

void neighbor_list_destroy(struct neighbor_list **pnl)
{
    if (!pnl || !*pnl)
        return;
    free((*pnl)->offset);
    free((*pnl)->idx);
    free(*pnl);
    *pnl = NULL;
}
