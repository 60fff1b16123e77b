/**
 * @file run_restart.h
 * @brief The run driver's checkpoint, restart and signal handling
 *        (`output.checkpoint`, `spall run --restart`; docs/restart.md),
 *        kept out of run.c so that the main loop stays readable.
 */
#ifndef SPALL_RUN_RESTART_H
#define SPALL_RUN_RESTART_H

#include <stdbool.h>
#include <stdio.h>

#include "io/checkpoint.h"

struct deck;
struct field_state;
struct field_writer;
struct history_writer;
struct sim;
struct spall_error;
struct spall_run_options;

struct run_ckpt {
    struct checkpoint_options opt;
    const struct deck *deck;
    struct field_state *fs;     /**< NULL until needed */
    char dir[1024];             /**< the run's output directory */
    bool restarted;             /**< continuing from @c file */
    char file[1200];            /**< restart: the checkpoint read */
    char src_dir[1024];         /**< restart: its directory */
    struct checkpoint_meta meta;/**< restart: the counters read */
    double wall_last;           /**< omp_get_wtime() of the last checkpoint */
    double next_t;              /**< next every_time checkpoint [s] */
    char last[1200];            /**< last checkpoint written */
    long last_step;             /**< its step (-1: none yet) */
};

/** After the sim is built: read the restart checkpoint into @p s when
 *  opt->restart is set (nothing on disk is touched yet).  @p out_dir is the
 *  directory the run will write (opt->out_dir, else the checkpoint's). */
int run_ckpt_begin(struct run_ckpt *c, const struct spall_run_options *opt, const struct deck *d,
                   const struct checkpoint_options *co, struct sim *s, char *out_dir,
                   size_t out_len, struct spall_error *err);

/** Restart into another directory than the checkpoint's: prepare it (as a
 *  new run) and copy history.csv up to the checkpoint and its frames. */
int run_ckpt_copy_outputs(struct run_ckpt *c, bool overwrite, struct spall_error *err);

/** Same directory: true. */
bool run_ckpt_same_dir(const struct run_ckpt *c);

/** Write a checkpoint now when one is due after this step (or @p force),
 *  with a `checkpoint:` line in @p log. */
int run_ckpt_maybe(struct run_ckpt *c, struct sim *s, const struct history_writer *hw,
                   const struct field_writer *fw, double next_frame_t, bool force, FILE *log,
                   struct spall_error *err);

/** run.log lines of a restart. */
void run_ckpt_log_restart(const struct run_ckpt *c, const struct sim *s, FILE *log);

void run_ckpt_end(struct run_ckpt *c);

/** SIGTERM, SIGINT and SIGUSR1 set a flag the loop reads after each step. */
void run_signals_install(void);
void run_signals_restore(void);
/** The signal received (0: none). */
int run_signal_pending(void);
/** The signal received by any rank (collective on a distributed run, where
 *  every rank calls it after each step; serial: run_signal_pending). */
int run_signal_agreed(void);

#endif
