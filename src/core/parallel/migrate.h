/**
 * @file migrate.h
 * @brief Migration of owned particles between ranks (issue 20 item 2) and
 *        the rebalancing that drives it.
 *
 * A particle that changes rank takes everything that describes it: every
 * per-particle array of the engine and every stored field of the field
 * registry, the model's own per-particle arrays, its group memberships
 * (with their serial positions, the order keys of the BC sums) and its
 * bond row: each half-bond with its partner's global id and every
 * per-half-bond array (rest length, broken/pre-cut state, type, the
 * model's coefficients and histories).  After the move every rank
 * re-resolves the partner ids to local indices, finds the owners of the
 * partners it does not own through a Zoltan distributed directory (no
 * rank holds the whole ownership map), fetches those ghosts' records from
 * their owners and rebuilds the halo lists.  A bond's two half-bonds carry
 * their own state, so a bond broken before the move is broken on both
 * sides after it.  Nothing is gathered on one rank: each rank sends and
 * receives only the particles that move and the ghosts it needs.
 *
 * Owned particles stay in ascending global id and each row keeps its
 * serial order, so a run with migrations gives the same bits as one rank.
 */
#ifndef SPALL_CORE_PARALLEL_MIGRATE_H
#define SPALL_CORE_PARALLEL_MIGRATE_H

#include <stddef.h>

struct bond_list;
struct sim;
struct spall_error;

#define PAR_MIGRATE_MAX_ARRAYS 112 /* SPH lends its ~100 state arrays */

/** What a model lends the migration (model_ops.migrate_arrays): its bond
 *  list, the address of its half-bond count, and its per-particle and
 *  per-half-bond arrays that are not stored fields of the registry (the
 *  addresses of the array pointers: migration replaces the arrays). */
struct par_model_arrays {
    struct bond_list *bl;
    size_t *n_half;
    int n_particle;
    void **particle[PAR_MIGRATE_MAX_ARRAYS];
    size_t particle_size[PAR_MIGRATE_MAX_ARRAYS];
    int n_bond;
    void **bond[PAR_MIGRATE_MAX_ARRAYS];
    size_t bond_size[PAR_MIGRATE_MAX_ARRAYS];
};

/** Move owned particle i (i < n_owned) to rank dest[i] with all its state,
 *  then rebuild ghosts and halo (collective; errors agreed).  *moved: the
 *  particles that changed rank, summed over all ranks. */
int par_migrate(struct sim *s, const int *dest, unsigned long long *moved,
                struct spall_error *err);

/** Rebalancing settings (deck `parallel:`, docs/decks.md). */
struct par_balance_opts {
    long rebalance_every;       /**< steps between imbalance checks (0: never rebalance) */
    double imbalance_threshold; /**< repartition when max/mean work >= this */
};

/** Work imbalance of the owned particles: max over ranks / mean, the work
 *  of a particle being 1 + its intact half-bonds (the force loop's cost).
 *  1 when serial (collective). */
double par_imbalance(const struct sim *s);

/** Repartition with Zoltan RCB on the current positions weighted by the
 *  work above, starting from the previous cuts, and migrate (collective).
 *  *before, *after: the imbalance; *moved: particles that changed rank. */
int par_rebalance(struct sim *s, double *before, double *after, unsigned long long *moved,
                  struct spall_error *err);

/** Rebalances and particles migrated so far (run.log). */
void par_balance_stats(const struct sim *s, long *rebalances, unsigned long long *migrated);

/** Migrations so far (par_migrate): a rebalance's and the distributed
 *  set-up's partition (which rebalances does not count).  Lists kept on
 *  local indices across force calls are stale once it changes. */
long par_layouts(const struct sim *s);

#endif
