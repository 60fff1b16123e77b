/**
 * @file sph_rates.c
 * @brief The SPH pair loops ([Meng2021] Eqs. 3.10-3.21, 2.21-2.27): neighbour
 *        list with a skin, CSPM matrix, summation density, velocity gradient,
 *        continuity, momentum and energy with Monaghan artificial viscosity,
 *        Monaghan-Gray artificial stress and XSPH, and the rigid wall.
 *
 * Every loop gathers over the full neighbour list of particle i (both i-j
 * and j-i are listed), so no two threads write the same entry and results
 * are bitwise independent of the thread count.  Sums run in the list's
 * ascending order.  Dimension is a literal argument of the inline pass
 * functions so each is compiled for 2 and 3 with fixed loop bounds.
 *
 * Sign convention: tension positive, sigma = -P I + S.
 *   dv_i/dt = sum_j m_j (sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I + R_ij f_ij^n) grad_i W_ij
 *   de_i/dt = -sum_j m_j (v_i - v_j) . sigma_i/rho_i^2 . grad_i W_ij
 *             -1/2 sum_j m_j (v_i - v_j) . (-Pi_ij I + R_ij f^n) . grad_i W_ij
 * (the form of de/dt that pairs sigma_i with particle i's own velocity
 * gradient; the artificial stress enters it too, so that kinetic + internal
 * energy is conserved exactly by the semi-discrete equations).
 * With CSPM the stress terms use each particle's corrected gradient
 * (sigma_i/rho_i^2 B_i^-T grad W + sigma_j/rho_j^2 B_j^-T grad W) and the
 * energy equation pairs sigma_i with the same corrected velocity gradient
 * (de_i = -sum_j m_j v_ij . sigma_i/rho_i^2 B_i^-T grad W): momentum and
 * kinetic + internal energy stay conserved.  Correcting only the velocity
 * gradient (the thesis' reading) breaks that pairing and, as measured on
 * the oscillating plate, pumps energy into the system exponentially.
 */
#include "models/sph/sph_internal.h"
#include "models/sph/sph_pairs.h"

#include "core/neighbor.h"
#include "core/exact_sum.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/parallel/psum.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <string.h>

/* The cell list is built with one radius from the largest h.  Where the
 * spacing is graded (the penetration targets: 8x from the shot line to the
 * far field) a fine particle would then carry ~64x (2D) the partners its
 * kernel reaches.  Drop the pairs beyond qmax max(h_i, h_j) plus the same
 * skin @p skin_abs the rebuild test of sph_neighbors_update allows for: the
 * kernel of such a pair (support qmax (h_i + h_j)/2) stays zero until the
 * next rebuild, so results are unchanged.  Fixed h only (variable_h grows h
 * between builds).  Rows stay ascending; serial, O(pairs). */
void sph_neighbors_trim(struct model *m, double *const x[3], const double *h, double skin_abs)
{
    struct neighbor_list *nl = m->nl;
    const size_t n = nl->n;
    const int dim = m->dim;
    /* One h for all (one spacing): every reach is q_max h + skin_abs, and
     * when that is not below the list radius every listed pair (r^2 <
     * radius^2 by the same sum of squares, neighbor_grid.h's pair_r2 and
     * sph_dist2 alike) is kept: nothing to drop, no pass over the pairs. */
    bool one_h = n > 0;
    for (size_t i = 1; i < n && one_h; i++)
        one_h = h[i] == h[0];
    if (one_h) {
        const double reach = m->qmax * h[0] + skin_abs;
        if (reach * reach >= m->nl_radius * m->nl_radius)
            return;
    }
    size_t w = 0, start = 0;
    for (size_t i = 0; i < n; i++) {
        size_t end = nl->offset[i + 1];
        for (size_t k = start; k < end; k++) {
            size_t j = (size_t)nl->idx[k];
            double reach = m->qmax * (h[i] > h[j] ? h[i] : h[j]) + skin_abs;
            if (sph_dist2(x, dim, i, j) <= reach * reach)
                nl->idx[w++] = nl->idx[k];
        }
        start = end;
        nl->offset[i + 1] = w;
    }
}

