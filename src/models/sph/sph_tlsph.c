/**
 * @file sph_tlsph.c
 * @brief Total-Lagrangian SPH (the remedy named in [Meng2021]'s conclusions
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
 * computed once (struct sph_tl), rebuilt only when model.reference_update
 * re-references the body (sph_tlsph_reref.c).  The corrections are
 * moved out of the pair sums, which is exact algebra (only the rounding
 * changes):
 *   F_i     = [sum_j (x_j - x_i) (x) G_ij] B0_i^-1,   G_ij = V0_j grad_X W (uncorrected)
 *   P_i g_i(ij) V0_j = Q_i G_ij,                     Q_i = P_i B0_i^-T   (per particle)
 *   sum_j V0_i V0_j v_ij . P_i g_i(ij) = -V0_i P_i : dF_i/dt           (stress power)
 * so a pair costs two 3x3 products ((Q_i + Q_j) X_ij and the hourglass
 * (F_i + F_j) X_ij) instead of four plus two kernel evaluations.  The force
 * stage walks the half list (j > i: the upper part of each sorted row)
 * and applies each pair's force to both particles (antisymmetric, exact
 * negatives), so each pair's AV (two divisions) and products are evaluated
 * once instead of twice; stage 1 (F, dF/dt) still gathers over full rows
 * (a scatter of its 18 sums would move as much data as the partner reads it
 * saves).  Each particle's sums run over its lower partners, then its upper
 * ones, each in increasing index, on any number of threads: bitwise thread
 * independent (tl_sweep has the scheme).
 *
 * Memory traffic (the race bar's state, ~30 MB, outgrows the cache): one
 * force call is one sweep over the particles (tl_sweep) that packs x, v,
 * runs stage 1 (F, L and the whole per-particle material update, with F,
 * dF/dt, F^-1 and PK1 in registers) and stage 2 (forces) with lags of the
 * list's index band b, so a partner's block is reused while cached; the
 * per-particle data live in two blocks (pk, self) instead of separate
 * arrays.  docs/performance.md ("TLSPH speed: how the sweep is built")
 * has the measured effect of each step (the half list:
 * docs/notes/performance-log.md, "Side by side with LAMMPS MACHDYN").
 *
 * CPU versions (docs/performance.md, "TLSPH speed: how the sweep is built"): the
 * stages are built twice (TL_CLONES, sph_tlsph_data.h), for x86-64-v3
 * (AVX2, FMA; this file is compiled with -ffp-contract=fast) and for the
 * build's baseline, picked once per run by the CPU.  The v3 version sums
 * the stage-1 gather and the stage-2 3x3 products four lanes at once (Q
 * and Fd are stored by columns).  Each stage is one out-of-line function
 * per version, so a pair's arithmetic is the same machine code wherever it
 * runs: bitwise thread independent and split = pipelined, as before; the
 * baseline version is bitwise the code before the versions.
 */
#include "models/sph/sph_internal.h"

#include "core/neighbor.h"
#include "core/parallel/comm.h"
#include "core/parallel/decomp.h"
#include "core/particles.h"
#include "core/sim.h"
#include "spall/error.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "models/sph/sph_tlsph_data.h"

/* Distortion of F: kappa = (|F|^2 / dim) / J^(2/dim) >= 1, = 1 exactly
 * for a rotation times an isotropic scaling (no shape change),
 * (l^2 + l^-2)/2 for a 2D isochoric stretch l; plane strain uses the
 * in-plane block.  Returned as kappa^dim' (dim' = 1 in 2D, 3 in 3D) so
 * that the per-particle test needs no cube root (measured: cbrt was 0.7 %
 * of a TLSPH Taylor bar's instructions). */
static inline double tl_distortion_pow(const double F[9], double J, int dim)
{
    double f2 = 0.0;
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++)
            f2 += F[a * 3 + b] * F[a * 3 + b];
    return dim == 2 ? f2 / (2.0 * J) : f2 * f2 * f2 / (27.0 * J * J);
}

/* F and dF/dt of particle i from the partners' packed x, v (dimension a
 * literal at the call; F_zz = 1 in 2D). */
