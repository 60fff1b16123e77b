/**
 * @file spall.h
 * @brief Public API of libspall: run a deck, or build a simulation from a
 *        deck and step it yourself.
 *
 * Units are SI everywhere (m, kg, s, N, Pa, J, K).
 */
#ifndef SPALL_SPALL_H
#define SPALL_SPALL_H

#include <stdbool.h>
#include <stddef.h>

#include "spall/error.h"

/** Library version string ("0.1.0") and git revision of the build. */
const char *spall_version(void);
const char *spall_git_revision(void);

/** Options of spall_run(). */
struct spall_run_options {
    const char *deck_path; /**< YAML deck */
    const char *out_dir;   /**< NULL: directory named after the deck (without .yaml) */
    bool overwrite;        /**< replace an existing, non-empty output directory */
    int progress;          /**< -1 auto (terminal only), 0 off, 1 on */
    int threads;           /**< > 0 overrides the deck's run.threads */
    bool quiet;            /**< no summary lines on stdout */
    const char *restart;   /**< continue from this checkpoint file or run directory
                                (its newest checkpoint); NULL: start at t = 0 */
    double progress_every; /**< batch progress lines (stderr not a terminal): seconds
                                between them (0: 60) */
    bool yes;              /**< run even when the set-up check finds the run's cost far
                                beyond the machine (deck key run.allow: [cost]) */
};

/** What a finished (or failed) run did. */
struct spall_run_result {
    long steps;
    double time;               /**< simulated time reached [s] */
    double wall_seconds;
    size_t particles;
    size_t bonds;              /**< interactions counted once (0 if not bonded) */
    double particle_steps_per_s;
    char out_dir[1024];
    size_t frames;
    int signal;                /**< != 0: stopped by this signal after a checkpoint */
    char checkpoint[1200];     /**< the last checkpoint written ("" if none) */
};

/** Exit status of `spall run` stopped by SIGTERM, SIGINT or SIGUSR1 after
 *  writing a checkpoint (EX_TEMPFAIL: "try again", i.e. restart). */
#define SPALL_EXIT_INTERRUPTED 75

/** Load, check and run a deck, writing history.csv, HDF5/XDMF frames and
 *  run.log into the output directory.  Bad input returns SPALL_ERR_INPUT
 *  or SPALL_ERR_PHYSICS before anything is written. */
int spall_run(const struct spall_run_options *opt, struct spall_run_result *res,
              struct spall_error *err);

#endif
