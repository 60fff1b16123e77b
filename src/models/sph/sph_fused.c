/**
 * @file sph_fused.c
 * @brief One-pass SPH rates for the common case (no CSPM, continuity
 *        density): velocity gradient (Eq. 3.31), continuity (Eq. 3.18),
 *        momentum and energy with Monaghan AV, Monaghan-Gray AS and XSPH in
 *        a single gather over each particle's neighbour list.
 *
 * Why a second implementation of sph_rates.c's two passes: without CSPM
 * the forces need only the state (S, P from rho and e), not this step's
 * velocity gradient, so both loops can share one distance, one kernel
 * evaluation and one set of gathers per pair.  Measured (perf, 3D Taylor
 * bar, 1 thread): the split passes took 56 % + 26 % of the run.  The
 * kernel is dispatched once per call (the Wendland kernel has a closed
 * form without a switch; F = dW/dr / r needs no division by r there), and
 * each particle's sigma / rho^2 is formed once per step instead of per pair.
 *
 * Mathematically the same equations as sph_rates.c (see its header for
 * the momentum / energy pairing); only the summation order of floating
 * point terms differs (tests/test_sph_fused.c compares both to 1e-12).
 * Gather over full lists, fixed order: bitwise independent of threads.
 *
 * Pairs gather from a struct sph_pair_src, which is either the model's own
 * arrays or, with symmetry planes, the real + mirrored ghost particles
 * (sph_symmetry.c).
 */
#include "models/sph/sph_internal.h"

#include "core/neighbor.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Particle i's rates from its pair sums: force, XSPH velocity, de, the
 * plain velocity gradient G (no CSPM on the fused path), and from it the
 * stress rate, continuity (Eq. 3.18) and dh. */
static inline void fused_store(struct model *m, struct particles *p, size_t i, const int dim,
                               const double a[3], const double xv[3], double de,
                               const double G[9])
{
    const double xs = m->opt.visc.xsph;
    p->f[0][i] += p->mass[i] * a[0];
    p->f[1][i] += p->mass[i] * a[1];
    m->xv[0][i] = xs * xv[0];
    m->xv[1][i] = xs * xv[1];
    if (dim == 3) {
        p->f[2][i] += p->mass[i] * a[2];
        m->xv[2][i] = xs * xv[2];
    }
    m->de[i] = de;
    for (int c = 0; c < 9; c++) {
        m->L[c][i] = G[c];
        m->Bi[c][i] = (c % 4 == 0) ? 1.0 : 0.0;
    }
    double trD;
    sph_stress_rate(m, i, &trD);
    m->drho[i] = m->opt.kern.density == SPH_DENSITY_SUMMATION ? 0.0 : -m->rho[i] * trD;
    double trp = m->L[0][i] + m->L[4][i] + (dim == 3 ? m->L[8][i] : 0.0);
    m->dh[i] = m->opt.kern.variable_h ? m->h[i] * trp / dim : 0.0;
}

/* The pair loop.  dim and wendland are literal at every call site so the
 * compiler emits four specialised copies. */
