/**
 * @file run_balance.h
 * @brief Rebalancing during `spall run` under mpirun (deck `parallel:`,
 *        docs/decks.md; core/parallel/migrate.h): the deck keys, the
 *        imbalance per history row in balance.csv and each rebalance in
 *        run.log.  Serial runs accept the keys and do nothing.
 */
#ifndef SPALL_IO_RUN_BALANCE_H
#define SPALL_IO_RUN_BALANCE_H

#include "core/parallel/migrate.h"

#include <stdio.h>

struct deck_node;
struct sim;
struct spall_error;

struct run_balance {
    struct par_balance_opts opt;
    FILE *csv;        /**< balance.csv (rank 0 of a distributed run) */
    double worst;     /**< largest imbalance seen at a check or history row */
};

/** Parse the optional top-level `parallel:` mapping. */
int run_balance_parse(const struct deck_node *root, struct par_balance_opts *o,
                      struct spall_error *err);

/** Before any output (run_par_setup): rebalancing asked of a model, or of
 *  model options, whose particles cannot migrate is refused at
 *  parallel.rebalance_every. */
int run_balance_check(const struct sim *s, const struct par_balance_opts *o,
                      struct spall_error *err);

/** After the decomposition (collective): refuse rebalancing for a model
 *  that cannot migrate, open balance.csv in @p dir and write its first row. */
int run_balance_begin(struct run_balance *b, const struct sim *s,
                      const struct par_balance_opts *o, const char *dir,
                      struct spall_error *err);
/** After each step (collective): rebalance when due and needed (logged),
 *  and at a history row append the imbalance to balance.csv. */
int run_balance_step(struct run_balance *b, struct sim *s, int history_row, FILE *log,
                     struct spall_error *err);
/** run.log summary; closes balance.csv. */
void run_balance_end(struct run_balance *b, const struct sim *s, FILE *log);

#endif
