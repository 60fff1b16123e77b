/**
 * @file lattice.h
 * @brief Public functions of the lattice model for callers above it (tests,
 *        calibration): a model built without a deck (options and materials
 *        as structs), the softening law's calibration, and views of a built
 *        model for white-box tests (bond laws, angle springs).  The model's
 *        state stays private (lattice_internal.h).
 */
#ifndef SPALL_LATTICE_H
#define SPALL_LATTICE_H

#include "models/lattice/lattice_laws.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct bond_list;
struct lattice_calib;
struct model;
struct sim;
struct spall_error;

#define LATTICE_MAX_TYPES 3 /* two shells, or three honeycomb families */

/** Model options (deck `model:` section). */
struct lattice_options {
    enum lattice_law law;
    int layers;                /**< 0: lattice default */
    int angular;               /**< -1 auto, 0 off, 1 on */
    double second_layer_ratio; /**< 0: default 1/sqrt3 */
};

/** Per-material input and derived constants. */
struct lattice_material {
    bool parsed;
    double E, nu;
    bool nu_given;
    double eps_t;          /**< tensile failure strain; INFINITY: never (LJ: the peak) */
    bool eps_t_given;
    double eps_c;          /**< compressive failure strain; INFINITY: never */
    double eps_0;          /**< softening law: onset strain sigma_TS / E */
    double gf;             /**< softening law: fracture energy [J/m^2]; 0: eps_t given */
    bool ang_fail;         /**< angular_failure given */
    double dphi_c, dphi_t; /**< angular failure limits [rad] */
    double lj_p, lj_q;     /**< LJ exponents */
    struct lattice_curve curve; /**< PWL curve (owned) */
    /* derived in init */
    double k[LATTICE_MAX_TYPES]; /**< per bond type: shell, or honeycomb family */
    double k_phi;
    double k_area;         /**< triangle-area stiffness [J] (area springs, nu > 1/3) */
};

/** Allocate a model with @p opt (no deck). */
int lattice_model_new(struct model **out, struct sim *sim, const struct lattice_options *opt,
                      struct spall_error *err);
/** Set material @p index from a filled struct (takes ownership of its curve). */
int lattice_model_set_material(struct model *m, int index, struct lattice_material *mt,
                               struct spall_error *err);
/** Overwrite the axial and angular constants of material 0 after init
 *  (patch test with the paper's constants). */
void lattice_model_override(struct model *m, double k1, double k_phi);

/* lattice_softening.c */
/** Full-separation strain *ef of the softening law from the fracture energy
 *  @p gf [J/m^2] and onset strain @p e0, for the calibrated lattice @p c
 *  (bonds cut per unit area of a crack between rows; see the file). */
int lattice_soft_final_strain(const struct lattice_calib *c, double e0, double gf, double *ef,
                              struct spall_error *err);

/* lattice_model.c: views of a built lattice model @p m */
/** Material @p k (input and derived stiffnesses). */
const struct lattice_material *lattice_material_get(const struct model *m, int k);
/** Axial law of the bonds of type @p type between materials @p ma and @p mb. */
const struct lattice_bond_law *lattice_pair_law(const struct model *m, int ma, int mb, int type);
/** The bond list; mutable so that a test can break bonds by hand. */
struct bond_list *lattice_bond_list(struct model *m);
/** Angular springs present. */
bool lattice_has_angles(const struct model *m);
/** Tests and benchmarks: @p rows true keeps the linear law's loop to the
 *  row loop (every bond evaluated from both rows, lattice_forces.c) instead
 *  of the once-per-bond loop (lattice_half.c) where that applies; the same
 *  results bit for bit either way. */
void lattice_set_row_loop(struct model *m, bool rows);
/** Whether the last force call took the once-per-bond loop. */
bool lattice_used_half_loop(const struct model *m);
/** Owned rows the last force call's once-per-bond loop evaluated in
 *  stencil blocks (rows of one regular pattern, lattice_half.c). */
size_t lattice_stencil_rows(const struct model *m);
/** Triangle-area stiffness [J] of material @p k (area springs, nu > 1/3). */
double lattice_area_stiffness(const struct model *m, int k);
/** Angular failure limits of material @p k [rad] (compression, tension). */
void lattice_set_angle_limits(struct model *m, int k, double dphi_c, double dphi_t);
/** Broken flags of the angles (one per half-bond slot, 1: broken); *n their number. */
uint8_t *lattice_angle_states(struct model *m, size_t *n);

#endif
