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
 * stretch (pd_lps.c).
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
static double eps_cd(int dim)
{
    return dim == 3 ? 2.0 / 3.0 : 0.5;
}

int pd_eps_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    struct pd_lps *L = &m->lps;
    const size_t nh = m->bl->offset[sim->p->n];
    /* a window of the distributed set-up computes no force: e^dp (zero),
     * t and the reverse slots would only be carried to pd_localize, which
     * makes them for the rank's rows (pd_eps_localized), not the window's */
    if (par_setup_window(sim))
        return SPALL_OK;
    if (!(L->ep = calloc(nh ? nh : 1, sizeof(double))) ||
        !(L->tb = calloc(nh ? nh : 1, sizeof(double))))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the plastic "
                               "extension state");
    /* t_ji of a pair comes from j's row: the slot of the same bond there */
    return m->bl->reverse ? SPALL_OK : bond_list_build_reverse(m->bl, err);
}

int pd_eps_localized(struct pd_lps *L, size_t nh, size_t n, struct spall_error *err)
{
    if (!(L->ep = calloc(nh ? nh : 1, sizeof(double))) ||
        !(L->tb = calloc(nh ? nh : 1, sizeof(double))) ||
        !(L->epr = calloc(nh ? nh : 1, sizeof(double))) ||
        !(L->hs = calloc(2 * (n ? n : 1), sizeof(double))))
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for the plastic "
                               "extension state");
    return SPALL_OK;
}

