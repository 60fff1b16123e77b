/**
 * @file reduce.c
 * @brief Sums in the serial order where the serial arithmetic must be kept
 *        (decomp.h): the per-particle terms travel to rank 0, which adds
 *        them in the serial order and broadcasts the result; probes from
 *        their owner.
 *
 * Used where a sum feeds the dynamics (the impactors' contact force: an
 * exact sum would change the serial run's last bits) and for the thermal
 * lattice's history; the energy account, BC reactions and work use the
 * exact sums of psum.h, which need no gather.
 */
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"

#include "core/model.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

void par_reduce_cols(const double *rows, size_t n, int ncol, double *out, const void *ctx)
{
    (void)ctx;
    for (int c = 0; c < ncol; c++) {
        double acc = 0.0;
        for (size_t q = 0; q < n; q++)
            acc += rows[q * (size_t)ncol + (size_t)c];
        out[c] = acc;
    }
}

#ifdef SPALL_HAVE_MPI

struct keyed {
    int64_t key;
    size_t at;
};

static int cmp_keyed(const void *a, const void *b)
{
    int64_t x = ((const struct keyed *)a)->key, y = ((const struct keyed *)b)->key;
    return (x > y) - (x < y);
}

/* Gather (key, row) pairs to rank 0 and sort them by key there; returns the
 * sorted rows (rank 0; NULL elsewhere) and their number in *n_all. */
static double *gather_sorted(const int64_t *key, const double *rows, size_t n, int ncol,
                             size_t *n_all)
{
    const int size = par_size(), rank = par_rank();
    int cnt = (int)n, *counts = NULL, *displs = NULL, *dcounts = NULL, *ddispls = NULL;
    if (rank == 0) {
        counts = malloc((size_t)size * sizeof *counts);
        displs = malloc((size_t)size * sizeof *displs);
        dcounts = malloc((size_t)size * sizeof *dcounts);
        ddispls = malloc((size_t)size * sizeof *ddispls);
    }
    MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    size_t total = 0;
    if (rank == 0)
        for (int r = 0; r < size; r++) {
            displs[r] = (int)total;
            ddispls[r] = (int)(total * (size_t)ncol);
            dcounts[r] = counts[r] * ncol;
            total += (size_t)counts[r];
        }
    int64_t *keys = rank == 0 ? malloc((total ? total : 1) * sizeof *keys) : NULL;
    double *vals = rank == 0 ? malloc((total ? total : 1) * (size_t)ncol * sizeof *vals) : NULL;
    MPI_Gatherv(key, cnt, MPI_INT64_T, keys, counts, displs, MPI_INT64_T, 0, MPI_COMM_WORLD);
    MPI_Gatherv(rows, cnt * ncol, MPI_DOUBLE, vals, dcounts, ddispls, MPI_DOUBLE, 0,
                MPI_COMM_WORLD);
    double *sorted = NULL;
    if (rank == 0) {
        struct keyed *ix = malloc((total ? total : 1) * sizeof *ix);
        sorted = malloc((total ? total : 1) * (size_t)ncol * sizeof *sorted);
        for (size_t q = 0; q < total; q++) {
            ix[q].key = keys[q];
            ix[q].at = q;
        }
        qsort(ix, total, sizeof *ix, cmp_keyed);
        for (size_t q = 0; q < total; q++)
            memcpy(sorted + q * (size_t)ncol, vals + ix[q].at * (size_t)ncol,
                   (size_t)ncol * sizeof *sorted);
        free(ix);
    }
    free(keys);
    free(vals);
    free(counts);
    free(displs);
    free(dcounts);
    free(ddispls);
    *n_all = total;
    return sorted;
}

void par_ordered_reduce(const int64_t *key, const double *rows, size_t n, int ncol,
                        par_reduce_fn fn, const void *ctx, double *out, int nout)
{
    size_t total = 0;
    double *sorted = gather_sorted(key, rows, n, ncol, &total);
    if (par_rank() == 0)
        fn(sorted, total, ncol, out, ctx);
    free(sorted);
    MPI_Bcast(out, nout, MPI_DOUBLE, 0, MPI_COMM_WORLD);
}

void par_probe(const struct sim *s, size_t k, double u[3], double v[3])
{
    const struct par_decomp *d = s->par;
    double buf[6] = {0, 0, 0, 0, 0, 0};
    if (d->probe_owner[k] == par_rank()) {
        size_t i = d->probe_local[k];
        for (int c = 0; c < s->dim; c++) {
            buf[c] = s->p->x[c][i] - s->p->x0[c][i];
            buf[3 + c] = s->p->v[c][i];
        }
    }
    MPI_Bcast(buf, 6, MPI_DOUBLE, d->probe_owner[k], MPI_COMM_WORLD);
    memcpy(u, buf, 3 * sizeof *u);
    memcpy(v, buf + 3, 3 * sizeof *v);
}

#else

void par_ordered_reduce(const int64_t *key, const double *rows, size_t n, int ncol,
                        par_reduce_fn fn, const void *ctx, double *out, int nout)
{
    (void)key;
    (void)nout;
    fn(rows, n, ncol, out, ctx);
}

void par_probe(const struct sim *s, size_t k, double u[3], double v[3])
{
    size_t i = s->probes[k].particle;
    for (int c = 0; c < 3; c++) {
        u[c] = c < s->dim ? s->p->x[c][i] - s->p->x0[c][i] : 0.0;
        v[c] = c < s->dim ? s->p->v[c][i] : 0.0;
    }
}

#endif
