/**
 * @file step.h
 * @brief The integrator's sums over particles on a distributed run
 *        (core/integrator.c calls these when sim->par is set): the same
 *        terms as the serial loops, added in the serial order
 *        (decomp.h, par_ordered_reduce), so every rank count gives the
 *        serial energy account, reactions and work bit for bit.
 */
#ifndef SPALL_CORE_PARALLEL_STEP_H
#define SPALL_CORE_PARALLEL_STEP_H

#include <stddef.h>
#include <stdint.h>

struct bc;
struct sim;

/** Damping loss and gravity work over the drift (account_body_work). */
void par_body_work(struct sim *s, double dt);
/** Set BC @p b's prescribed components from vp[d] (the previous
 *  imposition's) to vb[d] on its owned members and book its reaction (when
 *  @p record) and work (impose_velocities, core/bc_work.h). */
void par_bc_velocities(struct sim *s, struct bc *b, const double vp[3], const double vb[3],
                       double half_dt, int record);
/** Work of load BC @p b over the drift (account_load_work); returns it. */
double par_load_work(const struct sim *s, const struct bc *b, double dt);
/** Kinetic energy of the particles (sim_update_energy). */
double par_kinetic(const struct sim *s);
/** Non-finite velocity or position anywhere: returns 1 and the smallest
 *  such global id; *kinetic: the screening kinetic energy (an unordered
 *  global sum: it only decides whether the full check runs). */
int par_check_finite(const struct sim *s, int64_t *bad_gid, double *kinetic);
/** Global id of the fastest particle (the first in gid order on ties). */
int64_t par_fastest_gid(const struct sim *s);

#endif