int pd_eps_forces(struct model *m, struct sim *sim)
{
    const struct pd_lps_bonds B = pd_lps_bonds(m);
    struct particles *p = sim->p;
    struct bond_list *bl = m->bl;
    struct pd_lps *L = &m->lps;
    const size_t n = p->n, no = p->n_owned;
    const int dim = p->dim;
    const double d = (double)dim, cd = eps_cd(dim);
    uint8_t *st = bl->state;
    const size_t *rev = bl->reverse;
    double *tb = L->tb, *ep = L->ep;
    /* distributed: theta_j and j's return-map scale per particle (sent to
     * the ghosts after pass 1), and per half-bond i's copy of e^dp_ji */
    double *hs = L->hs, *epr = L->epr;
    const bool late = m->opt.break_late; /* next_step: bonds past s0 dropped in pass 2 */
    /* pass 1, per particle (its own half-bonds only): breaking, dilatation,
     * return map, scalar force state t_ij / omega into tb */
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; i++) {
        const size_t s0 = bl->offset[i], s1 = bl->offset[i + 1];
        const struct pd_material *mt = &m->mat[p->material[i]];
        double sum = 0.0;
        for (size_t s = s0; s < s1; s++) {
            if (st[s] & BOND_BROKEN)
                continue;
            size_t j = (size_t)bl->partner[s];
            const size_t row = pd_lps_row(&B, s);
            double l2 = 0.0;
            for (int c = 0; c < dim; c++) {
                double r = p->x[c][j] - p->x[c][i];
                l2 += r * r;
            }
            const double xi = B.rest[row], e = sqrt(l2) - xi;
            if (!late && e / xi > m->s0_tab[B.type[row]]) {
                st[s] |= BOND_BROKEN;
                /* elastic energy of the half-bond at the last state: t (e - e^dp) / 2 */
                double t = L->alpha[i] * (e - ep[s]) + L->bcoef[i] * xi * L->theta[i];
                m->diss[i] += 0.5 * B.ob[row] * t * (e - ep[s]) * p->volume[i] * p->volume[j];
                continue;
            }
            tb[s] = e; /* kept for the return map below */
            sum += B.ob[row] * xi * e * p->volume[j];
        }
        const double wv = L->wvol[i];
        const double th = wv > 0.0 ? d * sum / wv : 0.0;
        L->theta[i] = th;
        if (hs) {
            hs[2 * i] = th;
            hs[2 * i + 1] = 1.0;
        }
        if (!(wv > 0.0))
            continue;
        const double al = L->alpha[i];
        double nrm2 = 0.0;
        for (size_t s = s0; s < s1; s++) {
            if (st[s] & BOND_BROKEN)
                continue;
            const double tau = al * (tb[s] - th * B.rest[pd_lps_row(&B, s)] / d - ep[s]);
            nrm2 += B.ob[pd_lps_row(&B, s)] * tau * tau * p->volume[bl->partner[s]];
        }
        /* with the surface correction's a_i on alpha_i (pd_lps_surface.c) the
         * homogeneous-state norm is ||tau||^2 = a_i alpha_i s : s / (2 mu) */
        const double lim2 = d * (d + 2.0) * cd * mt->yield_stress * mt->yield_stress /
                            (2.0 * wv) * (L->afac ? L->afac[i] : 1.0);
        const double scale = nrm2 > lim2 ? sqrt(lim2 / nrm2) : 1.0;
        if (hs)
            hs[2 * i + 1] = scale;
        const double iso = (d * mt->kd / wv) * th; /* d k theta / m_i, times |xi| below */
        double work = 0.0;
        for (size_t s = s0; s < s1; s++) {
            if (st[s] & BOND_BROKEN)
                continue;
            const double xi = B.rest[pd_lps_row(&B, s)], ed = tb[s] - th * xi / d;
            double tau = al * (ed - ep[s]);
            if (scale < 1.0) {
                tau *= scale;
                const double dep = ed - tau / al - ep[s];
                ep[s] += dep;
                work += B.ob[pd_lps_row(&B, s)] * tau * dep * p->volume[bl->partner[s]];
            }
            tb[s] = iso * xi + tau;
        }
        m->diss[i] += work * p->volume[i];
    }
    /* distributed: the partner's half t_ji needs its whole family (the
     * return map's scale), which a ghost's owner has.  Rather than the
     * values t_ji themselves (one per bond that crosses ranks), its owner
     * sends theta_j and the scale (two per ghost), and i repeats j's update
     * of e^dp_ji on its copy epr: the same operations on the same operands
     * (the length and rest length of a bond are bitwise symmetric), so the
     * same bits (docs/parallel.md, "Elastic-plastic peridynamics") */
    if (sim->par)
        par_halo_values(sim, hs, 2);
    /* pass 2: F_i = V_i sum_j (t_ij + t_ji) beta V_j M_ij; t_ji from j's row,
     * or distributed from j's theta and scale */
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < no; i++) {
        double fi[3] = {0.0, 0.0, 0.0};
        for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
            if (st[s] & BOND_BROKEN)
                continue;
            size_t j = (size_t)bl->partner[s];
            double r[3] = {0.0, 0.0, 0.0}, l2 = 0.0;
            for (int c = 0; c < dim; c++) {
                r[c] = p->x[c][j] - p->x[c][i];
                l2 += r[c] * r[c];
            }
            double tji;
            if (epr) { /* pass 1 of j for this half-bond, as j's owner runs it */
                const double xi = B.rest[pd_lps_row(&B, s)], e = sqrt(l2) - xi;
                const double thj = hs[2 * j], scj = hs[2 * j + 1], alj = L->alpha[j];
                const double ed = e - thj * xi / d;
                double tau = alj * (ed - epr[s]);
                if (scj < 1.0) {
                    tau *= scj;
                    const double dep = ed - tau / alj - epr[s];
                    epr[s] += dep;
                }
                tji = (d * m->mat[p->material[j]].kd / L->wvol[j]) * thj * xi + tau;
            } else {
                tji = tb[rev[s]];
            }
            const size_t row = pd_lps_row(&B, s);
            const double ob = B.ob[row];
            const double g = ob * (tb[s] + tji) * (p->volume[i] * p->volume[j]) / sqrt(l2);
            for (int c = 0; c < dim; c++)
                fi[c] += g * r[c];
            /* break_order next_step: pd_lps_break_rows' rule on this length,
             * in row order (the same bits as its own pass) */
            if (late) {
                const double xi = B.rest[row], e = sqrt(l2) - xi;
                if (e / xi > m->s0_tab[B.type[row]]) {
                    st[s] |= BOND_BROKEN;
                    const double ee = e - ep[s];
                    const double t = L->alpha[i] * ee + L->bcoef[i] * xi * L->theta[i];
                    m->diss[i] += 0.5 * ob * t * ee * p->volume[i] * p->volume[j];
                }
            }
        }
        for (int c = 0; c < dim; c++)
            p->f[c][i] += fi[c];
    }
    if (late && n > no) /* distributed: the ghosts' rows (empty) */
        pd_lps_break_rows(m, sim, no, n);
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
    return sqrt(eps_cd(sim->dim) * d * (d + 2.0) * q / (2.0 * L->wvol[i]));
}
