/* The decomposition context (decomp.c, reduce.c, step.c only). */
#ifndef SPALL_CORE_PARALLEL_DECOMP_INTERNAL_H
#define SPALL_CORE_PARALLEL_DECOMP_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

struct par_decomp {
    size_t n_global;     /**< particles of the whole body */
    size_t interactions; /**< the model's interaction count at set-up (whole body) */
    size_t n_owned, n_ghost;
    /* halo exchange of positions (point to point, counts in doubles) */
    int *send_counts, *send_displs, *recv_counts, *recv_displs;
    size_t *send_idx; /**< local owned index of each particle sent, rank-major */
    size_t *recv_idx; /**< local ghost index of each particle received, rank-major */
    size_t n_send, n_recv;
    double *sbuf, *rbuf;
    void *req; /**< MPI_Request[2 size] (void: this header does not include mpi.h) */
    /* groups and probes of the whole run */
    size_t n_groups;
    size_t *group_n;     /**< members over all ranks */
    int64_t **group_key; /**< per local member: its position in the serial list */
    int *probe_owner;
    size_t *probe_local;
    /* timing (run.log; not performance numbers on a loaded machine) */
    double setup_seconds, comm_seconds;
    long halo_calls;
};

#endif
