/**
 * @file decomp.h
 * @brief Domain decomposition of a bonded run over MPI ranks (issue 20):
 *        Zoltan RCB partition weighted by bond count, owned particles and
 *        their ghosts, the halo exchange of positions, and the
 *        decomposition-independent values the engine needs.
 *
 * First increment (docs/parallel.md): every rank builds and prepares the
 * whole body exactly as a serial run does (so the set-up, pre-cracks, the
 * stable time step and the initial energy account are the serial ones),
 * then par_distribute() partitions it with Zoltan and keeps, renumbered,
 * the rank's owned particles [0, n_owned) in ascending global id followed
 * by its ghosts [n_owned, n) in ascending global id.  Ghosts are the bond
 * partners of owned particles: for a model with fixed bonds that is exactly
 * the interaction range, so no particle can leave its ghost-covered region
 * and no migration is needed.  Bond rows keep the serial order (ascending
 * partner gid), so every particle's force sum is the serial one bit for bit.
 *
 * Sums over particles (energies, BC reactions and work) are exact
 * (core/exact_sum.h): each rank accumulates its owned terms and one
 * collective completes them (psum.h), so history.csv does not depend on
 * the rank count.
 *
 * Everything here is collective: every rank calls it in the same order.
 * Without MPI (or on one rank) sim->par is NULL and nothing here is used.
 */
#ifndef SPALL_CORE_PARALLEL_DECOMP_H
#define SPALL_CORE_PARALLEL_DECOMP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct bc;
struct fragments;
struct sim;
struct spall_error;

struct par_decomp;

/** Refuse, before any output exists, what cannot yet run on more than one
 *  rank (SPALL_ERR_INPUT, one line).  Not collective: every rank decides
 *  the same from the same deck. */
int par_check_supported(const struct sim *s, struct spall_error *err);

/** Partition the prepared run with Zoltan and keep owned + ghosts (see
 *  above); sets s->par.  Collective; errors are agreed (comm.h). */
int par_distribute(struct sim *s, struct spall_error *err);
void par_decomp_destroy(struct par_decomp **d);

/** Decomposition summary for run.log (collective; the text is complete on
 *  rank 0): ranks x threads, owned and ghost particles per rank, bytes of
 *  the halo per step. */
void par_describe(const struct sim *s, char *buf, size_t len);

/** Halo exchanges so far and the wall seconds this rank spent in them
 *  (run.log; 0 when serial). */
void par_halo_stats(const struct sim *s, long *calls, double *seconds);

/** Particles of the whole run (s->p->n_owned when serial). */
size_t par_n_global(const struct sim *s);
/** Half-bonds or interactions of the whole run as counted at set-up. */
size_t par_interactions_global(const struct sim *s, size_t local);
/** Members of group @p g over all ranks (s->groups[g].n when serial). */
size_t sim_group_count(const struct sim *s, int g);

/** Copy the owners' current positions and velocities into the ghosts
 *  (collective; before every force call). */
void par_halo_x(struct sim *s);

/** Reducer run on rank 0 over @p n rows of @p ncol terms, sorted in the
 *  serial order; writes @p nout results. */
typedef void (*par_reduce_fn)(const double *rows, size_t n, int ncol, double *out,
                              const void *ctx);
/** out[c] = rows[0][c] + rows[1][c] + ... in row order (one accumulator per column). */
void par_reduce_cols(const double *rows, size_t n, int ncol, double *out, const void *ctx);

/** Gather each rank's @p n rows (@p ncol doubles each) with their order
 *  keys to rank 0, sort them by key, reduce with @p fn there and broadcast
 *  the @p nout results to every rank (collective).  For sums that feed the
 *  dynamics in the serial order (impactor contact forces: an exact sum
 *  would change the serial run's last bits) and the thermal history;
 *  diagnostics use the exact sums of psum.h. */
void par_ordered_reduce(const int64_t *key, const double *rows, size_t n, int ncol,
                        par_reduce_fn fn, const void *ctx, double *out, int nout);

/** Order key of local member @p q of group @p g: its position in the
 *  serial group list. */
int64_t par_group_key(const struct sim *s, int g, size_t q);

/** Displacement and velocity of probe @p k, from its owner (collective). */
void par_probe(const struct sim *s, size_t k, double u[3], double v[3]);

/** Fragments of the whole run (core/fragments.h), computed distributed
 *  (parallel/fragments_par.c): every rank gets the labels of its owned
 *  particles, rank 0 the whole fragment list, other ranks none (collective). */
int par_fragments(const struct sim *s, struct fragments *f, struct spall_error *err);
/** Fragment id (smallest gid of its fragment) of each owned particle into
 *  @p label (n_owned entries; NULL: this rank has no memory for it, which
 *  fails all ranks, but it still takes part).  Collective. */
int par_fragment_labels(const struct sim *s, int64_t *label, struct spall_error *err);
/** Copy @p ncomp doubles per particle from the owners into the ghosts
 *  (the halo lists of par_halo_x; collective). */
void par_halo_values(const struct sim *s, double *vals, int ncomp);
/** The same for any @p ncomp (own buffers, halo_block.c; collective):
 *  SPALL_ERR_NOMEM on every rank when one is out of memory. */
int par_halo_block(const struct sim *s, double *vals, int ncomp);

#endif
