/**
 * @file sph.h
 * @brief Public functions of the SPH model for callers above it (validation
 *        cases, benchmarks, tests): the material laws as pure functions,
 *        views of a built model (counters, per-particle kinematics), and the
 *        few units the white-box tests drive directly (neighbour and
 *        interface lists, TLSPH re-reference, artificial-stress smoothing).
 *        The model's state stays private (sph_internal.h); its per-particle
 *        state (density, pressure, deviatoric stress, ...) is in the field
 *        registry (core/fields.h).
 */
#ifndef SPALL_SPH_H
#define SPALL_SPH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct model;
struct neighbor_list;
struct sim;
struct spall_error;

/** Stress / tensor component order (symmetric): xx yy zz xy yz xz. */
enum { SXX, SYY, SZZ, SXY, SYZ, SXZ };

/* ---- material laws (sph_material.c) ------------------------------------- */

enum sph_eos { SPH_EOS_LINEAR, SPH_EOS_MIE_GRUNEISEN, SPH_EOS_MIE_GRUNEISEN_CK };
enum sph_yield { SPH_YIELD_ELASTIC, SPH_YIELD_PERFECT, SPH_YIELD_POWER, SPH_YIELD_JOHNSON_COOK };
/** Strain-rate scaling of the yield stress (not with Johnson-Cook, which has its own). */
enum sph_rate { SPH_RATE_NONE, SPH_RATE_COWPER_SYMONDS };
enum sph_failure { SPH_FAIL_NONE, SPH_FAIL_STRESS, SPH_FAIL_PLASTIC_STRAIN };

/** Per-material input and derived constants (deck `materials:`). */
struct sph_material {
    bool parsed;
    double rho0, E, nu, K, G;
    enum sph_eos eos;
    double mg_c, mg_s, mg_gamma, mg_p0; /**< Mie-Grueneisen C, S, Gamma, P0 */
    enum sph_yield yield;
    double sy;                          /**< perfect plasticity */
    double A, B, n;                     /**< A + B ep^n (also JC a, b, n) */
    double jc_c, jc_m, Tm, Troom, eps0; /**< Johnson-Cook */
    enum sph_rate rate;                 /**< rate_model */
    double cs_d, cs_q;                  /**< Cowper-Symonds D [1/s], q */
    double cp, beta_tq;                 /**< heat capacity, Taylor-Quinney */
    enum sph_failure failure;
    double fail_value;                  /**< stress [Pa] or plastic strain */
    bool failed_tension;                /**< failed particles keep the EOS tension */
};

/** Pressure from the EOS (compression positive). */
double sph_eos_pressure(const struct sph_material *mt, double rho, double e);
/** Longitudinal sound speed at the given state. */
double sph_sound_speed(const struct sph_material *mt, double rho, double e);
/** Current yield stress (INFINITY: elastic). */
double sph_yield_stress(const struct sph_material *mt, double ep, double epdot, double T);
/** Rate factor of the yield (and stress-failure) stress: 1 + (epdot / D)^(1/q)
 *  with Cowper-Symonds, else 1. */
double sph_rate_factor(const struct sph_material *mt, double epdot);

/** Material @p k of a built SPH model. */
const struct sph_material *sph_material_get(const struct model *m, int k);

/* ---- a built model (views in sph_access.c) -------------------------------- */

/** Counters and timers of an SPH run (benchmarks, diagnostics). */
struct sph_stats {
    size_t n_builds;       /**< neighbour-list builds */
    double t_neighbor;     /**< wall seconds spent building neighbour lists */
    size_t cspm_fallbacks; /**< particles whose CSPM matrix was singular (total) */
    double h_factor;       /**< h = h_factor * dx (model.h_factor) */
    size_t tl_rerefs;      /**< TLSPH reference updates so far */
    double t_reref;        /**< wall seconds spent in reference updates */
    size_t tl_hgrown;      /**< TLSPH h growths (x1.2) at reference updates */
    double tl_jmin, tl_kmax; /**< TLSPH: smallest det F, largest distortion (last step) */
    size_t iface_pairs;    /**< interface pairs in contact at the last force evaluation */
    bool total_lagrangian; /**< some (or every) body is TLSPH */
    size_t n_total;        /**< particles on TLSPH in a run split by formulation (else 0) */
    double nl_radius;      /**< neighbour-list radius [m] (kernel support + skin) */
    double qmax;           /**< kernel support / h */
    bool as_smooth;        /**< artificial stress smoothed (model.artificial_stress_smoothing) */
};
void sph_stats_get(const struct model *m, struct sph_stats *out);
/** Smoothing length h [m] of particle @p i. */
double sph_smoothing_length(const struct model *m, size_t i);
/** Initial spacing dx [m] of particle @p i (its lattice spacing). */
double sph_spacing(const struct model *m, size_t i);
/** Velocity gradient dv^a/dx^b of particle @p i at the last force call
 *  ([a*3+b]; CSPM-corrected when model.cspm is on). */
