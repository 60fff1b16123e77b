/**
 * @file pd_eps.c
 * @brief Elastic-plastic state-based peridynamics (deck `model.formulation:
 *        eps`): the linear peridynamic solid of pd_lps.c with perfectly
 *        plastic flow of the deviatoric extension state ([Mitchell2011]; the
 *        model LAMMPS pair peri/eps implements, which differs from it in three
 *        formulas: docs/performance.md, bench/pd_lps_vs_lammps.sh).
 *
 * Notation of pd_lps.c (omega, beta, m_i, theta_i, d, k, alpha_i = d (d + 2)
 * mu / m_i).  The deviatoric extension e^d = e - theta |xi| / d splits into
 * an elastic part and the plastic extension state e^dp (one value per
 * half-bond, the history of the model).  With tau = alpha_i (e^d - e^dp):
 *   t_ij = omega (d k theta_i |xi| / m_i + tau),
 *   W_i  = k theta^2 / 2 + ||tau||^2 / (2 alpha_i),
 *   ||tau||^2 = sum_j omega beta tau^2 V_j   (the weighted norm of the state),
 *   yield:  ||tau||^2 / 2 <= psi_i = d (d + 2) c_d sigma_Y^2 / (4 m_i).
 * psi_i follows from the homogeneous state: e^d = eps^d : (n (x) n) |xi| with
 * an isotropic family gives ||tau||^2 = alpha_i s : s / (2 mu), s the
 * deviatoric stress, and J2 yield is s : s <= c_d sigma_Y^2.  In 3D c_3 = 2/3
 * (von Mises), and with omega = 1 and m = 4 pi delta^5 / 5 psi = 25
 * sigma_Y^2 / (8 pi delta^5), the constant of [Mitchell2011] / peri/eps; here
 * each particle's own m_i is used, as for alpha_i.  In 2D the criterion is
 * that of the in-plane deviator, c_2 = 1/2, which yields at sigma_Y in
 * uniaxial stress (a 2D J2 surface: not the plane-stress or plane-strain
 * reduction of the 3D von Mises surface, with which it agrees in uniaxial
 * plane stress only).
 * Return map (backward Euler, radial): tau_trial = alpha_i (e^d - e^dp_n); if
 * ||tau_trial||^2 > 2 psi_i, tau = tau_trial sqrt(2 psi_i) / ||tau_trial||
 * and e^dp = e^d - tau / alpha_i.  The flow direction is tau itself (not
 * omega tau as in [Mitchell2011], the same for omega = 1), so e^dp stays
 * deviatoric in the omega-weighted sense (sum omega beta |xi| e^dp V = 0)
 * and the dilatation stays elastic.  Plastic work tau . delta e^dp V_i goes
 * to the particle's dissipated energy.  Bonds break at the LPS critical
 * stretch (pd_lps.c).  The force passes are in pd_lps_kernel.c.
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/parallel/decomp.h"
#include "core/parallel/setup_dist.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>

/* c_d of the J2 criterion s : s <= c_d sigma_Y^2 (see the file comment) */
double pd_eps_cd(int dim)
{
    return dim == 3 ? 2.0 / 3.0 : 0.5;
}

/* The reverse slot of each half-bond i->j as its place in j's row: one
 * byte where no family has more than 256 bonds (a 3D horizon of 3 dx has
 * 122), else 16 bits; bond_list_build_reverse keeps 8 B. */
static int eps_reverse(struct model *m, struct spall_error *err)
{
    const struct bond_list *bl = m->bl;
    const size_t n = bl->n, nh = bl->offset[n];
    struct pd_lps *L = &m->lps;
    size_t len = 0;
    for (size_t i = 0; i < n; i++)
        len = bl->offset[i + 1] - bl->offset[i] > len ? bl->offset[i + 1] - bl->offset[i] : len;
    if (len > (size_t)UINT16_MAX + 1)
        return spall_error_set_key(err, SPALL_ERR_INPUT, "model.formulation",
                                   "formulation eps: a family of %zu bonds (at most 65 536)",
                                   len);
    const bool narrow = len <= (size_t)UINT8_MAX + 1;
    if (narrow ? !(L->rloc8 = malloc(nh ? nh : 1)) : !(L->rloc = malloc((nh ? nh : 1) * 2)))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the reverse slots");
    int missing = 0;
#pragma omp parallel for schedule(static) reduction(| : missing)
    for (size_t i = 0; i < n; i++)
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            const size_t j = (size_t)bl->partner[s];
            const size_t r = bond_list_slot(bl, j, (int32_t)i);
            missing |= r == SIZE_MAX;
            const size_t q = r == SIZE_MAX ? 0 : r - bl->offset[j];
            if (narrow)
                L->rloc8[s] = (uint8_t)q;
            else
                L->rloc[s] = (uint16_t)q;
        }
    if (missing)
        return spall_error_set(err, SPALL_ERR_INTERNAL,
                               "bond list is not symmetric: a bond has no reverse half");
    return SPALL_OK;
}

int pd_eps_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct pd_lps *L = &m->lps;
    const size_t n = sim->p->n, nh = m->bl->offset[n];
    /* a window of the distributed set-up computes no force: e^dp (zero)
     * and the reverse slots would only be carried to pd_localize, which
     * makes them for the rank's rows (pd_eps_localized), not the window's */
    if (par_setup_window(sim))
        return SPALL_OK;
    /* hs: theta, return-map scale and d k theta / m_i per particle, which
     * t_ji reads (pd_lps_kernel.c) */
    if (!(L->ep = calloc(nh ? nh : 1, sizeof(double))) ||
        !(L->hs = calloc(3 * (n ? n : 1), sizeof(double))))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the plastic "
                               "extension state");
    /* t_ji of a pair reads e^dp of j's half: the slot of the same bond there */
    return eps_reverse(m, err);
}

int pd_eps_localized(struct pd_lps *L, size_t nh, size_t n, struct spall_error *err)
{
    /* distributed: no reverse slots; i's copy epr of e^dp_ji instead */
    if (!(L->ep = calloc(nh ? nh : 1, sizeof(double))) ||
        !(L->epr = calloc(nh ? nh : 1, sizeof(double))) ||
        !(L->hs = calloc(3 * (n ? n : 1), sizeof(double))))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the plastic "
                               "extension state");
    return SPALL_OK;
}

/* For a homogeneous plastic strain eps^p (deviatoric) and an isotropic family,
 * sum omega beta (e^dp)^2 V = 2 m eps^p : eps^p / (d (d + 2)); the equivalent
 * plastic strain of the J2 criterion is sqrt(c_d eps^p : eps^p) (3D: the usual
 * sqrt(2/3 eps^p : eps^p); 2D: the axial plastic strain in uniaxial stress). */
double pd_eps_plastic_strain(const struct model *m, const struct sim *sim, size_t i)
{
    const struct pd_lps_bonds B = pd_lps_bonds(m);
    const struct bond_list *bl = m->bl;
    const struct pd_lps *L = &m->lps;
    const double d = (double)sim->dim;
    if (!L->ep || !(L->wvol[i] > 0.0))
        return 0.0;
    double q = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++)
        if (!(bl->state[s] & BOND_BROKEN))
            q += B.ob[pd_lps_row(&B, s)] * L->ep[s] * L->ep[s] * sim->p->volume[bl->partner[s]];
    return sqrt(pd_eps_cd(sim->dim) * d * (d + 2.0) * q / (2.0 * L->wvol[i]));
}
