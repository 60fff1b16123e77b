/**
 * @file sghost.h
 * @brief Spatial ghosts (issue 22): the second ghost kind, for models whose
 *        partners come from a neighbour search (SPH, macro-particles,
 *        particle contact) rather than from fixed bonds (decomp.h).
 *
 * A rank's ghosts are the particles owned by other ranks that lie within
 * the interaction range plus a skin of the bounding box of the rank's owned
 * particles (the boxes of all ranks are exchanged at every build).  Between
 * builds the ghosts' positions are refreshed from their owners along the
 * lists of the last build (par_sghost_update); the set is rebuilt when any
 * particle has moved more than half the skin since the last build, because
 * two particles that each moved less than skin/2 cannot have come closer
 * than the range without one of them being a ghost of the other's rank
 * (par_sghost_check).  A particle that has moved more than the whole skin
 * when checked means the check ran too seldom: interactions may already
 * have been missed, and the check stops with an error naming the particle.
 *
 * Ghosts are held in ascending global id, so anything computed from them
 * in a fixed order does not depend on the rank count.
 *
 * Every function is collective over MPI_COMM_WORLD (serially there are no
 * ghosts, and the check only compares displacements).
 */
#ifndef SPALL_CORE_PARALLEL_SGHOST_H
#define SPALL_CORE_PARALLEL_SGHOST_H

#include <stddef.h>
#include <stdint.h>

struct spall_error;
struct par_sghost;

/** A ghost set for @p dim-dimensional positions with interaction @p range
 *  and @p skin (both > 0, metres).  Not collective. */
int par_sghost_create(struct par_sghost **out, int dim, double range, double skin,
                      struct spall_error *err);
void par_sghost_destroy(struct par_sghost **g);

/** A new @p range and @p skin (both > 0, metres) for the builds that follow:
 *  a model whose interaction range grows during the run (SPH with a
 *  variable smoothing length: its list radius follows h_max) gives the
 *  range of the list it is about to build.  Not collective (every rank
 *  must set the same values). */
int par_sghost_set_range(struct par_sghost *g, double range, double skin,
                         struct spall_error *err);

/** Mirror planes through the origin (bit d: the plane x_d = 0) for the
 *  builds that follow: a particle is also sent to a rank when one of its
 *  images in these planes (each plane and each combination) lies within
 *  range + skin of the rank's box, so that a model which mirrors every
 *  particle it holds near a plane (SPH's symmetry planes) holds the source
 *  of every image its owned particles can reach.  Default none.  Not
 *  collective (every rank must set the same planes). */
void par_sghost_set_mirror(struct par_sghost *g, unsigned planes);

/** Particles to send at the next build whatever their distance: owned
 *  index idx[k] to rank rank[k] (k < @p n; repeats and this rank's own
 *  number are ignored).  For a model that also needs fixed partners on
 *  other ranks as ghosts (TLSPH bodies behind an interface: the reference
 *  partners, whose current distance the box test does not bound): the
 *  ghost set becomes the union, each ghost once, in ascending gid.  Used
 *  by the next par_sghost_build only.  Not collective. */
int par_sghost_set_forced(struct par_sghost *g, size_t n, const size_t *idx, const int *rank,
                          struct spall_error *err);

/** Build the ghost set from this rank's @p n owned particles (positions
 *  x[d][i], ids gid[i]); remembers the positions for par_sghost_check and
 *  the send lists for par_sghost_update.  Collective. */
int par_sghost_build(struct par_sghost *g, size_t n, const double *const x[3],
                     const int64_t *gid, struct spall_error *err);

/** Copy the owners' current positions (same owned order as at the build)
 *  into the ghosts.  Collective. */
void par_sghost_update(struct par_sghost *g, const double *const x[3]);

/** Copy @p ncomp doubles per particle from the owners (owned[i * ncomp + c],
 *  same owned order as at the build) into the ghosts (ghost[q * ncomp + c],
 *  q in ascending gid).  Collective; errors agreed. */
int par_sghost_values(struct par_sghost *g, const double *owned, double *ghost, int ncomp,
                      struct spall_error *err);

/** Has any particle (on any rank) moved more than skin/2 since the build?
 *  *rebuild = 1 then.  A particle that moved more than the whole skin fails
 *  (SPALL_ERR_UNSTABLE, the smallest such global id named, on every rank).
 *  Collective. */
int par_sghost_check(const struct par_sghost *g, const double *const x[3], int *rebuild,
                     struct spall_error *err);

/** The ghosts of the last build, in ascending global id. */
size_t par_sghost_count(const struct par_sghost *g);
const int64_t *par_sghost_gid(const struct par_sghost *g);
/** Component @p d of the ghosts' positions (as of the last build or update). */
const double *par_sghost_x(const struct par_sghost *g, int d);
/** Owner rank of each ghost. */
const int *par_sghost_owner(const struct par_sghost *g);
/** Builds so far (for run.log). */
long par_sghost_builds(const struct par_sghost *g);

/** The exchange lists of the last build, for a caller that refreshes more
 *  than positions (core/parallel/spatial.c): per rank r, scount[r]
 *  particles sent from sdispl[r] of send_idx (owned indices, ascending gid)
 *  and rcount[r] received from rdispl[r], the k-th received being ghost
 *  recv_idx[k].  Arrays of par_size() entries; NULL before a build on a
 *  distributed run, and always on one rank. */
struct par_sghost_lists {
    const int *scount, *sdispl, *rcount, *rdispl;
    const size_t *send_idx, *recv_idx;
    size_t n_send, n_recv;
};
void par_sghost_lists(const struct par_sghost *g, struct par_sghost_lists *out);

#endif