TL_INLINE void tl_deformation(const struct model *m, size_t i, const int dim, double Fd[9],
                                  double Fdot[9])
{
    const struct sph_tl *t = m->tl->ref;
    const size_t *off = t->nl->offset;
    const int32_t *nb = t->nl->idx;
    const double *pk = t->pk, *qi = pk + i * TL_STRIDE;
    /* A[b][c] = sum_j d_c G_b with d = (x_j - x_i, v_j - v_i): the 18 sums
     * as three rows of 2 dim, so that they stay in registers (as Ad[a][b],
     * Av[a][b] the compiler kept one on the stack: a store-to-load chain
     * through every pair).  Each sum's terms and order are unchanged. */
    double A[3][6] = {{0}};
#ifdef TL_HAVE_V4
    if (dim == 3 && t->wide) { /* rows of A as lanes (dx, dv_0 | dv_1, dv_2, -, -) */
        tl_v4 a0[3], a1[3], xi0, xi1;
        for (int b = 0; b < 3; b++)
            a0[b] = a1[b] = (tl_v4){0, 0, 0, 0};
        memcpy(&xi0, qi + TL_X, sizeof xi0);
        memcpy(&xi1, qi + TL_V + 1, sizeof xi1);
        for (size_t k = off[i]; k < off[i + 1]; k++) {
            const double *qj = pk + (size_t)nb[k] * TL_STRIDE;
            const double VF = qj[TL_VOL] * t->pair[k].F;
            tl_v4 d0, d1;
            memcpy(&d0, qj + TL_X, sizeof d0);
            memcpy(&d1, qj + TL_V + 1, sizeof d1);
            d0 -= xi0;
            d1 -= xi1;
            for (int b = 0; b < 3; b++) {
                const double G = VF * (qi[TL_X0 + b] - qj[TL_X0 + b]);
                a0[b] += d0 * G;
                a1[b] += d1 * G;
            }
        }
        for (int b = 0; b < 3; b++)
            for (int c = 0; c < 6; c++)
                A[b][c] = c < 4 ? a0[b][c] : a1[b][c - 4];
    } else
#endif
    for (size_t k = off[i]; k < off[i + 1]; k++) {
        const struct tl_pair *pr = &t->pair[k];
        const double *qj = pk + (size_t)nb[k] * TL_STRIDE;
        const double VF = qj[TL_VOL] * pr->F;
        double G[3], dxv[6];
        for (int d = 0; d < dim; d++) {
            G[d] = VF * (qi[TL_X0 + d] - qj[TL_X0 + d]);
            dxv[d] = qj[TL_X + d] - qi[TL_X + d];
            dxv[dim + d] = qj[TL_V + d] - qi[TL_V + d];
        }
        for (int b = 0; b < dim; b++)
            for (int c = 0; c < 2 * dim; c++)
                A[b][c] += dxv[c] * G[b];
    }
    double Ad[9] = {0}, Av[9] = {0};
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++) {
            Ad[a * 3 + b] = A[b][a];
            Av[a * 3 + b] = A[b][dim + a];
        }
    double Bi[9];
    for (int c = 0; c < 9; c++) {
        Bi[c] = t->self[i * TL_SELF + TL_BI + c];
        Fd[c] = Fdot[c] = 0.0;
    }
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++) {
            double sd = 0.0, sv = 0.0;
            for (int c = 0; c < dim; c++) {
                sd += Ad[a * 3 + c] * Bi[c * 3 + b];
                sv += Av[a * 3 + c] * Bi[c * 3 + b];
            }
            Fd[a * 3 + b] = sd;
            Fdot[a * 3 + b] = sv;
        }
    if (dim == 2)
        Fd[8] = 1.0;
}

/* Stage 1 for particle i: F, dF/dt, L (tl_deformation), then everything
 * that needs particle i alone -- the leapfrog state advance, pressure,
 * Jaumann stress rate, PK1 = J sigma F^-T, Q = PK1 B0^-T and i's packed
 * block for stage 2 (dimension a literal at the call).  F, dF/dt and F^-1
 * stay in registers: no per-particle arrays are streamed for them.
 * *Jout = det F, *kout = tl_distortion_pow (INFINITY when inverted) for
 * the det F guard.  Returns 1 when det F <= 0 (identity used meanwhile). */
