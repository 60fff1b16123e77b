/**
 * @file lattice_calib.h
 * @brief Spring constants of the hybrid lattice particle model (HLPM) from
 *        E, nu, strength and density, and the numerical patch test that
 *        checks them with the model's real force code.
 *
 * Used by the lattice model itself (init), by `spall calibrate` and by the
 * validation programs.  Derivations are in lattice_calib.c; in short
 * (r0 = nearest-neighbour spacing, t = plate thickness, A = chain area):
 *   chain       k = E A / r0
 *   triangular  k = E t / (sqrt3 (1 - nu)),
 *               k_phi = r0^2 E t (1 - 3 nu) / (6 sqrt3 (1 - nu^2))   (alpha-beta)
 *               two layers: k1 + 3 k2 = sqrt3 E t / 2, nu = 1/3
 *               nu > 1/3, area springs (spall's own construction, not the
 *               paper's alpha-beta-gamma): k = 2 E t / (sqrt3 (1 + nu)),
 *               k_area = sqrt3 r0^2 E t (3 nu - 1) / (8 (1 - nu^2))
 *   triple honeycomb (alpha-beta-gamma, [Wang2010] Fig. 3d), nu in [1/3, 1):
 *               families alpha <= beta = gamma with kappa t = (a+b+g)/(2 sqrt3),
 *               mu t = 3 sqrt3 / (4 (1/a + 1/b + 1/g))  (lattice_honeycomb.c)
 *   square      k1 = 3 E t / 4 (axes), k2 = 3 E t / 8 (diagonals), nu = 1/3
 *   sc          k1 = k2 = 2 E r0 / 5, nu = 1/4
 *   fcc         k = E r0 / sqrt2 (Voigt average), nu = 1/4
 */
#ifndef SPALL_LATTICE_CALIB_H
#define SPALL_LATTICE_CALIB_H

#include "core/lattice_gen.h"

struct spall_error;

/** Cauchy value of nu of a central-force lattice is accepted within this. */
#define LATTICE_NU_TOL 1e-3

/** Inputs and outputs of a calibration. */
struct lattice_calib {
    /* inputs */
    enum lattice_kind kind;    /**< lattice */
    int layers;                /**< axial shells: 1 or 2; 0 = the lattice's default */
    int angular;               /**< angular springs: -1 auto, 0 off, 1 on (triangular only) */
    double second_layer_ratio; /**< k2/k1 for a two-layer triangular lattice; 0 = 1/sqrt3 */
    double E;                  /**< Young's modulus [Pa] */
    double nu;                 /**< Poisson's ratio */
    double rho;                /**< density [kg/m^3]; 0: no mass / dt */
    double sigma_ts;           /**< tensile strength [Pa]; 0: use eps_max */
    double eps_max;            /**< failure strain (output when sigma_ts > 0); 0 = never breaks */
    double r0;                 /**< nearest-neighbour spacing [m] */
    double thickness;          /**< 2D plate thickness [m]; 1D cross-section area [m^2] */
    /* outputs */
    int layers_used;           /**< layers actually used */
    int angular_used;          /**< 1 when angular springs are present */
    double k1;                 /**< first-shell axial stiffness [N/m] */
    double k2;                 /**< second-shell axial stiffness [N/m] (0 with one layer) */
    double k_phi;              /**< angular stiffness [N m / rad^2]: energy k_phi dphi^2 / 2 */
    int area_used;             /**< 1: area springs (triangular lattice, nu > 1/3) */
    double k_area;             /**< triangle-area stiffness [J]: energy k_area (A/A0 - 1)^2 / 2
                                    per lattice triangle (0 unless area_used) */
    int honeycomb_used;        /**< 1: triple honeycomb; k1 = beta = gamma */
    double k_family[3];        /**< triple honeycomb: alpha, beta, gamma [N/m] (bond
                                    family f joins the two sublattices other than f) */
    double site_volume;        /**< volume per particle [m^3] */
    double mass;               /**< rho * site_volume [kg] */
    double dt;                 /**< stable time step of a bulk site [s] ([Wang2010] Eq. 25) */
    double paper_S0;           /**< [Wang2010] Eq. 16, 2 E r0 / (3 (1 - nu)) [N/m] */
    double paper_S_phi;        /**< [Wang2010] Eq. 18, sqrt3 (1-3nu) E r0^2 / (18 (1-nu^2)) [N] */
};

/** Patch-test result: moduli from uniform strain states. */
struct lattice_patch_result {
    double C11, C12, C66;   /**< measured elastic constants [Pa] (3D: C66 = C44) */
    double E, nu;           /**< 1D: E; 2D: plane stress; 3D: Voigt average */
    double E_100, nu_100;   /**< 3D: [100] direction (2D: same as E, nu) */
    double f_interior_max;  /**< largest interior force / (k1 r0 strain): equilibrium check */
    double E_affine, nu_affine; /**< triple honeycomb: without the sublattice shifts (the
                                     unrelaxed, affine lattice); elsewhere = E, nu */
    size_t n_particles, n_interior;
};

/** Derive spring constants, mass and the stable time step.  Refuses
 *  impossible combinations (e.g. nu != 1/3 on a central-force triangular
 *  lattice) with SPALL_ERR_PHYSICS and a reason. */
int lattice_calibrate(struct lattice_calib *c, struct spall_error *err);

/** Patch test: fill a block, impose uniform strains of size @p strain, call
 *  the lattice model's compute_forces and read the virial stress of the
 *  interior particles.  @p use_paper_constants: use [Wang2010] Eqs. 16/18
 *  (scaled to the thickness t, k_phi = S_phi r0) instead of the calibrated
 *  constants (triangular lattice only).  Returns E and nu measured (see
 *  struct lattice_patch_result for which). */
int lattice_patch_test(const struct lattice_calib *c, double strain, int use_paper_constants,
                       double *E_meas, double *nu_meas, struct spall_error *err);

/** Same, with every measured quantity. */
int lattice_patch_test_full(const struct lattice_calib *c, double strain,
                            int use_paper_constants, struct lattice_patch_result *res,
                            struct spall_error *err);

/** Seed 000 Eq. 18 angular constant as an angular stiffness k_phi = S_phi r0
 *  scaled to plate thickness @p t (the paper's constants assume t = 2 r0/sqrt3);
 *  it is sqrt3/2 times the value the patch test confirms. */
double lattice_paper_k_phi(double E, double nu, double r0, double t);
/** Seed 000 Eq. 16 axial constant scaled to thickness @p t. */
double lattice_paper_k(double E, double nu, double r0, double t);

#endif
