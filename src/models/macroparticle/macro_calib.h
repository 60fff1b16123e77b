/**
 * @file macro_calib.h
 * @brief Calibration of the macro-particle model ([Saitoh], digest
 *        spec/macroparticle.md): atoms per particle, particle energy, Mie well
 *        depth, particle mass and the predicted Young's modulus.
 *
 * Equations ([Saitoh]):
 *   N_atom = (rho pi r0^3 / 6) / (m 0.74)            Eq. 11
 *   P_atom = N_atom e0                               Eq. 10
 *   D      = P_atom / 6     (12 bonds, 6 per particle, Eq. 13)
 *   phi(r) = D/(q-p) [p (r0/r)^q - q (r0/r)^p],  phi''(r0) = D p q / r0^2
 *   E      = phi''(r0) / (2 r0) = pi rho p q e0 / (0.74 * 72 * m)   Eqs. 14-15
 * The particle mass is rho times the FCC volume per site r0^3/sqrt2 (Eq. 1),
 * equal to N_atom m up to 0.74 vs pi/(3 sqrt2) = 0.7405.
 *
 * Two calibrations of D (macro_lattice.c):
 *   MACRO_CAL_EQ15    the seed's: D = P_atom / 6.  The FCC crystal of these
 *                     pairs has E_[100] = 1.886 x Eq. 15 (nearest shell).
 *   MACRO_CAL_LATTICE D scaled so that E_[100] of the FCC lattice, summed over
 *                     every shell inside the cut-off (Cauchy-Born), equals the
 *                     target (Eq. 15 by default, the "fitted value" of the
 *                     seed's section 3.1): a [001] rod then converges to it.
 */
#ifndef SPALL_MACRO_CALIB_H
#define SPALL_MACRO_CALIB_H

struct spall_error;

/** Boltzmann constant [J/K] and reduced Planck constant [J s] (CODATA 2018). */
#define MACRO_KB 1.380649e-23
#define MACRO_HBAR 1.054571817e-34
/** Atomic mass unit [kg] and electron-volt [J] (CODATA 2018). */
#define MACRO_AMU 1.66053906660e-27
#define MACRO_EV 1.602176634e-19
/** FCC packing fraction used by [Saitoh] Eq. 11. */
#define MACRO_PACKING 0.74

/** How the well depth D is set. */
enum macro_calibration {
    MACRO_CAL_EQ15 = 0,  /**< [Saitoh]: D = P_atom / 6 (Eq. 13) */
    MACRO_CAL_LATTICE    /**< D so that the lattice's E_[100] equals the target */
};

struct macro_calib {
    /* input */
    enum macro_calibration mode; /**< default (0) MACRO_CAL_EQ15 */
    double e_target;   /**< lattice mode: target E_[100] [Pa] (0: Eq. 15's E) */
    double taper;      /**< r_on / r0 (0: 1.2, the model's default) */
    double cutoff;     /**< r_c / r0 (0: 1.35, the model's default) */
    double rho;        /**< density [kg/m^3] */
    double atom_mass;  /**< atomic mass m [kg] */
    double e0;         /**< cohesive energy per atom [J] */
    double p, q;       /**< Mie exponents, q > p > 0 */
    double r0;         /**< macro-particle spacing [m] */
    /* output */
    double n_atom;     /**< Eq. 11 */
    double p_atom;     /**< Eq. 10 [J] */
    double D;          /**< pair well depth [J]: P_atom/6 (Eq. 13) times d_scale */
    double d_scale;    /**< 1 (eq15) or target / E_[100] of the P_atom/6 lattice */
    double k;          /**< phi''(r0) = D p q / r0^2 [N/m] */
    double mass;       /**< particle mass rho r0^3/sqrt2 [kg] */
    double E;          /**< Eq. 15 [Pa] (of P_atom/6, whatever the mode) */
    double E_fcc100;   /**< Young's modulus along [100] of the FCC crystal of the pairs
                            actually used (depth D), summed over the cut-off shells [Pa];
                            nearest shell only: (2 sqrt2 / 3) k / r0 */
    double nu_fcc100;  /**< Poisson's ratio of the same crystal (1/3 nearest shell only) */
    double c11, c12, c44; /**< its cubic elastic constants [Pa] (Born term) */
    double pressure;   /**< residual pressure of the lattice at r0 [Pa] (0 nearest shell) */
};

/** Fill the outputs from the inputs; SPALL_ERR_PHYSICS names a bad input
 *  (exponents, spacing, or a cut-off/taper outside 1 < taper < cutoff). */
int macro_calibrate(struct macro_calib *c, struct spall_error *err);

/** Eq. 15 alone: E = pi rho p q e0 / (0.74 * 72 m) [Pa]. */
double macro_eq15_modulus(double rho, double atom_mass, double e0, double p, double q);

/** Debye angular frequency k_B theta_D / hbar [1/s]. */
double macro_debye_omega(double theta_d);

#endif
