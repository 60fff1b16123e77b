/**
 * @file step_passes.h
 * @brief The integrator's per-particle passes (step_passes.c): kicks,
 *        drift, the kick and drift fused, the kinetic-energy block sums.
 *        Core-internal (core/integrator.c).
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

/** Sum of m v^2 over [lo, hi): four interleaved partial sums, combined as
 *  (a0 + a1) + (a2 + a3), then the rest in order. */
double step_block_mv2(const double *m, const double *v, size_t lo, size_t hi);

#endif
