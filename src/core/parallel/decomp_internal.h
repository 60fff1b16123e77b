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
    /* rebalancing and migration (migrate.c, balance.c) */
    void *zz;              /**< Zoltan_Struct kept between rebalances (its cuts are reused) */
    long rebalances;
    unsigned long long migrated;
    long layouts; /**< migrations so far, the set-up's partition included (par_layouts) */
    void *bhalo; /**< per-half-bond halo plan (bhalo.c), built on first use; NULL */
    /* spatial ghosts (spatial.c) of a model with spatial_ghosts */
    struct par_sghost *sg;
    long sg_rebuilds;      /**< rebuilds in the step (the one after the partition not counted) */
    int sg_bonds;          /**< the spatial ghosts also hold the model's fixed partners
                                (par_spatial_model.bonds) */
};

struct sim;

/** Every per-particle array of the engine and the registry (addresses of
 *  the array pointers, element sizes), each array once. */
#define PAR_MAX_SLOTS 192
struct par_slots {
    void **ptr[PAR_MAX_SLOTS];
    size_t esize[PAR_MAX_SLOTS];
    size_t n;
};
/** Add an array (a NULL array or one already listed is skipped); -1: full. */
int par_slot_add(struct par_slots *sl, void **ptr, size_t esize);
/** The engine's and the registry's stored arrays; -1: too many. */
int par_particle_slots(struct sim *s, struct par_slots *sl);
/** A particle's work for the partition: 1 + the half-bonds of its row
 *  (@p intact_only: the intact ones), 1 without a bond list. */
struct bond_list;
double par_particle_work(const struct bond_list *bl, size_t i, int intact_only);

/** Objects handed to Zoltan: rows [lo, hi) with global ids gid[i] (NULL:
 *  i), positions pos[c][i] and the work above as weight. */
struct par_zobjs {
    size_t lo, hi;
    const int64_t *gid;
    double *const *pos;
    int dim;
    const struct bond_list *bl;
    int intact_only;
};
struct Zoltan_Struct;
struct spall_error;
/** A Zoltan RCB object with spall's parameters (NULL on failure); with
 *  @p reuse it keeps its cuts and starts each repartition from them. */
struct Zoltan_Struct *par_zoltan_rcb(int reuse);
/** Install the query functions over @p z (kept by address) in @p zz. */
void par_zoltan_queries(struct Zoltan_Struct *zz, struct par_zobjs *z);
/** Partition the objects of @p z with @p zz: *dest (malloc'd, one rank per
 *  object) and *leaving, the objects this rank exports (balance.c). */
int par_rcb_dest(struct Zoltan_Struct *zz, struct par_zobjs *z, int **dest, size_t *leaving,
                 struct spall_error *err);

/* The steps of par_distribute (decomp.c), also used by the distributed
 * set-up (setup_dist.c) on a rank's own block and its halo: keep[0, n_keep)
 * (old indices, the first n_owned owned), new_of_old, owner[old index]. */
/** After the owned particles keep[0, n_owned) (new_of_old set for them, -1
 *  for the rest of the @p n old ones): the partners of their rows held by
 *  other ranks become the ghosts (ascending old index), *n_keep in all; the
 *  halo plan of @p d. */
int par_keep_ghosts(struct sim *s, struct par_decomp *d, const struct bond_list *bl,
                    const int *owner, int64_t *new_of_old, size_t *keep, size_t n_owned,
                    size_t n, size_t *n_keep, struct spall_error *err);
/** The model's localize, then the engine's arrays compacted to keep. */
int par_localize_kept(struct sim *s, const size_t *keep, size_t n_keep, size_t n_owned,
                      const int64_t *new_of_old, struct spall_error *err);

/** Release the spatial ghosts (spatial.c). */
void par_spatial_free(struct par_decomp *d);

/** Release the rebalancing state (balance.c). */
void par_balance_free(struct par_decomp *d);

#endif