static inline void fused_pass(struct model *m, struct sim *s, const struct sph_pair_src *src,
                              const int dim, const int wendland)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const size_t *off = m->nl->offset;
    const int32_t *nb = m->nl->idx;
    const enum sph_kernel kern = m->opt.kern.kernel;
    const double alpha = m->alpha, q2max = m->qmax * m->qmax;
    const double qa = m->opt.visc.av_a, qb = m->opt.visc.av_b, zeta = m->opt.visc.as_zeta, asn = m->opt.visc.as_n;
    const double lav = m->opt.visc.av_length;
    const bool av = qa > 0.0 || qb > 0.0, as = zeta > 0.0;
    const double xs = m->opt.visc.xsph;
    const double *const X0 = src->x[0], *const X1 = src->x[1], *const X2 = src->x[2];
    const double *const V0 = src->v[0], *const V1 = src->v[1], *const V2 = src->v[2];
    const double *const Hs = src->h, *const Rho = src->rho, *const Cs = src->c,
                 *const M2 = src->m2, *const DX = src->dx;
    /* symmetric tensor storage xx yy zz xy yz xz */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        if (sph_skip(m, i, SPH_FORM_UPDATED))
            continue; /* a TLSPH particle of a mixed run (sph_forms.c) */
        const double hi = m->h[i], rhoi = m->rho[i], ci = m->c[i];
        const double xi0 = X0[i], xi1 = X1[i], xi2 = dim == 3 ? X2[i] : 0.0;
        const double vi0 = V0[i], vi1 = V1[i], vi2 = dim == 3 ? V2[i] : 0.0;
        double sri[6], Ri[6];
        for (int c = 0; c < 6; c++) {
            sri[c] = src->sr[c][i];
            Ri[c] = as ? src->R[c][i] : 0.0;
        }
        const double hdi = dim == 2 ? hi * hi : hi * hi * hi;
        const double normi = alpha / hdi, ihi = 1.0 / hi;
        double Wdi = 0.0; /* W(dx_i, h_i): the AS reference value (Eq. 2.26) */
        if (as) {
            double Fd;
            sph_kernel_eval(kern, alpha, m->dx[i], hi, hdi, &Wdi, &Fd);
        }
        double G[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        double a0 = 0.0, a1 = 0.0, a2 = 0.0, de = 0.0, xv0 = 0.0, xv1 = 0.0, xv2 = 0.0;
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            const size_t j = (size_t)nb[k];
            const double x0 = xi0 - X0[j], x1 = xi1 - X1[j], x2 = dim == 3 ? xi2 - X2[j] : 0.0;
            const double r2 = x0 * x0 + x1 * x1 + x2 * x2;
            const double hj = Hs[j];
            const bool same_h = hj == hi;
            const double hb = same_h ? hi : 0.5 * (hi + hj);
            if (r2 >= q2max * hb * hb)
                continue;
            double W, F;
            const double ihb = same_h ? ihi : 1.0 / hb;
            const double norm = same_h ? normi : (dim == 2 ? alpha * ihb * ihb
                                                           : alpha * ihb * ihb * ihb);
            if (wendland) {
                /* Wendland C2: K = a^4 (2q + 1), a = 1 - q/2; dK/dq = -5 q a^3,
                 * so F = norm dK/dq / (h r) = -5 norm a^3 / h^2 */
                const double q = sqrt(r2) * ihb;
                const double a = 1.0 - 0.5 * q, a3 = a * a * a;
                W = norm * a3 * a * (2.0 * q + 1.0);
                F = -5.0 * norm * a3 * ihb * ihb;
            } else {
                sph_kernel_eval(kern, alpha, sqrt(r2), hb, dim == 2 ? hb * hb : hb * hb * hb, &W,
                                &F);
            }
            const double v0 = vi0 - V0[j], v1 = vi1 - V1[j], v2 = dim == 3 ? vi2 - V2[j] : 0.0;
            const double rhoj = Rho[j], mj = M2[j];
            /* velocity gradient, Eq. 3.31: G_ab += (v_j - v_i)_a V_j F x_ij,b */
            const double VF = mj / rhoj * F;
            const double g0 = -v0 * VF, g1 = -v1 * VF, g2 = -v2 * VF;
            G[0] += g0 * x0;
            G[1] += g0 * x1;
            G[3] += g1 * x0;
            G[4] += g1 * x1;
            if (dim == 3) {
                G[2] += g0 * x2;
                G[5] += g1 * x2;
                G[6] += g2 * x0;
                G[7] += g2 * x1;
                G[8] += g2 * x2;
            }
            double Pi = 0.0;
            const double vx = v0 * x0 + v1 * x1 + v2 * x2;
            if (av && vx < 0.0) {
                /* Monaghan AV, Eq. 2.21: mu = h v.x / (r^2 + 0.01 h^2) */
                const double mu = (lav > 0.0 ? lav : hb) * vx / (r2 + 0.01 * hb * hb);
                const double cb = 0.5 * (ci + Cs[j]);
                Pi = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + rhoj));
            }
            /* ua = sigma_i/rho_i^2 x_ij, ub = sigma_j/rho_j^2 x_ij,
             * uc = (fn (R_i + R_j) - Pi I) x_ij; the force uses all three,
             * the energy the own term fully and half of the symmetric
             * AV / AS term (sph_rates.c header) */
            double sj[6];
            for (int c = 0; c < 6; c++)
                sj[c] = src->sr[c][j];
            double ua0, ua1, ua2 = 0.0, ub0, ub1, ub2 = 0.0;
            ua0 = sri[SXX] * x0 + sri[SXY] * x1;
            ua1 = sri[SXY] * x0 + sri[SYY] * x1;
            ub0 = sj[SXX] * x0 + sj[SXY] * x1;
            ub1 = sj[SXY] * x0 + sj[SYY] * x1;
            if (dim == 3) {
                ua0 += sri[SXZ] * x2;
                ua1 += sri[SYZ] * x2;
                ua2 = sri[SXZ] * x0 + sri[SYZ] * x1 + sri[SZZ] * x2;
                ub0 += sj[SXZ] * x2;
                ub1 += sj[SYZ] * x2;
                ub2 = sj[SXZ] * x0 + sj[SYZ] * x1 + sj[SZZ] * x2;
            }
            double uc0 = -Pi * x0, uc1 = -Pi * x1, uc2 = -Pi * x2;
            if (as) {
                double Wd = Wdi;
                if (!same_h || DX[j] != m->dx[i]) {
                    double Fd;
                    sph_kernel_eval(kern, alpha, 0.5 * (m->dx[i] + DX[j]), hb,
                                    dim == 2 ? hb * hb : hb * hb * hb, &Wd, &Fd);
                }
                const double f1 = Wd > 0.0 ? W / Wd : 0.0;
                const double fn = asn == 4.0 ? (f1 * f1) * (f1 * f1) : pow(f1, asn);
                double Rs[6];
                for (int c = 0; c < 6; c++)
                    Rs[c] = fn * (Ri[c] + src->R[c][j]);
                uc0 += Rs[SXX] * x0 + Rs[SXY] * x1;
                uc1 += Rs[SXY] * x0 + Rs[SYY] * x1;
                if (dim == 3) {
                    uc0 += Rs[SXZ] * x2;
                    uc1 += Rs[SYZ] * x2;
                    uc2 += Rs[SXZ] * x0 + Rs[SYZ] * x1 + Rs[SZZ] * x2;
                }
            }
            const double mF = mj * F;
            a0 += mF * (ua0 + ub0 + uc0);
            a1 += mF * (ua1 + ub1 + uc1);
            a2 += mF * (ua2 + ub2 + uc2);
            de -= mF * (v0 * (ua0 + 0.5 * uc0) + v1 * (ua1 + 0.5 * uc1) + v2 * (ua2 + 0.5 * uc2));
            if (xs > 0.0) {
                const double w = 2.0 * mj / (rhoi + rhoj) * W;
                xv0 -= w * v0;
                xv1 -= w * v1;
                xv2 -= w * v2;
            }
        }
        const double a[3] = {a0, a1, a2}, xv[3] = {xv0, xv1, xv2};
        fused_store(m, p, i, dim, a, xv, de, G);
    }
}