double sph_max_move2(const struct model *m, const struct particles *p)
{
    double d2max = 0.0;
    for (size_t i = 0; i < p->n_owned; i++) {
        double d2 = 0.0;
        for (int d = 0; d < m->dim; d++) {
            double dd = p->x[d][i] - m->x_build[d][i];
            d2 += dd * dd;
        }
        if (d2 > d2max)
            d2max = d2;
    }
    return d2max;
}

int sph_neighbors_update(struct model *m, struct sim *s, bool force, struct spall_error *err)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    double hmax = 0.0;
    for (size_t i = 0; i < n; i++)
        if (m->h[i] > hmax)
            hmax = m->h[i];
    if (!force && s->par)
        return SPALL_OK; /* distributed: the engine's test over all ranks (sph_ulpar.c) */
    if (!force && m->nl) {
        /* a pair can close in by at most twice the largest displacement */
        if (m->qmax * hmax + 2.0 * sqrt(sph_max_move2(m, p)) <= m->nl_radius)
            return SPALL_OK;
    }
    double t0 = omp_get_wtime();
    neighbor_list_destroy(&m->nl);
    m->nl_radius = m->qmax * hmax * (1.0 + m->opt.kern.skin);
    m->nl_hmax = hmax;
    int rc = neighbor_list_build_pairs(&m->nl, NULL, dim, n, p->x, m->nl_radius, err);
    if (rc)
        return rc;
    if (!m->opt.kern.variable_h)
        sph_neighbors_trim(m, p->x, m->h, m->nl_radius - m->qmax * hmax);
    /* interface between bodies: their pairs leave the kernel list */
    if (m->opt.iface.kind != SPH_IFACE_NONE &&
        (rc = sph_interface_split(m, s, p->x, m->nl_radius - m->qmax * hmax, err)))
        return rc;
    for (int d = 0; d < dim; d++)
        memcpy(m->x_build[d], p->x[d], n * sizeof(double));
    if (m->h_build)
        memcpy(m->h_build, m->h, n * sizeof(double));
    if (sph_ul_view(m)) /* the partition's work, before a distributed run */
        return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (SPH neighbour rows)");
    m->n_builds++;
    m->t_neighbor += omp_get_wtime() - t0;
    return SPALL_OK;
}

/** Smallest |det B| accepted for the CSPM correction.  B ~ I in the bulk;
 * a corner particle of a 3D block keeps det B ~ 0.03-0.1; an isolated or
 * nearly isolated particle drives it to 0: below this the plain gradient
 * is used and the fallback counted. */
#define SPH_CSPM_MIN_DET 0.01

/* Invert a dim x dim matrix (row-major 3x3 storage); 0 if (near) singular
 * relative to the identity it should approximate. */
static inline int inv_small(int dim, const double A[9], double out[9])
{
    double inv[9];
    if (!(fabs(sph_inverse(dim, A, inv)) > SPH_CSPM_MIN_DET))
        return 0;
    memcpy(out, inv, sizeof inv);
    return 1;
}

/* Pass B, first part: the summation density (when chosen). */
static inline void pass_density(struct model *m, struct sim *s, const int dim)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kern.kernel;
    const struct sph_support sp = sph_support_of(m);
    const double alpha = m->alpha;
    if (m->opt.kern.density == SPH_DENSITY_SUMMATION) {
#pragma omp parallel for schedule(static) firstprivate(sp)
        for (size_t i = 0; i < n; i++) {
            if (sph_skip(m, i, SPH_FORM_UPDATED))
                continue;
            double hi = m->h[i];
            double W0, F0;
            sph_kernel_eval(kern, alpha, 0.0, hi, pow(hi, dim), &W0, &F0);
            double rho = m->m2[i] * W0;
            for (size_t k = off[i]; k < off[i + 1]; k++) {
                size_t j = (size_t)nb[k];
                double W, F;
                if (sph_pair_kernel(&sp, dim, sph_dist2(p->x, dim, i, j), 0.5 * (hi + m->h[j]),
                                    &W, &F))
                    rho += m->m2[j] * W;
            }
            m->rho[i] = rho;
        }
    }
}

