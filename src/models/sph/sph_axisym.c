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
 * tested in tests/test_sph_axisym.c and test_sph_axisym_cons.c; docs/sph.md
 * has the measurements):
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
 *  - momentum and energy are the adjoint of that velocity gradient: with
 *    the internal power P = sum_i M_i sig_i : L_i / rho_i (L_i including
 *    the images and D_tt), the force is F_k = -dP/dv_k and de_i =
 *    sig_i : L_i / rho_i, so that kinetic + internal energy is conserved
 *    exactly by the semi-discrete equations, and axial momentum too (P does
 *    not change when every v_z is shifted by the same amount, images
 *    included).  (As in sph_rates.c the pair weights of de and of the
 *    force are mu_j / rho_i^2 where L has mu_j / (rho_i rho_j): force and
 *    de are exact adjoints of each other, de and the stress update differ
 *    by rho_i / rho_j - 1 per pair.)  Written out: the pair force between rings i and j is
 *    2 pi mu_i mu_j (r_i sig_i g_i / rho_i^2 + r_j sig_j g_j / rho_j^2),
 *    g = B^-T grad W (the Bonet-Lok pairing of sph_rates.c, 1/rho^2 form),
 *    i.e. the cylindrical rho a = (1/r) div(r sig) with the hoop term
 *    -sig_tt / r on the radial component; the artificial viscosity is
 *    weighted by (r_i + r_j) / 2 for the same reason;
 *  - images: the image of j enters L_i with the reflected velocity
 *    (v_r odd, v_z even, the smooth continuation; L stays exact for linear
 *    fields, first ring included), so in the adjoint its pair term carries
 *    tau = r sig with the EVEN continuation (weight +r_j, sig_rz odd): the
 *    pair terms of (i, image of j) and (j, image of i) then cancel in z
 *    and in power.  The odd continuation, used before, is what a uniform
 *    stress needs, but its pair terms are not antisymmetric: a solid
 *    elastic cylinder drifted by 3.3 % in energy and 1.6 % in axial
 *    momentum over ~17 wave transits (tests/test_sph_axisym_cons.c; 11 %
 *    over 15 transits in the earlier measurement of docs/sph.md), a tube
 *    without images 0.01 %.  Odd continuation and adjoint cannot both
 *    hold for the image pairs (their weights must be equal for the
 *    cancellation and opposite for the uniform stress);
 *  - axis weights: with the even images a uniform stress s pulls the first
 *    ring towards the axis by 1.08 s / (rho dx) (its hoop term is
 *    2 s / (rho dx); 0.024 on the second ring).  Each particle with an
 *    image in reach gets a weight lam_i, a function of the positions only,
 *    and the radial velocity gradient of the stress update becomes
 *    L_rr = (1 - lam) L_rr + lam v_r / r (exact for v_r = a r as before);
 *    its adjoint scales sig_rr by (1 - lam) in the pair terms and adds
 *    lam sig_rr to the hoop stress.  lam is solved (Jacobi) so that the
 *    uniform stress exerts no radial force on those particles: measured
 *    lam = -0.56, -0.17 on the first two rings, residual 2.4e-4 and
 *    2e-5 s / (rho dx); the third ring (no image in reach, lam = 0) is
 *    left with 0.047 s / (rho dx) from its neighbours' weights (extending
 *    the weights outwards makes the iteration diverge).  Conservation
 *    does not depend on lam;
 *  - gradients are always corrected (CSPM, Eqs. 3.10-3.11, images
 *    included; the image of j uses Q B_j^-1 Q, Q = diag(-1, 1)), in L and,
 *    paired as in sph_rates.c, in the stress terms of momentum and energy:
 *    with the plain gradient the kernel sum's deficit (2.6 % at h = 1.3 dx)
 *    multiplies tau / r = sig / r, i.e. a uniform stress pushes every ring
 *    (and the solid cylinder of the test blew up);
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
#include "core/mathconst.h"
#include "models/sph/sph_internal.h"
#include "models/sph/sph_pairs.h"

#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <string.h>


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
        p->volume[i] = SPALL_TWO_PI * r * area;
        p->mass[i] = mt->rho0 * p->volume[i];
        m->m2[i] = mt->rho0 * area;
        if (p->x[1][i] + 0.5 * m->dx[i] > ztop)
            ztop = p->x[1][i] + 0.5 * m->dx[i];
    }
    m->ax.surface_z = ztop;
    s->axisymmetric = true;
}

