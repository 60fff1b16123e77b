/**
 * @file gather.h
 * @brief Read-back of a distributed run for library callers that measure
 *        it themselves (`spall validate`, `spall bench`; docs/parallel.md,
 *        "validate and bench under mpirun"): values of particles by global
 *        id, on every rank.
 *
 * A distributed run (decomp.h) renumbers the particles: a rank holds its
 * owned particles and ghosts, so an index taken before par_distribute()
 * means nothing afterwards.  The global id does: before distribution it is
 * the serial index.  These functions hand every rank the owners' values,
 * unchanged (no arithmetic), so a measurement computed from them is the
 * serial one bit for bit.  They move data to every rank and are meant for
 * measurements, not for the time step.  Serial (s->par NULL): plain copies.
 * All are collective when distributed.
 */
#ifndef SPALL_CORE_PARALLEL_GATHER_H
#define SPALL_CORE_PARALLEL_GATHER_H

#include <stddef.h>
#include <stdint.h>

struct sim;
struct spall_error;

/** Local index of the owned particle with global id @p gid on this rank,
 *  or SIZE_MAX when another rank owns it (not collective). */
size_t par_owned_index(const struct sim *s, int64_t gid);

/** The whole run's values of the per-particle array @p local (indexed by
 *  local particle) into @p global (par_n_global(s) entries, indexed by
 *  global id) on every rank.  Fails (agreed over the ranks) when a rank is
 *  out of memory. */
int par_gather_by_gid(const struct sim *s, const double *local, double *global,
                      struct spall_error *err);

/** Values of @p local at the @p k particles with global ids @p gid into
 *  @p out, on every rank (each id must exist). */
void par_values_at(const struct sim *s, const double *local, const int64_t *gid, size_t k,
                   double *out);

/** The same for one particle. */
double par_value_at(const struct sim *s, const double *local, int64_t gid);

/** Barrier that sleeps while it waits (1 ms polls) instead of spinning in
 *  MPI: for a rank that idles while rank 0 runs something alone
 *  (`spall validate`'s serial cases), so that it leaves its core to the
 *  work.  No-op without MPI or on one rank. */
void par_barrier_idle(void);

/** This rank's share of a distributed run's halo (what `spall bench`
 *  reports; all zero when serial). */
struct par_halo_volume {
    size_t owned, ghosts;  /**< particles held: owned, and ghosts of other ranks' */
    size_t sent;           /**< particles sent per position halo exchange */
    size_t bytes;          /**< bytes sent per position halo exchange (x and v) */
    long exchanges;        /**< position halo exchanges so far */
    double seconds;        /**< wall seconds spent in them (not a performance number on a
                                loaded machine) */
};
void par_halo_volume(const struct sim *s, struct par_halo_volume *out);

#endif