TL_INLINE int tl_stage_deform(struct model *m, size_t i, double lfdt, const int dim,
                                  double *Jout, double *kout)
{
    struct sph_tl *t = m->tl->ref;
    double *qi = t->pk + i * TL_STRIDE;
    double Bi[9];
    for (int c = 0; c < 9; c++)
        Bi[c] = t->self[i * TL_SELF + TL_BI + c];
    double Fd[9], Fdot[9];
    tl_deformation(m, i, dim, Fd, Fdot);
    double Fi[9];
    double J = sph_inverse(dim, Fd, Fi);
    int bad = 0;
    *Jout = J;
    *kout = INFINITY;
    if (!(J > 0.0) || !isfinite(J)) {
        bad = 1;
        J = 1.0;
        for (int c = 0; c < 9; c++)
            Fi[c] = (c % 4 == 0) ? 1.0 : 0.0;
    } else {
        *kout = tl_distortion_pow(Fd, J, dim);
    }
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double acc = 0.0;
            for (int c = 0; c < dim; c++)
                acc += Fdot[a * 3 + c] * Fi[c * 3 + b];
            m->L[a * 3 + b][i] = (a < dim && b < dim) ? acc : 0.0;
        }
    /* the per-particle material update (was three loops over all particles) */
    if (lfdt > 0.0) {
        /* leapfrog: advance rho, S, e with this L; the rates dS, drho at the
         * new state would only feed the predictor-corrector (the next
         * advance recomputes them from its own L), so they are not formed */
        sph_leapfrog_advance_one(m, i, lfdt);
        sph_update_pressure_one(m, i);
    } else {
        sph_update_pressure_one(m, i);
        double trD;
        sph_stress_rate(m, i, &trD);
        m->drho[i] = -m->rho[i] * trD; /* dh stays 0 (allocated zero): h is fixed */
    }
    static const int tix[3][3] = {{SXX, SXY, SXZ}, {SXY, SYY, SYZ}, {SXZ, SYZ, SZZ}};
    double PK[9];
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double acc = 0.0;
            for (int c = 0; c < dim; c++) {
                double sg = m->S[tix[a][c]][i] - (a == c ? m->P[i] : 0.0);
                acc += sg * Fi[b * 3 + c];
            }
            PK[a * 3 + b] = J * acc;
        }
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) {
            double acc = 0.0;
            for (int b = 0; b < dim; b++)
                acc += PK[a * 3 + b] * Bi[c * 3 + b];
            qi[TL_Q + c * 3 + a] = acc; /* by columns (tl_row_forces) */
        }
    for (int c = 0; c < 9; c++)
        qi[TL_FD + c] = Fd[c % 3 * 3 + c / 3]; /* by columns */
    qi[TL_C] = m->c[i];
    qi[TL_RHO] = m->rho[i];
    qi[TL_H] = m->h[i];
    double pw = 0.0;
    for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++)
            pw += PK[a * 3 + b] * Fdot[a * 3 + b];
    double *si = t->self + i * TL_SELF;
    si[TL_PW] = pw;
    if (m->opt.visc.av_balsara) {
        /* Balsara's switch ([Meng2021] Tab. 2.2 "BAL", as sph_axisym.c):
         * f = |div v| / (|div v| + |curl v| + 1e-4 c/h) from this L; the
         * AV of pair ij is scaled by (f_i + f_j)/2 in stage 2 */
        const double cx = m->L[7][i] - m->L[5][i], cy = m->L[2][i] - m->L[6][i];
        const double cz = m->L[3][i] - m->L[1][i];
        si[TL_SW] = sph_balsara_factor(fabs(m->L[0][i] + m->L[4][i] + m->L[8][i]),
                                       sqrt(cx * cx + cy * cy + cz * cz), m->c[i], m->h[i]);
    }
    for (int c = 0; c < 4; c++) /* stage-2 accumulators (TL_ACC, TL_FV): the */
        si[TL_ACC + c] = 0.0;   /* lower rows scatter into them after this */
    return bad;
}

/* det F guard: the run stops at the first (lowest-index) TLSPH particle
 * whose F is inverted (det F <= 0), whose det F leaves model.det_f_range or
 * whose distortion exceeds model.max_distortion, naming the particle: past
 * that the reference configuration no longer describes its neighbourhood
 * (the fixed list of a TLSPH body cannot follow large shear or mixing).
 * F is recomputed from the packed positions of this force call. */
static int tl_guard_error(const struct model *m, const struct sim *s, size_t i, int dim,
                          struct spall_error *err)
{
    const struct particles *p = s->p;
    double F[9], Fdot[9], Fi[9];
    if (dim == 3)
        tl_deformation(m, i, 3, F, Fdot);
    else
        tl_deformation(m, i, 2, F, Fdot);
    const double J = sph_inverse(dim, F, Fi);
    const bool inv = !(J > 0.0) || !isfinite(J);
    const double kp = inv ? INFINITY : tl_distortion_pow(F, J, dim);
    const double kap = dim == 3 ? cbrt(kp) : kp;
    char why[160];
    if (inv)
        snprintf(why, sizeof why, "is inverted or singular (det F = %.4g <= 0)", J);
    else if (J < m->opt.tl.det_f_range[0] || J > m->opt.tl.det_f_range[1])
        snprintf(why, sizeof why, "has det F = %.4g outside det_f_range [%g, %g]", J,
                 m->opt.tl.det_f_range[0], m->opt.tl.det_f_range[1]);
    else
        snprintf(why, sizeof why, "has distortion %.4g above max_distortion %g (det F = %.4g)",
                 kap, m->opt.tl.max_distortion, J);
    char xs[128];
    if (dim == 3)
        snprintf(xs, sizeof xs, "(%.6g, %.6g, %.6g) m, now at (%.6g, %.6g, %.6g) m", p->x0[0][i],
                 p->x0[1][i], p->x0[2][i], p->x[0][i], p->x[1][i], p->x[2][i]);
    else
        snprintf(xs, sizeof xs, "(%.6g, %.6g) m, now at (%.6g, %.6g) m", p->x0[0][i],
                 p->x0[1][i], p->x[0][i], p->x[1][i]);
    return spall_error_set(err, SPALL_ERR_UNSTABLE,
                           "TLSPH: the deformation gradient of particle %zu (body %d, initial "
                           "position %s) %s at t = %.6g s, step %ld; its reference "
                           "neighbourhood no longer describes it (finer dx, a larger "
                           "hourglass, model.reference_update, or the updated "
                           "formulation for this body)",
                           (size_t)p->gid[i], (int)p->body[i], xs, why, s->t, s->step);
}

