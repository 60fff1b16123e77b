/**
 * @file halo_block.c
 * @brief The halo of a block of per-particle values wider than a position
 *        and velocity (decomp.h, par_halo_block): e.g. the total-Lagrangian
 *        SPH stage-1 values a particle's partners read (28 doubles), sent
 *        in one exchange rather than one per value.
 */
#include "core/parallel/decomp.h"
#include "core/parallel/decomp_internal.h"

#include "core/parallel/comm.h"
#include "core/sim.h"
#include "spall/error.h"

#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>

int par_halo_block(const struct sim *s, double *vals, int ncomp)
{
    struct par_decomp *d = s->par;
    const int size = par_size(), w = 2 * s->dim;
    const size_t nc = (size_t)ncomp;
    /* the halo lists of par_halo_x, whose counts are in units of w doubles */
    double *sb = malloc((d->n_send ? d->n_send : 1) * nc * sizeof *sb);
    double *rb = malloc((d->n_recv ? d->n_recv : 1) * nc * sizeof *rb);
    int bad = !sb || !rb;
    if (par_sum_u64((uint64_t)bad)) { /* collective: every rank returns */
        free(sb);
        free(rb);
        return SPALL_ERR_NOMEM;
    }
    const double t0 = MPI_Wtime();
    for (size_t k = 0; k < d->n_send; k++)
        memcpy(sb + k * nc, vals + d->send_idx[k] * nc, nc * sizeof *vals);
    MPI_Request *req = d->req;
    int nreq = 0;
    for (int r = 0; r < size; r++)
        if (d->recv_counts[r])
            MPI_Irecv(rb + (size_t)(d->recv_displs[r] / w) * nc, d->recv_counts[r] / w * ncomp,
                      MPI_DOUBLE, r, 23, MPI_COMM_WORLD, &req[nreq++]);
    for (int r = 0; r < size; r++)
        if (d->send_counts[r])
            MPI_Isend(sb + (size_t)(d->send_displs[r] / w) * nc, d->send_counts[r] / w * ncomp,
                      MPI_DOUBLE, r, 23, MPI_COMM_WORLD, &req[nreq++]);
    MPI_Waitall(nreq, req, MPI_STATUSES_IGNORE);
    for (size_t k = 0; k < d->n_recv; k++)
        memcpy(vals + d->recv_idx[k] * nc, rb + k * nc, nc * sizeof *vals);
    d->comm_seconds += MPI_Wtime() - t0;
    free(sb);
    free(rb);
    return SPALL_OK;
}

#else

int par_halo_block(const struct sim *s, double *vals, int ncomp)
{
    (void)s;
    (void)vals;
    (void)ncomp;
    return SPALL_OK;
}

#endif