/* The Wendland rows without artificial stress (the default deck): the same
 * arithmetic as fused_pass, split so that the pair terms vectorise.
 * fused_pass spends most of its time on two unpredictable branches (the
 * support test, r < 2 h over a list with a 20 % skin; the AV's v.x < 0) and
 * on spills of its 16 running sums.  Here a first loop keeps the partners
 * within the support, a branch-free vector loop evaluates their terms into
 * per-thread arrays (a receding pair gets the exact +0 the skipped AV
 * branch meant), and a third loop adds them in list order.  Every term is formed
 * by the same operations as in fused_pass (no FMA: this file is compiled
 * with ISO C's fp-contract=off, also in the x86-64-v3 clone), and a sum
 * that starts at +0 is unchanged by adding +0 or -0, so the result is
 * bitwise fused_pass's (tests/test_sph_fused.c compares the two).  */
enum { FT_G = 0, FT_A = 9, FT_DE = 12, FT_XV = 13, FT_N = 16 };

struct fused_vec {
    const size_t *off;
    const int32_t *nb;
    const double *X[3], *V[3], *H, *Rho, *Cs, *M2, *Sr[6];
    double alpha, q2max, qa, qb, lav;
    bool av;
};

/* The row is inlined into one function per dimension and CPU version
 * (fused_vec_row3, ...): AVX2 gathers in the x86-64-v3 one. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(SPALL_NO_CLONES)
/* (no SLP: it packs the row sums' scalar adds four terms from four arrays
 * into a register per add, more instructions than the adds themselves) */
#define FUSED_CLONES                                                                               \
    __attribute__((target_clones("arch=x86-64-v3", "default"), optimize("no-tree-slp-vectorize")))
