/**
 * @file lattice_laws.h
 * @brief Axial force laws of the hybrid lattice particle model (HLPM),
 *        written as static inline kernels for the force loops.
 *
 * Every law is written in dimensionless form in the stretch s = r / r_rest:
 *   F(r) = k r_rest phi(s)        (positive = repulsive, [Wang2010] convention)
 *   U(r) = k r_rest^2 u(s)        (u(1) = 0, U = -int F dr)
 * so a bond needs only its stiffness k = |dF/dr| at rest and its rest length.
 * The force on particle i from partner j (dx = x_j - x_i, r = |dx|) is
 *   f_i = -F dx / r = -(k phi(s) / s) dx  =: c dx.
 *
 *  - linear ([Wang2010] Eq. 15): phi = 1 - s, u = (s - 1)^2 / 2.
 *  - Lennard-Jones type (Eq. 1) F = -G/r^p + H/r^q with F(r0) = 0, i.e.
 *    G = H r0^(p-q), and dF/dr(r0) = -k (stiffness matched to the calibrated
 *    spring so that E is honoured):  H = k r0^(q+1)/(q-p), G = k r0^(p+1)/(q-p),
 *    phi = (s^-q - s^-p)/(q-p).  The tensile peak (Eq. 4, dF/dr = 0) sits at
 *    s_d = (q/p)^(1/(q-p)).
 *  - piecewise linear ("polynomial", Eq. 15-17 piece by piece): phi = -g(s-1)
 *    with g = sigma(eps)/E_initial from the measured curve (g(eps) = eps in
 *    compression, the first segment continued).
 *
 * Post-fracture (spec: repulsion only) a broken bond keeps max(0, F): it
 * pushes back when compressed and never attracts.
 */
#ifndef SPALL_LATTICE_LAWS_H
#define SPALL_LATTICE_LAWS_H

#include <math.h>
#include <stddef.h>

#include "core/mathconst.h"

#if defined(__GNUC__)
#define LATTICE_UNLIKELY(x) __builtin_expect(!!(x), 0)
#define LATTICE_INLINE static inline __attribute__((always_inline))
#else
#define LATTICE_UNLIKELY(x) (x)
#define LATTICE_INLINE static inline
#endif

/** Axial law of the whole model (deck `model.law`). */
enum lattice_law {
    LATTICE_LAW_LINEAR = 0,
    LATTICE_LAW_LJ = 1,
    LATTICE_LAW_PWL = 2,
    LATTICE_LAW_SOFT = 3 /**< bilinear cohesive softening (lattice_softening.h); intact = linear */
};

/** Piecewise-linear curve normalised by the initial modulus: g = sigma/E0. */
struct lattice_curve {
    size_t n;      /**< points, the first is (0, 0) */
    double *e;     /**< strain at the points, strictly increasing */
    double *g;     /**< sigma / E0 at the points */
    double *slope; /**< slope of segment k (k < n-1), the last one repeated at n-1 */
    double *G;     /**< int_0^e[k] g de (energy density / E0) */
};

/** Constants of one (material pair, bond shell) combination. */
struct lattice_bond_law {
    double k;        /**< stiffness |dF/dr| at rest [N/m] */
    double t_lim;    /**< bond breaks when r > t_lim * r_rest (INFINITY: never) */
    double c_lim;    /**< bond breaks when r < c_lim * r_rest (-INFINITY: never) */
    double dfdr_max; /**< max |dF/dr| over the intact range [N/m] (stable dt) */
    int curve;       /**< piecewise-linear: index of the material whose curve is used */
    double e0;       /**< softening law: strain where softening starts (t_lim - 1 = full separation) */
};

/** Law parameters shared by every bond. */
struct lattice_law_params {
    enum lattice_law law;
    double p, q;                        /**< LJ exponents (q > p >= 1) */
    const struct lattice_curve *curves; /**< PWL curves, one per material */
};

