/**
 * @file sph_axisym_vec.c
 * @brief The pair sums of the axisymmetric passes (sph_axisym.c: corrected
 *        velocity gradient, forces) as vector rows, for the Wendland kernel
 *        without Balsara's switch (the penetration decks).
 *
 * Why: the two passes were 80 % of the gelatin case (perf, 1 thread), most
 * of it in branches a vector unit does not take: every listed pair is
 * tried twice (itself and its axis image, which is out of reach for all
 * but the first rings), the kernel goes through the six-way switch, and the
 * AV test v.x < 0 is unpredictable.  Here a first loop keeps the entries
 * within the support (a pair, then its image, then the particle's own
 * image: the order of sph_axisym.c's loops), a branch-free loop forms their
 * terms, and a third adds them in that order.  Every term is formed by the
 * operations of sph_axisym.c in the same order (the Wendland shape and
 * F = norm dK / (h r) as sph_kernel_eval; no FMA: ISO C's fp-contract=off,
 * also in the x86-64-v3 clone), and the sums skip exactly what the
 * scalar loops skipped or added as +0, so the results are bitwise those of
 * the scalar loops (tests/test_sph_axisym.c compares the two).
 */
#include "models/sph/sph_internal.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(SPALL_NO_CLONES)
#define AXI_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#define AXI_INLINE static inline __attribute__((always_inline))
#else
#define AXI_CLONES
#define AXI_INLINE static inline
#endif

size_t sph_axi_vec_cap(const struct model *m)
{
    /* a listed pair and its image, and the particle's own image */
    size_t cap = 1;
    const size_t *off = m->nl->offset;
    for (size_t i = 0; i < m->nl->n; i++)
        if (off[i + 1] - off[i] > cap)
            cap = off[i + 1] - off[i];
    cap = 2 * cap + 1;
    return (cap + 7) & ~(size_t)7; /* each term array 64-byte aligned */
}

int sph_axi_vec_alloc(struct sph_axi_scratch *sc, size_t cap)
{
    sc->cap = cap;
    sc->t = aligned_alloc(64, SPH_AXI_TERMS * cap * sizeof(double));
    sc->cj = malloc(cap * sizeof *sc->cj);
    sc->sg = aligned_alloc(64, cap * sizeof(double));
    return sc->t && sc->cj && sc->sg ? 0 : -1;
}

void sph_axi_vec_free(struct sph_axi_scratch *sc)
{
    free(sc->t);
    free(sc->cj);
    free(sc->sg);
    sc->t = sc->sg = NULL;
    sc->cj = NULL;
}

/* The entries of row i within the support, in the scalar loops' order:
 * for each listed j the pair (sign +1) then j's image (sign -1), and last
 * i's own image; returns their number.  The test is sph_pair_kernel's. */
AXI_INLINE size_t axi_entries(const struct model *m, const struct particles *p, size_t i,
                              int32_t *restrict cj, double *restrict sg)
{
    const size_t *off = m->nl->offset;
    const int32_t *restrict nb = m->nl->idx;
    const double *restrict X = p->x[0], *restrict Z = p->x[1], *restrict H = m->h;
    const double q2 = m->qmax * m->qmax, hi = H[i], xi = X[i], zi = Z[i];
    size_t len = 0;
    for (size_t k = off[i]; k < off[i + 1]; k++) {
        const int32_t j = nb[k];
        const double hb = 0.5 * (hi + H[j]), lim = q2 * hb * hb;
        const double dz = zi - Z[j], dr = xi - X[j], di = xi + X[j];
        const double r2 = dr * dr + dz * dz, ri2 = di * di + dz * dz;
        cj[len] = j;
        sg[len] = 1.0;
        len += !(r2 >= lim);
        cj[len] = j;
        sg[len] = -1.0;
        len += !(ri2 >= lim);
    }
    const double hb = 0.5 * (hi + hi), di = xi + xi;
    cj[len] = (int32_t)i;
    sg[len] = -1.0;
    len += !(di * di >= q2 * hb * hb);
    return len;
}

/* Wendland W and F of a pair inside the support: sph_kernel_eval's
 * operations for the 2D kernel (q >= 2 and r = 0 as there). */
