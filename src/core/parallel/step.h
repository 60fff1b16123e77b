/**
 * @file step.h
 * @brief The integrator's per-step checks on a distributed run
 *        (core/integrator.c calls these when sim->par is set).  The energy
 *        account, reactions and work need no distributed replica: their
 *        sums are exact and complete with one collective (psum.h).
 */
#ifndef SPALL_CORE_PARALLEL_STEP_H
#define SPALL_CORE_PARALLEL_STEP_H

#include <stddef.h>
#include <stdint.h>

struct sim;

/** Non-finite velocity or position anywhere: returns 1 and the smallest
 *  such global id; *kinetic: the screening kinetic energy (the same value
 *  on every rank: one collective of exact accumulators; a second one only
 *  when some component's sum is not finite). */
int par_check_finite(const struct sim *s, int64_t *bad_gid, double *kinetic);
/** Global id of the fastest particle (the first in gid order on ties). */
int64_t par_fastest_gid(const struct sim *s);

#endif
