/**
 * @file sph_kernels.h
 * @brief The six SPH smoothing kernels of [Meng2021] Fig. 3.1, W = alpha_d K(q),
 *        q = r/h, with their radial derivatives and normalisation constants.
 *
 * alpha_d (in units of 1/h^d) makes the integral of W over R^d equal one:
 * alpha_1 = 1/(2 I0), alpha_2 = 1/(2 pi I1), alpha_3 = 1/(4 pi I2) with
 * I_k = integral of K(q) q^k over the support.  The closed forms below were
 * derived piecewise (polynomials, cosines) and, for the Gaussian, for the
 * kernel truncated at q = 3 so that the truncated kernel integrates to one
 * exactly (the untruncated constants leave an error of ~1e-4 in 2D).
 * tests/test_sph_kernels.c checks every constant by a lattice sum.
 *
 *  type | name            | support | alpha_1 | alpha_2              | alpha_3
 *  1    | cubic B-spline  | 2       | 2/3     | 10/(7 pi)            | 1/pi
 *  2    | Gaussian (q<3)  | 3       | 1/(sqrt(pi) erf 3) | 1/(pi (1-e^-9)) | 1/(pi (sqrt(pi) erf3 - 6 e^-9))
 *  3    | quintic B-spline| 3       | 1/120   | 7/(478 pi)           | 1/(120 pi)
 *  4    | Wendland C2     | 2       | 3/4     | 7/(4 pi)             | 21/(16 pi)
 *  5    | double cosine   | 2       | 1/12    | pi/(4 (3 pi^2 - 16)) | pi/(16 (2 pi^2 - 15))
 *  6    | hyperbolic      | 2       | 1/7     | 1/(3 pi)             | 15/(62 pi)
 * (Gaussian 3D: integral of q^2 e^{-q^2} on [0,3] = sqrt(pi)/4 erf 3 - 1.5 e^-9.)
 * The double-cosine kernel is used with k = 2 (support 2h), as in its source
 * (Yang, Liu & Peng 2014), where K and dK/dq vanish at q = 2.
 */
#ifndef SPALL_SPH_KERNELS_H
#define SPALL_SPH_KERNELS_H

#include <math.h>

#include "core/mathconst.h"

enum sph_kernel {
    SPH_KERNEL_CUBIC = 1,
    SPH_KERNEL_GAUSSIAN = 2,
    SPH_KERNEL_QUINTIC = 3,
    SPH_KERNEL_WENDLAND = 4,
    SPH_KERNEL_DOUBLE_COSINE = 5,
    SPH_KERNEL_HYPERBOLIC = 6
};


/** Support radius in units of h. */
static inline double sph_kernel_support(enum sph_kernel k)
{
    return (k == SPH_KERNEL_GAUSSIAN || k == SPH_KERNEL_QUINTIC) ? 3.0 : 2.0;
}

/** Normalisation alpha_d (multiply by h^-d). */
static inline double sph_kernel_alpha(enum sph_kernel k, int dim)
{
    const double pi = SPALL_PI;
    const double e9 = exp(-9.0), erf3 = erf(3.0);
    switch (k) {
    case SPH_KERNEL_CUBIC:
        return dim == 1 ? 2.0 / 3.0 : dim == 2 ? 10.0 / (7.0 * pi) : 1.0 / pi;
    case SPH_KERNEL_GAUSSIAN:
        return dim == 1 ? 1.0 / (sqrt(pi) * erf3)
               : dim == 2 ? 1.0 / (pi * (1.0 - e9))
                          : 1.0 / (pi * (sqrt(pi) * erf3 - 6.0 * e9));
    case SPH_KERNEL_QUINTIC:
        return dim == 1 ? 1.0 / 120.0 : dim == 2 ? 7.0 / (478.0 * pi) : 1.0 / (120.0 * pi);
    case SPH_KERNEL_WENDLAND:
        return dim == 1 ? 0.75 : dim == 2 ? 7.0 / (4.0 * pi) : 21.0 / (16.0 * pi);
    case SPH_KERNEL_DOUBLE_COSINE:
        return dim == 1 ? 1.0 / 12.0
               : dim == 2 ? pi / (4.0 * (3.0 * pi * pi - 16.0))
                          : pi / (16.0 * (2.0 * pi * pi - 15.0));
    case SPH_KERNEL_HYPERBOLIC:
        return dim == 1 ? 1.0 / 7.0 : dim == 2 ? 1.0 / (3.0 * pi) : 15.0 / (62.0 * pi);
    }
    return 0.0;
}