/* Pass B proper: CSPM matrix and velocity gradient (the partners' density
 * of this call: summed by pass_density, or the continuity state). */
static inline size_t pass_gradient(struct model *m, struct sim *s, const int dim)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const struct sph_support sp = sph_support_of(m);
    const bool cspm = m->opt.kern.cspm;
    size_t fallbacks = 0;
#pragma omp parallel for schedule(static) firstprivate(sp) reduction(+ : fallbacks)
    for (size_t i = 0; i < n; i++) {
        if (sph_skip(m, i, SPH_FORM_UPDATED))
            continue; /* a TLSPH particle of a mixed run (sph_forms.c) */
        double G[9] = {0}, B[9] = {0};
        const double hi = m->h[i];
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            size_t j = (size_t)nb[k];
            double xij[3] = {0, 0, 0};
            const double r2 = sph_sep(p->x, dim, i, j, xij), hb = 0.5 * (hi + m->h[j]);
            double W, F;
            if (!sph_pair_kernel(&sp, dim, r2, hb, &W, &F))
                continue;
            double Vj = m->m2[j] / m->rho[j];
            double VF = Vj * F; /* grad_i W = F x_ij */
            for (int a = 0; a < dim; a++) {
                double dv = p->v[a][j] - p->v[a][i];
                double dxa = -xij[a];
                for (int b = 0; b < dim; b++) {
                    G[a * 3 + b] += dv * VF * xij[b];
                    B[a * 3 + b] += dxa * VF * xij[b];
                }
            }
        }
        double L[9] = {0};
        double Bi[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        int ok = cspm ? inv_small(dim, B, Bi) : 0;
        if (!ok) {
            for (int c = 0; c < 9; c++)
                Bi[c] = (c % 4 == 0) ? 1.0 : 0.0;
        }
        for (int c = 0; c < 9; c++)
            m->Bi[c][i] = Bi[c];
        if (cspm && !ok)
            fallbacks++;
        if (ok) {
            /* Eq. 3.11: grad v = G B^-1 */
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++) {
                    double acc = 0.0;
                    for (int c = 0; c < dim; c++)
                        acc += G[a * 3 + c] * Bi[c * 3 + b];
                    L[a * 3 + b] = acc;
                }
        } else {
            memcpy(L, G, sizeof L); /* plain SPH gradient, Eq. 3.31 */
        }
        for (int c = 0; c < 9; c++)
            m->L[c][i] = L[c];
    }
    return fallbacks;
}