/* Refresh the planar masses m / (2 pi r).  Particles that crossed the axis
 * were reflected by the engine just before this force call (the mirror
 * image of the ring is the same ring; s->axisymmetric, set above).
 *
 * The reflection is the core's (sim_reflect_particle, core/integrator.c):
 * it mirrors every copy of the odd quantities that outlives this call:
 * r, v_r and the force through the field registry's parities, the stress
 * S and the predictor-corrector's S_n and dS_n (registered with
 * FIELD_SYMTENSOR parity: S_rz, component xy, odd) and the integrator's
 * half-step velocity v_half.  All of them matter: the predictor-corrector
 * (integrator.c, sim_step) calls the rates with v_pred and then restores
 * v_half, and sph_advance_state corrects S from S_n and dS_n; mirroring
 * only p->v left the reflected particle at -r -> +r with the velocity of
 * the unmirrored side, i.e. still heading for the axis, crossing it again
 * every step (measured, examples/pen_sph_deformable with `failure:
 * stress`: a failed gel ring at the axis at 9-15 km/s, energy balance
 * +218 %; tests/test_sph_axisym_axis.c). */
static void axis_masses(struct model *m, const struct sim *s)
{
    const struct particles *p = s->p;
    for (size_t i = 0; i < p->n_owned; i++)
        m->m2[i] = p->mass[i] / (SPALL_TWO_PI * hoop_radius(m, p->x[0], i));
}

/* The pair sums as vector rows (sph_axisym_vec.c): Wendland kernel, no
 * Balsara switch (its factor is not in the rows), not switched off for a
 * verification (sph_set_scalar_rows). */
static bool axi_vec(const struct model *m)
{
    return m->opt.kern.kernel == SPH_KERNEL_WENDLAND && !m->opt.visc.av_balsara &&
           !m->loops.scalar_rows;
}

/* Planar corrected (CSPM, Eqs. 3.10-3.11) velocity gradient with the axis
 * images, hoop rate into L[8]; returns the number of CSPM fallbacks. */
static size_t pass_gradient_axi(struct model *m, struct sim *s)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const struct sph_support sp = sph_support_of(m);
    const double *X = p->x[0], *Z = p->x[1], *VR = p->v[0], *VZ = p->v[1];
    const bool vec = axi_vec(m);
    const size_t cap = vec ? sph_axi_vec_cap(m) : 0;
    size_t fallbacks = 0;
