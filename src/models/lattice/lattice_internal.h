/**
 * @file lattice_internal.h
 * @brief State of the lattice model shared by lattice_model.c (life cycle),
 *        lattice_forces.c (hot loops) and lattice_calib.c (patch test).
 *        Not part of the public interface.
 */
#ifndef SPALL_LATTICE_INTERNAL_H
#define SPALL_LATTICE_INTERNAL_H

#include "models/lattice/lattice.h"
#include "models/lattice/lattice_laws.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct bond_list;
struct lattice_thermal;
struct sim;
struct spall_error;

#define LATTICE_NO_ANGLE 0xFFu

/** Law of the bonds between two materials (deck `model.interfaces`, lattice_interface.c). */
struct lattice_interface {
    char a[64], b[64];  /**< material names */
    int ia, ib;         /**< their indices (-1 until init resolves them) */
    double eps_t;       /**< tensile failure strain (0: from strength, or the default) */
    double strength;    /**< tensile strength [Pa] (0: none) */
    double eps_c;       /**< compressive failure strain (0: the default) */
    double stiffness;   /**< factor on the pair's series stiffness */
};

/** Upper partners per stencil of the once-per-bond loop (FCC: 6). */
#define LATTICE_STENCIL_MAX 8

/** A row's slots: nl lower partners, then nu upper ones at offsets j - i
 *  (ascending); on a regular lattice whole runs of rows share one
 *  (lattice_half.c, "stencil runs"). */
struct lattice_stencil {
    size_t nl, nu;                     /**< lower and upper partners */
    size_t off[LATTICE_STENCIL_MAX];   /**< j - i of the upper ones */
};

/** Owned rows [a, b) with stencil st. */
struct lattice_run {
    size_t a, b, st;
};

struct model {
    struct sim *sim; /**< borrowed */
    struct lattice_options opt;
    int dim;
    int layers;       /**< resolved */
    bool angular;     /**< angular springs present */
    bool honeycomb;   /**< triple honeycomb: bond type = family (lattice_honeycomb.c) */
    size_t n_mat;
    struct lattice_material *mat;
    struct lattice_curve *curves;    /**< view: curves[i] = mat[i].curve (for the law params) */
    struct lattice_law_params lp;
    struct lattice_bond_law *pair;   /**< [(ma * n_mat + mb) * LATTICE_MAX_TYPES + type] */
    double *mat_k_phi;               /**< per material */
    double *mat_k_area;              /**< per material: triangle-area stiffness [J] */
    double *mat_dphi_c, *mat_dphi_t; /**< per material, INFINITY: never breaks */

    struct bond_list *bl;
    /* angles, indexed by the slot of their first arm (counter-clockwise
     * from arm a to arm b = row start + ang_b[slot]) */
    uint8_t *ang_b;       /**< local index of arm b in the row, LATTICE_NO_ANGLE if none */
    double *ang_phi0;     /**< reference angle [rad] */
    uint8_t *ang_state;   /**< 1: broken */
    double *ang_buf;      /**< 2 per slot: force on the slot's partner from angles at the row's particle */

    double *kappa;        /**< softening law: per half-bond history (largest strain beyond e0) */
    double *diss;         /**< per particle: energy released by its broken bonds/angles [J] */
    struct lattice_thermal *th; /**< thermal lattice (lattice_thermal.c); NULL: none */
    const double *kscale; /**< per half-bond stiffness factor E(T)/E_ref, owned by th;
                               NULL: none (youngs_modulus_table absent) */
    size_t n_half;
    struct lattice_interface *ifc; /**< material-pair bond laws (lattice_interface.c) */
    size_t n_ifc;
    /* the once-per-bond linear loop (lattice_half.c): what the row check
     * found for the list of generation half_gen with half_n owned rows */
    bool half_known;      /**< false: check the rows again (new list) */
    unsigned long half_gen;
    size_t half_n;
    size_t half_ring;     /**< ring entries per thread (power of 2); 0: rows unsuited */
    double *half_buf;     /**< the threads' rings of row sums, all zero between calls */
    size_t half_buf_len;  /**< doubles in half_buf */
    bool half_off;        /**< lattice_set_row_loop: the row loop only */
    bool half_used;       /**< the last force call took the once-per-bond loop */
    size_t half_stencil_rows; /**< ... and took this many rows in stencil blocks */
    struct lattice_stencil *half_st; /**< the distinct stencils of the runs */
    size_t half_n_st;
    struct lattice_run *half_runs;   /**< ascending, disjoint */
    size_t half_n_runs;
    bool initialised;
};

/* lattice_interface.c */
struct deck_node;
/** Read `model.interfaces` (names only; resolved at init). */
int lattice_interfaces_parse(struct model *m, const struct deck_node *params,
                             struct spall_error *err);
/** Material indices of the interfaces (init, before the pair table). */
int lattice_interfaces_resolve(struct model *m, const struct sim *sim, struct spall_error *err);
/** Overwrite the pair table's entries of the interfaces (after each rebuild). */
void lattice_interfaces_apply(struct model *m);

/* lattice_restart.c */
struct field_state;
int lattice_register_state(struct model *m, struct sim *sim, struct field_state *fs,
                           struct spall_error *err);

/* lattice_localize.c: model_ops.localize (distributed runs) */
int lattice_localize(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                     size_t n_owned, const int64_t *new_of_old, struct spall_error *err);
struct par_model_arrays;
int lattice_migrate_arrays(struct model *m, struct par_model_arrays *a, struct spall_error *err);
int lattice_migrated(struct model *m, struct sim *sim, struct spall_error *err);
struct model_energy;

/* lattice_half.c */
/** Ring entries per thread for the once-per-bond linear loop over the
 *  owned rows of the current list, 0 when its rows do not allow it
 *  (cached until the list changes). */
size_t lattice_half_ring(struct model *m, const struct sim *sim);

/* lattice_forces.c */
int lattice_compute_forces(struct model *m, struct sim *sim, struct spall_error *err);
/* The same forces written over the owned ones instead of added (the same
 * bits as on cleared forces; f is not read): the model's compute_forces
 * (model_ops.sets_forces). */
int lattice_set_forces(struct model *m, struct sim *sim, struct spall_error *err);
/** Energy [J] (half of each bond + the angles centred at i) and virial
 *  stress (tension positive; 1D: xx; 2D: xx yy xy; 3D: xx yy zz xy yz xz)
 *  of particle i from the current positions; changes nothing. */
void lattice_particle_eval(const struct model *m, const struct sim *sim, size_t i,
                           double *energy, double *stress);

/* lattice_softening.c */
struct deck_node;
/** Softening-law material keys (tensile_strength | onset_strain,
 *  fracture_energy | failure_strain = @p eps, already read) into @p mt. */
int lattice_soft_parse(const struct deck_node *node, const char *what, double eps,
                       struct lattice_material *mt, struct spall_error *err);

/* lattice_material.c */
/** Free the arrays of a piecewise-linear curve and zero it. */
void lattice_curve_free(struct lattice_curve *c);
/** model_ops.parse_material of the lattice model: the material keys of the
 *  run's axial law, thermal keys, calibration into material @p index. */
int lattice_parse_material(struct model *m, struct sim *sim, int index,
                           const struct deck_node *node, struct spall_error *err);

#endif
