/**
 * @file run_summary.h
 * @brief What a built simulation is, in the words of run.log: model, sizes,
 *        lattice, time step and every constant the model derived.  Shared by
 *        the run log and `spall calibrate DECK.yaml`, so the two always agree.
 */
#ifndef SPALL_IO_RUN_SUMMARY_H
#define SPALL_IO_RUN_SUMMARY_H

#include <stdio.h>

#include "spall/error.h"

struct sim;

/** Writes the summary of @p s as YAML-like `key: value` lines (the run.log
 *  header's middle part): model, dimension, particles, interactions,
 *  lattice, materials by name, pre-cut bonds, dt and its stability limit,
 *  steps, end time and the model's derived constants. */
void run_summary_write(FILE *f, const struct sim *s);

/** `spall calibrate DECK.yaml`: loads and checks the deck exactly as
 *  `spall run` does, builds the simulation (nothing is run or written) and
 *  writes its summary to @p out.  The deck is the file @p name, or the text
 *  @p text (named @p name in messages) when that is not NULL.  Errors as
 *  spall_run's (file:line:column). */
int run_summary_of_deck(const char *name, const char *text, FILE *out, struct spall_error *err);

#endif