#pragma omp parallel firstprivate(sp) reduction(+ : fallbacks)
    {
    /* the vector rows (sph_axisym_vec.c) where the scratch is there, else
     * the scalar loop: bitwise the same sums */
    struct sph_axi_scratch sc = {0};
    const bool vrow = vec && !sph_axi_vec_alloc(&sc, cap);
#pragma omp for schedule(static)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i];
        double G[4] = {0, 0, 0, 0}; /* rr rz zr zz */
        double B[9] = {0, 0, 0, 0, 0, 0, 0, 0, 1};
        if (vrow) {
            double Bs[4];
            sph_axi_grad_row(m, p, i, &sc, G, Bs);
            B[0] = Bs[0];
            B[1] = Bs[1];
            B[3] = Bs[2];
            B[4] = Bs[3];
        }
        /* the listed neighbours and their images, then the own image (j = i) */
        for (size_t k = off[i]; !vrow && k <= off[i + 1]; k++) {
            const bool self = k == off[i + 1];
            const size_t j = self ? i : (size_t)nb[k];
            const double hb = 0.5 * (hi + m->h[j]);
            const double Vj = m->m2[j] / m->rho[j];
            const double dz = Z[i] - Z[j], dvz = VZ[j] - VZ[i];
            for (int img = self ? 1 : 0; img < 2; img++) {
                double dr = img ? X[i] + X[j] : X[i] - X[j];
                double dvr = img ? -VR[j] - VR[i] : VR[j] - VR[i];
                double r2 = dr * dr + dz * dz;
                double W, F;
                if (!sph_pair_kernel(&sp, 2, r2, hb, &W, &F))
                    continue;
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
    sph_axi_vec_free(&sc);
    }
    return fallbacks;
}

/* Balsara's switch (Balsara, J. Comput. Phys. 121 (1995) 357, cited from
 * memory; [Meng2021] Tab. 2.2 "BAL"): f = |div v| / (|div v| + |curl v| +
 * 1e-4 c / h), from the corrected velocity gradient of pass_gradient_axi
 * (L[0] = dv_r/dr, L[1] = dv_r/dz, L[3] = dv_z/dr, L[4] = dv_z/dz, L[8] =
 * v_r / r).  f -> 1 in compression, -> 0 in shear, so the AV stays on the
 * shock and leaves the shear flow around the sphere. */
static inline double balsara(const struct model *m, size_t i)
{
    return sph_balsara_factor(fabs(m->L[0][i] + m->L[4][i] + m->L[8][i]),
                              fabs(m->L[1][i] - m->L[3][i]), m->c[i], m->h[i]);
}

/* Jacobi sweeps of the axis weights, solved from 0 after each
 * neighbour-list build and kept until the next: 9 sweeps leave a residual
 * of 1.2e-4 of the hoop term on the first ring, 3e-5 on the second
 * (measured, square lattice, h = 1.3 dx).  (Solving every step cost
 * +53 % CPU on the gelatin case, this schedule +6-7 % per step against
 * the former form, docs/sph.md; 2 sweeps a step
 * warm-started from the previous weights, +7 %, let the iteration run
 * away on the deformed axis of the deformable-sphere case: blow-up at
 * 44 ns.)  A particle whose weight still moved by more than AXIS_TOL in
 * the last sweep (the iteration not converging for its neighbourhood)
 * keeps 0.  The weights only set the consistency: any value keeps the
 * conservation exact. */
#define AXIS_SWEEPS 9
#define AXIS_TOL 1e-2

/* One Jacobi sweep of the axis weights (file comment, "axis weights"):
 * lam_out_i solves, with the neighbours' lam_in, the radial force balance
 * of particle i under a uniform stress sig_rr = sig_tt = sig_zz:
 *   sum_j mu_j [(1 - l_i) g_i,r / rho_i^2 + (R_j/R_i)(1 - l_j) g_j,r / rho_j^2]
 *     = (1 + l_i) / (rho_i R_i),
 * the pair sum over real neighbours and images as in pass_forces_axi.
 * Particles without an image in reach get exactly 0. */
static void axis_weight_sweep(struct model *m, struct sim *s, const double *lin, double *lout)
{
    const struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const struct sph_support sp = sph_support_of(m);
    const double qmax = m->qmax;
    const double *X = p->x[0], *Z = p->x[1];
#pragma omp parallel for schedule(static) firstprivate(sp)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i], rhoi = m->rho[i];
        const double Ri = hoop_radius(m, X, i);
        /* an image lies at least r_i away: none in reach of distant
         * particles (exact for uniform h) */
        if (!(X[i] < qmax * hi)) {
            lout[i] = 0.0;
            continue;
        }
        double a = 0.0, b = 0.0, d = 0.0, g = 0.0;
        int images = 0;
        for (size_t k = off[i]; k <= off[i + 1]; k++) {
            const bool self = k == off[i + 1];
            const size_t j = self ? i : (size_t)nb[k];
            const double hb = 0.5 * (hi + m->h[j]);
            const double dz = Z[i] - Z[j];
            const double w = m->m2[j] * hoop_radius(m, X, j) / (Ri * m->rho[j] * m->rho[j]);
            for (int img = self ? 1 : 0; img < 2; img++) {
                const double sgn = img ? -1.0 : 1.0, dr = X[i] - sgn * X[j];
                const double r2 = dr * dr + dz * dz;
                double W, F;
                if (!sph_pair_kernel(&sp, 2, r2, hb, &W, &F))
                    continue;
                const double gr = dr * F, gz = dz * F;
                const double gir = m->Bi[0][i] * gr + m->Bi[3][i] * gz;
                const double gjr = m->Bi[0][j] * gr + sgn * m->Bi[3][j] * gz;
                a += m->m2[j] * gir / (rhoi * rhoi);
                b += w * gjr;
                if (self)
                    d += w * gjr;
                else
                    g += w * lin[j] * gjr;
                images += img;
            }
        }
        const double hoop = 1.0 / (rhoi * Ri), den = a + d + hoop;
        double l = (images && den > 0.5 * hoop) ? (a + b - hoop - g) / den : 0.0;
        /* bounded for sparse, disordered supports (lattice: -0.56 at most);
         * any value keeps the conservation */
        lout[i] = fmin(fmax(l, -1.0), 1.0);
    }
}