#define FUSED_INLINE static inline __attribute__((always_inline))
#else
#define FUSED_CLONES
#define FUSED_INLINE static inline
#endif

/* Row i: its partners within the support into cj, their pair terms into
 * t[c * cap + k] (c < FT_N), and the terms' sums in list order into sum[c].
 * @p uh: every particle and partner has the same h (fixed h, one spacing:
 * the Taylor bar); then h_j = h_i, hb = h_i and norm = normi for every
 * pair, which the general code finds per pair from a load of h_j and a
 * division: the same values, without the per-pair work. */
FUSED_INLINE void fused_vec_row(const struct fused_vec *fv, size_t i, double *restrict t,
                                int32_t *restrict cj, size_t cap, double sum[FT_N], const int dim,
                                const bool uh)
{
    const size_t k0 = fv->off[i], row = fv->off[i + 1] - k0;
    const int32_t *restrict nb = fv->nb + k0;
    const double *restrict X0 = fv->X[0], *restrict X1 = fv->X[1], *restrict X2 = fv->X[2];
    const double *restrict V0 = fv->V[0], *restrict V1 = fv->V[1], *restrict V2 = fv->V[2];
    const double *restrict Hs = fv->H, *restrict Rho = fv->Rho, *restrict Cs = fv->Cs,
                           *restrict M2 = fv->M2;
    const double *restrict S0 = fv->Sr[SXX], *restrict S1 = fv->Sr[SYY],
                           *restrict S2 = fv->Sr[SZZ], *restrict S3 = fv->Sr[SXY],
                           *restrict S4 = fv->Sr[SYZ], *restrict S5 = fv->Sr[SXZ];
    const double alpha = fv->alpha, q2max = fv->q2max, qa = fv->qa, qb = fv->qb, lav = fv->lav;
    const bool av = fv->av;
    const double hi = Hs[i], rhoi = Rho[i], ci = Cs[i];
    const double xi0 = X0[i], xi1 = X1[i], xi2 = dim == 3 ? X2[i] : 0.0;
    const double vi0 = V0[i], vi1 = V1[i], vi2 = dim == 3 ? V2[i] : 0.0;
    const double sxx = S0[i], syy = S1[i], szz = S2[i], sxy = S3[i], syz = S4[i], sxz = S5[i];
    const double hdi = dim == 2 ? hi * hi : hi * hi * hi;
    const double normi = alpha / hdi;
    double *restrict tg0 = t, *restrict tg1 = t + cap, *restrict tg2 = t + 2 * cap,
                     *restrict tg3 = t + 3 * cap, *restrict tg4 = t + 4 * cap,
                     *restrict tg5 = t + 5 * cap, *restrict tg6 = t + 6 * cap,
                     *restrict tg7 = t + 7 * cap, *restrict tg8 = t + 8 * cap;
    double *restrict ta0 = t + FT_A * cap, *restrict ta1 = t + (FT_A + 1) * cap,
                     *restrict ta2 = t + (FT_A + 2) * cap, *restrict tde = t + FT_DE * cap;
    double *restrict tx0 = t + FT_XV * cap, *restrict tx1 = t + (FT_XV + 1) * cap,
                     *restrict tx2 = t + (FT_XV + 2) * cap;
    /* The partners within the support, in list order (the list carries a
     * skin: about 40 % of the listed pairs of the Taylor bar lie outside),
     * by fused_pass's test; a store and a count, no branch. */
    size_t len = 0;
    const double r2u = q2max * hi * hi; /* (uh: q2max hb hb of every pair) */
    for (size_t k = 0; k < row; k++) {
        const int32_t j = nb[k];
        const double x0 = xi0 - X0[j], x1 = xi1 - X1[j], x2 = dim == 3 ? xi2 - X2[j] : 0.0;
        const double r2 = x0 * x0 + x1 * x1 + x2 * x2;
        double r2lim = r2u;
        if (!uh) {
            const double hj = Hs[j];
            const double hb = hj == hi ? hi : 0.5 * (hi + hj);
            r2lim = q2max * hb * hb;
        }
        cj[len] = j;
        len += !(r2 >= r2lim);
    }
    /* no reductions in this loop, only independent lanes: simd is a
     * statement about aliasing (the term arrays are not the state) */
#pragma omp simd
    for (size_t k = 0; k < len; k++) {
        const int32_t j = cj[k]; /* an int index: the vectoriser gathers by it */
        const double x0 = xi0 - X0[j], x1 = xi1 - X1[j], x2 = dim == 3 ? xi2 - X2[j] : 0.0;
        const double r2 = x0 * x0 + x1 * x1 + x2 * x2;
        const double hj = uh ? hi : Hs[j];
        const bool same_h = uh || hj == hi;
        const double hm = 0.5 * (hi + hj);
        const double hb = same_h ? hi : hm;
        /* every value is formed whether or not it is used, so that the
         * loop has no branch: 1 / hb is fused_pass's ihi when h_j = h_i */
        const double ihb = 1.0 / hb;
        const double normb = dim == 2 ? alpha * ihb * ihb : alpha * ihb * ihb * ihb;
        const double norm = same_h ? normi : normb;
        /* Wendland C2 as in fused_pass */
        const double q = sqrt(r2) * ihb;
        const double a = 1.0 - 0.5 * q, a3 = a * a * a;
        const double W = norm * a3 * a * (2.0 * q + 1.0);
        const double F = -5.0 * norm * a3 * ihb * ihb;
        const double v0 = vi0 - V0[j], v1 = vi1 - V1[j], v2 = dim == 3 ? vi2 - V2[j] : 0.0;
        const double rhoj = Rho[j], mj = M2[j];
        const double VF = mj / rhoj * F;
        const double g0 = -v0 * VF, g1 = -v1 * VF, g2 = -v2 * VF;
        const double p00 = g0 * x0, p01 = g0 * x1, p10 = g1 * x0, p11 = g1 * x1;
        tg0[k] = p00;
        tg1[k] = p01;
        tg3[k] = p10;
        tg4[k] = p11;
        if (dim == 3) {
            const double p02 = g0 * x2, p12 = g1 * x2, p20 = g2 * x0, p21 = g2 * x1,
                         p22 = g2 * x2;
            tg2[k] = p02;
            tg5[k] = p12;
            tg6[k] = p20;
            tg7[k] = p21;
            tg8[k] = p22;
        }
        const double vx = v0 * x0 + v1 * x1 + v2 * x2;
        const double lb = lav > 0.0 ? lav : hb;
        const double mu = lb * vx / (r2 + 0.01 * hb * hb);
        const double cb = 0.5 * (ci + Cs[j]);
        const double Pa = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + rhoj));
        const double Pi = (av & (vx < 0.0)) ? Pa : 0.0;
        double ua0 = sxx * x0 + sxy * x1, ua1 = sxy * x0 + syy * x1, ua2 = 0.0;
        double ub0 = S0[j] * x0 + S3[j] * x1, ub1 = S3[j] * x0 + S1[j] * x1, ub2 = 0.0;
        if (dim == 3) {
            ua0 += sxz * x2;
            ua1 += syz * x2;
            ua2 = sxz * x0 + syz * x1 + szz * x2;
            ub0 += S5[j] * x2;
            ub1 += S4[j] * x2;
            ub2 = S5[j] * x0 + S4[j] * x1 + S2[j] * x2;
        }
        const double uc0 = -Pi * x0, uc1 = -Pi * x1, uc2 = -Pi * x2;
        const double mF = mj * F;
        const double f0 = mF * (ua0 + ub0 + uc0), f1 = mF * (ua1 + ub1 + uc1),
                     f2 = mF * (ua2 + ub2 + uc2);
        const double pw =
            mF * (v0 * (ua0 + 0.5 * uc0) + v1 * (ua1 + 0.5 * uc1) + v2 * (ua2 + 0.5 * uc2));
        const double w = 2.0 * mj / (rhoi + rhoj) * W;
        const double w0 = w * v0, w1 = w * v1, w2 = w * v2;
        ta0[k] = f0;
        ta1[k] = f1;
        ta2[k] = f2;
        tde[k] = pw;
        tx0[k] = w0;
        tx1[k] = w1;
        tx2[k] = w2;
    }
    /* the sums in list order, as fused_pass adds them: one scalar chain
     * each (as an array, G was vectorised across its components, four
     * terms gathered from four arrays into a register per add: more
     * instructions than the sixteen scalar adds) */
    double g0 = 0.0, g1 = 0.0, g2 = 0.0, g3 = 0.0, g4 = 0.0, g5 = 0.0, g6 = 0.0, g7 = 0.0,
           g8 = 0.0;
    double a0 = 0.0, a1 = 0.0, a2 = 0.0, de = 0.0, xv0 = 0.0, xv1 = 0.0, xv2 = 0.0;
    for (size_t k = 0; k < len; k++) {
        g0 += tg0[k];
        g1 += tg1[k];
        g3 += tg3[k];
        g4 += tg4[k];
        if (dim == 3) {
            g2 += tg2[k];
            g5 += tg5[k];
            g6 += tg6[k];
            g7 += tg7[k];
            g8 += tg8[k];
        }
        a0 += ta0[k];
        a1 += ta1[k];
        a2 += ta2[k];
        de -= tde[k];
        xv0 -= tx0[k];
        xv1 -= tx1[k];
        xv2 -= tx2[k];
    }
    const double G[9] = {g0, g1, g2, g3, g4, g5, g6, g7, g8};
    for (int c = 0; c < 9; c++)
        sum[FT_G + c] = G[c];
    sum[FT_A] = a0;
    sum[FT_A + 1] = a1;
    sum[FT_A + 2] = a2;
    sum[FT_DE] = de;
    sum[FT_XV] = xv0;
    sum[FT_XV + 1] = xv1;
    sum[FT_XV + 2] = xv2;
}

