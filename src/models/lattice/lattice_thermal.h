/**
 * @file lattice_thermal.h
 * @brief Thermal lattice ([Wang2010] sec. 2.2, Eqs. 19-21): particle
 *        temperatures, conduction along intact bonds, volumetric heating per
 *        material (microwave power density), thermal expansion of the bonds'
 *        rest lengths and bond removal above a melting temperature.
 *        Internal to the lattice model.
 *
 * Per step (after the mechanical step, sub-cycled if the thermal explicit
 * limit is below the mechanical dt):
 *   m_i C_i dT_i/dt = sum_j kappa_ij (T_j - T_i) + P_d,i V_i   (Eqs. 19-20),
 *   r0_ij(T) = r0_ij (1 + alpha_ij ((T_i + T_j)/2 - T_ref,ij))   (Eq. 21),
 *   bond ij removed (BOND_BROKEN) once T_i or T_j exceeds its melting point.
 *
 * Bond conductance (W/K) from the conductivity k_th (W/(m K)): for a lattice
 * whose bond second moment is isotropic, sum_j d_j d_j = (S / D) I with
 * S = sum_j |d_j|^2, a Taylor expansion of sum_j kappa (T_j - T_i) gives
 * kappa S / (2 D) lap T; matching the continuum rho C dT/dt = k lap T with
 * m = rho V gives kappa = 2 D k V / S (chain: k A / r0; triangular with
 * thickness t: k t / sqrt3), S and V taken at a bulk particle (the largest
 * S).  Across two materials the series (harmonic-mean) conductivity is used.
 * Broken bonds do not conduct (a crack insulates).
 *
 * The seed's Eq. 20 writes the heating term as P_d / (C dt), which is not
 * dimensionally consistent; we use the energy balance P_d V dt / (m C)
 * (= P_d dt / (rho C)), as the digest (spec/lattice.md) states.
 */
#ifndef SPALL_LATTICE_THERMAL_H
#define SPALL_LATTICE_THERMAL_H

#include <stdbool.h>
#include <stddef.h>

struct deck_node;
struct field_registry;
struct field_state;
struct model;
struct sim;
struct spall_error;

/** Material keys read by the thermal module (appended to the lattice's
 *  allowed key lists). */
#define LATTICE_THERMAL_KEYS                                                                      \
    "specific_heat", "conductivity", "thermal_expansion", "power_density",                       \
        "melting_temperature", "initial_temperature", "reference_temperature",           \
        "youngs_modulus_table"

struct lattice_thermal;

/** Parse the thermal keys of material @p index (absent: the material has no
 *  thermal behaviour; then every other material must have none either). */
int lattice_thermal_parse_material(struct model *m, struct sim *sim, int index,
                                   const struct deck_node *node, struct spall_error *err);
/** Parse `model.thermal` ({boundary: [{group, temperature}, ...]}). */
int lattice_thermal_parse_options(struct model *m, const struct deck_node *node,
                                  struct spall_error *err);
/** After the bonds exist: temperatures, conductances, rest lengths. */
int lattice_thermal_init(struct model *m, struct sim *sim, struct spall_error *err);
/** Advance temperatures by dt, update rest lengths, melt bonds. */
int lattice_thermal_step(struct model *m, struct sim *sim, double dt, struct spall_error *err);
/** Register the `temperature` field. */
/** Restart state of the thermal lattice (lattice_restart.c calls it). */
int lattice_thermal_register_state(struct model *m, size_t n_owned, struct field_state *fs,
                                   struct spall_error *err);
int lattice_thermal_register_fields(struct model *m, struct field_registry *reg,
                                    struct spall_error *err);
struct bond_rows;
/** Distributed runs (lattice_localize): keep the state of particles
 *  @p keep (owned, then ghosts) and of the half-bonds of the kept rows. */
int lattice_thermal_localize(struct model *m, const size_t *keep, size_t n_keep,
                             const struct bond_rows *rows, struct spall_error *err);
struct par_model_arrays;
/** Distributed runs, migration: lend the thermal state per particle and per
 *  half-bond (appended to @p a), and after the move take the new count @p n
 *  of local particles and the moved arrays. */
void lattice_thermal_migrate_arrays(struct model *m, struct par_model_arrays *a);
void lattice_thermal_migrated(struct model *m, size_t n);
/** History columns (temperature_mean, temperature_max, melted bonds); returns
 *  how many were written at @p names / @p values. */
size_t lattice_thermal_history(const struct model *m, const struct sim *sim, const char **names,
                               double *values);
bool lattice_thermal_enabled(const struct model *m);
void lattice_thermal_destroy(struct lattice_thermal **th);

#endif
