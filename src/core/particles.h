/**
 * @file particles.h
 * @brief Structure-of-arrays particle storage shared by every model.
 *
 * Positions, velocities and forces are stored per component (x[0], x[1], x[2])
 * so that per-particle loops vectorise; only the first `dim` components are
 * allocated.  Particles [0, n_owned) belong to this rank; [n_owned, n) are
 * ghosts (copies of other ranks' particles, filled by the parallel layer).
 * The global id `gid` is what survives re-ordering and migration.
 * Model-specific per-particle state lives in arrays owned by the model, with
 * the same index.  Units: SI (m, m/s, N, kg).
 */
#ifndef SPALL_PARTICLES_H
#define SPALL_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

struct spall_error;

/** Below this many particles, per-particle loops run on one thread: the
 *  fork/join and barrier cost of OpenMP exceeds the work (and a busy machine
 *  makes spinning partner threads very expensive).  Results do not depend
 *  on it: every particle's arithmetic is the same either way. */
#define SPALL_OMP_MIN_PARTICLES 4096

/** Default of the most particles a run may hold (deck `run.max_particles`;
 *  lattice_fill refuses more, before allocating).  A particle costs ~130 B
 *  here and ~1 kB with a model's state and neighbour lists: 1e7 particles
 *  need ~10 GB; a deck that asks for more (a typo in a spacing) would be
 *  killed for memory on most machines. */
#define SPALL_MAX_PARTICLES_DEFAULT 1.0e7
/** Largest allowed `run.max_particles`. */
#define SPALL_MAX_PARTICLES_LIMIT 1.0e9

struct particles {
    int dim;          /**< 1, 2 or 3 */
    size_t n;         /**< owned + ghost particles */
    size_t n_owned;   /**< particles owned by this rank */
    size_t cap;       /**< allocated capacity */
    size_t max_n;     /**< lattice_fill stops here (0: SPALL_MAX_PARTICLES_DEFAULT) */
    double *x[3];     /**< current position */
    double *x0[3];    /**< reference (initial) position */
    double *v[3];     /**< velocity */
    double *f[3];     /**< total force of the current step */
    double *mass;     /**< kg */
    double mass_uniform; /**< > 0: every owned particle of every rank has this mass, and
                              the integrator's passes stream no masses (the same bits:
                              a division by the same double); 0: they read p->mass.
                              Set at a run's first step (sim_step, a collective when
                              distributed); whoever changes a mass during a run calls
                              particles_masses_changed */
    int mass_checked; /**< 1: mass_uniform describes the masses as they are */
    double *volume;   /**< m^3, volume the particle stands for */
    int64_t *gid;     /**< global id, unique over all ranks */
    int32_t *material;/**< index into the material table */
    int32_t *body;    /**< body (deck `bodies:` order, 0 for `body:`): bonds never
                           cross bodies; core/contact_particles.h acts between them */
};

/** Create an empty particle set of dimension @p dim with room for @p cap. */
int particles_create(struct particles **out, int dim, size_t cap, struct spall_error *err);
void particles_destroy(struct particles **p);

/** Grow capacity to at least @p cap (keeps contents). */
int particles_reserve(struct particles *p, size_t cap, struct spall_error *err);

/** Append one owned particle at @p pos (reference = current), zero velocity;
 *  gid = index.  Returns its index in @p *index. */
int particles_append(struct particles *p, const double pos[3], int32_t material,
                     size_t *index, struct spall_error *err);

/** A mass was written after the run's first step: the next step looks
 *  again whether all masses are equal (particles.mass_uniform; a
 *  collective when distributed, so every rank calls this alike).  The
 *  set-up before the first step needs no call, nor does migration between
 *  ranks (the property holds over all ranks). */
void particles_masses_changed(struct particles *p);

/** Zero the force arrays of all particles. */
void particles_zero_forces(struct particles *p);

#endif
