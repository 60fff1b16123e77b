/**
 * @file pd_mixed.c
 * @brief Mixed-mode matrix failure of orthotropic laminae: the matrix-bond
 *        critical stretch follows the local mode mix between G_Ic and G_IIc
 *        (issue 4: "critical stretches from G_I and G_II").
 *
 * Seed 003 relates the critical stretches to the mode I and mode II fracture
 * energies, but its formulas were lost in extraction.  Our rule (documented
 * in docs/decks.md, peridynamics section):
 *  - s0_m is calibrated on G_Ic (pd_calib.c: the energy of the matrix bonds
 *    crossing a unit fiber-parallel crack = G_Ic at s = s0_m).  The energy
 *    of those bonds at breaking scales with s0^2, so a crack that needs G_c
 *    takes s0 = s0_m sqrt(G_c / G_Ic).
 *  - G_c follows the Benzeggagh-Kenane law (Compos. Sci. Technol. 56, 1996):
 *    G_c = G_Ic + (G_IIc - G_Ic) beta^eta, beta = G_II / (G_I + G_II).
 *  - beta of particle i from its own family: deformation gradient
 *    F = (sum y (x) xi)(sum xi (x) xi)^-1 over intact bonds (y current, xi
 *    reference bond), Green strain E = (F^T F - I)/2 in material axes
 *    (1 = fiber): the mode-I energy of a fiber-parallel crack plane
 *    w_I = Q22 <E22>^2 / 2 (only opening counts), the mode-II energy
 *    w_II = G12 (2 E12)^2 / 2; beta = w_II / (w_I + w_II).  Green strain is
 *    rotation invariant, so rigid rotations do not change beta.
 *  - a matrix bond i-j breaks at s > s0_m (g_i + g_j) / 2, g = sqrt(G_c/G_Ic):
 *    the same number from both ends (thread-count independent).
 *  Particles with fewer than two independent intact bonds keep beta = 0
 *  (pure mode I: the lower, conservative G_Ic).
 */
#include "models/peridynamics/pd_internal.h"

#include "core/bond_list.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int pd_mixed_init(struct model *m, struct sim *sim, struct spall_error *err)
{
    const size_t nm = m->n_mat, n = sim->p->n;
    memset(m->mm_type, 0, sizeof m->mm_type);
    m->mixed = false;
    if (!m->opt.mixed_mode || sim->dim != 2)
        return SPALL_OK;
    for (size_t a = 0; a < nm; a++)
        for (size_t b = 0; b < nm; b++) {
            const struct pd_material *A = &m->mat[a], *B = &m->mat[b];
            /* the bond's s0 comes from the lamina (the smaller of both ends
             * is taken; a lamina-isotropic bond uses the lamina's rule) */
            int use = (A->ortho && A->GIc > 0.0 && A->GIIc > 0.0 && A->GIIc != A->GIc) ||
                      (B->ortho && B->GIc > 0.0 && B->GIIc > 0.0 && B->GIIc != B->GIc);
            m->mm_type[(a * nm + b) * 2] = (uint8_t)use; /* matrix bonds only */
            m->mixed |= use != 0;
        }
    if (!m->mixed)
        return SPALL_OK;
    for (size_t k = 0; k < nm; k++) {
        m->mat[k].fa_cos = cos(m->mat[k].fiber_angle);
        m->mat[k].fa_sin = sin(m->mat[k].fiber_angle);
    }
    m->mm_g = malloc((n ? n : 1) * sizeof *m->mm_g);
    m->mm_beta = calloc(n ? n : 1, sizeof *m->mm_beta);
    if (!m->mm_g || !m->mm_beta)
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory for mixed-mode factors");
    for (size_t i = 0; i < n; i++)
        m->mm_g[i] = 1.0;
    return SPALL_OK;
}

/* beta of particle i (0 when its family cannot define F) */
static double particle_beta(const struct model *m, const struct sim *sim, size_t i,
                            const struct pd_material *mt)
{
    const struct particles *p = sim->p;
    const struct bond_list *bl = m->bl;
    double k00 = 0.0, k01 = 0.0, k11 = 0.0, n00 = 0.0, n01 = 0.0, n10 = 0.0, n11 = 0.0;
    for (size_t s = bl->offset[i]; s < bl->offset[i + 1]; s++) {
        if (bl->state[s] & BOND_BROKEN)
            continue;
        size_t j = (size_t)bl->partner[s];
        double x0 = p->x0[0][j] - p->x0[0][i], y0 = p->x0[1][j] - p->x0[1][i];
        double x1 = p->x[0][j] - p->x[0][i], y1 = p->x[1][j] - p->x[1][i];
        k00 += x0 * x0;
        k01 += x0 * y0;
        k11 += y0 * y0;
        n00 += x1 * x0;
        n01 += x1 * y0;
        n10 += y1 * x0;
        n11 += y1 * y0;
    }
    double det = k00 * k11 - k01 * k01, tr = k00 + k11;
    if (!(det > 1e-6 * tr * tr))
        return 0.0;
    /* F = N K^-1 */
    double i00 = k11 / det, i01 = -k01 / det, i11 = k00 / det;
    double F00 = n00 * i00 + n01 * i01, F01 = n00 * i01 + n01 * i11;
    double F10 = n10 * i00 + n11 * i01, F11 = n10 * i01 + n11 * i11;
    double Exx = 0.5 * (F00 * F00 + F10 * F10 - 1.0);
    double Eyy = 0.5 * (F01 * F01 + F11 * F11 - 1.0);
    double Exy = 0.5 * (F00 * F01 + F10 * F11);
    const double c = mt->fa_cos, sn = mt->fa_sin;
    /* material axes: a = (c, s) fiber, b = (-s, c) */
    double E22 = sn * sn * Exx + c * c * Eyy - 2.0 * c * sn * Exy;
    double E12 = -c * sn * Exx + c * sn * Eyy + (c * c - sn * sn) * Exy;
    double op = E22 > 0.0 ? E22 : 0.0;
    double wI = 0.5 * mt->Q22 * op * op, wII = 2.0 * mt->G12 * E12 * E12;
    return wI + wII > 0.0 ? wII / (wI + wII) : 0.0;
}

void pd_mixed_update(struct model *m, const struct sim *sim)
{
    const struct particles *p = sim->p;
    const size_t n = p->n;
    const double eta = m->opt.bk_exponent;
    double *g = m->mm_g, *beta = m->mm_beta;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        const struct pd_material *mt = &m->mat[p->material[i]];
        if (!mt->ortho || !(mt->GIc > 0.0) || !(mt->GIIc > 0.0)) {
            g[i] = 1.0;
            beta[i] = 0.0;
            continue;
        }
        double b = particle_beta(m, sim, i, mt);
        double bp = eta == 2.0 ? b * b : pow(b, eta);
        double gc = mt->GIc + (mt->GIIc - mt->GIc) * bp;
        beta[i] = b;
        g[i] = sqrt(gc / mt->GIc);
    }
}