/* Principal-axes artificial stress R_i (Monaghan-Gray, Eqs. 2.25-2.27). */
void sph_artificial_stress(struct model *m, size_t i)
{
    const double zeta = m->opt.visc.as_zeta;
    const double r2 = m->rho[i] * m->rho[i];
    for (int c = 0; c < 6; c++)
        m->R[c][i] = 0.0;
    if (m->dim == 2) {
        double sxx = m->sig[SXX][i], syy = m->sig[SYY][i], sxy = m->sig[SXY][i];
        double mean = 0.5 * (sxx + syy), rad = sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
        double s1 = mean + rad, s2 = mean - rad;
        double th = 0.5 * atan2(2.0 * sxy, sxx - syy);
        double c = cos(th), sn = sin(th);
        double R1 = s1 > 0.0 ? -zeta * s1 / r2 : 0.0;
        double R2 = s2 > 0.0 ? -zeta * s2 / r2 : 0.0;
        m->R[SXX][i] = R1 * c * c + R2 * sn * sn;
        m->R[SYY][i] = R1 * sn * sn + R2 * c * c;
        m->R[SXY][i] = (R1 - R2) * c * sn;
        return;
    }
    /* 3D: cyclic Jacobi rotations on the symmetric stress */
    double A[3][3] = {{m->sig[SXX][i], m->sig[SXY][i], m->sig[SXZ][i]},
                      {m->sig[SXY][i], m->sig[SYY][i], m->sig[SYZ][i]},
                      {m->sig[SXZ][i], m->sig[SYZ][i], m->sig[SZZ][i]}};
    double V[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int sweep = 0; sweep < 8; sweep++) {
        double off = fabs(A[0][1]) + fabs(A[0][2]) + fabs(A[1][2]);
        double scale = fabs(A[0][0]) + fabs(A[1][1]) + fabs(A[2][2]);
        if (off <= 1e-14 * scale || off == 0.0)
            break;
        for (int pp = 0; pp < 2; pp++)
            for (int q = pp + 1; q < 3; q++) {
                if (A[pp][q] == 0.0)
                    continue;
                double th = 0.5 * (A[q][q] - A[pp][pp]) / A[pp][q];
                double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), sn = t * c;
                for (int k = 0; k < 3; k++) {
                    double akp = A[k][pp], akq = A[k][q];
                    A[k][pp] = c * akp - sn * akq;
                    A[k][q] = sn * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {
                    double apk = A[pp][k], aqk = A[q][k];
                    A[pp][k] = c * apk - sn * aqk;
                    A[q][k] = sn * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    double vkp = V[k][pp], vkq = V[k][q];
                    V[k][pp] = c * vkp - sn * vkq;
                    V[k][q] = sn * vkp + c * vkq;
                }
            }
    }
    double Rp[3];
    for (int a = 0; a < 3; a++)
        Rp[a] = A[a][a] > 0.0 ? -zeta * A[a][a] / r2 : 0.0;
    static const int ia[6] = {0, 1, 2, 0, 1, 0}, ib[6] = {0, 1, 2, 1, 2, 2};
    for (int c = 0; c < 6; c++) {
        double acc = 0.0;
        for (int a = 0; a < 3; a++)
            acc += Rp[a] * V[ia[c]][a] * V[ib[c]][a];
        m->R[c][i] = acc;
    }
}

/* Pass C: momentum, energy, XSPH. */
static inline void pass_forces(struct model *m, struct sim *s, double lfdt, const int dim)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kern.kernel;
    const struct sph_support sp = sph_support_of(m);
    const double alpha = m->alpha;
    const double qa = m->opt.visc.av_a, qb = m->opt.visc.av_b, zeta = m->opt.visc.as_zeta, asn = m->opt.visc.as_n;
    const double lav = m->opt.visc.av_length;
    const double xs = m->opt.visc.xsph;
    const bool cm = m->opt.kern.cspm, bal = m->opt.visc.av_balsara;
    /* leapfrog step: the stress power is booked by sph_leapfrog_advance */
    const double wstress = lfdt > 0.0 ? 0.0 : 1.0;
    static const int tix[3][3] = {{SXX, SXY, SXZ}, {SXY, SYY, SYZ}, {SXZ, SYZ, SZZ}};