AXI_INLINE void axi_wendland(double alpha, double r2, double hb, double *W, double *F)
{
    const double r = sqrt(r2), q = r / hb;
    const double a = 1.0 - 0.5 * q, a3 = a * a * a;
    const double K = q < 2.0 ? a3 * a * (2.0 * q + 1.0) : 0.0;
    const double dK = q < 2.0 ? -5.0 * q * a3 : 0.0;
    const double norm = alpha / (hb * hb);
    const double Fv = norm * dK / (hb * r);
    *W = norm * K;
    *F = r > 0.0 ? Fv : 0.0;
}

/* Row i of pass_gradient_axi: G (rr rz zr zz) and the B sums (rr rz zr zz,
 * to be subtracted) of its entries, added in order. */
AXI_INLINE void axi_grad_row(const struct model *m, const struct particles *p, size_t i,
                             struct sph_axi_scratch *sc, double G[4], double Bs[4])
{
    int32_t *restrict cj = sc->cj;
    double *restrict sg = sc->sg;
    const size_t len = axi_entries(m, p, i, cj, sg), cap = sc->cap;
    const double *restrict X = p->x[0], *restrict Z = p->x[1], *restrict VR = p->v[0],
                           *restrict VZ = p->v[1], *restrict H = m->h, *restrict M2 = m->m2,
                           *restrict Rho = m->rho;
    const double alpha = m->alpha, hi = H[i], xi = X[i], zi = Z[i], vri = VR[i], vzi = VZ[i];
    double *restrict t0 = sc->t, *restrict t1 = t0 + cap, *restrict t2 = t0 + 2 * cap,
                     *restrict t3 = t0 + 3 * cap, *restrict t4 = t0 + 4 * cap,
                     *restrict t5 = t0 + 5 * cap, *restrict t6 = t0 + 6 * cap,
                     *restrict t7 = t0 + 7 * cap;
#pragma omp simd
    for (size_t k = 0; k < len; k++) {
        const int32_t j = cj[k];
        const double s = sg[k];
        const double hb = 0.5 * (hi + H[j]);
        const double Vj = M2[j] / Rho[j];
        const double dz = zi - Z[j], dvz = VZ[j] - vzi;
        /* the pair: x_i - x_j, v_j - v_i; the image: x_i + x_j, -v_j - v_i */
        const double drp = xi - X[j], dri = xi + X[j];
        const double dr = s > 0.0 ? drp : dri;
        const double dvp = VR[j] - vri, dvi = -VR[j] - vri;
        const double dvr = s > 0.0 ? dvp : dvi;
        const double r2 = dr * dr + dz * dz;
        double W, F;
        axi_wendland(alpha, r2, hb, &W, &F);
        const double VF = Vj * F;
        t0[k] = dvr * VF * dr;
        t1[k] = dvr * VF * dz;
        t2[k] = dvz * VF * dr;
        t3[k] = dvz * VF * dz;
        t4[k] = dr * VF * dr;
        t5[k] = dr * VF * dz;
        t6[k] = dz * VF * dr;
        t7[k] = dz * VF * dz;
    }
    double g0 = 0.0, g1 = 0.0, g2 = 0.0, g3 = 0.0, b0 = 0.0, b1 = 0.0, b2 = 0.0, b3 = 0.0;
    for (size_t k = 0; k < len; k++) {
        g0 += t0[k];
        g1 += t1[k];
        g2 += t2[k];
        g3 += t3[k];
        b0 -= t4[k];
        b1 -= t5[k];
        b2 -= t6[k];
        b3 -= t7[k];
    }
    G[0] = g0;
    G[1] = g1;
    G[2] = g2;
    G[3] = g3;
    Bs[0] = b0;
    Bs[1] = b1;
    Bs[2] = b2;
    Bs[3] = b3;
}

AXI_CLONES void sph_axi_grad_row(const struct model *m, const struct particles *p, size_t i,
                                 struct sph_axi_scratch *sc, double G[4], double Bs[4])
{
    axi_grad_row(m, p, i, sc, G, Bs);
}

/* Row i of pass_forces_axi's pair sum: ar, az, de, xr, xz (XSPH sums
 * without the factor), added in order. */
