/**
 * @file sph_tlsph.c
 * @brief Total-Lagrangian SPH (the remedy named in seed 004's conclusions
 *        for the tensile instability): kernel and neighbours on the
 *        reference configuration, corrected reference gradients, the
 *        deformation gradient, first Piola-Kirchhoff stress forces and a
 *        pairwise hourglass control.
 *
 *   g_i(ij) = B0_i^-T grad_X W(X_i - X_j),  B0_i = sum_j V0_j (X_j - X_i) (x) grad_X W
 *   F_i     = sum_j V0_j (x_j - x_i) (x) g_i(ij)      (= I at the start, exactly)
 *   dF_i/dt = sum_j V0_j (v_j - v_i) (x) g_i(ij),  L_i = dF_i/dt F_i^-1
 *   m_i a_i = sum_j V0_i V0_j (P_i g_i(ij) + P_j g_j(ij)),  P = J sigma F^-T
 *   de_i/dt = (1/rho0) P_i : dF_i/dt  (the pairing that conserves energy)
 * The stress S and the pressure use the same Jaumann-rate / EOS / radial
 * return machinery as the updated form (L_i from above).  Hourglass
 * (zero-energy) modes are resisted by a pair force along the mismatch
 * between the current separation and the one predicted by the mean F:
 *   f_i += kappa E V0_i V0_j W0_ij / |X_ij|^2 (x_ij - Fbar X_ij)   (x_ij = x_j - x_i)
 * which vanishes for any affine motion (it never resists a homogeneous
 * deformation) and is antisymmetric (momentum conserving); kappa =
 * model.hourglass (default 0.1).  Its work is booked as internal energy.
 * Monaghan AV acts on the current pair geometry: mu from x_ij, v_ij and the
 * force along x_ij with the reference kernel's dW/dr / r.
 */
#include "models/sph/sph_internal.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int sph_tlsph_init(struct model *m, struct sim *s, struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    double hmax = 0.0;
    for (size_t i = 0; i < n; i++)
        hmax = fmax(hmax, m->h[i]);
    neighbor_list_destroy(&m->nl);
    m->nl_radius = m->qmax * hmax;
    int rc = neighbor_list_build(&m->nl, dim, n, p->x0, m->nl_radius, err);
    if (rc)
        return rc;
    m->n_builds = 1;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    for (size_t i = 0; i < n; i++) {
        double B[9] = {0};
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            size_t j = (size_t)nb[k];
            double hb = 0.5 * (m->h[i] + m->h[j]), X[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                X[d] = p->x0[d][i] - p->x0[d][j];
                r2 += X[d] * X[d];
            }
            double W, F;
            sph_kernel_eval(m->opt.kernel, m->alpha, sqrt(r2), hb, pow(hb, dim), &W, &F);
            double V = m->m2[j] / m->mat[p->material[j]].rho0;
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++)
                    B[a * 3 + b] += -X[a] * V * F * X[b];
        }
        double Bi[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, inv[9];
        if (fabs(sph_inverse(dim, B, inv)) > 1e-3)
            memcpy(Bi, inv, sizeof Bi);
        else
            m->cspm_fallbacks++;
        for (int c = 0; c < 9; c++)
            m->Bi[c][i] = Bi[c];
    }
    return SPALL_OK;
}

