/**
 * @file psum.h
 * @brief Exact sums over all ranks (issue 20): each rank accumulates its
 *        owned terms in exact accumulators (core/exact_sum.h) and one
 *        MPI_Allreduce of the accumulators' integer words completes them.
 *
 * Integer addition is associative, so every rank receives the same words
 * whatever the decomposition and the reduction tree, and the rounded sums
 * are identical on every rank and for every rank count (and to the serial
 * run, which rounds the same exact value).  Nothing travels to rank 0 and
 * nothing is sorted: a sum costs one collective of XSUM_WORDS int64 words
 * per accumulator.
 */
#ifndef SPALL_CORE_PARALLEL_PSUM_H
#define SPALL_CORE_PARALLEL_PSUM_H

#include <stddef.h>

struct model;
struct sim;
struct xsum;

/** Complete @p n local exact sums: on a distributed run (s->par set) add
 *  the accumulators of all ranks (collective: every rank calls it with the
 *  same @p n), then out[k] = acc[k] rounded to the nearest double.  Serial:
 *  the rounding alone. */
void par_xsum_finish(const struct sim *s, struct xsum *acc, size_t n, double *out);

/** A model's per-particle strain energy (and stress, may be NULL). */
typedef void (*par_particle_energy_fn)(const struct model *m, const struct sim *s, size_t i,
                                       double *energy, double *stress);
/** A bond model's energy account: the exact sums of the strain energy
 *  @p eval gives each owned particle and of its dissipated store @p diss,
 *  over all ranks when distributed (collective then), serial otherwise. */
void par_bond_energy(const struct model *m, const struct sim *s, par_particle_energy_fn eval,
                     const double *diss, double *strain, double *dissipated);

#endif
