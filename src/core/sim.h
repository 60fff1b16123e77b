/**
 * @file sim.h
 * @brief The simulation context passed explicitly everywhere (no globals).
 *
 * Owns the particles, the field registry, the model instance, materials,
 * groups, boundary conditions, probes and the energy account.  Built from a
 * deck by io/deck_build.c or by hand through the library API.
 */
#ifndef SPALL_SIM_H
#define SPALL_SIM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/lattice_gen.h"
#include "core/time_function.h"

struct bond_list;
struct deck_node;
struct field_registry;
struct model;
struct model_ops;
struct par_decomp;
struct particle_contact;
struct particles;
struct precrack;
struct rigid_set;
struct spall_error;

#define SPALL_NAME_LEN 64

struct material {
    char name[SPALL_NAME_LEN];
    double density; /**< kg/m^3 */
};

/** A named set of particles (indices into the particle arrays). */
struct group {
    char name[SPALL_NAME_LEN];
    size_t n;
    size_t *idx;
};

enum bc_kind {
    BC_FIXED,     /**< listed velocity components held at 0 */
    BC_VELOCITY,  /**< listed components follow value * f(t) */
    BC_FORCE,     /**< total force value * f(t) shared equally by the group's particles */
    BC_TRACTION   /**< traction value * f(t) [Pa] times area, shared equally */
};

struct bc {
    enum bc_kind kind;
    int group;          /**< index into sim->groups */
    unsigned comp_mask; /**< bit d set: component d is prescribed */
    double value[3];    /**< m/s (velocity), N (force), Pa (traction) */
    double area;        /**< traction: loaded area [m^2] */
    struct time_function tf;
    double reaction[3]; /**< force the BC applied to the group this step [N] */
    double work;        /**< work done on the body so far [J] */
};

struct probe {
    char name[SPALL_NAME_LEN];
    double pos[3];   /**< requested point */
    size_t particle; /**< nearest particle at start */
};

/** Running energy account [J]. */
struct energy_account {
    double kinetic;
    double strain;       /**< model potential energy */
    double model_dissipated; /**< broken bonds, plasticity (from the model) */
    double damping;      /**< removed by mass-proportional damping */
    double external;     /**< work of boundary conditions and gravity */
    double initial_total;
    double balance;      /**< kinetic + strain + dissipated + damping - external - initial */
};

/** Time integrators (all second order, same positions):
 *  verlet: forces of step n+1 see the half-step velocities;
 *  predictor_corrector: they see the predicted v_n + dt a_n ([Meng2021]
 *  Eqs. 3.35-3.37), which velocity-dependent forces (artificial viscosity)
 *  expect; the model's state is predicted and corrected around the force
 *  call (model_ops.advance_state);
 *  leapfrog: velocity Verlet with the model's state staggered on the
 *  velocities, advanced by dt inside the force call of each step
 *  (model_ops.compute_forces_kick; sph_leapfrog.c). */
enum integrator_kind { INTEGRATOR_VERLET, INTEGRATOR_PREDICTOR_CORRECTOR, INTEGRATOR_LEAPFROG };

/** The time integration a model asks for (model_ops.time_scheme); the
 *  engine's default is velocity Verlet, fixed dt, dt_factor 0.5. */
struct time_scheme {
    enum integrator_kind integrator;
    bool adaptive_dt; /**< dt = dt_factor * stable_dt every step */
    double dt_factor; /**< default factor on the stable step (run.dt_factor wins) */
};

struct sim {
    int dim;
    enum integrator_kind integrator;
    struct particles *p;
    struct field_registry *fields;
    const struct model_ops *ops;
    struct model *model;

    struct material *materials;
    size_t n_materials;
    struct group *groups;
    size_t n_groups;
    struct bc *bcs;
    size_t n_bcs;
    struct probe *probes;
    size_t n_probes;
    struct precrack *precracks; /**< applied by sim_prepare after model init */
    size_t n_precracks;
    size_t n_precut;            /**< bonds removed by pre-cracks */

