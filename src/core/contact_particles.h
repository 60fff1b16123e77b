/**
 * @file contact_particles.h
 * @brief Particle-particle contact for any model (deck key `contact:`):
 *        particles of different bodies, and unbonded particles of the same
 *        body (bonded models only), repel when closer than a contact
 *        distance d:
 *
 *            F = k d (delta / d)^n,   delta = d - r > 0,   never attracts,
 *
 *        n = 1 a linear penalty spring of stiffness k, n = 3/2 Hertz-like
 *        (stiffening with overlap).  Potential U = k d^2 (delta/d)^(n+1)/(n+1)
 *        is booked as strain energy, so the contact conserves energy.
 *
 * Why: bonds never cross bodies (core/bond_list.c), so without this two
 * bodies pass through each other; and fragments of a bonded body that meet
 * with particles that were never bonded need the same push (bonded pairs,
 * broken or not, are left to the model, whose broken bonds keep their
 * post-fracture repulsion).  Any pair in the model's bond list is left to
 * the model (a peridynamic family may reach into another body).  Models
 * without a bond list (SPH, macro-particles) get only the body-body part:
 * their same-body pairs are the model's business.
 *
 * Search: Verlet candidate lists — every eligible pair within d + skin
 * (skin = 0.5 d), found with a cell list (counting sort, O(N)) and rebuilt
 * only when some particle has moved more than skin/2 since the last build;
 * between builds a step costs one O(N) displacement check plus the
 * (few) candidate pairs.  Lists and forces are gathered per particle in a
 * fixed cell/particle order (no atomics): bitwise the same for any thread
 * count.
 */
#ifndef SPALL_CONTACT_PARTICLES_H
#define SPALL_CONTACT_PARTICLES_H

#include <stddef.h>

struct field_state;
struct sim;
struct spall_error;

/** Contact parameters (deck `contact:`). */
struct particle_contact_params {
    double distance;  /**< contact distance d [m] (> 0) */
    double stiffness; /**< k [N/m] (> 0) */
    double exponent;  /**< n in [1, 2]: 1 linear penalty, 1.5 Hertz-like */
};

struct particle_contact;

/** Create the contact set; refuses d <= 0, k <= 0 or n outside [1, 2]. */
int particle_contact_create(struct particle_contact **out,
                            const struct particle_contact_params *prm, struct spall_error *err);
void particle_contact_destroy(struct particle_contact **c);

/** Add the contact forces of the current positions into s->p->f (no-op
 *  when s->pcontact is NULL).  Returns an error only when out of memory. */
int particle_contact_forces(struct sim *s, struct spall_error *err);

/** Contact potential energy of the last force evaluation [J] (fixed-order sum). */
double particle_contact_energy(const struct sim *s);

/** Stable time step bound of the contact springs alone [s]: a particle with
 *  z contacts of slope n k (the slope at delta = d) has omega^2 <= 2 z n k / m
 *  (Gershgorin), z = 2, 6, 12 in 1D, 2D, 3D; INFINITY without contact. */
double particle_contact_stable_dt(const struct sim *s);

/** Number of contacting pairs (each counted once) at the last evaluation. */
size_t particle_contact_pairs(const struct sim *s);

/** Register the contact state a restart needs (candidate lists, the
 *  positions they were built at, counters); no-op without contact. */
int particle_contact_register_state(struct sim *s, struct field_state *fs,
                                    struct spall_error *err);

/** The address of the positions the candidate lists were built at,
 *  component @p d: a per-particle array the distributed engine keeps with
 *  the particles (partition, migration, ghosts; core/parallel/decomp.c),
 *  so that a re-laid-out run rebuilds the lists of the last build. */
void **particle_contact_built_at(struct particle_contact *c, int d);

#endif
