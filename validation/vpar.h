/**
 * @file vpar.h
 * @brief `spall validate` under mpirun (docs/parallel.md, "validate and
 *        bench under mpirun"): which cases run distributed, the call that
 *        distributes a case's prepared sim, and the read-back of particle
 *        values by global id.
 *
 * A case listed as distributed (vpar.c) runs on every rank: each rank
 * builds the same sim, vpar_distribute() partitions it, every sim_step is
 * the distributed step, and the case reads particles through vpar_at() /
 * vpar_gather() by global id (the serial index before distribution), so
 * its numbers are the one-rank numbers bit for bit.  When a sim of such a
 * case is refused distributed (par_check_supported), the case continues
 * serially on rank 0 alone (the other ranks leave it) with the note
 * "serial: <reason>", or, when the case already has a distributed sim, on
 * every rank as one.  Every other case runs on rank 0 alone with its note.
 * Only rank 0 prints and writes files.
 */
#ifndef SPALL_VALIDATION_VPAR_H
#define SPALL_VALIDATION_VPAR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct sim;
struct spall_error;
struct vcase;
struct vreport;

/** How the current case runs under mpirun. */
struct vpar {
    bool all_ranks;   /**< every rank runs the case (a distributed case) */
    bool distributed; /**< a sim of the case has been distributed */
    bool serial;      /**< a sim was refused: the rest of the case is serial */
    bool left;        /**< this rank left the case (not rank 0) */
    bool noted;       /**< the "serial:" note has been printed */
};

/** Reason why case @p name runs on one rank, or NULL for a distributed case. */
const char *vpar_serial_reason(const char *name);

/** Start case @p c under mpirun (@p r->par set): returns true when this
 *  rank runs it; rank 0 prints the case's "serial:" note if it has one. */
bool vpar_begin_case(struct vreport *r, const struct vcase *c);

/** Partition the prepared @p s over the ranks (after the case's own set-up,
 *  before its first step).  No-op on one rank and in a serial case.  A
 *  refusal is not an error: see the file comment; a rank that leaves the
 *  case gets a non-zero status so that the case unwinds. */
int vpar_distribute(struct vreport *r, struct sim *s, struct spall_error *err);

/** Value of the per-particle array @p local (local indices) at the particle
 *  with global id @p gid, on every rank (collective when distributed). */
double vpar_at(const struct sim *s, const double *local, int64_t gid);

/** The same for the @p k particles @p gid into @p out (one collective). */
void vpar_values(const struct sim *s, const double *local, const int64_t *gid, size_t k,
                 double *out);

/** The whole run's values of @p local by global id into @p global
 *  (par_n_global entries) on every rank (collective when distributed). */
int vpar_gather(const struct sim *s, const double *local, double *global,
                struct spall_error *err);

/** A new array (free() it) of par_n_global(s) values of @p local by
 *  global id, on every rank; NULL with @p err set on every rank when one
 *  is out of memory (collective when distributed). */
double *vpar_whole(const struct sim *s, const double *local, struct spall_error *err);

/** Mean-arrival wave speed between probes 0 (q) and 1 (h) of @p s driven
 *  at particle velocity @p v_behind: once the front has passed a probe,
 *  u = v_behind (t - t_a) on average, so t_a = t - u / v_behind, and the
 *  speed is (x0_h - x0_q) / (t_a,h - t_a,q).  Probes from their owners
 *  (collective when distributed). */
double vpar_probe_wave_speed(const struct sim *s, double v_behind);

/** Particles of the whole run (par_n_global). */
size_t vpar_n(const struct sim *s);

#endif
