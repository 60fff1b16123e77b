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
 *
 * Cost (issue 6 item 8): the neighbour list, the kernel values and every
 * per-pair constant live on the reference configuration, so they are
 * computed once (struct sph_tl) and never rebuilt.  The corrections are
 * moved out of the pair sums, which is exact algebra (only the rounding
 * changes):
 *   F_i     = [sum_j (x_j - x_i) (x) G_ij] B0_i^-1,   G_ij = V0_j grad_X W (uncorrected)
 *   P_i g_i(ij) V0_j = Q_i G_ij,                     Q_i = P_i B0_i^-T   (per particle)
 *   sum_j V0_i V0_j v_ij . P_i g_i(ij) = -V0_i P_i : dF_i/dt           (stress power)
 * so a pair costs two 3x3 products (Q_j G_ij and the hourglass F X_ij)
 * instead of four plus two kernel evaluations.  Every sum still gathers
 * over particle i's full row in list order: bitwise thread independent.
 */
#include "models/sph/sph_internal.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* Reference-configuration constants of a pair (fixed list: never rebuilt).
 * X_i - X_j is gathered from the packed block instead (x0 shares its cache
 * line with v and V0): the pair stream was the stall of pass 1. */
struct tl_pair {
    double F;    /**< (dW/dr) / r of the reference kernel */
    double hg;   /**< kappa (E_i + E_j)/2 V0_i V0_j W / |X_ij|^2 */
};

/* What a pair loop gathers from partner j, packed in one block per
 * particle (4 cache lines) instead of 26 separate arrays: the SoA layout
 * spilled the array pointers and touched a line per array and partner.
 * Refreshed each step from the SoA state (O(N)). */
enum { TL_Q = 0, TL_FD = 9, TL_X = 18, TL_V = 21, TL_C = 24, TL_RHO, TL_H, TL_M, TL_VOL,
       TL_X0 = 29, TL_STRIDE = 32 };

struct sph_tl {
    double *S0[3];        /**< sum_j G_ij (nonzero at surfaces) */
    double *pk;           /**< per particle, TL_STRIDE doubles (TL_Q ...) */
    struct tl_pair *pair; /**< per listed pair, same index as the neighbour list */
};

void sph_tlsph_destroy(struct sph_tl **tl)
{
    if (!tl || !*tl)
        return;
    struct sph_tl *t = *tl;
    free(t->pk);
    free(t->pair);
    for (int c = 0; c < 3; c++)
        free(t->S0[c]);
    free(t);
    *tl = NULL;
}

static int sph_tl_alloc(struct sph_tl **out, size_t n, size_t np, struct spall_error *err)
{
    struct sph_tl *t = calloc(1, sizeof *t);
    int bad = !t;
    if (t) {
        const size_t nn = n ? n : 1, pp = np ? np : 1;
        bad |= !(t->pk = calloc(nn * TL_STRIDE, sizeof(double)));
        bad |= !(t->pair = calloc(pp, sizeof *t->pair));
        for (int c = 0; c < 3; c++)
            bad |= !(t->S0[c] = calloc(nn, sizeof(double)));
    }
    *out = t;
    if (bad) {
        sph_tlsph_destroy(out);
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH pair constants)");
    }
    return SPALL_OK;
}

