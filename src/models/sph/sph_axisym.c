/**
 * @file sph_axisym.c
 * @brief Axisymmetric (r, z) SPH for solids (`plane: axisymmetric`, issue 6
 *        item 2, issue 7 item 3): the lattice's x is the radius r >= 0, y the
 *        axis z; each particle is a ring.
 *
 * Formulation (the "Cartesian SPH in the meridian plane + hoop source terms"
 * form used for axisymmetric impact codes, e.g. Johnson, Stryk & Beissel,
 * CMAME 139 (1996) 347, and compared against the r-weighted forms of
 * Petschek & Libersky, J. Comput. Phys. 109 (1993) 76, Brookshaw, ANZIAM J.
 * 44 (2003) C114 and Garcia-Senz et al., MNRAS 392 (2009) 346):
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
 *  - momentum: rho a_r = d sig_rr/dr + d sig_rz/dz + (sig_rr - sig_tt)/r,
 *    rho a_z = d sig_rz/dr + d sig_zz/dz + sig_rz/r: the planar symmetric
 *    SPH divergence (Eq. 3.20 with mu_j) plus the two hoop source terms;
 *  - energy: the planar form of sph_rates.c plus sig_tt v_r / (rho r);
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
 * summation density, TLSPH, the model's half-space wall.
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

/* Planar velocity gradient with mirror images, hoop rate into L[8]. */
static void pass_gradient_axi(struct model *m, struct sim *s)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kernel;
    const double alpha = m->alpha, qmax = m->qmax;
    const double *X = p->x[0], *Z = p->x[1], *VR = p->v[0], *VZ = p->v[1];
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i];
        double G[4] = {0, 0, 0, 0}; /* rr rz zr zz */
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
            }
        }
        for (int c = 0; c < 9; c++)
            m->L[c][i] = 0.0;
        m->L[0][i] = G[0];
        m->L[1][i] = G[1];
        m->L[3][i] = G[2];
        m->L[4][i] = G[3];
        m->L[8][i] = VR[i] / hoop_radius(m, X, i); /* D_tt = v_r / r */
        for (int c = 0; c < 9; c++)
            m->Bi[c][i] = (c % 4 == 0) ? 1.0 : 0.0;
    }
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
    const double qa = m->opt.av_a, qb = m->opt.av_b, xs = m->opt.xsph;
    const double *X = p->x[0], *Z = p->x[1], *VR = p->v[0], *VZ = p->v[1];
    const double *Srr = m->sig[SXX], *Szz = m->sig[SYY], *Stt = m->sig[SZZ], *Srz = m->sig[SXY];
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i], rhoi = m->rho[i];
        const double ri2 = 1.0 / (rhoi * rhoi);
        double ar = 0.0, az = 0.0, de = 0.0, xr = 0.0, xz = 0.0;
        for (size_t k = off[i]; k <= off[i + 1]; k++) {
            const bool self = k == off[i + 1];
            const size_t j = self ? i : (size_t)nb[k];
            const double hb = 0.5 * (hi + m->h[j]), R2 = qmax * qmax * hb * hb;
            const double rhoj = m->rho[j], rj2 = 1.0 / (rhoj * rhoj), mj = m->m2[j];
            const double dz = Z[i] - Z[j], vz = VZ[i] - VZ[j];
            for (int img = self ? 1 : 0; img < 2; img++) {
                /* image of j: r -> -r, v_r -> -v_r, sig_rz -> -sig_rz */
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
                    double mu = hb * vx / (r2 + 0.01 * hb * hb); /* Eq. 2.21 */
                    double cb = 0.5 * (m->c[i] + m->c[j]);
                    Pi = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + rhoj));
                }
                const double gr = dr * F, gz = dz * F;
                const double Air = (Srr[i] * gr + Srz[i] * gz) * ri2;
                const double Aiz = (Srz[i] * gr + Szz[i] * gz) * ri2;
                const double Ajr = (Srr[j] * gr + sgn * Srz[j] * gz) * rj2;
                const double Ajz = (sgn * Srz[j] * gr + Szz[j] * gz) * rj2;
                ar += mj * (Air + Ajr - Pi * gr);
                az += mj * (Aiz + Ajz - Pi * gz);
                de -= mj * (vr * (Air - 0.5 * Pi * gr) + vz * (Aiz - 0.5 * Pi * gz));
                if (xs > 0.0) {
                    double w = 2.0 * mj / (rhoi + rhoj) * W;
                    xr -= w * vr;
                    xz -= w * vz;
                }
            }
        }
        /* hoop sources (cylindrical momentum and energy equations) */
        const double r = hoop_radius(m, X, i);
        ar += (Srr[i] - Stt[i]) / (rhoi * r);
        az += Srz[i] / (rhoi * r);
        de += Stt[i] * VR[i] / (rhoi * r);
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
    pass_gradient_axi(m, s);
    sph_update_pressure(m, s);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double trD;
        sph_stress_rate(m, i, &trD); /* uses L[8] = v_r / r as D_tt */
        m->drho[i] = -m->rho[i] * trD;
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