/* Stage 2, row i: every pair (i, j) with j > i evaluated once, in this
 * orientation whoever evaluates it (so a pair crossing two threads' shares,
 * evaluated by both, is bitwise the same on each side).  The pair force is
 * antisymmetric, so particle j gets exactly its negative (exact in floating
 * point): with Q = PK1 B0^-T and X_ij = X_i - X_j,
 *   f_i(ij) = V0_i V0_j F_ij (Q_i + Q_j) X_ij               (stress: P_i g_i + P_j g_j)
 *           + cav x_ij + hg ((Fd_i + Fd_j) X_ij / 2 - x_ij)  (AV, hourglass)
 * and f_j(ij) = -f_i(ij); the heating -1/2 f . v_ij is the same for both.
 * j in [lo, hi) gets its share in its accumulator; i's sums continue from
 * its own (the lower rows' contributions, in increasing row order) in
 * acc[0..2], acc[3] (sum f . v_ij).  So each particle's sums run over its
 * lower partners, then its upper ones, each in increasing index, whatever
 * the thread shares: bitwise thread independent.  Dimension a literal. */
TL_INLINE void tl_row_forces(struct sph_tl *t, size_t i, const struct tl_span *rw, size_t lo,
                                 size_t hi, const int dim, const double qa, const double qb,
                                 const double lav, const bool bal, double acc[4])
{
    const int32_t *nb = rw->nb;
    const double *pk = t->pk, *qi = pk + i * TL_STRIDE;
    const double Vi = qi[TL_VOL], mi = qi[TL_M], hi_ = qi[TL_H], ci = qi[TL_C];
    const double rhoi = qi[TL_RHO];
    const double fsi = bal ? t->self[i * TL_SELF + TL_SW] : 1.0;
    const size_t end = rw->k1;
#ifdef TL_HAVE_V4
    const bool wide = t->wide;
#endif
    for (size_t k = rw->k0; k < end; k++) {
        const struct tl_pair *pr = &rw->pair[k];
        const size_t j = (size_t)nb[k];
        const double *qj = pk + j * TL_STRIDE;
        const double F = pr->F, hg = pr->hg, sv = Vi * qj[TL_VOL] * F;
        double X[3], xij[3], vij[3], cr2 = 0.0, vx = 0.0;
        for (int d = 0; d < dim; d++) {
            X[d] = qi[TL_X0 + d] - qj[TL_X0 + d];
            xij[d] = qi[TL_X + d] - qj[TL_X + d];
            vij[d] = qi[TL_V + d] - qj[TL_V + d];
            cr2 += xij[d] * xij[d];
            vx += xij[d] * vij[d];
        }
        const double hb = 0.5 * (hi_ + qj[TL_H]);
        const double mu = (lav > 0.0 ? lav : hb) * vx / (cr2 + 0.01 * hb * hb);
        const double cb = 0.5 * (ci + qj[TL_C]);
        const double Pv = (-qa * cb * mu + qb * mu * mu) / (0.5 * (rhoi + qj[TL_RHO]));
        /* Pi = vx < 0 ? Pv : +0, as a bit mask: the sign of v_ij . x_ij is a
         * coin toss in a bar moving as a whole, and the compiler turns a
         * select back into a branch (mispredicted half the time) */
        uint64_t pb;
        memcpy(&pb, &Pv, sizeof pb);
        pb &= (uint64_t)0 - (uint64_t)(vx < 0.0);
        double Pi;
        memcpy(&Pi, &pb, sizeof Pi);
        /* Balsara: Pi (f_i + f_j)/2, symmetric in i, j (momentum kept); off: x 1 exactly */
        const double sw = bal ? 0.5 * (fsi + t->self[j * TL_SELF + TL_SW]) : 1.0;
        const double cav = -mi * qj[TL_M] * Pi * F * sw;
        /* (Q_i + Q_j) X and (Fd_i + Fd_j) X by columns (stored column by
         * column): four lanes at once, lane 3 (the next column's first
         * entry) unused.  Per entry the same sum, in the same order, as
         * tq_a = sum_b (Q_i + Q_j)_ab X_b. */
        double tq[3] = {0, 0, 0}, fx[3] = {0, 0, 0};
#ifdef TL_HAVE_V4
        if (wide) { /* the AVX2 version runs (t->wide) */
            tl_v4 tq4 = {0, 0, 0, 0}, fx4 = {0, 0, 0, 0};
            for (int b = 0; b < dim; b++) {
                tl_madd4(&tq4, qi + TL_Q + 3 * b, qj + TL_Q + 3 * b, X[b]);
                tl_madd4(&fx4, qi + TL_FD + 3 * b, qj + TL_FD + 3 * b, X[b]);
            }
            for (int a = 0; a < dim; a++) {
                tq[a] = tq4[a];
                fx[a] = fx4[a];
            }
        } else
#endif
        {
            for (int a = 0; a < dim; a++)
                for (int b = 0; b < dim; b++) {
                    tq[a] += (qi[TL_Q + 3 * b + a] + qj[TL_Q + 3 * b + a]) * X[b];
                    fx[a] += (qi[TL_FD + 3 * b + a] + qj[TL_FD + 3 * b + a]) * X[b];
                }
        }
        double fp[3] = {0, 0, 0}, fv = 0.0;
        for (int a = 0; a < dim; a++) {
            /* hourglass: mismatch of x_j - x_i against Fbar (X_j - X_i);
             * AV along the CURRENT pair line (reference kernel magnitude):
             * -Pi F x_ij does negative work for any rotation */
            const double fo = cav * xij[a] + hg * (0.5 * fx[a] - xij[a]);
            fv += fo * vij[a];
            fp[a] = sv * tq[a] + fo;
        }
        for (int a = 0; a < dim; a++)
            acc[a] += fp[a];
        acc[3] += fv;
        if (j - lo < hi - lo) { /* lo <= j < hi: mine (j > i >= lo - b) */
            double *sj = t->self + j * TL_SELF;
            for (int a = 0; a < dim; a++)
                sj[TL_ACC + a] -= fp[a];
            sj[TL_FV] += fv;
        }
    }
}