/* ---- piecewise linear helpers ------------------------------------------ */

/** Segment of strain @p e: the k with e[k] <= e < e[k+1] (last segment beyond). */
LATTICE_INLINE size_t lattice_curve_seg(const struct lattice_curve *c, double e)
{
    size_t k = 0;
    while (k + 2 < c->n && e >= c->e[k + 1])
        k++;
    return k;
}

LATTICE_INLINE double lattice_curve_g(const struct lattice_curve *c, double e)
{
    if (e <= 0.0)
        return e;
    size_t k = lattice_curve_seg(c, e);
    return c->g[k] + c->slope[k] * (e - c->e[k]);
}

LATTICE_INLINE double lattice_curve_energy(const struct lattice_curve *c, double e)
{
    if (e <= 0.0)
        return 0.5 * e * e;
    size_t k = lattice_curve_seg(c, e);
    double d = e - c->e[k];
    return c->G[k] + c->g[k] * d + 0.5 * c->slope[k] * d * d;
}

/* ---- dimensionless laws -------------------------------------------------- */

/** phi(s) = F / (k r_rest), positive repulsive. */
LATTICE_INLINE double lattice_phi(const struct lattice_law_params *lp, int curve, double s)
{
    switch (lp->law) {
    case LATTICE_LAW_LJ:
        return (pow(s, -lp->q) - pow(s, -lp->p)) / (lp->q - lp->p);
    case LATTICE_LAW_PWL:
        return -lattice_curve_g(&lp->curves[curve], s - 1.0);
    case LATTICE_LAW_LINEAR:
    default:
        return 1.0 - s;
    }
}

/** int_1^s of (s'^-a) ds' (a = 1: log). */
LATTICE_INLINE double lattice_ipow(double s, double a)
{
    return a == 1.0 ? log(s) : (pow(s, 1.0 - a) - 1.0) / (1.0 - a);
}

/** u(s) = U / (k r_rest^2) with u(1) = 0 (intact law). */
LATTICE_INLINE double lattice_u(const struct lattice_law_params *lp, int curve, double s)
{
    switch (lp->law) {
    case LATTICE_LAW_LJ:
        /* U = -int_r0^r F dr: for s = 1 + e this is e^2/2 + O(e^3) */
        return -(lattice_ipow(s, lp->q) - lattice_ipow(s, lp->p)) / (lp->q - lp->p);
    case LATTICE_LAW_PWL:
        return lattice_curve_energy(&lp->curves[curve], s - 1.0);
    case LATTICE_LAW_LINEAR:
    default:
        return 0.5 * (s - 1.0) * (s - 1.0);
    }
}

/** Force coefficient c (f_i = c dx) of a bond of stiffness k at stretch s;
 *  broken bonds keep only repulsion. */
LATTICE_INLINE double lattice_coef(const struct lattice_law_params *lp, int curve, double k,
                                   double s, int broken)
{
    double phi = lattice_phi(lp, curve, s);
    if (broken && phi < 0.0)
        phi = 0.0;
    return -k * phi / s;
}

/** Bond energy [J]: intact law, or for a broken bond only the repulsive part
 *  (U of the intact law for s < 1, zero when stretched). */
LATTICE_INLINE double lattice_energy(const struct lattice_law_params *lp, int curve, double k,
                                     double rest, double s, int broken)
{
    if (broken && s >= 1.0)
        return 0.0;
    return k * rest * rest * lattice_u(lp, curve, s);
}

/** Stretch of the LJ force peak ([Wang2010] Eq. 4: dF/dr(r_d) = 0). */
static inline double lattice_lj_peak_stretch(double p, double q)
{
    return pow(q / p, 1.0 / (q - p));
}

/** |d phi / ds| of the LJ law at stretch s. */
static inline double lattice_lj_slope(double p, double q, double s)
{
    return fabs(-q * pow(s, -q - 1.0) + p * pow(s, -p - 1.0)) / (q - p);
}

#endif
