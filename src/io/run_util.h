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
 *  Only drawn when enabled (mode 1) or on a terminal (mode -1). */
struct progress {
    int on;
    long n_steps;
    size_t n_particles;
    double t_start, t_last;
};
void progress_start(struct progress *p, int mode, long n_steps, size_t n_particles);
void progress_update(struct progress *p, long step, double t, double end_time);
void progress_finish(struct progress *p);

#endif
