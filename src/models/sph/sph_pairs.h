/**
 * @file sph_pairs.h
 * @brief SPH-internal: the "pair within kernel support" step every SPH pair
 *        pass repeats (summation density, CSPM gradient, forces, smoothed
 *        artificial stress, the three axisymmetric passes): separation
 *        x_ij and r^2, mean smoothing length h_ij = (h_i + h_j)/2, the
 *        support test r < qmax h_ij and the kernel W, F ([Meng2021]
 *        Eqs. 3.8-3.9; grad_i W = F x_ij).
 *
 * One definition instead of eight copies, so that no pass can disagree
 * with the others on which pairs interact.  Everything is static inline;
 * every value is computed by the same operations in the same order as in
 * the copies it replaces (bitwise the same results: histories and fields
 * of SPH cases compared before/after, docs/sph.md).  The fused loop
 * (sph_fused.c) keeps its own specialised test (same-h shortcut, inlined
 * Wendland): it is the tuned hot loop of the default path.
 */
#ifndef SPALL_SPH_PAIRS_H
#define SPALL_SPH_PAIRS_H

#include "models/sph/sph_internal.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

/** Kernel parameters of the support test, copied out of the model once per
 *  pass (the passes list it firstprivate: one private copy per thread). */
struct sph_support {
    enum sph_kernel kern;
    double alpha; /**< normalisation alpha_d */
    double q2;    /**< (kernel support / h)^2 */
};

static inline struct sph_support sph_support_of(const struct model *m)
{
    struct sph_support sp = {m->opt.kern.kernel, m->alpha, m->qmax * m->qmax};
    return sp;
}

/** x_ij = x_i - x_j into @p xij (xij[2] = 0 in 2D); returns |x_ij|^2.
 *  SPH runs in 2D and 3D only (refused in 1D at create), so the sum is
 *  written out: no loop over dim in the pair loops, where the OpenMP
 *  outlining leaves dim a run-time value (the loop cost ~4 % of the
 *  two-pass rates, measured).  The value is the former loop's bit for bit:
 *  0 + a = a for a >= 0, and (a + b) + 0 = a + b. */
static inline double sph_sep(double *const x[3], int dim, size_t i, size_t j, double xij[3])
{
    xij[0] = x[0][i] - x[0][j];
    xij[1] = x[1][i] - x[1][j];
    xij[2] = dim == 3 ? x[2][i] - x[2][j] : 0.0;
    return xij[0] * xij[0] + xij[1] * xij[1] + xij[2] * xij[2];
}

/** |x_i - x_j|^2 (2D or 3D), as sph_sep without the vector. */
static inline double sph_dist2(double *const x[3], int dim, size_t i, size_t j)
{
    double xij[3];
    return sph_sep(x, dim, i, j, xij);
}

/** Support test and kernel of a pair at squared distance @p r2 with mean
 *  smoothing length @p hb: false outside (r >= qmax hb, where W = 0);
 *  inside, W and F (grad_i W = F x_ij) of the @p dim-dimensional kernel. */
static inline bool sph_pair_kernel(const struct sph_support *sp, int dim, double r2, double hb,
                                   double *W, double *F)
{
    if (r2 >= sp->q2 * hb * hb)
        return false;
    sph_kernel_eval(sp->kern, sp->alpha, sqrt(r2), hb, dim == 2 ? hb * hb : hb * hb * hb, W, F);
    return true;
}

#endif
