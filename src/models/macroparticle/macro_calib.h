/**
 * @file macro_calib.h
 * @brief Calibration of the macro-particle model (seed 001, digest
 *        spec/macroparticle.md): atoms per particle, particle energy, Mie well
 *        depth, particle mass and the predicted Young's modulus.
 *
 * Equations (seed 001):
 *   N_atom = (rho pi r0^3 / 6) / (m 0.74)            Eq. 11
 *   P_atom = N_atom e0                               Eq. 10
 *   D      = P_atom / 6     (12 bonds, 6 per particle, Eq. 13)
 *   phi(r) = D/(q-p) [p (r0/r)^q - q (r0/r)^p],  phi''(r0) = D p q / r0^2
 *   E      = phi''(r0) / (2 r0) = pi rho p q e0 / (0.74 * 72 * m)   Eqs. 14-15
 * The particle mass is rho times the FCC volume per site r0^3/sqrt2 (Eq. 1),
 * equal to N_atom m up to 0.74 vs pi/(3 sqrt2) = 0.7405.
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
/** FCC packing fraction used by seed 001 Eq. 11. */
#define MACRO_PACKING 0.74

struct macro_calib {
    /* input */
    double rho;        /**< density [kg/m^3] */
    double atom_mass;  /**< atomic mass m [kg] */
    double e0;         /**< cohesive energy per atom [J] */
    double p, q;       /**< Mie exponents, q > p > 0 */
    double r0;         /**< macro-particle spacing [m] */
    /* output */
    double n_atom;     /**< Eq. 11 */
    double p_atom;     /**< Eq. 10 [J] */
    double D;          /**< pair well depth P_atom/6 [J] */
    double k;          /**< phi''(r0) = D p q / r0^2 [N/m] */
    double mass;       /**< particle mass rho r0^3/sqrt2 [kg] */
    double E;          /**< Eq. 15 [Pa] */
    double E_fcc100;   /**< modulus of a nearest-neighbour FCC crystal along [100],
                            (2 sqrt2 / 3) k / r0 [Pa] (Cauchy-Born, C11 = 2 C12 = 2 C44) */
    double nu_fcc100;  /**< 1/3 for the same crystal */
};

/** Fill the outputs from the inputs; SPALL_ERR_PHYSICS names a bad input. */
int macro_calibrate(struct macro_calib *c, struct spall_error *err);

/** Eq. 15 alone: E = pi rho p q e0 / (0.74 * 72 m) [Pa]. */
double macro_eq15_modulus(double rho, double atom_mass, double e0, double p, double q);

/** Debye angular frequency k_B theta_D / hbar [1/s]. */
double macro_debye_omega(double theta_d);

#endif
