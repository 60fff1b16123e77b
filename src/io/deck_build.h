/**
 * @file deck_build.h
 * @brief Turn a parsed YAML deck into a ready-to-prepare simulation plus the
 *        run's output settings.  Every key is documented in docs/decks.md.
 */
#ifndef SPALL_DECK_BUILD_H
#define SPALL_DECK_BUILD_H

#include <stdbool.h>
#include <stddef.h>

#include "core/parallel/migrate.h"
#include "io/checkpoint.h"

struct deck;
struct sim;
struct spall_error;

#define RUN_MAX_FIELDS 32

/** Output settings read from the deck's `output:` section. */
struct run_output {
    char title[128];
    double field_interval;  /**< s between field frames (0: use field_every) */
    long field_every;       /**< steps between frames (0 with interval 0: no frames) */
    long history_every;     /**< steps between history rows */
    const char *fields[RUN_MAX_FIELDS]; /**< names, pointing into the deck */
    size_t n_fields;
    int threads;            /**< run.threads (0 = default) */
    struct checkpoint_options checkpoint; /**< output.checkpoint (io/checkpoint.h) */
    struct par_balance_opts parallel;     /**< parallel: rebalancing (io/run_balance.h) */
};

/** Build the simulation described by @p d.  On success the model is created,
 *  particles, masses, groups, BCs and probes exist; call sim_prepare() next
 *  (deck_build_sim does that too, so *out is ready to step). */
int deck_build_sim(const struct deck *d, struct sim **out, struct run_output *ro,
                   struct spall_error *err);
/** deck_build_sim for `spall run`: with @p distribute, on several MPI ranks
 *  a deck the distributed set-up supports builds each rank's region only
 *  (io/deck_setup_dist.h; run_par_distribute completes it); @p note (may be
 *  NULL) gets run.log's line on the set-up (empty on one rank). */
int deck_build_sim_setup(const struct deck *d, struct sim **out, struct run_output *ro,
                         bool distribute, char *note, size_t note_len, struct spall_error *err);

#endif
