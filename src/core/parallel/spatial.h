/**
 * @file spatial.h
 * @brief Spatial ghosts in the step (issue 22): the engine side of a model
 *        whose partners come from a neighbour search (model_ops
 *        spatial_ghosts and spatial_rebuilt), on the building block
 *        core/parallel/sghost.h.
 *
 * After the partition, and whenever an owned particle has moved half the
 * skin since the model's last list build, every rank keeps as ghosts the
 * particles of other ranks within range + skin of its owned particles'
 * build positions (sghost.h), re-lays out its arrays (owned particles
 * unchanged, then the ghosts in ascending global id, each with its owner's
 * record: every per-particle array of the engine, the field registry and
 * the model) and lets the model rebuild its list.  Between rebuilds the
 * halo (decomp.h, par_halo_x) refreshes the ghosts' positions and
 * velocities from their owners before every force call, along the lists
 * of the last build.
 *
 * The rebuild test is the serial model's own, |x - x_build|^2 * 4 >= skin^2
 * for some particle, taken over the owned particles of all ranks: the
 * lists are rebuilt in the same steps, from the same positions, as on one
 * rank, so each owned particle's list holds the serial partners.  Every
 * function is collective.
 */
#ifndef SPALL_CORE_PARALLEL_SPATIAL_H
#define SPALL_CORE_PARALLEL_SPATIAL_H

#include <stdbool.h>
#include <stddef.h>

struct bond_list;
struct model;
struct sim;
struct spall_error;

#define PAR_SPATIAL_MAX_ARRAYS 12

/** What a model with spatial ghosts tells the engine (model_ops.spatial_ghosts). */
struct par_spatial_model {
    double range;  /**< interaction range [m] of the list built next (read at every
                        ghost build: it may grow during the run) */
    double skin;   /**< Verlet skin [m]: the list covers range + skin */
    double **xb;   /**< the model's array pointers xb[0..dim): positions at its last list build */
    int n_particle;
    void **particle[PAR_SPATIAL_MAX_ARRAYS]; /**< per-particle arrays ghosts carry (xb among them) */
    size_t particle_size[PAR_SPATIAL_MAX_ARRAYS];
    /** Optional: the serial model's own rebuild test, given the largest
     *  squared move of an owned particle since the build over all ranks
     *  (called on every rank: it may use collectives).  NULL: the test
     *  4 d2max >= skin^2.  (SPH tests qmax h_max + 2 sqrt(d2max) against
     *  its list radius, sph_rates.c: the same comparison, not an
     *  equivalent one, keeps the rebuild steps bitwise the serial ones.) */
    bool (*rebuild_due)(struct model *m, const struct sim *s, double d2max);
    /** Mirror planes through the origin (bit d: x_d = 0) whose images of
     *  its particles the model adds to its partners (SPH symmetry planes):
     *  a particle is a ghost of a rank also when one of its images lies
     *  within range + skin of it (sghost.h, par_sghost_set_mirror). */
    unsigned mirror_planes;
    /** Optional: before the rebuild test of every force call, the model
     *  places the owned particles whose position and velocity it
     *  prescribes for the force call (SPH's mirrored clamp), so that the
     *  test, a rebuild and the halo see them where the serial force call
     *  does.  Called on every rank (it may use collectives); errors are
     *  agreed by the caller. */
    int (*place)(struct model *m, struct sim *s, struct spall_error *err);
    /** Optional: fixed partners the model also reads beside its spatial
     *  ones (TLSPH bodies behind an interface: the reference lists, whose
     *  partners may lie farther than range + skin in the current
     *  configuration): rows of the owned particles, local indices.  Every
     *  ghost build sends each owned particle to the ranks that own one of
     *  its partners (bonds are symmetric, so each rank then holds every
     *  partner of its rows), besides the particles within range + skin:
     *  one ghost set, each ghost once, in ascending gid.  The model
     *  renumbers the rows itself in spatial_rebuilt (they held the old
     *  local indices). */
    const struct bond_list *bonds;
};

/** Right after the partition (decomp.c): the first ghost set, built at the
 *  model's build positions (no new list: spatial_rebuilt with moved false).
 *  A model whose spatial_ghosts returns > 0 has no spatial ghosts in this
 *  run (e.g. total-Lagrangian SPH, whose partners are fixed bonds). */
int par_spatial_init(struct sim *s, struct spall_error *err);

/** Before every force call of a distributed run: rebuild the spatial
 *  ghosts when needed, then refresh the ghosts' positions and velocities
 *  (par_halo_x).  For bond models the halo alone. */
int par_ghosts_step(struct sim *s, struct spall_error *err);

/** A bond model about to replace its bonds by a neighbour search (TLSPH's
 *  re-reference, which lists the particles near each one's current
 *  position): the ghosts become the particles of other ranks within
 *  @p range of the box of the owned particles' current positions, each
 *  with its owner's record (the engine's and the registry's arrays and
 *  sm->particle; the other fields of @p sm are not read), and the halo
 *  lists follow them.  With @p keep, every current ghost stays a ghost as
 *  well (the union, each ghost once, in ascending gid): a model that also
 *  has spatial ghosts (TLSPH bodies behind an interface) finds the
 *  partners of its current list among them again.  Without, no spatial
 *  ghosts are kept: the model's new bonds must list only particles held
 *  now, and the next migration takes the ghosts back to its bond
 *  partners.  Collective. */
int par_spatial_regather(struct sim *s, double range, const struct par_spatial_model *sm,
                         bool keep, struct spall_error *err);

/** Spatial ghost rebuilds in the step so far (0 without spatial ghosts). */
long par_spatial_rebuilds(const struct sim *s);

#endif
