/**
 * @file model.h
 * @brief The particle-model plug-in interface.
 *
 * A model (lattice, peridynamics, macro-particle, SPH, ...) is a table of
 * function pointers registered in models/registry.c and chosen at run time by
 * the deck's `model.type`.  The engine calls each hook once per step for the
 * whole particle set (never per pair), so the model's inner loops stay
 * inlined and vectorised.  Adding a model means adding a folder under
 * src/models/ and one line in the registry; no other model changes.
 *
 * Life cycle (see docs/architecture.md):
 *   create -> parse_material (per material) -> [core builds particles, masses]
 *   -> init (bonds / neighbour lists / state) -> precrack (per pre-crack)
 *   -> register_fields -> loop { compute_forces ; end_step } -> destroy.
 * Per step (velocity Verlet, integrator.c):
 *   half kick, drift, [advance_state] , zero f, compute_forces, boundary
 *   forces, half kick, velocity BCs, end_step, diagnostics.
 */
#ifndef SPALL_MODEL_H
#define SPALL_MODEL_H

#include <stdbool.h>
#include <stddef.h>

struct bond_list;
struct deck_node;
struct field_registry;
struct precrack;
struct sim;
struct spall_error;
struct model; /* opaque, defined by each model */

/** Energies summed over owned particles [J]. */
struct model_energy {
    double strain;      /**< recoverable (potential) energy */
    double dissipated;  /**< energy lost in the model: broken bonds, plastic work, friction */
};

#define MODEL_HISTORY_MAX 16

/** A small elastic free body of one model/formulation for the model
 *  contract test (tests/test_model_contract.c), defined in the model's own
 *  folder (*_fixture.c).  The test places the body (a disc or sphere of
 *  material `m` on the lattice, translated and rotated) and runs it.
 *  Allowances are for properties of the method only, each stated in `why`
 *  with its measured value. */
struct model_fixture {
    const char *label;   /**< e.g. "sph-total"; NULL ends the list */
    const char *deck;    /**< the deck's `model:` and `materials:` sections */
    const char *lattice; /**< lattice type (sets the dimension) */
    double spacing;      /**< lattice spacing [m] */
    double rotation_deg; /**< 2D rotation of the frame check; 0: a generic angle */
    double torque;       /**< allowed |sum r x f| / sum |r||f|; 0: round-off */
    const char *why;     /**< cause and measured value of any allowance */
};

struct model_ops {
    const char *name;    /**< deck `model.type` */
    const char *summary; /**< one line for `spall --help` */
    /** The model takes each particle's own volume and spacing from the fill
     *  (not the lattice's): bodies may then use other lattice types than
     *  the deck's `lattice:`, including the body-fitted rings and shells. */
    bool particle_volumes;

    /** Parse the `model:` mapping (keys other than `type`) and create the model. */
    int (*create)(struct model **out, struct sim *sim, const struct deck_node *params,
                  struct spall_error *err);
    /** Parse the model-specific keys of material @p index (the core already
     *  read `density`).  Impossible physics is refused here. */
    int (*parse_material)(struct model *m, struct sim *sim, int index,
                          const struct deck_node *node, struct spall_error *err);
    /** Particles exist (positions, volumes, masses from density): build bonds
     *  or neighbour lists, per-particle state; may adjust masses. */
    int (*init)(struct model *m, struct sim *sim, struct spall_error *err);
    /** Remove interactions crossing a pre-crack; optional (NULL: not supported). */
    int (*precrack)(struct model *m, struct sim *sim, const struct precrack *c, size_t *n_cut,
                    struct spall_error *err);
    /** Declare per-particle output fields. */
    int (*register_fields)(struct model *m, struct sim *sim, struct field_registry *reg,
                           struct spall_error *err);
    /** Add interaction forces into sim->p->f (already zeroed). */
    int (*compute_forces)(struct model *m, struct sim *sim, struct spall_error *err);
    /** Largest stable time step for the current state [s]. */
    double (*stable_dt)(const struct model *m, const struct sim *sim);
    /** After the step: irreversible updates (bond breaking, damage). */
    int (*end_step)(struct model *m, struct sim *sim, struct spall_error *err);
    /** Energies for diagnostics. */
    void (*energy)(const struct model *m, const struct sim *sim, struct model_energy *out);
    /** Extra `history.csv` columns; returns how many (<= MODEL_HISTORY_MAX). */
    size_t (*history)(const struct model *m, const struct sim *sim, const char **names,
                      double *values);
    /** Print derived constants (for the run log / calibrate); optional. */
    void (*describe)(const struct model *m, const struct sim *sim, char *buf, size_t len);
    void (*destroy)(struct model **m);
    /** Optional: integrate the model's own per-particle state (density,
     *  internal energy, deviatoric stress, ...).  Stage 0 (predictor) is
     *  called after the drift, before compute_forces of the new step; stage
     *  1 (corrector) after compute_forces and the second kick.  With the
     *  predictor-corrector integrator (seed 004 Eqs. 3.35-3.37) a model
     *  predicts state_n + dt rate_n at stage 0 and corrects to
     *  state_n + dt/2 (rate_n + rate_n+1) at stage 1. */
    int (*advance_state)(struct model *m, struct sim *sim, double dt, int stage,
                         struct spall_error *err);
    /** Number of pair interactions (bonds counted once) for throughput
     *  reports; optional (NULL: 0). */
    size_t (*interactions)(const struct model *m, const struct sim *sim);
    /** Optional: the model's bond list (CSR, BOND_BROKEN marks broken bonds),
     *  used for fragments (core/fragments.h); NULL hook or NULL result for
     *  unbonded models. */
    const struct bond_list *(*bonds)(const struct model *m);
    /** Contract-test fixtures, ended by a NULL label: every formulation of
     *  the model, each must pass tests/test_model_contract.c. */
    const struct model_fixture *fixtures;
};

/** Find a model by name; NULL if unknown. */
const struct model_ops *model_find(const char *name);
/** NULL-terminated list of registered model names (for messages). */
const char *const *model_names(void);

#endif
