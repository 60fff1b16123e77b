/**
 * @file setup_dist.h
 * @brief Distributed set-up of lattice and peridynamic bodies (issue 20):
 *        each rank builds only its region of the body.
 *
 * The replicated set-up (decomp.h) builds the whole body on every rank and
 * then keeps a part, so its peak memory per rank is that of the whole
 * body.  Here each rank generates only a block of the lattice generator's
 * outer index layers, balanced by site count, plus a halo of whole layers
 * (core/lattice_gen.h, lattice_window) two interaction ranges deep on
 * either side, in the serial generation order: local index order is then
 * global-id order, global ids are the serial indices, and every rank runs
 * the serial set-up (model init, bonds, pre-cracks, initial forces) on its
 * window.  Bond rows, per-particle constants that depend on the partners'
 * families (surface corrections, weighted volumes) and the initial forces
 * of the rank's own block are then exactly the serial ones: two ranges of
 * halo hold every particle they read.  Halo rows are incomplete and are
 * dropped.
 *
 * par_setup_distribute() then turns the window into an ordinary
 * decomposition (the rank's block owned, the bond partners of its rows as
 * ghosts), completes the whole-body values of the set-up (pre-cut bonds,
 * interaction count, the initial energy account, groups and probes keyed
 * by their serial positions) and repartitions with Zoltan RCB weighted by
 * bond count (par_rebalance), migrating to the final decomposition.
 *
 * Several bodies (bodies:) are several such windows, one per body, each
 * split over the ranks by its own layers (struct par_setup_seg): the
 * serial order is body 1's particles, then body 2's, so each body's blocks
 * start after all of the earlier bodies' particles.  This holds every
 * particle a bond reads only where bonds never cross bodies (the lattice
 * model's shells) or the bodies lie more than an interaction range apart
 * (deck_setup_dist_bodies decides, io/deck_setup_dist.h).
 *
 * Everything here is collective over the ranks.
 */
#ifndef SPALL_CORE_PARALLEL_SETUP_DIST_H
#define SPALL_CORE_PARALLEL_SETUP_DIST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct lattice_window;
struct sim;
struct spall_error;

/** One body's part of the window: the rank's layers of that body and their
 *  halo, appended after the earlier bodies' (local order = global-id order). */
struct par_setup_seg {
    size_t start, n;     /**< local particles [start, start + n) are this body's */
    int64_t gid_first;   /**< global id of local particle start */
    size_t lo, n_own;    /**< local particles [lo, lo + n_own) are the rank's block */
    int64_t *own_first;  /**< size + 1: global id of the first particle of each
                              rank's block of this body (own_first[size]: one
                              past the body's last) */
};

/** The window of a distributed set-up (sim->setup; NULL: replicated). */
struct par_setup {
    int rank, size;
    double halo;         /**< halo depth [m] each side of the block */
    struct par_setup_seg *seg; /**< per body, in deck order */
    size_t n_seg;
    int64_t n_global;    /**< particles of all bodies filled so far */
    int *probe_owner;    /**< per probe: the rank whose block holds it */
    int64_t *probe_gid;  /**< per probe: its particle's global id */
    double *probe_d2;    /**< per probe: squared distance to it [m^2] */
    size_t n_probes;
    unsigned long long moved; /**< particles that left their block for the partition */
    double imbalance[2];      /**< the blocks' work imbalance, the partition's */
};

/** A window for this rank with @p halo metres each side. */
int par_setup_create(struct par_setup **out, double halo, struct spall_error *err);
void par_setup_destroy(struct par_setup **ps);

/** Global id offsets of the blocks from each rank's own count (a
 *  prefix sum, MPI_Exscan): own_first[r] over all ranks.  @p n_own is
 *  this rank's block.  Pure bookkeeping, exposed for the unit test. */
void par_setup_offsets(const size_t *n_own, int size, int64_t *own_first);

/** After the fill of one body's window @p w, appended from local particle
 *  @p first on: its segment, the particles' global ids (after the earlier
 *  bodies') and the blocks' offsets (collective); SPALL_ERR_INTERNAL when
 *  the offsets from the counts disagree with the generator's serial
 *  positions. */
int par_setup_filled(struct sim *s, const struct lattice_window *w, size_t first,
                     struct spall_error *err);

/** Members of idx[0, n) (local indices, ascending) in the rank's own
 *  block, summed over all ranks (collective): a group's or region's size. */
size_t par_setup_count(const struct sim *s, const size_t *idx, size_t n);

/** Probe @p k: the nearest particle of the whole body (ties: the lowest
 *  global id, as the serial search), its owner and, on ranks whose
 *  window holds it, its local index (else SIZE_MAX).  Collective. */
int par_setup_probe(struct sim *s, size_t k, struct spall_error *err);

/** The dt limit of the whole body from each rank's (collective): the
 *  minimum.  A model whose bound reads only a particle's own row may take
 *  every window particle (a halo particle's incomplete row only lowers its
 *  stiffness); one whose bound reads the partners' families too (the
 *  state-based Gershgorin bound: a halo edge's small weighted volumes raise
 *  it) takes the block's particles only (par_setup_in_block), whose
 *  partners' families lie whole inside the two-range halo. */
double par_setup_dt_limit(double local);

/** Whether local particle @p i of the window lies in the rank's block (of
 *  any body), not in its halo: its row and its partners' rows are the
 *  serial ones.  Pure bookkeeping, no communication. */
bool par_setup_in_block(const struct par_setup *ps, size_t i);

/** The window while the set-up builds it (sim->setup until
 *  par_setup_distribute sets sim->par; NULL after, and in a replicated or
 *  serial set-up): local indices are window indices only then. */
const struct par_setup *par_setup_window(const struct sim *s);

/** In the window: @p ncomp values per local particle, v[i * ncomp + c];
 *  every halo particle's (one outside the rank's block) are replaced by
 *  those the rank whose block holds it computed (by global id; collective).
 *  For a per-particle quantity iterated over the whole body, whose block
 *  values are right only if the halo's are. */
int par_setup_halo_values(const struct sim *s, double *v, int ncomp, struct spall_error *err);

/** Make a table of distinct keys (core/distinct.h) the same on every rank:
 *  each rank's rows built from its window differ, but a particle that
 *  migrates takes its 16-bit row numbers along.  The union of the ranks'
 *  tables in rank order, first seen first, replaces *table (*n_rows rows of
 *  @p key_size bytes; NULL with 0 rows: this rank has no table), and
 *  idx[0, n_idx) is renumbered into it.  All ranks must agree on having a
 *  table; more than 65 536 rows in the union is an error (collective). */
int par_setup_merge_table(void **table, size_t key_size, size_t *n_rows, uint16_t *idx,
                          size_t n_idx, struct spall_error *err);

/** From the window to the final decomposition (above); sets s->par. */
int par_setup_distribute(struct sim *s, struct spall_error *err);

#endif
