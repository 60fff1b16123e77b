/**
 * @file sph_pairs.h
 * @brief SPH-internal: the "pair within kernel support" step every SPH pair
 *        pass repeats (summation density, CSPM gradient, forces, smoothed
 *        artificial stress, the axisymmetric passes): mean smoothing length
 *        h_ij = (h_i + h_j)/2, the support test r < qmax h_ij and the
 *        kernel W, F (seed 004 Eqs. 3.8-3.9; grad_i W = F x_ij).
 *
 * One definition instead of eight copies, so that a pass cannot disagree
 * with the others on which pairs interact.  Everything is static inline
 * and takes dim as an argument that is literal (or loop-invariant) at the
 * call sites: the passes compile to the same loops as the copies they
 * replace, and every value is computed by the same operations in the same
 * order (bitwise the same results).  The fused loop (sph_fused.c) keeps its
 * own specialised test (same h shortcut, inlined Wendland): it is the hot
 * loop and was tuned separately.
 */
#ifndef SPALL_SPH_PAIRS_H
#define SPALL_SPH_PAIRS_H

#include "models/sph/sph_internal.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>

/** Kernel parameters of the support test, copied out of the model before a
 *  pass so the pair loop keeps them in registers. */
struct sph_support {
    enum sph_kernel kern;
    double alpha; /**< normalisation alpha_d */
    double q2;    /**< (kernel support / h)^2 */
};

static inline struct sph_support sph_support_of(const struct model *m)
{
    struct sph_support sp = {m->opt.kernel, m->alpha, m->qmax * m->qmax};
    return sp;
}

/** |x_i - x_j|^2 over the first @p dim components. */
static inline double sph_dist2(double *const x[3], int dim, size_t i, size_t j)
{
    double r2 = 0.0;
    for (int d = 0; d < dim; d++) {
        double dd = x[d][i] - x[d][j];
        r2 += dd * dd;
    }
    return r2;
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

/** One pair (i, j) of the Cartesian passes. */
struct sph_pair {
    double x[3]; /**< x_ij = x_i - x_j (components >= dim are 0) */
    double r2;   /**< |x_ij|^2 */
    double hb;   /**< (h_i + h_j) / 2 */
    double W, F; /**< kernel and radial factor (valid when in support) */
};

/** Fill @p pr for particles i, j at positions @p x with smoothing lengths
 *  @p h; true when j is within i's kernel support (W, F then set). */
static inline bool sph_pair_in_support(const struct sph_support *sp, int dim, double *const x[3],
                                       const double *h, size_t i, size_t j, struct sph_pair *pr)
{
    pr->hb = 0.5 * (h[i] + h[j]);
    double r2 = 0.0;
    pr->x[0] = pr->x[1] = pr->x[2] = 0.0;
    for (int d = 0; d < dim; d++) {
        pr->x[d] = x[d][i] - x[d][j];
        r2 += pr->x[d] * pr->x[d];
    }
    pr->r2 = r2;
    return sph_pair_kernel(sp, dim, r2, pr->hb, &pr->W, &pr->F);
}

#endif
