/**
 * @file step_passes.h
 * @brief The integrator's per-particle passes (step_passes.c): kicks,
 *        drift, the kick and drift fused, the kick with the kinetic-energy
 *        block sums, the block sums alone, the largest shift since a list
 *        build.  Core's (core/integrator.c, core/parallel), the shift also
 *        the models' with Verlet lists.
 */
#ifndef SPALL_STEP_PASSES_H
#define SPALL_STEP_PASSES_H

#include "core/particles.h"

#include <stdbool.h>
#include <stddef.h>

/** v += half_dt f / m over the owned particles, every component. */
void step_kick(struct particles *p, double half_dt);

/** x += dt v over the owned particles, every component. */
void step_drift(struct particles *p, double dt);

/** step_kick then step_drift in one pass (per particle: the kick, then the
 *  drift with the new velocity; the same operations, so the same bits),
 *  and with @p zero_forces the owned forces cleared after the kick read
 *  them (particles_zero_forces' share of the owned rows). */
void step_kick_drift(struct particles *p, double half_dt, double dt, bool zero_forces);

/** Particles per block of the kinetic-energy sums (the NaN check's). */
#define STEP_SUM_BLOCK 4096

/** step_kick, and per block b of STEP_SUM_BLOCK owned particles and
 *  component d the sum of m v^2 with the kicked velocities into
 *  part[3 b + d]: step_block_mv2 of the block, bit for bit, without a
 *  second pass over m and v (a block is summed by one thread, so the sums
 *  do not depend on the thread count). */
void step_kick_sum(struct particles *p, double half_dt, double *part);

/** Sum of m v^2 over [lo, hi): four interleaved partial sums, combined as
 *  (a0 + a1) + (a2 + a3), then the rest in order. */
double step_block_mv2(const double *m, const double *v, size_t lo, size_t hi);

/** The largest |x_i - xb_i|^2 over particles [0, n) (a maximum: exact in
 *  any order, a NaN never one), over the threads: the Verlet-skin test of
 *  a list built at xb (the macro-particle model's, and the engine's over
 *  the owned particles of every rank, core/parallel/spatial.c). */
double step_max_shift2(int dim, size_t n, double *const x[3], double *const xb[3]);

#endif
