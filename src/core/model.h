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
 *   create -> time_scheme -> parse_material (per material) -> [core builds
 *   particles, masses]
 *   -> init (bonds / neighbour lists / state) -> precrack (per pre-crack)
 *   -> register_fields -> loop { sim_step } -> destroy.
 *
 * Who owns what in a step: the engine's integrator (core/integrator.c) alone
 * moves x, changes v, t and dt and writes the engine's fields (damping,
 * energy account); a model computes forces and rates and changes its own
 * per-particle state only inside the hooks below, at these points of
 * sim_step (t -> t + dt):
 *   1. kick:   v += dt/2 f/m; prescribed velocities set
 *   2. drift:  x += dt v, then x += dt u for u = drift_velocity (XSPH) on
 *              particles whose velocity no BC prescribes
 *   3. predictor-corrector only: v_pred = v + dt/2 f/m;
 *              advance_state(MODEL_STAGE_PREDICT)
 *   4. f = 0; compute_forces (leapfrog: compute_forces_kick, which advances
 *      the state by dt at the drifted state before forming the forces);
 *      damping (the engine takes the coefficient); contact, loads, gravity,
 *      mass-proportional damping
 *   5. kick:   v += dt/2 f/m (predictor-corrector: from the unpredicted v);
 *      prescribed velocities set, reactions recorded
 *   6. predictor-corrector only: advance_state(MODEL_STAGE_CORRECT)
 *   7. end_step (bond breaking, damage); adaptive dt from stable_dt;
 *      instability checks (non-finite x or v; energy blow-up)
 */
#ifndef SPALL_MODEL_H
#define SPALL_MODEL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct bond_list;
struct deck_node;
struct field_registry;
struct field_state;
struct par_model_arrays;
struct par_spatial_model;
struct precrack;
struct sim;
struct spall_error;
struct time_scheme;
struct model; /* opaque, defined by each model */

/** Energies summed over owned particles [J]. */
struct model_energy {
    double strain;      /**< recoverable (potential) energy */
    double dissipated;  /**< energy lost in the model: broken bonds, plastic work, friction */
};

#define MODEL_HISTORY_MAX 16

/** Stages of model_ops.advance_state (predictor-corrector integrator). */
enum model_stage { MODEL_STAGE_PREDICT = 0, MODEL_STAGE_CORRECT = 1 };

