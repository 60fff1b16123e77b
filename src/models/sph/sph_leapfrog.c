/**
 * @file sph_leapfrog.c
 * @brief Staggered (kick-drift-kick) leapfrog for the SPH state:
 *        model.time_integration: leapfrog.
 *
 * Why: the predictor-corrector of [Meng2021] Eqs. 3.35-3.37 as run by the
 * engine (positions by leapfrog; rho, e, S by the trapezoid of the rate of
 * step n and the rate at the predicted state; forces of step n+1 from the
 * PREDICTED stress S_n + dt dS_n) is unstable for an undamped elastic
 * oscillation at every time step.  Model problem v' = s, s' = -w^2 v run
 * through exactly that sequence: the amplitude grows by 2.6e-5 per step at
 * w dt = 0.1, 2.4e-3 at w dt = 0.3, 2.6e-2 at w dt = 0.5.  Artificial
 * viscosity hides it for the low modes; the highest modes of a plain-SPH
 * beam (w dt ~ 1 at run.dt_factor 0.5) blow up in ~3000 steps (measured:
 * cubic-spline cantilever, energy 1e-7 J -> 1e3 J between 0.25 and
 * 0.55 ms, in the interior of the beam, stable at dt_factor 0.25).
 *
 * The leapfrog here is the engine's velocity Verlet with the state
 * staggered on the velocities (INTEGRATOR_LEAPFROG):
 *   v_{n+1/2} = v_n + dt/2 a_n,  x_{n+1} = x_n + dt v_{n+1/2}
 *   L = grad v_{n+1/2} at x_{n+1}        (the model's force call)
 *   S_{n+1} = S_n + dt dS/dt(S_n, L), rho_{n+1} = rho_n (1 - dt tr D), radial return
 *   a_{n+1} = forces(S_{n+1}, rho_{n+1}, x_{n+1}),  v_{n+1} = v_{n+1/2} + dt/2 a_{n+1}
 * which for v' = s, s' = -w^2 v is the classic leapfrog: stable up to
 * w dt = 2, no amplitude drift.  The stress power enters e with the mean
 * of the old and new stress (sigma_n + sigma_{n+1})/2 : D, which for a
 * linear elastic step is the exact elastic energy increment; the artificial
 * viscosity / stress heating is added after the force pass (sph_rates.c).
 * The engine calls the force call of each step as compute_forces_kick
 * with dt (the state advance in the middle of it); the initial forces are
 * the plain compute_forces, which leaves the state alone.  The XSPH drift
 * is the engine's (sph_drift_velocity).
 */
#include "models/sph/sph_internal.h"

#include "core/particles.h"
#include "core/sim.h"

#include <math.h>

/* sigma : D of particle i (3D contraction; in 2D D_zz = L[8] as set by
 * sph_stress_rate, sigma_zz = S_zz - P). */
static inline double stress_power(const struct model *m, size_t i, double P)
{
    static const int ia[6] = {0, 1, 2, 0, 1, 0}, ib[6] = {0, 1, 2, 1, 2, 2};
    double pw = 0.0;
    for (int c = 0; c < 6; c++) {
        double d = 0.5 * (m->L[ia[c] * 3 + ib[c]][i] + m->L[ib[c] * 3 + ia[c]][i]);
        double sg = m->S[c][i] - (c < 3 ? P : 0.0);
        pw += (c < 3 ? 1.0 : 2.0) * sg * d;
    }
    return pw;
}

void sph_leapfrog_advance_one(struct model *m, size_t i, double dt)
{
    const struct sph_material *mt = &m->mat[m->sim->p->material[i]];
    const bool integ_rho = m->opt.kern.density == SPH_DENSITY_CONTINUITY;
    double trD;
    sph_stress_rate(m, i, &trD); /* dS (Jaumann) and D_zz from L */
    const double rho0 = m->rho[i];
    const double pw0 = stress_power(m, i, m->P[i]);
    if (integ_rho)
        m->rho[i] = rho0 * (1.0 - dt * trD); /* Eq. 3.18 */
    if (m->opt.kern.variable_h) {
        double trp = m->L[0][i] + m->L[4][i] + (m->dim == 3 ? m->L[8][i] : 0.0);
        m->h[i] += dt * m->h[i] * trp / m->dim;
    }
    for (int c = 0; c < 6; c++)
        m->S[c][i] += dt * m->dS[c][i];
    sph_plastic_return(m, i, dt, true);
    const double P =
        sph_carried_pressure(mt, m->failed[i], sph_eos_pressure(mt, m->rho[i], m->e[i]));
    const double pw1 = stress_power(m, i, P);
    m->e[i] += dt * 0.5 * (pw0 + pw1) / (0.5 * (rho0 + m->rho[i]));
}

void sph_leapfrog_advance(struct model *m, struct sim *s, double dt, int mine)
{
    const size_t n = s->p->n_owned;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        if (!sph_skip(m, i, mine))
            sph_leapfrog_advance_one(m, i, dt);
}