/* Row and force stage out of line, one instance each per CPU version: the
 * pair arithmetic must be the same machine code wherever a row runs (its
 * owner's stage 2, the neighbour share's re-evaluation for the scatter,
 * the split or pipelined order), since FMA contraction is decided per
 * inlined copy (tests/test_sph_tlsph.c caught the copies disagreeing). */
#define TL_ROW_INSTANCE(NAME, DIM, BAL)                                                         \
    TL_CLONES static void NAME(struct sph_tl *t, size_t i, const struct tl_span *rw, size_t lo,  \
                               size_t hi, const double av[3], double acc[4])                     \
    {                                                                                            \
        tl_row_forces(t, i, rw, lo, hi, DIM, av[0], av[1], av[2], BAL, acc);                     \
    }
/* 3D and 2D, without and with Balsara's switch (model.viscosity_switch):
 * the switch a literal in each instance, so the default rows carry no
 * per-pair cost of it */
TL_ROW_INSTANCE(tl_row3, 3, false)
TL_ROW_INSTANCE(tl_row2, 2, false)
TL_ROW_INSTANCE(tl_row3_bal, 3, true)
TL_ROW_INSTANCE(tl_row2_bal, 2, true)
#undef TL_ROW_INSTANCE

/* Row i's pairs rw (the upper part of its reference row unless given). */
static inline void tl_row_span(struct sph_tl *t, size_t i, const struct tl_span *rw, size_t lo,
                               size_t hi, const int dim, const bool bal, const double av[3],
                               double acc[4])
{
    if (dim == 3)
        (bal ? tl_row3_bal : tl_row3)(t, i, rw, lo, hi, av, acc);
    else
        (bal ? tl_row2_bal : tl_row2)(t, i, rw, lo, hi, av, acc);
}

static inline void tl_row(struct sph_tl *t, size_t i, size_t lo, size_t hi, const int dim,
                          const bool bal, const double av[3], double acc[4])
{
    const struct tl_span rw = {t->up[i], t->nl->offset[i + 1], t->nl->idx, t->pair};
    tl_row_span(t, i, &rw, lo, hi, dim, bal, av, acc);
}

/* Stage 2 of a row of mine: its sums from the lower rows (own accumulator),
 * its own row, then the force and the internal energy rate. */
