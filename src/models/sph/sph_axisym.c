/**
 * @file sph_axisym.c
 * @brief Axisymmetric (r, z) SPH for solids (`plane: axisymmetric`, issue 6
 *        item 2, issue 7 item 3): the lattice's x is the radius r >= 0, y the
 *        axis z; each particle is a ring.
 *
 * Formulation: the cylindrical equations written for tau = r sig, in the
 * family of the r-weighted forms of Petschek & Libersky, J. Comput. Phys.
 * 109 (1993) 76 and Brookshaw, ANZIAM J. 44 (2003) C114, with reflective
 * axis images as in Garcia-Senz et al., MNRAS 392 (2009) 346 (cited from
 * memory, papers not re-checked; the discretisation is derived here and
 * tested in tests/test_sph_axisym.c; docs/sph.md has the measurements):
 *
 *  - particle i carries its ring mass M_i = 2 pi r_i A_i rho_0 (p->mass; the
 *    integrator, the rigid contact and the energies use it), and in the
 *    planar (r, z) sums the planar mass mu_j = M_j / (2 pi r_j), so that
 *    mu_j / rho_j is the particle's current meridian area (a ring moving
 *    outwards gets longer and thinner: its area shrinks as 1/r);
 *  - velocity gradient: the 2D SPH gradient in (r, z) (Eq. 3.31) plus the
 *    hoop strain rate D_tt = v_r / r; continuity drho/dt = -rho tr D with
 *    the hoop rate included; the Jaumann rate acts on S_rr, S_zz, S_tt, S_rz
 *    (components xx, yy, zz, xy);
 *  - momentum: rho a_r = (1/r) div(r sig)_r - sig_tt / r,
 *    rho a_z = (1/r) div(r sig)_z (the cylindrical equations written for
 *    tau = r sig), the divergence by the planar symmetric SPH form (Eq. 3.20
 *    with mu_j) applied to tau: the pair force on ring i from ring j is
 *    2 pi mu_i mu_j (r_i sig_i / rho_i^2 + r_j sig_j / rho_j^2) grad W,
 *    antisymmetric, so axial momentum is conserved exactly; the artificial
 *    viscosity is weighted by (r_i + r_j) / 2 for the same reason.  (The
 *    simpler "planar divergence + source terms (sig_rr - sig_tt)/r,
 *    sig_rz / r" form was tried first: it passes the same static checks but
 *    its pair forces differ by r_i / r_j, O(1) near the axis, and it created
 *    3.5x the input energy in an elastic cylinder over ~15 wave transits);
 *  - energy: de_i = -sum_j mu_j v_ij . sig_i / rho_i^2 . grad W + the AV
 *    half share + sig_tt v_r / (rho r), which is exactly the power of the
 *    forces above between real particles (Bonet-Lok pairing as in
 *    sph_rates.c): measured 0.01 % energy error on a hollow cylinder (no
 *    axis) over ~15 wave transits;
 *  - gradients are always corrected (CSPM, Eqs. 3.10-3.11, images
 *    included; the image of j uses Q B_j^-1 Q, Q = diag(-1, 1)), in L and,
 *    paired as in sph_rates.c, in the stress terms of momentum and energy:
 *    with the plain gradient the kernel sum's deficit (2.6 % at h = 1.3 dx)
 *    multiplies tau / r = sig / r, i.e. a uniform stress pushes every ring;
 *  - the axis images carry tau = r sig with its odd continuation (needed
 *    for consistency: uniform stress exerts no force on the first rings);
 *    their pair terms are then not the exact adjoint of the imaged velocity
 *    gradient, and a solid elastic cylinder gains ~11 % of the input energy
 *    over ~15 wave transits (a hollow one, no images: 0.01 %); the even
 *    continuation would be conservative but pushes the first rings under
 *    uniform stress.  Without the correction the first rings' 1/r terms
 *    went unstable at c_s = 0.3; with it (and the |B^-1| scaling of the
 *    stable step, sph_model.c) c_s = 0.3 runs.
 *  - near the axis: every particle j within reach of r = 0 has a mirror
 *    image at (-r_j, z_j) with v_r, sig_rz odd and v_z, sig_rr, sig_zz,
 *    sig_tt even (the fields' smooth continuation across the axis), which
 *    completes the kernel support of particles near the axis (reflective
 *    ghosts, as in Garcia-Senz et al. 2009); the image of j lies no closer
 *    to i than j itself, so the ordinary neighbour list already holds every
 *    j whose image matters, plus i's own image.  The hoop terms divide by
 *    max(r_i, dx_i / 4) (particles start at r >= dx/2; the floor only
 *    guards a particle driven onto the axis), and a particle that crosses
 *    the axis is reflected back (its ring is the same ring).
 *
 * Not available here (refused at create): CSPM, artificial stress,
 * summation density, TLSPH.  The model's half-space wall works for a wall
 * normal to the axis (sph_rates.c: its k = factor M (c0/dx)^2 is per ring
 * mass, the force axial); unlike a rigid `wall` impactor with the default
 * k = eta M / dt^2 it keeps its stiffness when the adaptive step changes
 * during contact, which otherwise creates energy (measured: +2.9 % of the
 * impact energy in the first two steps of the 2D Taylor rod, n = 16).
 */
