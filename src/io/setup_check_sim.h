/**
 * @file setup_check_sim.h
 * @brief Checks of a built simulation before step 0 (issue 24 item 1): set-ups
 *        that cannot be right (impactors inside a body, walls and symmetry
 *        planes through it, probes far from every particle, a large initial
 *        strain energy) and the cost of the run (particle-steps, output
 *        size) against the machine.
 *
 * A refusal is SPALL_ERR_INPUT positioned at the deck key of the likely
 * cause ("FILE:L:C: ...", err->key set); a warning is one line in the
 * report.  `run.allow: [NAME, ...]` in the deck turns the refusals and
 * warnings of those checks off (the names are listed in docs/decks.md and
 * in the message of each check); `spall run --yes` allows the cost.
 */
#ifndef SPALL_SETUP_CHECK_SIM_H
#define SPALL_SETUP_CHECK_SIM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

struct deck;
struct run_output;
struct sim;
struct spall_error;

#define SETUP_WARN_MAX 8
#define SETUP_LINE_LEN 1024

struct setup_report {
    char warn[SETUP_WARN_MAX][SETUP_LINE_LEN]; /**< "FILE:L:C: ... (run.allow: NAME)" */
    size_t n_warn;
    char estimate[SETUP_LINE_LEN]; /**< the cost estimate, one line ("" before the check) */
    double particle_steps;         /**< particles x steps still to run */
    double output_bytes;           /**< frames x bytes per frame + history rows */
    double initial_strain_fraction; /**< initial strain energy / initial kinetic energy */
};

/** The set-up checks on a prepared simulation at t = 0 (deck_build_sim
 *  done); warnings go to @p rep. */
int setup_check_sim(const struct deck *d, const struct sim *s, struct setup_report *rep,
                    struct spall_error *err);

/** The cost of the run: particle-steps and output size, printed into
 *  rep->estimate; refused (at `run`) when the output would not fit on the
 *  disk holding @p out_dir (NULL: not checked) or the particle-steps are
 *  far beyond a day of any machine, unless @p yes or run.allow: [cost]. */
int setup_check_cost(const struct deck *d, const struct sim *s, const struct run_output *ro,
                     const char *out_dir, bool yes, struct setup_report *rep,
                     struct spall_error *err);

/** Why group geometry @p g holds no particle, when the lattice explains it
 *  (a region thinner than the spacing, a spacing larger than the body): a
 *  sentence into @p buf, else "" (the caller names the geometry instead). */
struct geom;
void setup_empty_group_hint(const struct sim *s, const struct geom *g, char *buf, size_t len);

/** The warnings ("spall: warning: ...") to @p warn_out and, with the
 *  estimate, as setup_warning / setup_estimate lines to @p log (either may
 *  be NULL); the estimate goes to @p warn_out too for runs above 1e9
 *  particle-steps. */
void setup_report_print(const struct setup_report *rep, FILE *log, FILE *warn_out);

#endif