/* One out-of-line function per dimension and CPU version (AVX2 gathers in
 * the x86-64-v3 one): every row runs the same machine code on any thread. */
FUSED_CLONES static void fused_vec_row3(const struct fused_vec *fv, size_t i, double *t,
                                        int32_t *cj, size_t cap, double sum[FT_N])
{
    fused_vec_row(fv, i, t, cj, cap, sum, 3, false);
}

FUSED_CLONES static void fused_vec_row3u(const struct fused_vec *fv, size_t i, double *t,
                                         int32_t *cj, size_t cap, double sum[FT_N])
{
    fused_vec_row(fv, i, t, cj, cap, sum, 3, true);
}

FUSED_CLONES static void fused_vec_row2(const struct fused_vec *fv, size_t i, double *t,
                                        int32_t *cj, size_t cap, double sum[FT_N])
{
    fused_vec_row(fv, i, t, cj, cap, sum, 2, false);
}

FUSED_CLONES static void fused_vec_row2u(const struct fused_vec *fv, size_t i, double *t,
                                         int32_t *cj, size_t cap, double sum[FT_N])
{
    fused_vec_row(fv, i, t, cj, cap, sum, 2, true);
}

/* fused_pass for the Wendland kernel without artificial stress, by rows of
 * fused_vec_row; per-thread term arrays of the longest row. */