#pragma omp parallel for schedule(static) firstprivate(sp)
    for (size_t i = 0; i < n; i++) {
        if (sph_skip(m, i, SPH_FORM_UPDATED))
            continue;
        const double hi = m->h[i], rhoi = m->rho[i];
        const double ri2 = 1.0 / (rhoi * rhoi);
        double acc[3] = {0, 0, 0}, xv[3] = {0, 0, 0}, de = 0.0;
        double Wdi = 0.0; /* W(dx_i, h_i): the AS reference value (Eq. 2.26) */
        if (zeta > 0.0) {
            double Fd;
            sph_kernel_eval(kern, alpha, m->dx[i], hi, dim == 2 ? hi * hi : hi * hi * hi, &Wdi,
                            &Fd);
        }
        /* Balsara's switch from pass A's velocity gradient (this call) */
        const double fi = bal ? sph_balsara_cartesian(m, i, dim) : 1.0;
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            size_t j = (size_t)nb[k];
            double xij[3] = {0, 0, 0}, vij[3] = {0, 0, 0};
            const double r2 = sph_sep(p->x, dim, i, j, xij), hb = 0.5 * (hi + m->h[j]);
            double vx = 0.0;
            for (int d = 0; d < dim; d++) {
                vij[d] = p->v[d][i] - p->v[d][j];
                vx += vij[d] * xij[d];
            }
            double W, F;
            if (!sph_pair_kernel(&sp, dim, r2, hb, &W, &F))
                continue;
            const double rhoj = m->rho[j];
            const double rj2 = 1.0 / (rhoj * rhoj);
            double Pi = 0.0;
            if (vx < 0.0 && (qa > 0.0 || qb > 0.0)) {
                /* Monaghan AV, Eq. 2.21: mu = h v.x / (r^2 + 0.01 h^2) */
                double mu = (lav > 0.0 ? lav : hb) * vx / (r2 + 0.01 * hb * hb);
                double cb = 0.5 * (m->c[i] + m->c[j]);
                Pi = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + rhoj));
                if (bal) /* symmetric in i, j: momentum kept (as sph_axisym.c) */
                    Pi *= 0.5 * (fi + sph_balsara_cartesian(m, j, dim));
            }
            double fn = 0.0;
            if (zeta > 0.0) {
                double Wd = Wdi;
                if (m->h[j] != hi || m->dx[j] != m->dx[i]) {
                    double Fd;
                    sph_kernel_eval(kern, alpha, 0.5 * (m->dx[i] + m->dx[j]), hb,
                                    dim == 2 ? hb * hb : hb * hb * hb, &Wd, &Fd);
                }
                double f1 = Wd > 0.0 ? W / Wd : 0.0;
                fn = asn == 4.0 ? (f1 * f1) * (f1 * f1) : pow(f1, asn);
            }
            const double mj = m->m2[j];
            /* CSPM-corrected gradients, each particle with its own B:
             * g_i = B_i^-T grad_i W_ij pairs with sigma_i, g_j = B_j^-T
             * grad_i W_ij with sigma_j.  The pair force stays antisymmetric
             * (momentum conserved) and the internal power equals
             * sum_i V_i sigma_i : L_i with the same corrected L_i, so
             * kinetic + internal energy is conserved (Bonet & Lok 1999
             * pairing).  Without CSPM, g_i = g_j = grad_i W_ij. */
            double gi[3], gj[3], g0[3];
            for (int b = 0; b < dim; b++)
                g0[b] = xij[b] * F;
            if (cm) {
                for (int b = 0; b < dim; b++) {
                    double ti = 0.0, tj = 0.0;
                    for (int c = 0; c < dim; c++) {
                        ti += m->Bi[c * 3 + b][i] * g0[c];
                        tj += m->Bi[c * 3 + b][j] * g0[c];
                    }
                    gi[b] = ti;
                    gj[b] = tj;
                }
            } else {
                for (int b = 0; b < dim; b++)
                    gi[b] = gj[b] = g0[b];
            }
            double Ai[3], Aj[3], Aa[3];
            for (int a = 0; a < dim; a++) {
                double ti = 0.0, tj = 0.0, ta = 0.0;
                for (int b = 0; b < dim; b++) {
                    int c = tix[a][b];
                    ti += m->sig[c][i] * gi[b];
                    tj += m->sig[c][j] * gj[b];
                    double A = fn * (m->R[c][i] + m->R[c][j]);
                    if (a == b)
                        A -= Pi;
                    ta += A * g0[b];
                }
                Ai[a] = ti * ri2;
                Aj[a] = tj * rj2;
                Aa[a] = ta;
            }
            for (int a = 0; a < dim; a++) {
                acc[a] += mj * (Ai[a] + Aj[a] + Aa[a]);
                /* own stress power + half of the symmetric AV/AS terms */
                de -= mj * vij[a] * (wstress * Ai[a] + 0.5 * Aa[a]);
            }
            if (xs > 0.0) {
                double w = 2.0 * mj / (rhoi + rhoj) * W;
                for (int a = 0; a < dim; a++)
                    xv[a] -= w * vij[a];
            }
        }
        for (int a = 0; a < dim; a++) {
            p->f[a][i] += p->mass[i] * acc[a];
            m->xv[a][i] = xs * xv[a];
        }
        m->de[i] = de;
    }
}