#include "models/sph/sph_internal.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <string.h>

#define TWO_PI 6.283185307179586

static inline double hoop_radius(const struct model *m, const double *x0, size_t i)
{
    double r = x0[i], f = 0.25 * m->dx[i];
    return r > f ? r : f;
}

void sph_axisym_init(struct model *m, struct sim *s)
{
    struct particles *p = s->p;
    const double t = s->thickness;
    double ztop = -INFINITY;
    for (size_t i = 0; i < p->n_owned; i++) {
        const struct sph_material *mt = &m->mat[p->material[i]];
        double area = p->volume[i] / t;
        double r = hoop_radius(m, p->x[0], i);
        p->volume[i] = TWO_PI * r * area;
        p->mass[i] = mt->rho0 * p->volume[i];
        m->m2[i] = mt->rho0 * area;
        if (p->x[1][i] + 0.5 * m->dx[i] > ztop)
            ztop = p->x[1][i] + 0.5 * m->dx[i];
    }
    m->surface_z = ztop;
    s->axisymmetric = true;
}

/* Reflect particles that crossed the axis, refresh the planar masses. */
static void axis_reflect(struct model *m, struct sim *s)
{
    struct particles *p = s->p;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (p->x[0][i] < 0.0) {
            p->x[0][i] = -p->x[0][i];
            p->v[0][i] = -p->v[0][i];
        }
        m->m2[i] = p->mass[i] / (TWO_PI * hoop_radius(m, p->x[0], i));
    }
}

/* Planar corrected (CSPM, Eqs. 3.10-3.11) velocity gradient with the axis
 * images, hoop rate into L[8]; returns the number of CSPM fallbacks. */
static size_t pass_gradient_axi(struct model *m, struct sim *s)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kernel;
    const double alpha = m->alpha, qmax = m->qmax;
    const double *X = p->x[0], *Z = p->x[1], *VR = p->v[0], *VZ = p->v[1];
    size_t fallbacks = 0;
#pragma omp parallel for schedule(static) reduction(+ : fallbacks)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i];
        double G[4] = {0, 0, 0, 0}; /* rr rz zr zz */
        double B[9] = {0, 0, 0, 0, 0, 0, 0, 0, 1};
        /* own image first (j = i), then the listed neighbours and theirs */
        for (size_t k = off[i]; k <= off[i + 1]; k++) {
            const bool self = k == off[i + 1];
            const size_t j = self ? i : (size_t)nb[k];
            const double hb = 0.5 * (hi + m->h[j]), R2 = qmax * qmax * hb * hb;
            const double Vj = m->m2[j] / m->rho[j];
            const double dz = Z[i] - Z[j], dvz = VZ[j] - VZ[i];
            for (int img = self ? 1 : 0; img < 2; img++) {
                double dr = img ? X[i] + X[j] : X[i] - X[j];
                double dvr = img ? -VR[j] - VR[i] : VR[j] - VR[i];
                double r2 = dr * dr + dz * dz;
                if (r2 >= R2)
                    continue;
                double W, F;
                sph_kernel_eval(kern, alpha, sqrt(r2), hb, hb * hb, &W, &F);
                double VF = Vj * F;
                G[0] += dvr * VF * dr;
                G[1] += dvr * VF * dz;
                G[2] += dvz * VF * dr;
                G[3] += dvz * VF * dz;
                B[0] -= dr * VF * dr;
                B[1] -= dr * VF * dz;
                B[3] -= dz * VF * dr;
                B[4] -= dz * VF * dz;
            }
        }
        /* the corrected gradient makes linear fields exact, images
         * included: without it the kernel sum's deficit (measured 2.6 % at
         * h = 1.3 dx) multiplies tau / r = sig / r, a spurious force on
         * every ring under uniform stress */
        double Bi[9];
        double det = sph_inverse(2, B, Bi);
        double nrm = fmax(fabs(Bi[0]) + fabs(Bi[1]), fabs(Bi[3]) + fabs(Bi[4]));
        /* plain gradient for failed particles (pressure only, often
         * isolated ejecta) and for sparse supports: B ~ 0.97 I in the bulk,
         * det ~ 0.5 and |B^-1| ~ 2 at a flat free surface; a sparser
         * support would amplify the pair forces and (sph_stable_dt scales
         * the step by |B^-1|) collapse the time step */
        if (m->failed[i] || !(det > 0.25) || !(nrm < 2.5)) {
            for (int c = 0; c < 9; c++)
                Bi[c] = (c % 4 == 0) ? 1.0 : 0.0;
            fallbacks++;
        }
        for (int c = 0; c < 9; c++) {
            m->L[c][i] = 0.0;
            m->Bi[c][i] = Bi[c];
        }
        m->L[0][i] = G[0] * Bi[0] + G[1] * Bi[3];
        m->L[1][i] = G[0] * Bi[1] + G[1] * Bi[4];
        m->L[3][i] = G[2] * Bi[0] + G[3] * Bi[3];
        m->L[4][i] = G[2] * Bi[1] + G[3] * Bi[4];
        m->L[8][i] = VR[i] / hoop_radius(m, X, i); /* D_tt = v_r / r */
    }
    return fallbacks;
}