int sph_tlsph_rates(struct model *m, struct sim *s, struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kernel;
    m->n_pairs = off[n];
    int bad = 0;
    /* pass 1: F, dF/dt, L = dF F^-1, PK1 stress of the current state */
#pragma omp parallel for schedule(static) reduction(| : bad)
    for (size_t i = 0; i < n; i++) {
        double Fd[9] = {0}, Fdot[9] = {0};
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            size_t j = (size_t)nb[k];
            double hb = 0.5 * (m->h[i] + m->h[j]), X[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                X[d] = p->x0[d][i] - p->x0[d][j];
                r2 += X[d] * X[d];
            }
            double W, F;
            sph_kernel_eval(kern, m->alpha, sqrt(r2), hb, dim == 2 ? hb * hb : hb * hb * hb, &W,
                            &F);
            double V = m->m2[j] / m->mat[p->material[j]].rho0;
            double g[3] = {0, 0, 0};
            for (int b = 0; b < dim; b++)
                for (int c = 0; c < dim; c++)
                    g[b] += m->Bi[c * 3 + b][i] * F * X[c];
            for (int a = 0; a < dim; a++) {
                double dx = p->x[a][j] - p->x[a][i], dv = p->v[a][j] - p->v[a][i];
                for (int b = 0; b < dim; b++) {
                    Fd[a * 3 + b] += V * dx * g[b];
                    Fdot[a * 3 + b] += V * dv * g[b];
                }
            }
        }
        if (dim == 2)
            Fd[8] = 1.0;
        double Fi[9];
        double J = sph_inverse(dim, Fd, Fi);
        if (!(J > 0.0) || !isfinite(J)) {
            bad = 1;
            J = 1.0;
            for (int c = 0; c < 9; c++)
                Fi[c] = (c % 4 == 0) ? 1.0 : 0.0;
        }
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                double acc = 0.0;
                for (int c = 0; c < dim; c++)
                    acc += Fdot[a * 3 + c] * Fi[c * 3 + b];
                m->L[a * 3 + b][i] = (a < dim && b < dim) ? acc : 0.0;
            }
        for (int c = 0; c < 9; c++) {
            m->Fdef[c][i] = Fd[c];
            m->Fdot[c][i] = Fdot[c];
            m->Finv[c][i] = Fi[c];
        }
        m->Jdet[i] = J;
    }
    if (bad)
        return spall_error_set(err, SPALL_ERR_UNSTABLE,
                               "TLSPH: a deformation gradient became singular or inverted at "
                               "t = %.6g s (det F <= 0)", s->t);
    const double lfdt = m->lf_dt; /* leapfrog: advance the state with this L */
    if (lfdt > 0.0)
        sph_leapfrog_advance(m, s, lfdt);
    sph_update_pressure(m, s);
    static const int tix[3][3] = {{SXX, SXY, SXZ}, {SXY, SYY, SYZ}, {SXZ, SYZ, SZZ}};
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double trD;
        sph_stress_rate(m, i, &trD);
        m->drho[i] = -m->rho[i] * trD;
        m->dh[i] = 0.0;
        /* PK1 = J sigma F^-T */
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                double acc = 0.0;
                for (int c = 0; c < dim; c++) {
                    double sg = m->S[tix[a][c]][i] - (a == c ? m->P[i] : 0.0);
                    acc += sg * m->Finv[b * 3 + c][i];
                }
                m->PK[a * 3 + b][i] = m->Jdet[i] * acc;
            }
    }
    /* pass 2: forces, energy */
    const double kappa = m->opt.hourglass, qa = m->opt.av_a, qb = m->opt.av_b;
    const double wstress = lfdt > 0.0 ? 0.0 : 1.0; /* leapfrog books it itself */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        const struct sph_material *mi = &m->mat[p->material[i]];
        const double Vi = m->m2[i] / mi->rho0;
        double acc[3] = {0, 0, 0}, de = 0.0;
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            size_t j = (size_t)nb[k];
            const struct sph_material *mj = &m->mat[p->material[j]];
            double hb = 0.5 * (m->h[i] + m->h[j]), X[3] = {0, 0, 0}, r2 = 0.0;
            double xij[3] = {0, 0, 0}, vij[3] = {0, 0, 0}, cr2 = 0.0, vx = 0.0;
            for (int d = 0; d < dim; d++) {
                X[d] = p->x0[d][i] - p->x0[d][j];
                r2 += X[d] * X[d];
                xij[d] = p->x[d][i] - p->x[d][j];
                vij[d] = p->v[d][i] - p->v[d][j];
                cr2 += xij[d] * xij[d];
                vx += xij[d] * vij[d];
            }
            double W, F;
            sph_kernel_eval(kern, m->alpha, sqrt(r2), hb, dim == 2 ? hb * hb : hb * hb * hb, &W,
                            &F);
            const double Vj = m->m2[j] / mj->rho0;
            double gi[3] = {0, 0, 0}, gj[3] = {0, 0, 0};
            for (int b = 0; b < dim; b++) {
                for (int c = 0; c < dim; c++) {
                    gi[b] += m->Bi[c * 3 + b][i] * F * X[c];
                    gj[b] += m->Bi[c * 3 + b][j] * F * X[c];
                }
            }
            double Pi = 0.0;
            if (vx < 0.0 && (qa > 0.0 || qb > 0.0)) {
                double mu = hb * vx / (cr2 + 0.01 * hb * hb);
                double cb = 0.5 * (m->c[i] + m->c[j]);
                Pi = (-qa * cb * mu + qb * mu * mu) / (0.5 * (m->rho[i] + m->rho[j]));
            }
            /* hourglass: mismatch of x_j - x_i against Fbar (X_j - X_i) */
            double hg = kappa * 0.5 * (mi->E + mj->E) * Vi * Vj * W / r2;
            for (int a = 0; a < dim; a++) {
                double ti = 0.0, tj = 0.0, pred = 0.0;
                for (int b = 0; b < dim; b++) {
                    ti += m->PK[a * 3 + b][i] * gi[b];
                    tj += m->PK[a * 3 + b][j] * gj[b];
                    pred += 0.5 * (m->Fdef[a * 3 + b][i] + m->Fdef[a * 3 + b][j]) * (-X[b]);
                }
                double fs = Vi * Vj * (ti + tj);
                /* AV along the CURRENT pair line (reference kernel
                 * magnitude): -Pi F x_ij does negative work for any
                 * rotation; along the reference direction g0 it pumps
                 * energy once the body has turned (17.5 kN beam) */
                double fav = -m->m2[i] * m->m2[j] * Pi * F * xij[a];
                double fhg = hg * (-xij[a] - pred);
                acc[a] += fs + fav + fhg;
                de -= wstress * Vi * Vj * vij[a] * ti + 0.5 * (fav + fhg) * vij[a];
            }
        }
        for (int a = 0; a < dim; a++)
            p->f[a][i] += p->mass[i] / m->m2[i] * acc[a];
        m->de[i] = de / m->m2[i];
        for (int a = 0; a < dim; a++)
            m->xv[a][i] = 0.0;
    }
    if (lfdt > 0.0) {
        for (size_t i = 0; i < n; i++)
            m->e[i] += lfdt * m->de[i]; /* AV / hourglass heating */
        m->lf_dt = 0.0;
    }
    return SPALL_OK;
}