/** K(q) and dK/dq (un-normalised shape), zero outside the support. */
static inline void sph_kernel_shape(enum sph_kernel k, double q, double *K, double *dK)
{
    double a, b, c;
    switch (k) {
    case SPH_KERNEL_CUBIC:
        if (q < 1.0) {
            *K = 1.0 - 1.5 * q * q + 0.75 * q * q * q;
            *dK = -3.0 * q + 2.25 * q * q;
        } else if (q < 2.0) {
            a = 2.0 - q;
            *K = 0.25 * a * a * a;
            *dK = -0.75 * a * a;
        } else {
            *K = *dK = 0.0;
        }
        return;
    case SPH_KERNEL_GAUSSIAN:
        if (q < 3.0) {
            *K = exp(-q * q);
            *dK = -2.0 * q * *K;
        } else {
            *K = *dK = 0.0;
        }
        return;
    case SPH_KERNEL_QUINTIC:
        a = 3.0 - q;
        b = 2.0 - q;
        c = 1.0 - q;
        if (q >= 3.0) {
            *K = *dK = 0.0;
            return;
        }
        {
            double a4 = a * a * a * a;
            *K = a4 * a;
            *dK = -5.0 * a4;
            if (q < 2.0) {
                double b4 = b * b * b * b;
                *K -= 6.0 * b4 * b;
                *dK += 30.0 * b4;
            }
            if (q < 1.0) {
                double c4 = c * c * c * c;
                *K += 15.0 * c4 * c;
                *dK -= 75.0 * c4;
            }
        }
        return;
    case SPH_KERNEL_WENDLAND:
        if (q < 2.0) {
            a = 1.0 - 0.5 * q;
            double a3 = a * a * a;
            *K = a3 * a * (2.0 * q + 1.0);
            /* d/dq: -2 a^3 (2q+1) + 2 a^4 = -5 q a^3 */
            *dK = -5.0 * q * a3;
        } else {
            *K = *dK = 0.0;
        }
        return;
    case SPH_KERNEL_DOUBLE_COSINE:
        if (q < 2.0) {
            const double w = 0.5 * SPALL_PI;
            *K = 4.0 * cos(w * q) + cos(2.0 * w * q) + 3.0;
            *dK = -4.0 * w * sin(w * q) - 2.0 * w * sin(2.0 * w * q);
        } else {
            *K = *dK = 0.0;
        }
        return;
    case SPH_KERNEL_HYPERBOLIC:
        if (q <= 1.0) {
            *K = q * q * q - 6.0 * q + 6.0;
            *dK = 3.0 * q * q - 6.0;
        } else if (q < 2.0) {
            a = 2.0 - q;
            *K = a * a * a;
            *dK = -3.0 * a * a;
        } else {
            *K = *dK = 0.0;
        }
        return;
    }
    *K = *dK = 0.0;
}

/** W(r, h) and F = (dW/dr)/r, so that grad_i W_ij = F (x_i - x_j).
 *  @p alpha is sph_kernel_alpha(k, dim); @p hd is h^dim. */
static inline void sph_kernel_eval(enum sph_kernel k, double alpha, double r, double h, double hd,
                                   double *W, double *F)
{
    double K, dK;
    double q = r / h;
    sph_kernel_shape(k, q, &K, &dK);
    double norm = alpha / hd;
    *W = norm * K;
    *F = r > 0.0 ? norm * dK / (h * r) : 0.0;
}

#endif