void sph_velocity_gradient(const struct model *m, size_t i, double L[9]);
/** F of TLSPH particle i at the last force call (tests, diagnostics). */
void sph_tlsph_deformation(const struct model *m, size_t i, double F[9]);
/** Rates of particle @p i at the last force call: density *drho and
 *  deviatoric stress dS (xx yy zz xy yz xz). */
void sph_state_rates(const struct model *m, size_t i, double *drho, double dS[6]);
/** Component @p c of the deviatoric stress rate dS of every particle (the
 *  last force call's; not a registered field, the next force call recomputes
 *  it): for tests of what a reflection must leave alone. */
double *sph_stress_rate_data(struct model *m, int c);
/** Plastic work of particle @p i so far [J]. */
double sph_plastic_work(const struct model *m, size_t i);
/** Formulation of every particle (1: TLSPH, 0: updated) in a run whose
 *  bodies are split by formulation; NULL when the run has one formulation. */
const uint8_t *sph_formulations(const struct model *m);
/** The kernel neighbour list (full list over the owned particles). */
const struct neighbor_list *sph_neighbors(const struct model *m);
/** Interface partners of particle @p i (pairs of different bodies or
 *  materials with model.interface): their number, and *idx their indices;
 *  0 when the interface is off. */
size_t sph_interface_partners(const struct model *m, size_t i, const int32_t **idx);
/** (Re)build the neighbour list if particles moved more than half the skin. */
int sph_neighbors_update(struct model *m, struct sim *s, bool force, struct spall_error *err);
/** Penalty forces between the groups into s->p->f; energy and pair count. */
void sph_interface_forces(struct model *m, struct sim *s);
/** Replace the TLSPH reference configuration by the current one now. */
int sph_tlsph_reref(struct model *m, struct sim *s, struct spall_error *err);
/** Component @p c (xx yy zz xy yz xz) of the artificial stress tensor R of
 *  every particle: the input and output of sph_artificial_stress_smooth. */
double *sph_artificial_stress_data(struct model *m, int c);
/** Replace R_i by its kernel (Shepard) average over i and its neighbours
 *  (model.artificial_stress_smoothing; split pair loops only). */
void sph_artificial_stress_smooth(struct model *m, const struct sim *s);
/** Pressure and sound speed of every particle from its density and energy
 *  by its material's EOS (failed particles carry no tension unless their
 *  material keeps it): after a caller set the density field. */
void sph_refresh_pressure(struct model *m, struct sim *s);
/** Pairs in the TLSPH reference list (0: none). */
size_t sph_tlsph_pairs(const struct model *m);
/** Switch the CSPM gradient correction (model.cspm) of a built model on or
 *  off: the velocity-gradient verification compares both on one state. */
void sph_set_cspm(struct model *m, bool on);
/** Verification only: run the two-pass loops of the updated form and the
 *  TLSPH stages one after the other (not pipelined), whatever the options
 *  chose; same equations, so results must agree with the fused / pipelined
 *  loops (tests/test_sph_fused.c, test_sph_tlsph.c, `spall bench
 *  sph_taylor_cu_tl_split`).  Call after the simulation is built. */
void sph_set_split_loops(struct model *m);
/** Verification only: the scalar rows of the fused loop and of the
 *  axisymmetric passes instead of their vector rows (Wendland kernel;
 *  sph_fused.c, sph_axisym_vec.c); bitwise the same results
 *  (tests/test_sph_fused.c, test_sph_axisym_vec.c).  Call after the build. */
void sph_set_scalar_rows(struct model *m);

#endif