static int fused_pass_vec(struct model *m, struct sim *s, const struct sph_pair_src *src,
                          struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    struct fused_vec fv = {
        .off = m->nl->offset,
        .nb = m->nl->idx,
        .H = src->h,
        .Rho = src->rho,
        .Cs = src->c,
        .M2 = src->m2,
        .alpha = m->alpha,
        .q2max = m->qmax * m->qmax,
        .qa = m->opt.visc.av_a,
        .qb = m->opt.visc.av_b,
        .lav = m->opt.visc.av_length,
        .av = m->opt.visc.av_a > 0.0 || m->opt.visc.av_b > 0.0,
    };
    for (int d = 0; d < 3; d++) {
        fv.X[d] = src->x[d];
        fv.V[d] = src->v[d];
    }
    for (int c = 0; c < 6; c++)
        fv.Sr[c] = src->sr[c];
    size_t cap = 1;
    for (size_t i = 0; i < n; i++)
        if (fv.off[i + 1] - fv.off[i] > cap)
            cap = fv.off[i + 1] - fv.off[i];
    cap = (cap + 7) & ~(size_t)7; /* each term array 64-byte aligned */
    /* one h for every particle and partner (images included): the rows
     * that skip the per-pair h (fused_vec_row) */
    bool uh = src->n_all > 0;
    for (size_t j = 1; j < src->n_all && uh; j++)
        uh = src->h[j] == src->h[0];
    const double xs = m->opt.visc.xsph;
    int nomem = 0;
#pragma omp parallel
    {
        double *t = aligned_alloc(64, FT_N * cap * sizeof(double));
        int32_t *cj = malloc(cap * sizeof *cj);
        if (!t || !cj) {
#pragma omp atomic write
            nomem = 1;
        }
#pragma omp for schedule(static)
        for (size_t i = 0; i < n; i++) {
            if (!t || !cj || sph_skip(m, i, SPH_FORM_UPDATED))
                continue; /* a TLSPH particle of a mixed run (sph_forms.c) */
            double sum[FT_N];
            if (dim == 3)
                (uh ? fused_vec_row3u : fused_vec_row3)(&fv, i, t, cj, cap, sum);
            else
                (uh ? fused_vec_row2u : fused_vec_row2)(&fv, i, t, cj, cap, sum);
            /* without XSPH fused_pass's sums stay +0 */
            const double *xv = xs > 0.0 ? sum + FT_XV : (const double[3]){0.0, 0.0, 0.0};
            fused_store(m, p, i, dim, sum + FT_A, xv, sum[FT_DE], sum + FT_G);
        }
        free(t);
        free(cj);
    }
    if (nomem)
        return spall_error_set(err, SPALL_ERR_NOMEM,
                               "out of memory for the SPH pair terms (%zu partners)", cap);
    return SPALL_OK;
}