/** A fixed plane a model enforces itself (model_ops.planes). */
struct model_plane {
    char name[32];     /**< e.g. "wall", "symmetry_x" */
    double point[3];   /**< a point of the plane [m] */
    double normal[3];  /**< unit, pointing to the particles' side */
};
#define MODEL_PLANES_MAX 4

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
    /** After the step: irreversible updates (bond breaking, damage).  It
     *  changes no velocity: the integrator's second kick has already
     *  summed the kinetic energy of the NaN check with them. */
    int (*end_step)(struct model *m, struct sim *sim, struct spall_error *err);
    /** Energies for diagnostics. */
    void (*energy)(const struct model *m, const struct sim *sim, struct model_energy *out);
    /** Extra `history.csv` columns; returns how many (<= MODEL_HISTORY_MAX). */
    size_t (*history)(const struct model *m, const struct sim *sim, const char **names,
                      double *values);
    /** Print derived constants (for the run log / calibrate); optional. */
    void (*describe)(const struct model *m, const struct sim *sim, char *buf, size_t len);
    void (*destroy)(struct model **m);
    /** Optional, called by the predictor-corrector integrator only (seed
     *  004 Eqs. 3.35-3.37): integrate the model's own per-particle state
     *  (density, internal energy, deviatoric stress, ...).  Stage
     *  MODEL_STAGE_PREDICT, after the drift and before compute_forces of
     *  the new step: state_n + dt rate_n; stage MODEL_STAGE_CORRECT, after
     *  the second kick: state_n + dt/2 (rate_n + rate_n+1). */
    int (*advance_state)(struct model *m, struct sim *sim, double dt, int stage,
                         struct spall_error *err);
    /** Optional, the leapfrog integrator's force call (state staggered on
     *  the velocities): from the drifted x_n+1 and v_n+1/2 form the rates,
     *  advance the per-particle state by @p dt with them (the "kick" of the
     *  state), then add the forces of the new state into sim->p->f.  The
     *  integrator calls it in place of compute_forces in every step; the
     *  initial force call (no step taken) is compute_forces.  One hook, not
     *  three, because the model fuses the three per particle. */
    int (*compute_forces_kick)(struct model *m, struct sim *sim, double dt,
                               struct spall_error *err);
    /** Optional: a velocity u [m/s] added to v in the drift, x += dt (v + u)
     *  (XSPH), for particles whose velocity no BC prescribes.  Returns false
     *  when there is none; else points u[d] at per-particle arrays (d < dim)
     *  that stay valid until the next force call. */
    bool (*drift_velocity)(const struct model *m, const struct sim *sim, const double *u[3]);
    /** Optional: the mass-proportional damping coefficient c [1/s] the model
     *  asks for (adaptive dynamic relaxation), read by the engine right
     *  after compute_forces and applied as F = -c m v.  Returns false to
     *  keep the engine's current coefficient. */
    bool (*damping)(const struct model *m, const struct sim *sim, double *c);
    /** Optional: the integrator, adaptive dt and default dt factor the model
     *  needs (@p ts holds the engine's defaults), read once by sim_set_model
     *  right after create; the deck's run keys, parsed later, still win. */
    void (*time_scheme)(const struct model *m, struct time_scheme *ts);
    /** Number of pair interactions (bonds counted once) for throughput
     *  reports; optional (NULL: 0). */
    size_t (*interactions)(const struct model *m, const struct sim *sim);
    /** Optional: the model's bond list (CSR, BOND_BROKEN marks broken bonds),
     *  used for fragments (core/fragments.h); NULL hook or NULL result for
     *  unbonded models. */
    const struct bond_list *(*bonds)(const struct model *m);
    /** Optional: the fixed planes the model enforces by itself, not as
     *  rigid bodies of core/rigid.h (the SPH wall and symmetry planes),
     *  for the frame index to draw (io/output_xdmf.c).  Fills at most
     *  MODEL_PLANES_MAX and returns the count. */
    size_t (*planes)(const struct model *m, const struct sim *sim, struct model_plane *out);
    /** Register the model's restart state (core/field_state.h): every array
     *  and counter that carries information from one step to the next and
     *  is not rebuilt from the deck by create/init/precrack (bond states,
     *  damage and plastic history, random-stream counters, partner lists
     *  with their set_rows callback).  Called after sim_prepare; a
     *  checkpoint written after step n and loaded into a freshly prepared
     *  run must continue bit for bit.  NULL: the model cannot restart. */
    int (*register_state)(struct model *m, struct sim *sim, struct field_state *fs,
                          struct spall_error *err);
    /** Contract-test fixtures, ended by a NULL label: every formulation of
     *  the model, each must pass tests/test_model_contract.c. */
    const struct model_fixture *fixtures;
    /** Optional (distributed runs, core/parallel/decomp.h): the rank keeps
     *  the particles keep[0, n_keep) (old indices; the first @p n_owned are
     *  its own, the rest ghosts), renumbered 0..n_keep-1 in that order
     *  (new_of_old[i]: the new index, or negative when dropped).  The model
     *  renumbers its rows and per-particle arrays that are NOT stored fields
     *  of the registry (the engine compacts those); the rows of owned
     *  particles keep all their partners in their order, ghost rows may be
     *  emptied.  Refuses what it cannot distribute (SPALL_ERR_INPUT); with
     *  @p keep NULL it only answers that question, changing nothing (asked
     *  before any output exists; a model whose damping hook is active
     *  refuses here, the engine does not distribute that estimate)
     *  before any output exists).  NULL: the model runs on one rank only. */
    int (*localize)(struct model *m, struct sim *sim, const size_t *keep, size_t n_keep,
                    size_t n_owned, const int64_t *new_of_old, struct spall_error *err);
    /** Optional (distributed runs): the fixed bond list whose partners are a
     *  particle's ghosts and whose row lengths weight the partition, for a
     *  model whose `bonds` hook is NULL (no fragments); else `bonds` is used. */
    const struct bond_list *(*halo_bonds)(const struct model *m);
    /** Optional (distributed runs with rebalancing, core/parallel/migrate.h):
     *  lend the migration the model's bond list and its per-particle and
     *  per-half-bond arrays that are not stored fields of the registry, so
     *  that a particle moving to another rank takes them along.  Called
     *  after localize, and once at set-up to learn whether the model's
     *  options allow migration (an error names the option that does not).
     *  NULL: the model's particles cannot migrate. */
    int (*migrate_arrays)(struct model *m, struct par_model_arrays *a, struct spall_error *err);
    /** Optional (distributed runs): after a migration (the lent arrays
     *  replaced, owned then ghosts in ascending gid, owned rows resolved),
     *  rebuild what the model derives from them (e.g. SPH's reference list
     *  and the split of its rows).  A failure stops every rank. */
    int (*migrated)(struct model *m, struct sim *sim, struct spall_error *err);
    /** Optional (distributed runs, core/parallel/spatial.h): the model
     *  finds its partners by a neighbour search, not through fixed bonds.
     *  It names its interaction range and skin, the positions its partner
     *  list was built at, and its per-particle arrays that ghosts carry;
     *  the engine then keeps as ghosts the particles of other ranks within
     *  range + skin of the owned ones and rebuilds that set (with
     *  spatial_rebuilt) when a particle has moved skin/2 since (or when
     *  the model's own test, sp->rebuild_due, says so).  Returns > 0 when
     *  this run has no spatial ghosts (e.g. SPH's total-Lagrangian form). */
    int (*spatial_ghosts)(struct model *m, struct par_spatial_model *sp);
    /** Optional, with spatial_ghosts: the ghosts were rebuilt and the
     *  local arrays re-laid out (owned particles unchanged, then the new
     *  ghosts in ascending global id, with their owners' records).  The
     *  model rebuilds its partner list from the build positions; @p moved
     *  false: the positions are those of its last build (after the
     *  partition), so the list is not a new one. */
    int (*spatial_rebuilt)(struct model *m, struct sim *sim, bool moved, struct spall_error *err);
    /** Optional (distributed set-up, core/parallel/setup_dist.h): an upper
     *  bound of the longest bond init will create [m], known after create;
     *  each rank then builds its region with two such ranges of halo.
     *  NULL: the model's set-up is replicated on every rank. */
    double (*setup_range)(const struct model *m, const struct sim *sim);
    /** Optional, with setup_range: after the distributed set-up's
     *  localisation, make the model's tables of distinct per-bond values
     *  the same on every rank (par_setup_merge_table), so that migrated
     *  bonds name the same values.  Collective. */
    int (*setup_tables)(struct model *m, struct sim *sim, struct spall_error *err);
    /** The model never bonds particles of different bodies (the lattice
     *  model's shells): the distributed set-up then builds each body's
     *  window alone wherever the bodies lie.  false (a radius search, as
     *  peridynamics): only bodies more than a range apart are distributed. */
    bool bonds_within_bodies;
    /** compute_forces writes the force of every owned particle, reading
     *  none: the integrator then does not clear them before the call (one
     *  write of the force arrays less per step).  Whatever it writes must
     *  be what adding to cleared forces gives (0 + f: the same bits); the
     *  contact, loads and body forces are added after it. */
    bool sets_forces;
};

#endif
