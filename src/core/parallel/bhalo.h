/**
 * @file bhalo.h
 * @brief Per-half-bond halo of a distributed bond model (docs/parallel.md,
 *        "Per-bond halo"): for a force that needs, on each bond i-j, a value
 *        that j computes on its own half-bond j->i (peridynamics'
 *        formulation eps: the partner's scalar force state t_ji after its
 *        plastic return map, which depends on j's whole family).
 *
 * A bond between an owned particle i and a ghost j has its half j->i on
 * j's owner.  After the owners have computed their half-bond values, one
 * point-to-point message per neighbour rank carries the value of every
 * half-bond whose partner is a ghost on the receiving rank.  Both sides
 * derive the message layout from the symmetric bond rows without talking:
 * the sender walks its owned particles in ascending gid and each row in
 * ascending partner gid, the receiver its ghosts of that rank in ascending
 * gid and, per ghost, its owned partners in ascending gid, so the two
 * walks visit the same (gid_j, gid_i) pairs in the same order.  Broken
 * half-bonds travel too, so the layout is fixed between migrations.
 *
 * The plan is built on first use and kept by the decomposition until the
 * particles migrate.  Collective where noted.
 */
#ifndef SPALL_CORE_PARALLEL_BHALO_H
#define SPALL_CORE_PARALLEL_BHALO_H

#include <stddef.h>

struct bond_list;
struct sim;
struct spall_error;

/** The reverse index of the local rows of @p bl (owned rows; ghost rows are
 *  empty): for half-bond k of i->j, the slot of j->i in j's row when j is
 *  owned, else nh + q, where nh = bl->offset[bl->n] and q is the position
 *  of j->i's value among the n_recv values par_bhalo_exchange returns.
 *  *n_recv: how many that is.  The first call after a distribution or a
 *  migration (the same call on every rank) builds the plan and is
 *  collective: a failure on any rank returns NULL on all, with the error
 *  agreed (comm.h par_agree). */
const size_t *par_bhalo_reverse(const struct sim *s, const struct bond_list *bl,
                                size_t *n_recv, struct spall_error *err);

/** Values per half-bond an exchange can carry. */
#define PAR_BHALO_MAX_WIDTH 3

/** Send the values val[k ncomp .. k ncomp + ncomp) of this rank's
 *  half-bonds k whose partner is a ghost, and return the n_recv x @p ncomp
 *  values of the reverse halves from the partners' owners (the plan's
 *  buffer, valid until the next exchange; received position q at
 *  q ncomp).  Collective over the ranks sharing bonds; the plan must exist
 *  (par_bhalo_reverse); 1 <= ncomp <= PAR_BHALO_MAX_WIDTH. */
const double *par_bhalo_exchange(const struct sim *s, const double *val, int ncomp);

/** Drop the plan (after migration; decomp destroy). */
struct par_decomp;
void par_bhalo_free(struct par_decomp *d);

#endif