/* sigma = S - P I, the artificial stress R_i and sigma / rho^2 of every
 * real particle (the pair loop's per-particle inputs). */
static void fused_prepare(struct model *m, struct sim *s)
{
    const size_t n = s->p->n_owned;
    const bool as = m->opt.visc.as_zeta > 0.0;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        if (sph_skip(m, i, SPH_FORM_UPDATED))
            continue;
        const double ir2 = 1.0 / (m->rho[i] * m->rho[i]);
        for (int c = 0; c < 6; c++) {
            m->sig[c][i] = m->S[c][i] - (c < 3 ? m->P[i] : 0.0);
            m->sr[c][i] = m->sig[c][i] * ir2;
        }
        if (as)
            sph_artificial_stress(m, i);
    }
}

int sph_rates_fused(struct model *m, struct sim *s, struct spall_error *err)
{
    struct particles *p = s->p;
    sph_update_pressure(m, s, SPH_FORM_UPDATED);
    fused_prepare(m, s);
    struct sph_pair_src src;
    int rc;
    if ((m->opt.bound.symmetry[0] || m->opt.bound.symmetry[1]) && s->par) {
        /* distributed: the list came with the ghosts (sph_ulpar.c); the
         * partners' state of this call from their owners, then the images */
        if ((rc = sph_par_halo(m, s, SPH_HALO_FUSED, err)))
            return rc;
        sph_symmetry_src(m, s, &src);
    } else if (m->opt.bound.symmetry[0] || m->opt.bound.symmetry[1]) {
        /* after a restart: first the ghosts and list the checkpointed run had */
        if (m->sym_restore && (rc = sph_symmetry_restore(m, s, err)))
            return rc;
        m->sym_restore = false;
        if ((rc = sph_symmetry_update(m, s, &src, err)))
            return rc;
    } else {
        if ((rc = sph_neighbors_update(m, s, false, err)))
            return rc;
        memset(&src, 0, sizeof src);
        /* distributed: the partners' state of this call from their owners */
        if (s->par && (rc = sph_par_halo(m, s, SPH_HALO_FUSED, err)))
            return rc;
        src.n_all = p->n;
        for (int d = 0; d < 3; d++) {
            src.x[d] = d < m->dim ? p->x[d] : NULL;
            src.v[d] = d < m->dim ? p->v[d] : NULL;
        }
        src.h = m->h;
        src.rho = m->rho;
        src.c = m->c;
        src.m2 = m->m2;
        src.dx = m->dx;
        for (int c = 0; c < 6; c++) {
            src.sr[c] = m->sr[c];
            src.R[c] = m->R[c];
        }
    }
    if (!s->par) /* distributed: the whole body's count at each build (sph_ulpar.c) */
        m->n_pairs = m->nl->offset[p->n_owned];
    const bool wend = m->opt.kern.kernel == SPH_KERNEL_WENDLAND;
    if (wend && !(m->opt.visc.as_zeta > 0.0) && !m->loops.scalar_rows)
        return fused_pass_vec(m, s, &src, err);
    if (m->dim == 2) {
        if (wend)
            fused_pass(m, s, &src, 2, 1);
        else
            fused_pass(m, s, &src, 2, 0);
    } else {
        if (wend)
            fused_pass(m, s, &src, 3, 1);
        else
            fused_pass(m, s, &src, 3, 0);
    }
    return SPALL_OK;
}