/* Balsara's switch (Balsara, J. Comput. Phys. 121 (1995) 357, cited from
 * memory; seed 004 Tab. 2.2 "BAL"): f = |div v| / (|div v| + |curl v| +
 * 1e-4 c / h), from the corrected velocity gradient of pass_gradient_axi
 * (L[0] = dv_r/dr, L[1] = dv_r/dz, L[3] = dv_z/dr, L[4] = dv_z/dz, L[8] =
 * v_r / r).  f -> 1 in compression, -> 0 in shear, so the AV stays on the
 * shock and leaves the shear flow around the sphere. */
static inline double balsara(const struct model *m, size_t i)
{
    const double dv = fabs(m->L[0][i] + m->L[4][i] + m->L[8][i]);
    const double cv = fabs(m->L[1][i] - m->L[3][i]);
    const double den = dv + cv + 1e-4 * m->c[i] / m->h[i];
    return den > 0.0 ? dv / den : 1.0;
}

/* Momentum (planar divergence + hoop sources), energy, XSPH. */
static void pass_forces_axi(struct model *m, struct sim *s)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kernel;
    const double alpha = m->alpha, qmax = m->qmax;
    const double qa = m->opt.av_a, qb = m->opt.av_b, xs = m->opt.xsph, lav = m->opt.av_length;
    const double *X = p->x[0], *Z = p->x[1], *VR = p->v[0], *VZ = p->v[1];
    const double *Srr = m->sig[SXX], *Szz = m->sig[SYY], *Stt = m->sig[SZZ], *Srz = m->sig[SXY];
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i], rhoi = m->rho[i];
        const double ri2 = 1.0 / (rhoi * rhoi);
        const double Ri = hoop_radius(m, X, i), iRi = 1.0 / Ri;
        double ar = 0.0, az = 0.0, de = 0.0, xr = 0.0, xz = 0.0;
        for (size_t k = off[i]; k <= off[i + 1]; k++) {
            const bool self = k == off[i + 1];
            const size_t j = self ? i : (size_t)nb[k];
            const double hb = 0.5 * (hi + m->h[j]), R2 = qmax * qmax * hb * hb;
            const double rhoj = m->rho[j], rj2 = 1.0 / (rhoj * rhoj), mj = m->m2[j];
            const double dz = Z[i] - Z[j], vz = VZ[i] - VZ[j];
            const double Rj = hoop_radius(m, X, j);
            for (int img = self ? 1 : 0; img < 2; img++) {
                /* image of j: r -> -r, v_r -> -v_r, sig_rz -> -sig_rz, and
                 * tau = r sig changes sign with r */
                const double sgn = img ? -1.0 : 1.0;
                const double dr = X[i] - sgn * X[j], vr = VR[i] - sgn * VR[j];
                const double r2 = dr * dr + dz * dz;
                if (r2 >= R2)
                    continue;
                double W, F;
                sph_kernel_eval(kern, alpha, sqrt(r2), hb, hb * hb, &W, &F);
                const double vx = vr * dr + vz * dz;
                double Pi = 0.0;
                if (vx < 0.0) {
                    /* Eq. 2.21; viscosity_length: a fixed length instead of h */
                    double mu = (lav > 0.0 ? lav : hb) * vx / (r2 + 0.01 * hb * hb);
                    double cb = 0.5 * (m->c[i] + m->c[j]);
                    Pi = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + rhoj));
                    if (m->opt.av_balsara) /* symmetric in i, j: momentum kept */
                        Pi *= 0.5 * (balsara(m, i) + balsara(m, j));
                }
                const double gr = dr * F, gz = dz * F;
                /* corrected gradients B^-T grad W, each particle its own B
                 * (the image of j: Q B_j^-1 Q, Q = diag(-1, 1)) */
                const double gir = m->Bi[0][i] * gr + m->Bi[3][i] * gz;
                const double giz = m->Bi[1][i] * gr + m->Bi[4][i] * gz;
                const double gjr = m->Bi[0][j] * gr + sgn * m->Bi[3][j] * gz;
                const double gjz = sgn * m->Bi[1][j] * gr + m->Bi[4][j] * gz;
                const double Air = (Srr[i] * gir + Srz[i] * giz) * ri2;
                const double Aiz = (Srz[i] * gir + Szz[i] * giz) * ri2;
                const double wj = sgn * Rj * iRi, wa = 0.5 * (Ri + Rj) * iRi;
                const double Ajr = wj * (Srr[j] * gjr + sgn * Srz[j] * gjz) * rj2;
                const double Ajz = wj * (sgn * Srz[j] * gjr + Szz[j] * gjz) * rj2;
                const double Pw = Pi * wa;
                ar += mj * (Air + Ajr - Pw * gr);
                az += mj * (Aiz + Ajz - Pw * gz);
                de -= mj * (vr * (Air - 0.5 * Pw * gr) + vz * (Aiz - 0.5 * Pw * gz));
                if (xs > 0.0) {
                    double w = 2.0 * mj / (rhoi + rhoj) * W;
                    xr -= w * vr;
                    xz -= w * vz;
                }
            }
        }
        /* hoop stress (the r-weighted divergence holds sig_rr / r and
         * sig_rz / r) and its power sig_tt D_tt / rho */
        ar -= Stt[i] * iRi / rhoi;
        de += Stt[i] * VR[i] * iRi / rhoi;
        p->f[0][i] += p->mass[i] * ar;
        p->f[1][i] += p->mass[i] * az;
        m->xv[0][i] = xs * xr;
        m->xv[1][i] = xs * xz;
        m->de[i] = de;
    }
}

