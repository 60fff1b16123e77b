/**
 * @file bc_work.h
 * @brief The work a prescribed-velocity constraint does on one particle
 *        over one half kick, shared by the serial integrator and its
 *        distributed form (core/parallel/step.c) so that both book the same
 *        number.
 *
 * Over a step the constraint must supply what the particle's kinetic energy
 * gains beyond the work of the other forces on it.  With velocity Verlet
 * that work is the one the strain energy sees: the force of each half kick
 * times the step's drift, f (dt/2) v_{n+1/2}.  So a half kick that takes the
 * particle from its prescribed velocity v_prev (kicked to v_kick by the
 * force) to the newly prescribed v_new books
 *     1/2 m (v_new^2 - v_prev^2) - m (v_kick - v_prev) v_drift,
 * v_drift the prescribed velocity of the drift that the kick's force acts
 * over (v_new for the first half kick, v_prev for the second).  For a
 * constant prescribed velocity this is m (v_new - v_kick) v_new, the
 * trapezoidal rule for the reaction's power, bit for bit what was booked
 * before; for a ramped one the earlier m (v_new - v_kick) v_new booked an
 * extra 1/2 m (v_new - v_prev)^2 per half kick, a first-order error in dt
 * (issue 24 item 9: a PD plate pulled through a ramp showed a balance of
 * -1.11 % / -0.57 % of the input at dt and dt/2).
 */
#ifndef SPALL_CORE_BC_WORK_H
#define SPALL_CORE_BC_WORK_H

static inline double bc_constraint_work(double m, double v_prev, double v_kick, double v_new,
                                        double v_drift)
{
    return m * (v_prev - v_kick) * v_drift + 0.5 * m * (v_new * v_new - v_prev * v_prev);
}

#endif
