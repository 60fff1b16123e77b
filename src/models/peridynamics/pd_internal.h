/**
 * @file pd_internal.h
 * @brief State of the peridynamics model shared by pd_model.c (life cycle,
 *        deck, fields), pd_forces.c (hot loop, breaking, energies) and
 *        pd_calib.c (micromoduli, critical stretches, patch test).
 *        Not part of the public interface.
 */
#ifndef SPALL_PD_INTERNAL_H
#define SPALL_PD_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct bond_list;
struct sim;
struct spall_error;

#define PD_PI 3.14159265358979323846
#define PD_MAX_MAT 8 /* bond type = (ma * n_mat + mb) * 2 + fiber must fit in uint8 */

/** Variants (deck `model.variant`). */
enum pd_variant {
    PD_PMB, /**< continuum PMB with a horizon delta = m dx (Silling & Askari 2005) */
    PD_PDLM /**< lattice variant of seed 003: triangular lattice, nearest neighbours */
};

/** 2D idealisation (deck `model.plane`). */
enum pd_plane { PD_PLANE_STRESS, PD_PLANE_STRAIN };

/** How fiber bonds are chosen in an orthotropic lamina. */
enum pd_fiber_model {
    PD_FIBER_LATTICE, /**< bonds parallel to the fiber (rotated lattice, seed 003) */
    PD_FIBER_ANGULAR  /**< c(phi) = c_m + c_f cos^2n(phi): arbitrary fiber angles */
};

/** Quasi-static option (deck `model.quasi_static`). */
enum pd_quasi { PD_QS_OFF, PD_QS_ADR };

struct pd_options {
    enum pd_variant variant;
    enum pd_plane plane;
    double horizon_factor;   /**< m: delta = m dx (PMB) */
    bool partial_volume;     /**< beta_ij for bonds cut by the horizon */
    bool break_late;         /**< a bond past s0 acts once more (PDLAMMPS order) */
    bool family_at_delta;    /**< family ends at delta, not delta + dx/2 (PDLAMMPS rule) */
    bool surface_correction; /**< energy method (Madenci & Oterkus 2014 sec. 4.2) */
    enum pd_quasi quasi;
    enum pd_fiber_model fiber_model;
    int fiber_power;         /**< n of cos^2n (angular fiber model) */
    bool mixed_mode;         /**< laminae: matrix bonds by the BK mixed-mode G_c (pd_mixed.c) */
    double bk_exponent;      /**< Benzeggagh-Kenane exponent eta */
    bool fiber_plane;        /**< matrix_crack: fiber_plane (pd_plane.c) */
};

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
};

struct model {
    struct sim *sim; /**< borrowed */
    struct pd_options opt;
    int dim;
    double dx;       /**< lattice spacing */
    double delta;    /**< horizon [m] */
    size_t n_mat;
    struct pd_material *mat;
    double s0_tab[256];      /**< critical stretch per bond type; INFINITY: never breaks */

    struct bond_list *bl;    /**< family (type = (ma*n_mat+mb)*2 + fiber) */
    double *coef;            /**< per half-bond: c V_i V_j beta G / xi [N/m] */
    size_t *n_init;          /**< per particle: bonds at t = 0 after pre-cracks (all types) */
    size_t *n_init_f;        /**< fiber bonds at t = 0 */
    double *diss;            /**< per particle: energy released by its broken bonds [J] */
    /* adaptive dynamic relaxation (Kilic & Madenci 2010) */
    double *f_prev[3];
    double adr_damping;    /**< ADR coefficient c_n [1/s] for the engine (pd_damping) */
    bool adr_estimated;    /**< adr_damping holds an estimate (else the engine keeps its own) */
    size_t n_half;
    /* mixed-mode matrix failure (pd_mixed.c): per particle factor on s0_m */
    double *mm_g;            /**< sqrt(G_c(beta_i) / G_Ic); 1 for isotropic particles */
    double *mm_beta;         /**< mode-II energy share beta_i of the last step */
    uint8_t mm_type[256];    /**< 1: matrix bond of a lamina with G_IIc != G_Ic */
    /* fiber-parallel matrix cracks (pd_plane.c) */
    size_t *twin;            /**< per half-bond: zigzag neighbour on the same interface */
    uint8_t *fresh;          /**< per half-bond: broken by stretch this step */
    bool mixed;              /**< some bond type uses the mixed-mode threshold */
    bool ortho;              /**< some material is orthotropic */
    bool initialised;
};

/* pd_calib.c */
/** Isotropic PMB micromodulus of material @p mt (Silling & Askari 2005; digest table). */
double pd_micromodulus(int dim, enum pd_plane plane, double E, double K, double delta,
                       double thickness);
/** Critical stretch from G0 for micromodulus @p c (energy of the bonds crossing a unit
 *  crack = G0, Silling & Askari 2005 Eq. 27 generalised). */
double pd_critical_stretch(int dim, double c, double G0, double delta, double thickness);
/** PDLM (triangular, nearest neighbours): c from strain-energy equivalence. */
double pd_pdlm_micromodulus(double E, double dx, double thickness);
/** PDLM critical stretch from G (2 bonds per dx cross a crack along a row). */
double pd_pdlm_critical_stretch(double E, double G, double dx);
/** Stress of particle @p i (tension positive; 2D xx yy xy, 3D xx yy zz xy yz xz) and
 *  its strain energy [J] from the current positions (virial 1/2 sum F (x) xi / V_i). */
void pd_particle_eval(const struct model *m, const struct sim *sim, size_t i, double *energy,
                      double *stress);
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
/** 3x3 inverse; -1 if singular. */
int pd_invert3(double A[3][3], double B[3][3]);

/* pd_mixed.c */
/** Sets m->mm_type / m->mixed and allocates the per-particle arrays. */
int pd_mixed_init(struct model *m, struct sim *sim, struct spall_error *err);
/** Per-particle mode mixity beta_i and threshold factor g_i from the current
 *  positions (Benzeggagh & Kenane 1996 G_c(beta)). */
void pd_mixed_update(struct model *m, const struct sim *sim);

/* pd_plane.c */
/** Twin table of the fiber-parallel matrix-crack rule (no-op when off). */
int pd_plane_init(struct model *m, struct sim *sim, struct spall_error *err);
/** Break the twins of this step's stretch-broken matrix bonds (serial). */
void pd_plane_end_step(struct model *m, const struct sim *sim);

/* pd_forces.c */
int pd_compute_forces(struct model *m, struct sim *sim, struct spall_error *err);
double pd_stable_dt(const struct model *m, const struct sim *sim);
/** Per-half-bond coefficients from the current c tables (beta, surface factor). */
int pd_build_coefficients(struct model *m, struct sim *sim, struct spall_error *err);
/** Adaptive dynamic relaxation damping update (Kilic & Madenci 2010 Eq. 19):
 *  the new estimate in m->adr_damping, which the engine takes through the
 *  model's damping hook right after the force call. */
void pd_adr_update(struct model *m, const struct sim *sim);

#endif