int sph_axisym_rates(struct model *m, struct sim *s, struct spall_error *err)
{
    const size_t n = s->p->n_owned;
    axis_reflect(m, s);
    int rc = sph_neighbors_update(m, s, false, err);
    if (rc)
        return rc;
    m->n_pairs = m->nl->offset[n];
    m->cspm_fallbacks += pass_gradient_axi(m, s);
    sph_update_pressure(m, s);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double trD;
        sph_stress_rate(m, i, &trD); /* uses L[8] = v_r / r as D_tt */
        m->drho[i] = -m->rho[i] * trD;
        /* a failed particle does not dilate below rho0: separating broken
         * material opens a void instead (ejecta would otherwise swell to a
         * few % of rho0 and swamp its neighbours' sums at fixed h) */
        if (m->failed[i] && m->drho[i] < 0.0 && !m->mat[s->p->material[i]].failed_tension &&
            m->rho[i] <= m->mat[s->p->material[i]].rho0)
            m->drho[i] = 0.0;
        m->dh[i] = m->opt.variable_h ? m->h[i] * (m->L[0][i] + m->L[4][i]) / 2.0 : 0.0;
        for (int c = 0; c < 6; c++)
            m->sig[c][i] = m->S[c][i] - (c < 3 ? m->P[i] : 0.0);
    }
    pass_forces_axi(m, s);
    return SPALL_OK;
}

/* Cavity diameters at depth cavity_depth below the initial surface: in the
 * slab |z - z_c| <= dx_i / 2, the smallest ring radius (less half a
 * spacing, the particle's own extent) of all particles (D1, the empty
 * cavity: failed particles still fill it) and of intact ones (D2: failed
 * particles count as cavity, the thesis' "including damaged particles"). */
size_t sph_axisym_history(const struct model *m, const struct sim *sim, const char **names,
                          double *values)
{
    if (!(m->opt.cavity_depth > 0.0))
        return 0;
    const struct particles *p = sim->p;
    const double zc = m->surface_z - m->opt.cavity_depth;
    double r1 = INFINITY, r2 = INFINITY;
    for (size_t i = 0; i < p->n_owned; i++) {
        if (fabs(p->x[1][i] - zc) > 0.5 * m->dx[i])
            continue;
        double r = p->x[0][i] - 0.5 * m->dx[i];
        if (r < 0.0)
            r = 0.0;
        if (r < r1)
            r1 = r;
        if (!m->failed[i] && r < r2)
            r2 = r;
    }
    names[0] = "cavity_D1 [m]";
    values[0] = isfinite(r1) ? 2.0 * r1 : 0.0;
    names[1] = "cavity_D2 [m]";
    values[1] = isfinite(r2) ? 2.0 * r2 : 0.0;
    return 2;
}