TL_INLINE void tl_stage_forces(struct model *m, struct particles *p, size_t i, size_t lo,
                                   size_t hi, double lfdt, const int dim)
{
    struct sph_tl *t = m->tl->ref;
    const double *si = t->self + i * TL_SELF, *qi = t->pk + i * TL_STRIDE;
    double acc[4] = {si[TL_ACC], si[TL_ACC + 1], si[TL_ACC + 2], si[TL_FV]};
    const double av[3] = {m->opt.visc.av_a, m->opt.visc.av_b, m->opt.visc.av_length};
    tl_row(t, i, lo, hi, dim, m->opt.visc.av_balsara, av, acc);
    if (sph_skip(m, i, SPH_FORM_TOTAL))
        return; /* an updated-form particle: empty row, no accumulator */
    const double Vi = qi[TL_VOL], mi = qi[TL_M];
    /* heating -1/2 sum f_ij . v_ij; the 1/2 outside the sum is exact
     * (scaling by 2^-1 commutes with rounding): bitwise the per-pair form */
    double de = 0.0 - 0.5 * acc[3];
    /* stress power V0_i P_i : dF_i/dt (the leapfrog books it itself) */
    if (!(lfdt > 0.0))
        de += Vi * si[TL_PW];
    for (int a = 0; a < dim; a++)
        p->f[a][i] += p->mass[i] / mi * acc[a];
    m->de[i] = de / mi;
    if (lfdt > 0.0)
        m->e[i] += lfdt * m->de[i]; /* leapfrog: AV / hourglass heating */
}

TL_CLONES static void tl_forces3(struct model *m, struct particles *p, size_t i, size_t lo,
                                 size_t hi, double lfdt)
{
    tl_stage_forces(m, p, i, lo, hi, lfdt, 3);
}

TL_CLONES static void tl_forces2(struct model *m, struct particles *p, size_t i, size_t lo,
                                 size_t hi, double lfdt)
{
    tl_stage_forces(m, p, i, lo, hi, lfdt, 2);
}

/* Stage 0 for particle i: its current x, v into its packed block. */
static inline void tl_pack(struct sph_tl *t, const struct particles *p, size_t i, const int dim)
{
    double *q = t->pk + i * TL_STRIDE;
    for (int d = 0; d < 3; d++) {
        q[TL_X + d] = d < dim ? p->x[d][i] : 0.0;
        q[TL_V + d] = d < dim ? p->v[d][i] : 0.0;
    }
}

/* What the det F guard collects over a thread's share. */
struct tl_watch {
    size_t first; /**< lowest index outside the guard's limits (SIZE_MAX: none) */
    double jmin;  /**< smallest det F */
    double kmax;  /**< largest tl_distortion_pow */
};

/* Stage 1 of particle k with the guard's bookkeeping; particles of
 * updated-form bodies (formulation per body) are skipped. */
TL_INLINE void tl_stage_deform_watch(struct model *m, size_t k, double lfdt, const int dim,
                                         const double lim[3], struct tl_watch *w)
{
    if (sph_skip(m, k, SPH_FORM_TOTAL))
        return;
    double J, kap;
    const int bad = tl_stage_deform(m, k, lfdt, dim, &J, &kap);
    if ((bad || J < lim[0] || J > lim[1] || kap > lim[2]) && k < w->first)
        w->first = k;
    w->jmin = J < w->jmin ? J : w->jmin;
    w->kmax = kap > w->kmax && !bad ? kap : w->kmax;
}

/* Stage 1 kept out of line (inlined into the sweep it spilled more: +9 %
 * instructions, callgrind), one version per CPU level like the sweep and
 * with the dimension a literal (a multi-versioned function is not
 * specialised by constant propagation). */
TL_CLONES static void tl_deform3(struct model *m, size_t k, double lfdt, const double lim[3],
                                 struct tl_watch *w)
{
    tl_stage_deform_watch(m, k, lfdt, 3, lim, w);
}

TL_CLONES static void tl_deform2(struct model *m, size_t k, double lfdt, const double lim[3],
                                 struct tl_watch *w)
{
    tl_stage_deform_watch(m, k, lfdt, 2, lim, w);
}

static inline void tl_deform(struct model *m, size_t k, double lfdt, const int dim,
                             const double lim[3], struct tl_watch *w)
{
    if (dim == 3)
        tl_deform3(m, k, lfdt, lim, w);
    else
        tl_deform2(m, k, lfdt, lim, w);
}