    struct lattice_spec lattice; /**< lattice used to fill the body */
    double thickness;            /**< 2D: plate thickness [m]; 1D: cross-section area [m^2] */
    bool thickness_given;        /**< false: the model's default thickness was used */
    bool axisymmetric;           /**< 2D (x = r, y = z) rings: set by the model (sph) */

    double gravity[3];    /**< m/s^2 */
    double damping;       /**< mass-proportional damping coefficient [1/s] */

    double t;             /**< current time [s] */
    double dt;            /**< time step [s]: the nominal one (stiffnesses scaled by
                               the step, e.g. impactor penalties, use it) */
    double dt_step;       /**< length of the step being taken [s]: dt, or shorter where
                               the step lands on end_time or a frame time (what the
                               hooks that integrate over the step use: sim_step_dt) */
    double dt_limit;      /**< stability limit at start [s] */
    double dt_factor;     /**< dt = dt_factor * dt_limit unless the deck sets dt */
    bool dt_override;     /**< allow dt above the limit (explicit deck key) */
    bool adaptive_dt;     /**< re-evaluate dt = dt_factor * stable_dt every step
                               (n_steps is then only an estimate) */
    double end_time;      /**< s; the step that would pass it is shortened to land on it */
    double stop_time;     /**< the driver's next output time (a frame): the step that would
                               pass it is split to land on it (0 or <= t: none) */
    double dt_rest;       /**< fixed dt: the rest of a step split at stop_time, taken next so
                               the steps stay on the grid k dt (0: none) */
    long step;
    long n_steps;         /**< steps to end_time (fixed dt: exact with n_split; adaptive
                               dt: the estimate at start) */
    long n_split;         /**< fixed dt: steps split at an output time so far (each adds
                               one step to the run) */

    double energy_blowup; /**< stop if total energy exceeds this factor x reference */
    long energy_check_every; /**< sim_step checks the full energy account for a
                                  blow-up every this many steps and at the last (0:
                                  never; the kinetic energy alone is checked every
                                  step; the run driver: its history interval) */
    struct energy_account energy;
    bool stress_skip;     /**< nothing reads the model's per-particle stress (virial)
                               after the coming step: a model may leave it as it was
                               (as LAMMPS forms its virial only on the steps that
                               output it).  Set by the run driver (io/run.c) before
                               each step; false (computed every step) otherwise */
    double *v_half[3];    /**< predictor-corrector scratch (owned) */
    double *drift_save;   /**< positions of velocity-BC members over the fused kick
                               and drift (core/integrator.c) */
    size_t drift_save_cap;
    double *kinetic_part; /**< the second kick's kinetic-energy block sums, 3 per block
                               (core/step_passes.h, step_kick_sum) */
    size_t kinetic_part_cap;
    bool kinetic_fused;   /**< the step's second kick formed kinetic_part, and nothing
                               after it changed a velocity */
    uint8_t *no_drift_velocity; /**< 1: a BC prescribes the particle's velocity, the
                                     model's drift velocity does not move it (owned) */
    uint64_t seed;        /**< random seed for stochastic features */
    struct rigid_set *rigid; /**< rigid impactors / supports (core/rigid.h), may be NULL */
    struct particle_contact *pcontact; /**< particle-particle contact (core/contact_particles.h), may be NULL */
    struct par_decomp *par; /**< distributed run (core/parallel/decomp.h); NULL: serial */
    struct par_setup *setup; /**< distributed set-up window (core/parallel/setup_dist.h);
                                  NULL: the body built whole */
};

/** Empty context for a @p dim-dimensional run. */
int sim_create(struct sim **out, int dim, struct spall_error *err);
void sim_destroy(struct sim **s);

/** Add a material; returns its index in *index. Refuses duplicates. */
int sim_add_material(struct sim *s, const char *name, double density, int *index,
                     struct spall_error *err);