/* Axis weights lam_i (Jacobi sweeps, above), refreshed after each
 * neighbour build; the radial velocity gradient of the stress update
 * becomes (1 - lam) L_rr + lam v_r / r (still exact for v_r = a r), whose
 * adjoint is in pass_forces_axi. */
static int pass_axis_weights(struct model *m, struct sim *s, struct spall_error *err)
{
    const size_t n = s->p->n_owned;
    if (m->ax.builds != m->n_builds) {
        memset(m->ax.axl, 0, s->p->n * sizeof *m->ax.axl);
        /* distributed (sph_ulpar.c): the partners' B^-1 of this call, then
         * their previous iterate before each sweep */
        double **bi[4] = {&m->Bi[0], &m->Bi[1], &m->Bi[3], &m->Bi[4]};
        int rc = s->par ? sph_par_halo_arrays(s, bi, 4, err) : SPALL_OK;
        for (int it = 0; it < AXIS_SWEEPS && !rc; it++) {
            double **in = (it % 2) ? &m->ax.axl_s : &m->ax.axl;
            double *out = (it % 2) ? m->ax.axl : m->ax.axl_s;
            if (s->par && it > 0 && (rc = sph_par_halo_arrays(s, &in, 1, err)))
                break;
            axis_weight_sweep(m, s, *in, out);
        }
        if (rc)
            return rc;
        /* AXIS_SWEEPS is odd: the last iterate is in axl_s, the one before in axl */
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++)
            m->ax.axl[i] = fabs(m->ax.axl_s[i] - m->ax.axl[i]) < AXIS_TOL ? m->ax.axl_s[i] : 0.0;
        m->ax.builds = m->n_builds;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        m->L[0][i] = (1.0 - m->ax.axl[i]) * m->L[0][i] + m->ax.axl[i] * m->L[8][i];
    return SPALL_OK;
}

/* Momentum, energy, XSPH: the adjoint of the velocity gradient (file
 * comment): pair terms with sig_rr scaled by (1 - lam), images of tau = r sig
 * even, hoop term (sig_tt + lam sig_rr) / r. */
static void pass_forces_axi(struct model *m, struct sim *s)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const struct sph_support sp = sph_support_of(m);
    const double qa = m->opt.visc.av_a, qb = m->opt.visc.av_b, xs = m->opt.visc.xsph, lav = m->opt.visc.av_length;
    const double *X = p->x[0], *Z = p->x[1], *VR = p->v[0], *VZ = p->v[1];
    const double *Srr = m->sig[SXX], *Szz = m->sig[SYY], *Stt = m->sig[SZZ], *Srz = m->sig[SXY];
    const double *lam = m->ax.axl;
    const bool vec = axi_vec(m);
    const size_t cap = vec ? sph_axi_vec_cap(m) : 0;