int sph_tlsph_init(struct model *m, struct sim *s, struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    double hmax = 0.0;
    for (size_t i = 0; i < n; i++)
        hmax = fmax(hmax, m->h[i]);
    neighbor_list_destroy(&m->nl);
    sph_tlsph_destroy(&m->tl);
    m->nl_radius = m->qmax * hmax;
    const double t0 = omp_get_wtime();
    int rc = neighbor_list_build(&m->nl, dim, n, p->x0, m->nl_radius, err);
    m->t_neighbor += omp_get_wtime() - t0;
    if (rc)
        return rc;
    m->n_builds = 1;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    if ((rc = sph_tl_alloc(&m->tl, n, off[n], err)))
        return rc;
    struct sph_tl *t = m->tl;
    for (size_t i = 0; i < n; i++) {
        double *q = t->pk + i * TL_STRIDE;
        q[TL_VOL] = m->m2[i] / m->mat[p->material[i]].rho0;
        q[TL_M] = m->m2[i];
        for (int d = 0; d < 3; d++)
            q[TL_X0 + d] = d < dim ? p->x0[d][i] : 0.0;
    }
    const double kappa = m->opt.hourglass;
    size_t fallbacks = 0;
#pragma omp parallel for schedule(static) reduction(+ : fallbacks)
    for (size_t i = 0; i < n; i++) {
        const double Ei = m->mat[p->material[i]].E;
        double B[9] = {0}, S0[3] = {0, 0, 0};
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            size_t j = (size_t)nb[k];
            double hb = 0.5 * (m->h[i] + m->h[j]), X[3] = {0, 0, 0}, r2 = 0.0;
            for (int d = 0; d < dim; d++) {
                X[d] = p->x0[d][i] - p->x0[d][j];
                r2 += X[d] * X[d];
            }
            double W, F;
            sph_kernel_eval(m->opt.kernel, m->alpha, sqrt(r2), hb, pow(hb, dim), &W, &F);
            const double Vi = t->pk[i * TL_STRIDE + TL_VOL], V = t->pk[j * TL_STRIDE + TL_VOL];
            struct tl_pair *pr = &t->pair[k];
            pr->F = F;
            pr->hg = kappa * 0.5 * (Ei + m->mat[p->material[j]].E) * Vi * V * W / r2;
            for (int a = 0; a < dim; a++) {
                S0[a] += V * F * X[a];
                for (int b = 0; b < dim; b++)
                    B[a * 3 + b] += -X[a] * V * F * X[b];
            }
        }
        double Bi[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, inv[9];
        if (fabs(sph_inverse(dim, B, inv)) > 1e-3)
            memcpy(Bi, inv, sizeof Bi);
        else
            fallbacks++;
        for (int c = 0; c < 9; c++)
            m->Bi[c][i] = Bi[c];
        for (int d = 0; d < 3; d++)
            t->S0[d][i] = S0[d];
    }
    m->cspm_fallbacks += fallbacks;
    return SPALL_OK;
}

/* Pass 1 for particle i: F, dF/dt, L (dimension a literal at the call). */
static inline int tl_deformation(struct model *m, size_t i, const int dim)
{
    const struct sph_tl *t = m->tl;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const double *pk = t->pk, *qi = pk + i * TL_STRIDE;
    double Ad[9] = {0}, Av[9] = {0};
    for (size_t k = off[i]; k < off[i + 1]; k++) {
        const struct tl_pair *pr = &t->pair[k];
        const double *qj = pk + (size_t)nb[k] * TL_STRIDE;
        const double VF = qj[TL_VOL] * pr->F;
        double G[3], dx[3], dv[3];
        for (int d = 0; d < dim; d++) {
            G[d] = VF * (qi[TL_X0 + d] - qj[TL_X0 + d]);
            dx[d] = qj[TL_X + d] - qi[TL_X + d];
            dv[d] = qj[TL_V + d] - qi[TL_V + d];
        }
        for (int a = 0; a < dim; a++)
            for (int b = 0; b < dim; b++) {
                Ad[a * 3 + b] += dx[a] * G[b];
                Av[a * 3 + b] += dv[a] * G[b];
            }
    }
    double Fd[9] = {0}, Fdot[9] = {0};
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++) {
            double sd = 0.0, sv = 0.0;
            for (int c = 0; c < dim; c++) {
                sd += Ad[a * 3 + c] * m->Bi[c * 3 + b][i];
                sv += Av[a * 3 + c] * m->Bi[c * 3 + b][i];
            }
            Fd[a * 3 + b] = sd;
            Fdot[a * 3 + b] = sv;
        }
    if (dim == 2)
        Fd[8] = 1.0;
    double Fi[9];
    double J = sph_inverse(dim, Fd, Fi);
    int bad = 0;
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
    return bad;
}

