/**
 * @file sim.h
 * @brief Public C API of libspall: set up a simulation from a deck (a YAML
 *        file or a YAML string held in memory), advance it, read its
 *        per-particle fields and energies, write HDF5/XDMF frames.
 *
 * Every fallible call returns an enum spall_status (SPALL_OK = 0) and fills
 * the caller's struct spall_error (initialise it with `= {0}`; NULL drops the
 * message) with one line naming the cause, and err->key with the deck key it
 * is about.  The library never exits and prints nothing.  Units are SI.
 * The deck keys are those of `spall run` (docs/decks.md); docs/api.md has a
 * walk-through and examples/api/ a program using this header.  Without a
 * deck: spall/setup.h sets the same keys by C calls (spall_sim_create_setup).
 *
 * Threads: OpenMP; the caller sets the count (OMP_NUM_THREADS or
 * omp_set_num_threads) - the deck's run.threads applies to `spall run` only.
 * One struct spall_sim may be used by one thread at a time; distinct
 * simulations are independent.
 */
#ifndef SPALL_SIM_API_H
#define SPALL_SIM_API_H

#include <stdbool.h>
#include <stddef.h>

#include "spall/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A simulation built from a deck (opaque). */
struct spall_sim;

/** Read the YAML deck at @p path and build the simulation: particles, model,
 *  materials, boundary conditions, the stable time step and the initial
 *  forces and energies.  Input errors name FILE:LINE:COLUMN and come back as
 *  SPALL_ERR_INPUT (or SPALL_ERR_PHYSICS for impossible physics).  The
 *  set-up checks of `spall run` apply (unit slips, impactors, walls and
 *  symmetry planes inside a body, probes off every body, a large initial
 *  strain energy; docs/decks.md "Set-up check", deck key run.allow), not
 *  the cost check.  Nothing is written to disk.  *out is NULL on failure. */
int spall_sim_create_file(struct spall_sim **out, const char *path, struct spall_error *err);

/** As spall_sim_create_file, for deck text in memory; @p name stands for
 *  the file name in messages (e.g. "plate.yaml"; NULL: "<string>"). */
int spall_sim_create_string(struct spall_sim **out, const char *yaml, const char *name,
                            struct spall_error *err);

/** Free everything (closing an output directory); *s becomes NULL.  NULL
 *  and an already destroyed handle are accepted. */
void spall_sim_destroy(struct spall_sim **s);

/** Advance @p n steps (n >= 0), or fewer when the run goes unstable
 *  (SPALL_ERR_UNSTABLE naming step, time and particle; the state is that
 *  of the failing step, frames written so far stay valid). */
int spall_sim_step(struct spall_sim *s, long n, struct spall_error *err);

/** Step until the simulated time reaches @p t (the step that crosses t is
 *  the last; nothing happens if t is already reached; the engine shortens
 *  the steps that would cross run.end_time or a frame time to land on
 *  them).  Steps past
 *  the deck's run.end_time are allowed: the deck's end is a default, not a
 *  limit.  A frame is written at the deck's output interval if an output
 *  directory is open (spall_sim_output_open). */
int spall_sim_run_to(struct spall_sim *s, double t, struct spall_error *err);

/** Step until the deck's end (run.end_time or run.steps), writing frames
 *  as spall_sim_run_to does, and the last one at the end. */
int spall_sim_run(struct spall_sim *s, struct spall_error *err);

/** Set-up findings that do not refuse the run (the set-up checks of
 *  `spall run`, which the create functions run: a refusal is their error).
 *  Today the warning is a large run (particle-steps or output size); the
 *  deck's `run.allow: [cost]` silences it, as for `spall run`. */
size_t spall_sim_warning_count(const struct spall_sim *s);
/** Warning @p k as one line "FILE:L:C: ... (to silence this: run.allow:
 *  [NAME])"; NULL when @p k is out of range. */
const char *spall_sim_warning(const struct spall_sim *s, size_t k);
/** The cost estimate of the deck's run, one line ("N particles x M steps =
 *  P particle-steps; output about B (F frames)"), as run.log's
 *  setup_estimate. */
const char *spall_sim_estimate(const struct spall_sim *s);

/** Where a simulation stands. */
struct spall_sim_info {
    int dim;                 /**< 1, 2 or 3 */
    bool axisymmetric;       /**< 2D rings about the axis x = r = 0 */
    const char *model;       /**< deck model.type ("lattice", "pd", ...) */
    size_t particles;        /**< particles owned by this process */
    size_t interactions;     /**< pair interactions (bonds counted once); 0 if unbonded */
    double time;             /**< simulated time [s] */
    long step;               /**< steps done */
    double dt;               /**< current time step [s] */
    double dt_limit;         /**< stability limit at start [s] */
    double end_time;         /**< the deck's end [s] */
    bool done;               /**< the deck's end is reached */
};
void spall_sim_get_info(const struct spall_sim *s, struct spall_sim_info *info);

/** Energy account [J] at the current state (recomputed on the call). */
struct spall_energy {
    double kinetic;
    double strain;         /**< the model's potential energy (and contact) */
    double dissipated;     /**< broken bonds, plasticity */
    double damping;        /**< removed by mass-proportional damping */
    double external;       /**< work of boundary conditions and gravity */
    double balance;        /**< kinetic + strain + dissipated + damping - external - initial */
};
void spall_sim_energy(struct spall_sim *s, struct spall_energy *e);

/** A per-particle field of the registry (position, velocity, damage, ...). */
struct spall_field_info {
    char name[48];
    char unit[16];  /**< SI unit, "1" for none */
    int ncomp;      /**< components per particle (1..9) */
    bool output;    /**< may be written to frames (output.fields) */
};

/** Number of registered fields, and field @p k of them (k < count). */
size_t spall_sim_field_count(const struct spall_sim *s);
int spall_sim_field_at(const struct spall_sim *s, size_t k, struct spall_field_info *info,
                       struct spall_error *err);
/** Look a field up by name; SPALL_ERR_INPUT listing the names if unknown. */
int spall_sim_field_info(const struct spall_sim *s, const char *name,
                         struct spall_field_info *info, struct spall_error *err);

/** Copy field @p name of every particle into @p out, interleaved
 *  (out[i * ncomp + c]) as doubles whatever the stored type; @p capacity is
 *  the length of @p out in doubles and must be >= particles x ncomp. */
int spall_sim_field_read(const struct spall_sim *s, const char *name, double *out,
                         size_t capacity, struct spall_error *err);

/** Resultant force [N] the boundary conditions applied this step to the
 *  particle group @p group (deck `groups:`); out[d] for d < dim. */
int spall_sim_group_reaction(const struct spall_sim *s, const char *group, double out[3],
                             struct spall_error *err);

/** Open @p dir for HDF5 frames and the XDMF index with the deck's
 *  output.fields (or the defaults), as `spall run` writes them; an existing
 *  non-empty directory is refused unless @p overwrite.  The current state
 *  is written as the first frame.  One directory per simulation. */
int spall_sim_output_open(struct spall_sim *s, const char *dir, bool overwrite,
                          struct spall_error *err);
/** Write the current state as one more frame (needs spall_sim_output_open). */
int spall_sim_write_frame(struct spall_sim *s, struct spall_error *err);
/** Frames written so far (0 without an output directory). */
size_t spall_sim_frames(const struct spall_sim *s);

#ifdef __cplusplus
}
#endif

#endif
