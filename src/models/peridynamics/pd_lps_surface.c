/**
 * @file pd_lps_surface.c
 * @brief Surface correction of the linear peridynamic solid (deck
 *        `model.surface_correction: true` with `formulation: lps | eps`,
 *        issue 26 item 1).
 *
 * Near a free surface a family is incomplete.  With each particle's own
 * weighted volume m_i (pd_lps.c) an isotropic expansion is still exact, but
 * the second moment of the family, K_i = sum omega beta xi (x) xi V, is no
 * longer isotropic (the lattice keeps the in-plane bonds of the surface
 * layer whole and loses those across it): the dilatation of a uniaxial
 * stretch along the normal comes out too small, and the deviatoric energy,
 * whose alpha_i = d (d + 2) mu / m_i assumes a full family's fourth moment,
 * wrong.  The correction has two parts, both kept inside the LPS energy
 * W_i = k theta^2 / 2 + alpha_i / 2 sum omega beta (e^d)^2 V (so the force
 * state is still dW_i / de and any nu is kept):
 *  1. dilatation (weighted-volume based): the influence of bond ij is scaled
 *     by the ellipsoidal mean ([MadenciOterkus2014] Eq. 4.31) of the two
 *     ends' directional factors r_k = (m / d) / K_kk, the factor that makes
 *     K_kk = m / d; symmetric in i, j.  Scaling one bond changes both ends'
 *     moments, so the factors are applied repeatedly (a fixed point; at most
 *     SURF_ITER passes, stopped once every |r_k - 1| < SURF_TOL) and the
 *     dilatation of a homogeneous stretch along each axis becomes exact
 *     (off-diagonal moments at edges and corners are not corrected).
 *  2. deviatoric (energy based, [MadenciOterkus2014] sec. 4.2, whose test
 *     deformations are uniform stretches along the axes): per particle
 *     a_i = sum_a mu eps_a^d : eps_a^d / sum_a W^d_i(eps_a) over the d
 *     uniaxial stretches eps_a = e_a (x) e_a, W^d_i = alpha_i / 2 sum omega
 *     beta (e^d)^2 V the discrete deviatoric energy density; alpha_i is
 *     multiplied by a_i.  With part 1 this makes the axial response (E, nu
 *     along the axes) of a body exact for a homogeneous strain; the shear
 *     response is not corrected (fitting shears too, with one a_i, spoils
 *     E and nu: measured in pd-lps-surface, docs/validation.md).
 * Interior particles (complete, isotropic families) keep r = 1 and a = 1 up
 * to the lattice's own anisotropy, which influence_correction (cubic)
 * removes first when asked.  Checked by `spall validate pd-lps-surface`.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/parallel/comm.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>

#define SURF_ITER 200
#define SURF_TOL 1e-6

/* K_kk of particle i (reference bonds, all of them: the correction is set up
 * before pre-cracks, which then leave the family in pd_lps_weights) */
static void second_moment(const struct model *m, const struct sim *sim, size_t i, double *K)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    K[0] = K[1] = K[2] = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        const size_t j = (size_t)bl->partner[s];
        for (int a = 0; a < sim->dim; a++) {
            const double e = p->x0[a][j] - p->x0[a][i];
            K[a] += m->lps.ob[s] * e * e * p->volume[j];
        }
    }
}

/* Part 1: bond factors on omega until every family's K is isotropic on the
 * diagonal.  r holds 3 factors per particle.
 * In a window of the distributed set-up (core/parallel/setup_dist.h) a
 * bond's factor after k passes depends on particles k ranges away, so the
 * window alone cannot iterate: the block's particles compute their r (their
 * rows are complete), the halo's r come from the ranks whose blocks hold
 * them, and the stop is the largest change of the whole body.  A row whose
 * family lies in the window (the block's and its partners', two ranges of
 * halo) then sees every factor it reads as serially, pass after pass; the
 * rows cut by the window's edge go wrong but are read by no such row. */
static int dilatation_factors(struct model *m, const struct sim *sim, double *r,
                              struct spall_error *err)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const struct par_setup *ps = par_setup_window(sim);
    const int dim = sim->dim;
    for (int it = 0; it < SURF_ITER; it++) {
        double worst = 0.0;
        for (size_t i = 0; i < p->n; i++) {
            double K[3], mi = 0.0;
            second_moment(m, sim, i, K);
            for (int a = 0; a < dim; a++)
                mi += K[a];
            const bool counts = !ps || par_setup_in_block(ps, i);
            for (int a = 0; a < 3; a++) {
                r[3 * i + (size_t)a] = a < dim && K[a] > 0.0 ? mi / (dim * K[a]) : 1.0;
                if (counts)
                    worst = fmax(worst, fabs(r[3 * i + (size_t)a] - 1.0));
            }
        }
        if (ps) {
            int rc = par_setup_halo_values(sim, r, 3, err);
            if (rc)
                return rc;
            worst = par_max_double(worst);
        }
        if (worst < SURF_TOL)
            return SPALL_OK;
        for (size_t i = 0; i < p->n; i++)
            for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
                const size_t j = (size_t)bl->partner[s];
                double q = 0.0;
                for (int a = 0; a < dim; a++) {
                    const double na = (p->x0[a][j] - p->x0[a][i]) / bl->rest[s];
                    const double g = 0.5 * (r[3 * i + (size_t)a] + r[3 * j + (size_t)a]);
                    q += (na / g) * (na / g);
                }
                if (q > 0.0)
                    m->lps.ob[s] /= sqrt(q);
            }
    }
    return SPALL_OK;
}

/* Part 2: deviatoric energy factor a_i of particle i (see the file comment),
 * from the uniaxial stretches eps = e_a (x) e_a, whose deviatoric energy in
 * the continuum is mu (d - 1) / d each; alpha_i / mu = d (d + 2) / m_i. */
static double deviatoric_factor(const struct model *m, const struct sim *sim, size_t i)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    const int dim = sim->dim;
    const double d = (double)dim;
    double mi = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
        mi += m->lps.ob[s] * bl->rest[s] * bl->rest[s] * p->volume[bl->partner[s]];
    if (!(mi > 0.0))
        return 1.0;
    double w_cont = 0.0, w_disc = 0.0;
    for (int a = 0; a < dim; a++) {
        w_cont += (d - 1.0) / d;
        /* e |xi| = (xi . e_a)^2 for a unit stretch along axis a */
        double sum = 0.0;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            const double xa = p->x0[a][j] - p->x0[a][i];
            sum += m->lps.ob[s] * xa * xa * p->volume[j];
        }
        const double th = d * sum / mi;
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            const double xa = p->x0[a][j] - p->x0[a][i], xi = bl->rest[s];
            const double ed = xa * xa / xi - th * xi / d;
            w_disc += 0.5 * d * (d + 2.0) / mi * m->lps.ob[s] * ed * ed * p->volume[j];
        }
    }
    return w_disc > 0.0 ? w_cont / w_disc : 1.0;
}

int pd_lps_surface_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    const size_t n = sim->p->n;
    double *r = malloc((n ? n : 1) * 3 * sizeof *r);
    int rc = SPALL_OK;
    if (!r || !(m->lps.afac = malloc((n ? n : 1) * sizeof(double))))
        rc = spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the LPS surface correction");
    if (par_setup_window(sim)) /* the passes are collective there */
        rc = par_agree(rc, err);
    if (!rc)
        rc = dilatation_factors(m, sim, r, err);
    free(r);
    if (rc)
        return rc;
    for (size_t i = 0; i < n; i++)
        m->lps.afac[i] = deviatoric_factor(m, sim, i);
    return SPALL_OK;
}