/* Pass 2 for particle i: force, internal energy rate (dimension literal). */
static inline void tl_forces(struct model *m, struct particles *p, size_t i, double wstress,
                             const int dim)
{
    const struct sph_tl *t = m->tl;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const double qa = m->opt.av_a, qb = m->opt.av_b, lav = m->opt.av_length;
    const bool av = qa > 0.0 || qb > 0.0;
    const double *pk = t->pk, *qi = pk + i * TL_STRIDE;
    const double Vi = qi[TL_VOL], mi = qi[TL_M], hi = qi[TL_H], ci = qi[TL_C], rhoi = qi[TL_RHO];
    double fs[3] = {0, 0, 0}, acc[3] = {0, 0, 0}, de = 0.0;
    for (size_t k = off[i]; k < off[i + 1]; k++) {
        const struct tl_pair *pr = &t->pair[k];
        const double *qj = pk + (size_t)nb[k] * TL_STRIDE;
        const double F = pr->F, VF = qj[TL_VOL] * F, hg = pr->hg;
        double X[3], G[3], xij[3], vij[3], cr2 = 0.0, vx = 0.0;
        for (int d = 0; d < dim; d++) {
            X[d] = qi[TL_X0 + d] - qj[TL_X0 + d];
            G[d] = VF * X[d];
            xij[d] = qi[TL_X + d] - qj[TL_X + d];
            vij[d] = qi[TL_V + d] - qj[TL_V + d];
            cr2 += xij[d] * xij[d];
            vx += xij[d] * vij[d];
        }
        double Pi = 0.0;
        if (vx < 0.0 && av) {
            const double hb = 0.5 * (hi + qj[TL_H]);
            const double mu = (lav > 0.0 ? lav : hb) * vx / (cr2 + 0.01 * hb * hb);
            const double cb = 0.5 * (ci + qj[TL_C]);
            Pi = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + qj[TL_RHO]));
        }
        const double cav = -mi * qj[TL_M] * Pi * F;
        for (int a = 0; a < dim; a++) {
            double tj = 0.0, fx = 0.0;
            for (int b = 0; b < dim; b++) {
                tj += qj[TL_Q + a * 3 + b] * G[b];
                fx += (qi[TL_FD + a * 3 + b] + qj[TL_FD + a * 3 + b]) * X[b];
            }
            fs[a] += tj;
            /* hourglass: mismatch of x_j - x_i against Fbar (X_j - X_i);
             * AV along the CURRENT pair line (reference kernel magnitude):
             * -Pi F x_ij does negative work for any rotation */
            const double fo = cav * xij[a] + hg * (0.5 * fx - xij[a]);
            acc[a] += fo;
            de -= 0.5 * fo * vij[a];
        }
    }
    /* P_i g_i summed over the row: Q_i S0_i */
    for (int a = 0; a < dim; a++) {
        double qs = 0.0;
        for (int b = 0; b < dim; b++)
            qs += qi[TL_Q + a * 3 + b] * t->S0[b][i];
        acc[a] += Vi * (fs[a] + qs);
    }
    /* stress power V0_i P_i : dF_i/dt (booked by the leapfrog itself) */
    double pw = 0.0;
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++)
            pw += m->PK[a * 3 + b][i] * m->Fdot[a * 3 + b][i];
    de += wstress * Vi * pw;
    for (int a = 0; a < dim; a++)
        p->f[a][i] += p->mass[i] / mi * acc[a];
    m->de[i] = de / mi;
    for (int a = 0; a < dim; a++)
        m->xv[a][i] = 0.0;
}

int sph_tlsph_rates(struct model *m, struct sim *s, struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    m->n_pairs = m->nl->offset[n];
    int bad = 0;
    struct sph_tl *t = m->tl;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double *q = t->pk + i * TL_STRIDE;
        for (int d = 0; d < 3; d++) {
            q[TL_X + d] = d < dim ? p->x[d][i] : 0.0;
            q[TL_V + d] = d < dim ? p->v[d][i] : 0.0;
        }
    }
    /* pass 1: F, dF/dt, L = dF F^-1 of the current state */
    if (dim == 3) {
#pragma omp parallel for schedule(static) reduction(| : bad)
        for (size_t i = 0; i < n; i++)
            bad |= tl_deformation(m, i, 3);
    } else {
#pragma omp parallel for schedule(static) reduction(| : bad)
        for (size_t i = 0; i < n; i++)
            bad |= tl_deformation(m, i, 2);
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
        /* PK1 = J sigma F^-T, then Q = PK1 B0^-T */
        double PK[9], *q = t->pk + i * TL_STRIDE;
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) {
                double acc = 0.0;
                for (int c = 0; c < dim; c++) {
                    double sg = m->S[tix[a][c]][i] - (a == c ? m->P[i] : 0.0);
                    acc += sg * m->Finv[b * 3 + c][i];
                }
                PK[a * 3 + b] = m->Jdet[i] * acc;
                m->PK[a * 3 + b][i] = PK[a * 3 + b];
            }
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                double acc = 0.0;
                for (int b = 0; b < dim; b++)
                    acc += PK[a * 3 + b] * m->Bi[c * 3 + b][i];
                q[TL_Q + a * 3 + c] = acc;
            }
        for (int c = 0; c < 9; c++)
            q[TL_FD + c] = m->Fdef[c][i];
        q[TL_C] = m->c[i];
        q[TL_RHO] = m->rho[i];
        q[TL_H] = m->h[i];
    }
    /* pass 2: forces, energy */
    const double wstress = lfdt > 0.0 ? 0.0 : 1.0; /* leapfrog books it itself */
    if (dim == 3) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++)
            tl_forces(m, p, i, wstress, 3);
    } else {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++)
            tl_forces(m, p, i, wstress, 2);
    }
    if (lfdt > 0.0) {
        for (size_t i = 0; i < n; i++)
            m->e[i] += lfdt * m->de[i]; /* AV / hourglass heating */
        m->lf_dt = 0.0;
    }
    return SPALL_OK;
}
