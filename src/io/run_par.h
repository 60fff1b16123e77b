/**
 * @file run_par.h
 * @brief The run driver's distributed pieces (`mpirun -np N spall run`,
 *        issue 20; core/parallel/decomp.h): set-up agreement and refusals,
 *        the decomposition in run.log, probes and fragments of the whole
 *        run.  With one rank every function reduces to the serial code.
 */
#ifndef SPALL_IO_RUN_PAR_H
#define SPALL_IO_RUN_PAR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

struct fragments;
struct run_output;
struct sim;
struct spall_error;
struct spall_run_options;

/** True on a run over more than one MPI rank. */
bool run_par_on(void);
/** True on the rank that writes files and messages (rank 0). */
bool run_par_root(void);
/** After the deck is built (@p rc its status, @p s NULL on failure): refuse
 *  what cannot run distributed yet, and agree on the outcome over the ranks
 *  so one rank's failure stops all with one message.  Serial: returns @p rc. */
int run_par_setup(const struct sim *s, const struct run_output *ro, int rc,
                  struct spall_error *err);
/** Agree on @p rc over the ranks (serial: returns it). */
int run_par_agree(int rc, struct spall_error *err);
/** Partition and localise the prepared run and record the decomposition
 *  in @p log (rank 0; NULL elsewhere).  Serial: nothing. */
/** After the deck is built (@p rc its status): agree on it and, when each
 *  rank built only its region (sim->setup), partition that set-up
 *  (core/parallel/setup_dist.h) so the run starts distributed.  Collective
 *  under mpirun; returns @p rc on one rank. */
int run_par_setup_window(struct sim *s, int rc, struct spall_error *err);

int run_par_distribute(struct sim *s, FILE *log, struct spall_error *err);
/** For library callers that build and step a sim themselves (`spall
 *  validate`, `spall bench`): partition the prepared @p s over the ranks
 *  (run_par_distribute, no log).  What cannot run distributed is not an
 *  error here: @p s stays whole on every rank and @p why receives the
 *  refusal (par_check_supported); "" when distributed or on one rank.
 *  Collective (every rank decides the same). */
int run_par_distribute_sim(struct sim *s, char *why, size_t len, struct spall_error *err);
/** Displacement @p u and velocity @p v of probe @p k (collective when distributed). */
void run_probe(const struct sim *s, size_t k, double u[3], double v[3]);
/** Fragments of the whole run (collective when distributed; rank 0 holds them). */
int run_fragments(struct fragments *f, const struct sim *s, struct spall_error *err);
/** Closing lines of run.log on a distributed run (halo time). */
void run_par_log_end(const struct sim *s, FILE *log);

#endif
