/**
 * @file run_util.h
 * @brief Output-directory policy and the terminal progress bar.
 */
#ifndef SPALL_RUN_UTIL_H
#define SPALL_RUN_UTIL_H

#include <stdbool.h>
#include <stddef.h>

struct spall_error;

/** "decks/epoxy.yaml" -> "epoxy" (in the current directory). */
void run_default_out_dir(const char *deck_path, char *out, size_t len);

/** Create @p dir (and parents).  An existing non-empty directory is refused
 *  unless @p overwrite, in which case spall's own result files in it
 *  (run.log, history.csv, fields.xdmf, fields_*.h5, *.png) are removed. */
int run_prepare_out_dir(const char *dir, bool overwrite, struct spall_error *err);

/** Progress bar on stderr: step, simulated time, %, particle-steps/s, ETA.
 *  Drawn when enabled (mode 1) or on a terminal (mode -1).  In a batch job
 *  (mode -1, stderr not a terminal) one line instead every @p every seconds
 *  of wall-clock time (progress_set_every; default 60 s), with the energy
 *  balance as a fraction of the energy put in (issue 24 item 3). */
#define PROGRESS_BATCH_EVERY 60.0
struct progress {
    int on;
    int batch;          /**< a line per interval instead of the bar */
    double every;       /**< batch interval [s] */
    long n_steps;
    size_t n_particles;
    double t_start, t_last;
};
struct sim;
void progress_start(struct progress *p, int mode, long n_steps, size_t n_particles);
/** The batch interval [s] (> 0; else the default stays). */
void progress_set_every(struct progress *p, double seconds);
void progress_update(struct progress *p, long step, double t, double end_time);
/** progress_update for a running simulation: the planned steps (with the
 *  steps split at frame times) and, in batch lines, its energy balance as
 *  last accounted (at the history rows) over the energy put in. */
void progress_update_sim(struct progress *p, const struct sim *s);
void progress_finish(struct progress *p);

#endif
