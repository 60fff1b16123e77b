/**
 * @file setup.h
 * @brief Set up a simulation by C calls, without a YAML deck: particles
 *        from the lattice generator filling a shape, materials, the model,
 *        groups, boundary conditions, the run's end and output settings.
 *
 * A struct spall_setup collects settings; spall_sim_create_setup (below)
 * builds a struct spall_sim (include/spall/sim.h) from it, which then runs
 * and is read exactly as one made from a deck.  Every setting is a key of
 * the deck reference (docs/decks.md) given by its key path (the syntax of
 * spall/error.h: "run.end_time", "materials.steel.density",
 * "boundary_conditions[0].group"), so every model and option a deck offers
 * is reachable; the typed helpers below set the common ones.  The settings
 * go through the checks a deck goes through, so a simulation set up by
 * calls and one read from the equivalent deck are the same simulation
 * (docs/api.md, tests/api_install.sh compares their histories).
 *
 * Sequences: "[k]" addresses item k; k equal to the current length appends
 * one ("bodies[0].geometry" on an empty setup starts the list).  A setter
 * on a key that holds a value replaces it.
 *
 * Errors: a malformed key path, a key path that crosses a value of another
 * kind, or a bad argument is refused at the setter (SPALL_ERR_INPUT, err->key
 * the path).  Values are checked by spall_sim_create_setup; its messages
 * read "spall_setup:N:1: ..." where N counts the setter calls (1 = the
 * first call on this setup) and name the key, and err->key holds its path.
 */
#ifndef SPALL_SETUP_API_H
#define SPALL_SETUP_API_H

#include <stddef.h>

#include "spall/error.h"
#include "spall/sim.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Settings of a simulation (opaque). */
struct spall_setup;

/** An empty setup; *out is NULL on failure (SPALL_ERR_NOMEM). */
int spall_setup_create(struct spall_setup **out, struct spall_error *err);
/** Free it; *s becomes NULL.  NULL is accepted. */
void spall_setup_destroy(struct spall_setup **s);

/* ---- any deck key ---------------------------------------------------- */

/** A number (written with 17 significant digits: the value read back is
 *  @p value exactly; integer keys take integral values). */
int spall_setup_number(struct spall_setup *s, const char *key, double value,
                       struct spall_error *err);
/** A word or name ("lattice", "triangular", "top"), or true / false. */
int spall_setup_text(struct spall_setup *s, const char *key, const char *value,
                     struct spall_error *err);
/** A list of @p n numbers (a point, a vector). */
int spall_setup_numbers(struct spall_setup *s, const char *key, const double *values, size_t n,
                        struct spall_error *err);
/** A list of @p n words (output.fields, components [x, y]). */
int spall_setup_texts(struct spall_setup *s, const char *key, const char *const *values,
                      size_t n, struct spall_error *err);

/** Items of the list (or keys of the mapping) at @p key; 0 when the key is
 *  not set or holds one value (so "LIST[spall_setup_length(s, LIST)]..."
 *  appends an item). */
size_t spall_setup_length(const struct spall_setup *s, const char *key);

/* ---- typed helpers (each sets the deck keys named) --------------------- */

/** model.type: "lattice", "peridynamics", "macroparticle", "sph". */
int spall_setup_model(struct spall_setup *s, const char *type, struct spall_error *err);

/** An elastic-brittle material; a field left 0 is not set (its key keeps
 *  the model's default or is reported missing). */
struct spall_material {
    double density;          /**< [kg/m^3] */
    double youngs_modulus;   /**< [Pa] */
    double poisson_ratio;    /**< [1] */
    double tensile_strength; /**< [Pa] */
    double fracture_energy;  /**< [J/m^2] */
};
/** materials.NAME.{density, youngs_modulus, poisson_ratio, tensile_strength,
 *  fracture_energy}. */
int spall_setup_material(struct spall_setup *s, const char *name,
                         const struct spall_material *m, struct spall_error *err);

/** lattice.{type, spacing}: the generator that fills the bodies
 *  ("triangular", "square", "hexagonal" in 2D; "fcc", "sc" ... in 3D). */
int spall_setup_lattice(struct spall_setup *s, const char *type, double spacing,
                        struct spall_error *err);

/** Shapes of geometry.NAME: an axis-aligned box of @p dim (2 or 3)
 *  coordinates, a circle (2D) / sphere (3D), the difference a - b. */
int spall_setup_box(struct spall_setup *s, const char *name, int dim, const double *min,
                    const double *max, struct spall_error *err);
int spall_setup_circle(struct spall_setup *s, const char *name, int dim, const double *center,
                       double radius, struct spall_error *err);
int spall_setup_difference(struct spall_setup *s, const char *name, const char *a,
                           const char *b, struct spall_error *err);

/** body.{geometry, material}: the lattice fills the shape @p geometry with
 *  @p material (more bodies: the "bodies[k]" keys). */
int spall_setup_body(struct spall_setup *s, const char *geometry, const char *material,
                     struct spall_error *err);

/** groups.NAME.box: the particles inside a box (for boundary conditions). */
int spall_setup_group_box(struct spall_setup *s, const char *name, int dim, const double *min,
                          const double *max, struct spall_error *err);

/** Appends to boundary_conditions: prescribed velocity @p value [m/s] on
 *  every component of @p dim for @p group, ramped linearly from 0 over
 *  @p ramp seconds (0: applied at once). */
int spall_setup_velocity_bc(struct spall_setup *s, const char *group, int dim,
                            const double *value, double ramp, struct spall_error *err);

/** run.end_time [s]. */
int spall_setup_end_time(struct spall_setup *s, double end_time, struct spall_error *err);

/* ---- the simulation --------------------------------------------------- */

/** Build the simulation the settings describe, as spall_sim_create_file
 *  does from a deck (the same checks; nothing written to disk).  The setup
 *  is not changed and may be changed and used again.  *out is NULL on
 *  failure. */
int spall_sim_create_setup(struct spall_sim **out, const struct spall_setup *setup,
                           struct spall_error *err);

#ifdef __cplusplus
}
#endif

#endif