int sim_find_material(const struct sim *s, const char *name);
/** Add a group holding copies of @p idx; refuses duplicate names. */
int sim_add_group(struct sim *s, const char *name, const size_t *idx, size_t n, int *index,
                  struct spall_error *err);
int sim_find_group(const struct sim *s, const char *name);
int sim_add_bc(struct sim *s, const struct bc *bc, struct spall_error *err);
int sim_add_precrack(struct sim *s, const struct precrack *c, struct spall_error *err);
int sim_add_probe(struct sim *s, const char *name, const double pos[3], struct spall_error *err);

/** Create the model @p ops (from the registry: model_find in
 *  models/registry.c, which the core does not call) with the deck's params
 *  (may be NULL); then take the model's time scheme (integrator, adaptive
 *  dt, dt factor). */
int sim_set_model(struct sim *s, const struct model_ops *ops, const struct deck_node *params,
                  struct spall_error *err);

/** After particles, masses and materials exist: init the model, register
 *  fields, compute the stable dt and initial forces/energies.  Refuses a
 *  dt above the limit unless dt_override is set. */
int sim_prepare(struct sim *s, struct spall_error *err);

/** Compute the forces of the initial state (called by sim_prepare) and
 *  the initial energy account. */
int sim_initial_forces(struct sim *s, struct spall_error *err);

/** Advance one step with s->integrator (the sequence is in core/model.h).
 *  Detects non-finite positions or velocities and an energy blow-up
 *  (mechanical energy above energy_blowup times the energy put in: the
 *  kinetic part every step, the full account every energy_check_every
 *  steps and at the last, after which the account is current) and returns
 *  SPALL_ERR_UNSTABLE naming step, time and particle. */
int sim_step(struct sim *s, struct spall_error *err);

/** True when the run has reached its end (steps, or end_time with an
 *  adaptive time step). */
bool sim_done(const struct sim *s);

/** The length of the step being taken (hooks that integrate over the step:
 *  heat conduction, Langevin noise, a stiffness estimate from a position
 *  change); s->dt outside a step. */
static inline double sim_step_dt(const struct sim *s)
{
    return s->dt_step > 0.0 ? s->dt_step : s->dt;
}

/** Length of the next step: dt, or shorter where the step would pass
 *  end_time or stop_time (*landing: the time it lands on, else NAN); a
 *  fixed-dt step after a split takes the rest of the split step. */
double sim_step_length(const struct sim *s, double *landing);

/** Recompute the energy account from the current state. */
void sim_update_energy(struct sim *s);

/** Reflect particle @p i in the plane x_k = 0 (k < dim) of the current
 *  configuration: every stored field of the registry negates its components
 *  odd in plane k (their declared enum field_parity: position, velocity,
 *  force and the models' vectors and tensors), and the integrator negates
 *  its own copies of the velocity (predictor-corrector v_half).  A second
 *  call with the same i, k restores the state bit for bit.  For models
 *  whose geometry is symmetric about the plane (the axis r = 0 of
 *  axisymmetric runs: the mirror image of a ring is the same ring). */
void sim_reflect_particle(struct sim *s, size_t i, int k);

/** Inside a model's force call: the velocities this step's positions were
 *  drifted with and, in *dt, the length of that drift (x_{n+1} = x_n + dt u),
 *  so a model can recover x_n without storing it (e.g. to book the energy of
 *  a bond that breaks within the step).  Velocity Verlet and leapfrog: the
 *  half-step velocities in p->v; predictor-corrector: the engine's copy
 *  v_half (p->v then holds the prediction).  A model drift velocity (XSPH)
 *  is not included. */
double *const *sim_drift_velocities(const struct sim *s, double *dt);

/** Resultant force [N] the constraints/loads applied to group @p g this step. */
void sim_group_reaction(const struct sim *s, int g, double out[3]);

#endif