#pragma omp parallel firstprivate(sp)
    {
    struct sph_axi_scratch sc = {0};
    const bool vrow = vec && !sph_axi_vec_alloc(&sc, cap);
#pragma omp for schedule(static)
    for (size_t i = 0; i < n; i++) {
        const double hi = m->h[i], rhoi = m->rho[i];
        const double ri2 = 1.0 / (rhoi * rhoi);
        const double Ri = hoop_radius(m, X, i), iRi = 1.0 / Ri;
        const double Srri = (1.0 - lam[i]) * Srr[i];
        double ar = 0.0, az = 0.0, de = 0.0, xr = 0.0, xz = 0.0;
        if (vrow) {
            double o[5];
            sph_axi_force_row(m, p, i, &sc, o);
            ar = o[0];
            az = o[1];
            de = o[2];
            if (xs > 0.0) { /* else the scalar loop's +0 */
                xr = o[3];
                xz = o[4];
            }
        }
        for (size_t k = off[i]; !vrow && k <= off[i + 1]; k++) {
            const bool self = k == off[i + 1];
            const size_t j = self ? i : (size_t)nb[k];
            const double hb = 0.5 * (hi + m->h[j]);
            const double rhoj = m->rho[j], rj2 = 1.0 / (rhoj * rhoj), mj = m->m2[j];
            const double dz = Z[i] - Z[j], vz = VZ[i] - VZ[j];
            const double Rj = hoop_radius(m, X, j);
            const double Srrj = (1.0 - lam[j]) * Srr[j];
            for (int img = self ? 1 : 0; img < 2; img++) {
                /* image of j: r -> -r, v_r -> -v_r, sig_rz -> -sig_rz; its
                 * weight R_j stays positive (tau even: the adjoint) */
                const double sgn = img ? -1.0 : 1.0;
                const double dr = X[i] - sgn * X[j], vr = VR[i] - sgn * VR[j];
                const double r2 = dr * dr + dz * dz;
                double W, F;
                if (!sph_pair_kernel(&sp, 2, r2, hb, &W, &F))
                    continue;
                const double vx = vr * dr + vz * dz;
                double Pi = 0.0;
                if (vx < 0.0) {
                    /* Eq. 2.21; viscosity_length: a fixed length instead of h */
                    double mu = (lav > 0.0 ? lav : hb) * vx / (r2 + 0.01 * hb * hb);
                    double cb = 0.5 * (m->c[i] + m->c[j]);
                    Pi = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + rhoj));
                    if (m->opt.visc.av_balsara) /* symmetric in i, j: momentum kept */
                        Pi *= 0.5 * (balsara(m, i) + balsara(m, j));
                }
                const double gr = dr * F, gz = dz * F;
                /* corrected gradients B^-T grad W, each particle its own B
                 * (the image of j: Q B_j^-1 Q, Q = diag(-1, 1)) */
                const double gir = m->Bi[0][i] * gr + m->Bi[3][i] * gz;
                const double giz = m->Bi[1][i] * gr + m->Bi[4][i] * gz;
                const double gjr = m->Bi[0][j] * gr + sgn * m->Bi[3][j] * gz;
                const double gjz = sgn * m->Bi[1][j] * gr + m->Bi[4][j] * gz;
                const double Air = (Srri * gir + Srz[i] * giz) * ri2;
                const double Aiz = (Srz[i] * gir + Szz[i] * giz) * ri2;
                const double wj = Rj * iRi, wa = 0.5 * (Ri + Rj) * iRi;
                const double Ajr = wj * (Srrj * gjr + sgn * Srz[j] * gjz) * rj2;
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
        /* hoop stress and its power (sig_tt + lam sig_rr) D_tt / rho */
        const double st = Stt[i] + lam[i] * Srr[i];
        ar -= st * iRi / rhoi;
        de += st * VR[i] * iRi / rhoi;
        p->f[0][i] += p->mass[i] * ar;
        p->f[1][i] += p->mass[i] * az;
        m->xv[0][i] = xs * xr;
        m->xv[1][i] = xs * xz;
        m->de[i] = de;
    }
    sph_axi_vec_free(&sc);
    }
}

int sph_axisym_rates(struct model *m, struct sim *s, struct spall_error *err)
{
    const size_t n = s->p->n_owned;
    axis_masses(m, s);
    int rc = sph_neighbors_update(m, s, false, err);
    if (rc)
        return rc;
    if (!s->par) /* distributed: the whole body's count at each build (sph_ulpar.c) */
        m->n_pairs = m->nl->offset[n];
    /* distributed: the partners' density, h and planar mass of this call */
    if (s->par && (rc = sph_par_halo(m, s, SPH_HALO_AXI_GRADIENT, err)))
        return rc;
    const size_t fb = pass_gradient_axi(m, s);
    m->cspm_fallbacks += s->par ? par_sum_u64(fb) : fb; /* a count of the whole body */
    if ((rc = pass_axis_weights(m, s, err)))
        return rc;
    sph_update_pressure(m, s, SPH_FORM_ALL);
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
        m->dh[i] = m->opt.kern.variable_h ? m->h[i] * (m->L[0][i] + m->L[4][i]) / 2.0 : 0.0;
        for (int c = 0; c < 6; c++)
            m->sig[c][i] = m->S[c][i] - (c < 3 ? m->P[i] : 0.0);
    }
    if (s->par && (rc = sph_par_halo(m, s, SPH_HALO_AXI_FORCES, err)))
        return rc;
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
    const double zc = m->ax.surface_z - m->opt.cavity_depth;
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
    if (sim->par) { /* the smallest over all ranks: exact in any order */
        r1 = -par_max_double(-r1);
        r2 = -par_max_double(-r2);
    }
    names[0] = "cavity_D1 [m]";
    values[0] = isfinite(r1) ? 2.0 * r1 : 0.0;
    names[1] = "cavity_D2 [m]";
    values[1] = isfinite(r2) ? 2.0 * r2 : 0.0;
    return 2;
}
