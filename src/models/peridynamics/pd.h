/**
 * @file pd.h
 * @brief Public functions of the peridynamics model for callers above it
 *        (the CLI's calibrate command, validation cases, tests): the
 *        calibration formulas, the patch test, and read-only views of a
 *        built model.  The model's state stays private (pd_internal.h).
 */
#ifndef SPALL_PD_H
#define SPALL_PD_H

#include <stdbool.h>
#include <stddef.h>

struct bond_list;
struct model;
struct sim;
struct spall_error;

/** 2D idealisation (deck `model.plane`). */
enum pd_plane { PD_PLANE_STRESS, PD_PLANE_STRAIN };

/** Per-material input and derived constants. */
struct pd_material {
    bool parsed;
    bool ortho;             /**< orthotropic lamina */
    double E, K, nu;        /**< isotropic: E (or K) and the fixed nu */
    double G0;              /**< fracture energy [J/m^2]; 0: unbreakable */
    double s0_given;        /**< critical stretch given directly (0: from G0) */
    /* orthotropic lamina (plane stress, material axes 1 = fiber) */
    double E1, E2, G12, nu12;
    double Gf, GIc, GIIc;   /**< fiber / matrix mode I / mode II fracture energies */
    double fiber_angle;     /**< rad, from the x axis */
    /* derived */
    double c, s0;           /**< isotropic micromodulus, critical stretch */
    double c_f, c_m, s0_f, s0_m;
    double fa_cos, fa_sin;  /**< cos, sin of fiber_angle (pd_mixed.c) */
    double Q22;             /**< plane-stress reduced stiffness (mode-I energy weight) */
    double mu, kd;          /**< LPS: shear modulus, bulk modulus of the dimension [Pa] */
    double yield_stress;    /**< EPS (formulation eps): yield stress sigma_Y [Pa] */
};

/** Isotropic PMB micromodulus of material @p mt (Silling & Askari 2005; digest table). */
double pd_micromodulus(int dim, enum pd_plane plane, double E, double K, double delta,
                       double thickness);
/** Critical stretch from G0 for micromodulus @p c (energy of the bonds crossing a unit
 *  crack = G0, Silling & Askari 2005 Eq. 27 generalised). */
double pd_critical_stretch(int dim, double c, double G0, double delta, double thickness);
/** LPS critical stretch from G0 (pd_calib.c); kd the bulk modulus of the dimension. */
double pd_lps_critical_stretch(int dim, double kd, double mu, double G0, double delta);
/** PDLM (triangular, nearest neighbours): c from strain-energy equivalence. */
double pd_pdlm_micromodulus(double E, double dx, double thickness);
/** PDLM critical stretch from G (2 bonds per dx cross a crack along a row). */
double pd_pdlm_critical_stretch(double E, double G, double dx);
/** 3x3 inverse; -1 if singular. */
int pd_invert3(double A[3][3], double B[3][3]);

/** Orthotropic calibration: c_f, c_m of material @p k from a patch test (needs the
 *  family); fills achieved E1, E2, G12, nu12. */
int pd_calibrate_ortho(struct model *m, struct sim *sim, int k, double achieved[4],
                       struct spall_error *err);

/** Particle of material @p k with the fullest family, nearest their centroid (2D). */
size_t pd_patch_particle(const struct model *m, const struct sim *sim, int k);
/** 2D stiffness [Pa] in axes rotated by @p th (Voigt 11, 22, 12, engineering shear) of
 *  particle @p i: uniform strains applied to every particle, virial stress read back;
 *  positions restored. */
void pd_patch_stiffness(struct model *m, struct sim *sim, size_t i, double th, double C[3][3]);

/* pd_model.c: read-only views of a built peridynamics model @p m */
/** The family: every particle's bonds (CSR, BOND_BROKEN marks broken ones). */
const struct bond_list *pd_bonds(const struct model *m);
/** Rows of the compact families' table (pd_compact.c); 0 when the model keeps
 *  per-half-bond arrays (deck bond_storage: full, or a layout it cannot compact). */
size_t pd_compact_kinds(const struct model *m);
/** Material @p k (input and derived constants: micromoduli, critical stretches). */
const struct pd_material *pd_material_get(const struct model *m, int k);
/** Mixed-mode matrix failure (pd_mixed.c) of particle @p i: *beta its mode-II
 *  energy share, *g its factor on the matrix critical stretch, from the last
 *  pd_mixed_update.  Returns false (and beta 0, g 1) when no bond type of the
 *  run uses the mixed-mode threshold, whose per-particle arrays then do not
 *  exist. */
bool pd_mixed_state(const struct model *m, size_t i, double *beta, double *g);
/** Per-particle mode mixity beta_i and threshold factor g_i from the current
 *  positions (Benzeggagh & Kenane 1996 G_c(beta); pd_mixed.c, called by the
 *  step itself). */
void pd_mixed_update(struct model *m, const struct sim *sim);
/** surface_correction position_aware (pd_lps_pals.c): the influences omega, sigma of
 *  half-bond @p s as its particle holds them; false without the option. */
bool pd_lps_pals_half(const struct model *m, size_t s, double *omega, double *sigma);
/** Tests: the split kernel only (@p rows), every half-bond from its own row,
 *  instead of the once-per-bond loop (pd_half.c), which gives the same bits. */
void pd_set_row_loop(struct model *m, bool rows);
/** Whether the last force computation took the once-per-bond loop. */
bool pd_used_half_loop(const struct model *m);

#endif