/* One thread's share [lo, hi) of the three stages, software-pipelined:
 * stage 1 of particle k needs stage 0 (x, v packed) of every partner j,
 * row i of stage 2 needs stage 1 of every partner, and |j - i| <= b
 * (t->band; the lattice order keeps b at a few layers).  So the sweep packs
 * b particles ahead of stage 1 and runs stage 2 b particles behind it,
 * while those blocks are still in cache: one pass over the particle data
 * per force call instead of five.  Stage 2 scatters each pair into the
 * upper particle, so its rows must run in increasing order: the rows of
 * the b particles below lo that reach into [lo, hi) (the lower neighbour's,
 * evaluated here again for the scatter into mine) come first, then mine.
 * They need stage 1 of the b particles at each end of every share, which
 * runs before a barrier (stage 0 of 2b at each end before a first one).
 * Every particle does the same arithmetic in the same order as with the
 * stages run one after the other (sph_set_split_loops, b = n): bitwise
 * the same result on any number of threads. */
TL_INLINE void tl_sweep(struct model *m, struct particles *p, size_t n, size_t lo, size_t hi,
                     double lfdt, bool pipelined, const int dim, const double lim[3],
                     struct tl_watch *w)
{
    struct sph_tl *t = m->tl->ref;
    const size_t b = pipelined ? t->band : n;
    /* stage 0 before the barriers for [lo, pa) and [pb, hi), in the sweep between */
    const size_t pa = hi - lo > 2 * b ? lo + 2 * b : hi, pb = hi - pa > 2 * b ? hi - 2 * b : pa;
    for (size_t i = lo; i < pa; i++)
        tl_pack(t, p, i, dim);
    for (size_t i = pb; i < hi; i++)
        tl_pack(t, p, i, dim);
#pragma omp barrier
    /* stage 1 before the second barrier for [lo, e1) and [e2, hi) */
    const size_t e1 = hi - lo > b ? lo + b : hi, e2 = hi - e1 > b ? hi - b : e1;
    for (size_t k = lo; k < e1; k++)
        tl_deform(m, k, lfdt, dim, lim, w);
    for (size_t k = e2; k < hi; k++)
        tl_deform(m, k, lfdt, dim, lim, w);
#pragma omp barrier
    const double av[3] = {m->opt.visc.av_a, m->opt.visc.av_b, m->opt.visc.av_length};
    for (size_t i = lo > b ? lo - b : 0; i < lo; i++) {
        double ghost[4] = {0, 0, 0, 0}; /* row i's own sums: its owner's */
        tl_row(t, i, lo, hi, dim, m->opt.visc.av_balsara, av, ghost);
    }
    size_t r = lo; /* next row of stage 2 */
    for (size_t k = e1; k < e2; k++) {
        if (k + b < pb)
            tl_pack(t, p, k + b, dim);
        tl_deform(m, k, lfdt, dim, lim, w);
        for (; r + b <= k; r++) /* partners r .. r + b <= k: stage 1 done */
            (dim == 3 ? tl_forces3 : tl_forces2)(m, p, r, lo, hi, lfdt);
    }
    for (; r < hi; r++) /* partners past hi: their stage 1 ran before the barrier */
        (dim == 3 ? tl_forces3 : tl_forces2)(m, p, r, lo, hi, lfdt);
}

/* tl_sweep with the dimension a literal (a multi-versioned function is not
 * specialised by constant propagation, so the literal is given here) */
TL_CLONES static void tl_sweep3(struct model *m, struct particles *p, size_t n, size_t lo,
                                size_t hi, double lfdt, bool pipelined, const double lim[3],
                                struct tl_watch *w)
{
    tl_sweep(m, p, n, lo, hi, lfdt, pipelined, 3, lim, w);
}

TL_CLONES static void tl_sweep2(struct model *m, struct particles *p, size_t n, size_t lo,
                                size_t hi, double lfdt, bool pipelined, const double lim[3],
                                struct tl_watch *w)
{
    tl_sweep(m, p, n, lo, hi, lfdt, pipelined, 2, lim, w);
}

/* A distributed run (sph_localize.c): owned particles [0, n_owned) in
 * ascending gid, then the ghosts (their reference partners on other ranks).
 * Each owned particle's sums must be the serial ones, term by term: the
 * serial force of i starts with what its lower partners' rows scattered
 * into it (in increasing gid), then its own row's upper part.  A lower
 * partner may be a ghost, whose row lives elsewhere, so here every owned
 * particle gathers instead: each lower pair (j, i) is evaluated in j's
 * orientation by the same row function, over a one-pair span (j's
 * constants of the pair, prev), scattering into i alone; then i's own row
 * with no scatter.  The pair arithmetic is the same machine code as in the
 * serial sweep (the row instances), so the terms and their order are the
 * serial ones; each pair is evaluated by both its particles (twice the
 * serial stage 2 arithmetic), and no particle writes another's sums, so
 * the owned particles run on any number of threads.  Stage 1 of the ghosts
 * comes from their owners: one halo of TL_HALO doubles per ghost. */