AXI_INLINE void axi_force_row(const struct model *m, const struct particles *p, size_t i,
                              struct sph_axi_scratch *sc, double out[5])
{
    int32_t *restrict cj = sc->cj;
    double *restrict sg = sc->sg;
    const size_t len = axi_entries(m, p, i, cj, sg), cap = sc->cap;
    const double *restrict X = p->x[0], *restrict Z = p->x[1], *restrict VR = p->v[0],
                           *restrict VZ = p->v[1], *restrict H = m->h, *restrict M2 = m->m2,
                           *restrict Rho = m->rho, *restrict Cs = m->c, *restrict DX = m->dx;
    const double *restrict Srr = m->sig[SXX], *restrict Szz = m->sig[SYY],
                           *restrict Srz = m->sig[SXY], *restrict lam = m->ax.axl;
    const double *restrict B0 = m->Bi[0], *restrict B1 = m->Bi[1], *restrict B3 = m->Bi[3],
                           *restrict B4 = m->Bi[4];
    const double qa = m->opt.visc.av_a, qb = m->opt.visc.av_b, lav = m->opt.visc.av_length;
    const double alpha = m->alpha;
    const double hi = H[i], rhoi = Rho[i], ci = Cs[i], xi = X[i], zi = Z[i];
    const double vri = VR[i], vzi = VZ[i];
    const double ri2 = 1.0 / (rhoi * rhoi);
    /* hoop_radius of sph_axisym.c: max(r, dx / 4) */
    const double fi = 0.25 * DX[i], Ri = xi > fi ? xi : fi, iRi = 1.0 / Ri;
    const double Srri = (1.0 - lam[i]) * Srr[i], Srzi = Srz[i], Szzi = Szz[i];
    const double b0i = B0[i], b1i = B1[i], b3i = B3[i], b4i = B4[i];
    double *restrict t0 = sc->t, *restrict t1 = t0 + cap, *restrict t2 = t0 + 2 * cap,
                     *restrict t3 = t0 + 3 * cap, *restrict t4 = t0 + 4 * cap;
#pragma omp simd
    for (size_t k = 0; k < len; k++) {
        const int32_t j = cj[k];
        const double sgn = sg[k];
        const double hb = 0.5 * (hi + H[j]);
        const double rhoj = Rho[j], rj2 = 1.0 / (rhoj * rhoj), mj = M2[j];
        const double dz = zi - Z[j], vz = vzi - VZ[j];
        const double fj = 0.25 * DX[j], Rj = X[j] > fj ? X[j] : fj;
        const double Srrj = (1.0 - lam[j]) * Srr[j];
        const double dr = xi - sgn * X[j], vr = vri - sgn * VR[j];
        const double r2 = dr * dr + dz * dz;
        double W, F;
        axi_wendland(alpha, r2, hb, &W, &F);
        const double vx = vr * dr + vz * dz;
        const double lb = lav > 0.0 ? lav : hb;
        const double mu = lb * vx / (r2 + 0.01 * hb * hb);
        const double cb = 0.5 * (ci + Cs[j]);
        const double Pa = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + rhoj));
        const double Pi = vx < 0.0 ? Pa : 0.0;
        const double gr = dr * F, gz = dz * F;
        const double gir = b0i * gr + b3i * gz;
        const double giz = b1i * gr + b4i * gz;
        const double gjr = B0[j] * gr + sgn * B3[j] * gz;
        const double gjz = sgn * B1[j] * gr + B4[j] * gz;
        const double Air = (Srri * gir + Srzi * giz) * ri2;
        const double Aiz = (Srzi * gir + Szzi * giz) * ri2;
        const double wj = Rj * iRi, wa = 0.5 * (Ri + Rj) * iRi;
        const double Ajr = wj * (Srrj * gjr + sgn * Srz[j] * gjz) * rj2;
        const double Ajz = wj * (sgn * Srz[j] * gjr + Szz[j] * gjz) * rj2;
        const double Pw = Pi * wa;
        t0[k] = mj * (Air + Ajr - Pw * gr);
        t1[k] = mj * (Aiz + Ajz - Pw * gz);
        t2[k] = mj * (vr * (Air - 0.5 * Pw * gr) + vz * (Aiz - 0.5 * Pw * gz));
        const double w = 2.0 * mj / (rhoi + rhoj) * W;
        t3[k] = w * vr;
        t4[k] = w * vz;
    }
    double ar = 0.0, az = 0.0, de = 0.0, xr = 0.0, xz = 0.0;
    for (size_t k = 0; k < len; k++) {
        ar += t0[k];
        az += t1[k];
        de -= t2[k];
        xr -= t3[k];
        xz -= t4[k];
    }
    out[0] = ar;
    out[1] = az;
    out[2] = de;
    out[3] = xr;
    out[4] = xz;
}

AXI_CLONES void sph_axi_force_row(const struct model *m, const struct particles *p, size_t i,
                                  struct sph_axi_scratch *sc, double out[5])
{
    axi_force_row(m, p, i, sc, out);
}