/* Rigid half-space wall by a penalty: a particle closer than dx/2 to the
 * plane is pushed out with k = factor m (c0/dx)^2, i.e. the stiffness of
 * its own column of material (stable for factor <= ~4 at c_s <= 0.3). */
static void wall_forces(struct model *m, struct sim *s)
{
    struct particles *p = s->p;
    const double *n = m->opt.bound.wall_normal, *x0 = m->opt.bound.wall_point;
    /* exact sums (core/exact_sum.h): the same on any rank count */
    struct xsum acc[4];
    for (int a = 0; a < 4; a++)
        xsum_init(&acc[a]);
    for (size_t i = 0; i < p->n_owned; i++) {
        double d = 0.0;
        for (int a = 0; a < m->dim; a++)
            d += (p->x[a][i] - x0[a]) * n[a];
        double g = d - 0.5 * m->dx[i];
        if (g >= 0.0)
            continue;
        const struct sph_material *mt = &m->mat[p->material[i]];
        double c0 = sph_sound_speed(mt, mt->rho0, 0.0);
        double k = m->opt.bound.wall_stiffness * p->mass[i] * c0 * c0 / (m->dx[i] * m->dx[i]);
        for (int a = 0; a < m->dim; a++) {
            p->f[a][i] += -k * g * n[a];
            xsum_add(&acc[a], -k * g * n[a]);
        }
        xsum_add(&acc[3], 0.5 * k * g * g);
    }
    double out[4];
    par_xsum_finish(s, acc, 4, out); /* over all ranks when distributed */
    m->wall.energy = out[3];
    memcpy(m->wall.force, out, sizeof m->wall.force);
}