static int tl_rates_par(struct model *m, struct sim *s, double lfdt, const double lim[3],
                        struct tl_watch *wout)
{
    struct particles *p = s->p;
    struct sph_tl *t = m->tl->ref;
    const size_t n_own = p->n_owned, n = p->n;
    const int dim = m->dim;
    for (size_t i = 0; i < n; i++) /* ghosts: x, v of this step from the halo */
        tl_pack(t, p, i, dim);
    size_t first = SIZE_MAX;
    double jmin = INFINITY, kmax = 1.0;
#pragma omp parallel reduction(min : first, jmin) reduction(max : kmax)
    {
        struct tl_watch w = {SIZE_MAX, INFINITY, 1.0};
#pragma omp for schedule(static)
        for (size_t k = 0; k < n_own; k++)
            tl_deform(m, k, lfdt, dim, lim, &w);
        first = w.first;
        jmin = w.jmin;
        kmax = w.kmax;
    }
    wout->first = first;
    wout->jmin = jmin;
    wout->kmax = kmax;
    double *hv = t->halo;
    for (size_t i = 0; i < n_own; i++) {
        memcpy(hv + i * TL_HALO, t->pk + i * TL_STRIDE, (TL_HALO - 1) * sizeof(double));
        hv[i * TL_HALO + TL_HALO - 1] = t->self[i * TL_SELF + TL_SW];
    }
    if (par_halo_block(s, hv, TL_HALO))
        return SPALL_ERR_NOMEM;
    for (size_t i = n_own; i < n; i++) {
        memcpy(t->pk + i * TL_STRIDE, hv + i * TL_HALO, (TL_HALO - 1) * sizeof(double));
        t->self[i * TL_SELF + TL_SW] = hv[i * TL_HALO + TL_HALO - 1];
    }
    const double av[3] = {m->opt.visc.av_a, m->opt.visc.av_b, m->opt.visc.av_length};
    const bool bal = m->opt.visc.av_balsara;
    const size_t *off = t->nl->offset;
    const int32_t *nb = t->nl->idx;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n_own; i++) {
        for (size_t k = off[i]; k < t->up[i]; k++) {
            const struct tl_span rw = {k, k + 1, t->rown, t->prev};
            double row_j[4] = {0, 0, 0, 0}; /* the lower row's own sums: its owner's */
            tl_row_span(t, (size_t)nb[k], &rw, i, i + 1, dim, bal, av, row_j);
        }
        (dim == 3 ? tl_forces3 : tl_forces2)(m, p, i, 0, 0, lfdt);
    }
    return SPALL_OK;
}

int sph_tlsph_rates(struct model *m, struct sim *s, double lfdt, struct spall_error *err)
{
    struct particles *p = s->p;
    const size_t n = p->n_owned;
    const int dim = m->dim;
    m->n_pairs = s->par ? m->tl->pairs_all : m->tl->ref->nl->offset[n];
    const bool pipelined = !m->loops.tl_split;
    /* det F guard limits; the distortion limit as tl_distortion_pow */
    const double md = m->opt.tl.max_distortion;
    const double lim[3] = {m->opt.tl.det_f_range[0], m->opt.tl.det_f_range[1],
                           dim == 3 ? md * md * md : md};
    size_t first = SIZE_MAX;
    double jmin = INFINITY, kmax = 1.0;
    if (s->par) {
        struct tl_watch w;
        if (tl_rates_par(m, s, lfdt, lim, &w))
            return spall_error_set(err, SPALL_ERR_NOMEM, "out of memory (TLSPH halo)");
        first = w.first;
        jmin = par_min_double(w.jmin); /* history and restart state: the */
        kmax = par_max_double(w.kmax); /* whole body's (exact in any order) */
    } else
    /* first offender: min reduction, thread independent */
#pragma omp parallel reduction(min : first, jmin) reduction(max : kmax)
    {
        const size_t nt = (size_t)omp_get_num_threads(), id = (size_t)omp_get_thread_num();
        const size_t lo = n * id / nt, hi = n * (id + 1) / nt;
        struct tl_watch w = {SIZE_MAX, INFINITY, 1.0};
        if (dim == 3)
            tl_sweep3(m, p, n, lo, hi, lfdt, pipelined, lim, &w);
        else
            tl_sweep2(m, p, n, lo, hi, lfdt, pipelined, lim, &w);
        first = w.first;
        jmin = w.jmin;
        kmax = w.kmax;
    }
    m->tl->jmin = jmin;
    m->tl->kmax = dim == 3 ? cbrt(kmax) : kmax;
    if (first != SIZE_MAX)
        return tl_guard_error(m, s, first, dim, err);
    return SPALL_OK;
}
