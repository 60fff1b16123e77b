/* Migration internals (migrate.c, migrate_local.c only). */
#ifndef SPALL_CORE_PARALLEL_MIGRATE_INTERNAL_H
#define SPALL_CORE_PARALLEL_MIGRATE_INTERNAL_H

#include "core/parallel/decomp_internal.h"
#include "core/parallel/migrate.h"

#include <stddef.h>
#include <stdint.h>

struct spall_error;

/* The layout of one particle's record: the arrays of the engine, the
 * registry and the model (migrate.h), then (migrants only) the group keys
 * and the bond row. */
struct layout {
    struct par_slots sl;     /**< per-particle arrays */
    size_t rec;              /**< bytes of the per-particle arrays */
    struct par_model_arrays ma;
    size_t half;             /**< bytes of one half-bond: partner gid, rest, state, type, model */
    size_t n_groups;
};

/* a new owned particle: from the old local index, or from a received record */
struct src {
    int64_t gid;
    size_t old;        /**< old local index (stayed) */
    const char *rec;   /**< received record (moved in), NULL when stayed */
};

struct mig {
    struct sim *s;
    struct par_decomp *d;
    struct layout L;
    int size, rank;
    size_t n_old, n_own_old;
    /* the exchange of migrants (bytes) */
    int *scnt, *sdsp, *rcnt, *rdsp;
    char *sbuf, *rbuf;
    /* the new owned set */
    struct src *own;
    int64_t *own_gid;
    size_t n_own;
    /* the new ghosts (ascending gid) and their owners */
    int64_t *gh_gid;
    int *gh_owner;
    size_t n_gh;
    /* group keys of the old owned particles, n_groups x n_own_old (-1: not a member) */
    int64_t *gkey;
};

/** Copy particle @p i's record in or out of the per-particle arrays. */
void mig_pack_rec(const struct layout *L, size_t i, char *buf);
void mig_unpack_rec(const struct layout *L, size_t i, const char *buf);
/** Index of @p g in the sorted @p a[0, n), or -1. */
int64_t mig_find_gid(const int64_t *a, size_t n, int64_t g);
/** Row of new owned particle @p j: its length in *cnt, and the packed
 *  half-bonds of a received record (NULL: the row is in the old list). */
const char *mig_row_of(const struct mig *M, size_t j, size_t *cnt);
/** Partner gid of half-bond @p q of new owned particle @p j. */
int64_t mig_partner_gid(const struct mig *M, size_t j, const char *row, size_t q);
/** The new local arrays, bonds, groups, ghosts, halo and probes (collective). */
int mig_rebuild_local(struct mig *M, struct spall_error *err);

#endif