/* The updated form (fused or two-pass loops) on its particles. */
static int updated_rates(struct model *m, struct sim *s, double lfdt, struct spall_error *err)
{
    const size_t n = s->p->n_owned;
    /* no CSPM, continuity density: one fused pair loop (sph_fused.c) */
    if (m->opt.bound.symmetry[0] || m->opt.bound.symmetry[1] ||
        (!m->opt.kern.cspm && m->opt.kern.density == SPH_DENSITY_CONTINUITY &&
         !m->loops.split_pairs))
        return sph_rates_fused(m, s, err);
    int rc = sph_neighbors_update(m, s, false, err);
    if (rc)
        return rc;
    if (!s->par) /* distributed: the whole body's count at each build (sph_ulpar.c) */
        m->n_pairs = m->nl->offset[n];
    if (m->dim == 2)
        pass_density(m, s, 2);
    else
        pass_density(m, s, 3);
    /* distributed: the partners' density (summed, or advanced by the
     * integrator) and h from their owners */
    if (s->par && (rc = sph_par_halo(m, s, SPH_HALO_DENSITY, err)))
        return rc;
    size_t fb = m->dim == 2 ? pass_gradient(m, s, 2) : pass_gradient(m, s, 3);
    m->cspm_fallbacks += s->par ? par_sum_u64(fb) : fb; /* a count of the whole body */
    if (lfdt > 0.0) /* leapfrog: advance the state with this L */
        sph_leapfrog_advance(m, s, lfdt, SPH_FORM_UPDATED);
    sph_update_pressure(m, s, SPH_FORM_UPDATED);
    const bool summ = m->opt.kern.density == SPH_DENSITY_SUMMATION;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        if (sph_skip(m, i, SPH_FORM_UPDATED))
            continue;
        double trD;
        sph_stress_rate(m, i, &trD);
        m->drho[i] = summ ? 0.0 : -m->rho[i] * trD; /* Eq. 3.18 */
        double trp = m->L[0][i] + m->L[4][i] + (m->dim == 3 ? m->L[8][i] : 0.0);
        m->dh[i] = m->opt.kern.variable_h ? m->h[i] * trp / m->dim : 0.0;
        for (int c = 0; c < 6; c++)
            m->sig[c][i] = m->S[c][i] - (c < 3 ? m->P[i] : 0.0);
        if (m->opt.visc.as_zeta > 0.0)
            sph_artificial_stress(m, i);
    }
    if (m->clamp && (rc = sph_clamp_stress(m, s, err))) /* sph_clamp.c */
        return rc;
    if (m->opt.visc.as_smooth && m->opt.visc.as_zeta > 0.0) {
        /* distributed: the partners' R, rho and h of this call first */
        if (s->par && (rc = sph_par_halo(m, s, SPH_HALO_AS_SMOOTH, err)))
            return rc;
        sph_artificial_stress_smooth(m, s); /* sph_as_smooth.c */
    }
    /* distributed: what pass_forces reads of a partner, from its owner */
    if (s->par && (rc = sph_par_halo(m, s, SPH_HALO_SPLIT, err)))
        return rc;
    if (m->dim == 2)
        pass_forces(m, s, lfdt, 2);
    else
        pass_forces(m, s, lfdt, 3);
    if (lfdt > 0.0) {
        /* leapfrog: AV / AS heating of this step (the stress power is in) */
        for (size_t i = 0; i < n; i++)
            if (!sph_skip(m, i, SPH_FORM_UPDATED))
                m->e[i] += lfdt * m->de[i];
    }
    return SPALL_OK;
}

/* The updated formulation's rates (sph_form_updated). */
static int updated_form_rates(struct model *m, struct sim *s, double lfdt,
                              struct spall_error *err)
{
    /* bodies split by formulation with every particle on TLSPH: only the
     * current list, which feeds the interface between the bodies */
    if (m->form && m->n_total == (s->par ? par_n_global(s) : s->p->n_owned))
        return sph_neighbors_update(m, s, false, err);
    /* the wall's k is per ring mass and its force axial: as in 2D */
    if (m->opt.kern.plane == SPH_PLANE_AXISYMMETRIC)
        return sph_axisym_rates(m, s, err);
    return updated_rates(m, s, lfdt, err);
}

static int updated_form_init(struct model *m, struct sim *s, struct spall_error *err)
{
    return sph_neighbors_update(m, s, true, err);
}

const struct sph_formulation sph_form_updated = {
    .name = "updated",
    .init = updated_form_init,
    .rates = updated_form_rates,
    .end_step = NULL,
};

/* The rates of every formulation of the run; with lfdt > 0 the leapfrog's
 * state advance in between. */
static int compute_rates(struct model *m, struct sim *s, double lfdt, struct spall_error *err)
{
    int rc = SPALL_OK;
    for (int k = 0; k < m->n_forms && !rc; k++)
        rc = m->forms[k]->rates(m, s, lfdt, err);
    if (m->form) /* split by formulation (sph_forms.c): both lists' pairs */
        m->n_pairs = (s->par ? m->ul_pairs_all : m->nl->offset[s->p->n_owned]) +
                     sph_tlsph_pairs(m);
    if (!rc && m->opt.bound.wall)
        wall_forces(m, s);
    return rc;
}

int sph_compute_rates(struct model *m, struct sim *s, struct spall_error *err)
{
    return compute_rates(m, s, 0.0, err);
}

int sph_compute_rates_kick(struct model *m, struct sim *s, double dt, struct spall_error *err)
{
    return compute_rates(m, s, dt, err);
}
