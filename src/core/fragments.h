/**
 * @file fragments.h
 * @brief Fragments: connected components of the particles over intact bonds
 *        (any bonded model: lattice, peridynamics), with per-fragment particle
 *        count, mass, centre-of-mass velocity and kinetic energy.
 *
 * Labels are deterministic and independent of the thread count and of the
 * particle order: a fragment's id is the smallest global id (gid) of its
 * particles.  The union-find runs serially over the CSR bond list (one pass
 * over the half-bonds, path halving, the smaller index always becomes the
 * root), so it costs O(bonds) with a tiny constant; sums run in particle order.
 *
 * Cost: one pass over all bonds, so it is not done every step but only when
 * a history row or a field frame is written (io/run.c; the `fragment_id`
 * output field is computed when a frame is written).
 *
 * A bond is intact unless BOND_BROKEN is set (pre-cut bonds are broken).
 * Only owned particles [0, n_owned) are considered.
 */
#ifndef SPALL_FRAGMENTS_H
#define SPALL_FRAGMENTS_H

#include <stddef.h>
#include <stdint.h>

struct bond_list;
struct particles;
struct sim;
struct spall_error;

/** One fragment. */
struct fragment_info {
    int64_t id;        /**< smallest gid of its particles */
    size_t count;      /**< particles */
    double mass;       /**< kg */
    double vcm[3];     /**< centre-of-mass velocity, m/s (unused components 0) */
    double kinetic;    /**< sum of 1/2 m v^2 over its particles, J */
    double kinetic_cm; /**< 1/2 M |vcm|^2 (translation of the fragment), J */
};

/** Summary of the mass distribution. */
struct fragment_summary {
    size_t count;          /**< fragments (single particles included) */
    size_t singles;        /**< fragments of one particle */
    size_t ge10;           /**< fragments of >= 10 particles */
    double largest_mass;   /**< kg */
    double second_mass;    /**< kg (0 if one fragment) */
    double total_mass;     /**< kg */
    double kinetic_cm;     /**< sum of the fragments' 1/2 M |vcm|^2, J */
};

struct fragments;

/** Workspace for up to @p n particles. */
int fragments_create(struct fragments **out, size_t n, struct spall_error *err);
void fragments_destroy(struct fragments **f);

/** Connected components of particles [0, p->n_owned) over the intact bonds
 *  of @p bl (a NULL bond list: every particle is its own fragment). */
int fragments_compute(struct fragments *f, const struct particles *p, int dim,
                      const struct bond_list *bl, struct spall_error *err);

/** Results of the last fragments_compute. */
size_t fragments_count(const struct fragments *f);
/** Fragments in order of their smallest particle index. */
const struct fragment_info *fragments_list(const struct fragments *f);
/** Per particle: its fragment id (smallest gid of the fragment). */
const int64_t *fragments_labels(const struct fragments *f);
void fragments_summarise(const struct fragments *f, struct fragment_summary *out);

/** Write the fragment table (id, particles, mass, vcm, kinetic) as CSV,
 *  largest fragment first. */
int fragments_write_csv(const struct fragments *f, const char *path, double time,
                        struct spall_error *err);

/** Union-find over the intact bonds between particles [0, @p n) of @p bl
 *  (bonds to ghosts, partner >= n, are left out): parent[] of n entries;
 *  every root is the smallest index of its component. */
void fragments_union_local(size_t *parent, const struct bond_list *bl, size_t n);
/** Root of @p i in a forest of fragments_union_local (path halving). */
size_t fragments_root(size_t *parent, size_t i);
/** Add particle @p gid (mass @p m, velocity @p v) to @p fi, zeroed for a new
 *  fragment: the serial loop's sums, one particle at a time, so a fragment
 *  whose particles are added in gid order gets the serial bits wherever it
 *  is summed (the distributed fragments, parallel/fragments_par.c). */
void fragment_add(struct fragment_info *fi, int64_t gid, double m, const double v[3], int dim);
/** Turn @p fi's momentum into the centre-of-mass velocity, set kinetic_cm. */
void fragment_finish(struct fragment_info *fi, int dim);
/** Set the result from outside (the distributed computation): @p n_frag
 *  fragments in order of their id, @p n per-particle labels. */
int fragments_set(struct fragments *f, const struct fragment_info *info, size_t n_frag,
                  const int64_t *label, size_t n, struct spall_error *err);
/** Register the computed output field `fragment_id` (int, the fragment's
 *  smallest gid; computed when a frame is written) if the model has bonds
 *  (model_ops.bonds); a no-op otherwise. */
int fragments_register_field(struct sim *s, struct spall_error *err);

/** Compute the fragments of @p s into @p f (no-op returning 0 fragments if
 *  the model has no bonds). */
int fragments_of_sim(struct fragments *f, const struct sim *s, struct spall_error *err);

#endif
