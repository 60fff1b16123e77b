/**
 * @file postprocess.h
 * @brief What a user does with a finished run directory (issue 23,
 *        docs/postprocessing.md): plot columns of history.csv, and the
 *        fragment mass and size distribution from fragments.csv.
 */
#ifndef SPALL_POSTPROCESS_H
#define SPALL_POSTPROCESS_H

#include <stddef.h>

struct spall_error;

/** Plot columns of RUN_DIR/history.csv against time as one PNG.  @p columns
 *  name the columns with or without their "[unit]" (NULL/0: the energy
 *  balance columns present: kinetic, strain, dissipated, damping,
 *  external_work, energy_balance).  An unknown name is refused listing the
 *  file's columns.  *rows_out: data rows plotted. */
int post_plot_history(const char *run_dir, const char *const *columns, size_t n_columns,
                      const char *png_path, size_t *rows_out, struct spall_error *err);

/** Fragment distribution from RUN_DIR/fragments.csv (written at the end of a
 *  run of a bonded model): CSV @p csv_path with one row per fragment,
 *  heaviest first: rank, particles, mass, the number of fragments at least
 *  this heavy and the mass fraction they hold; PNG @p png_path: that
 *  cumulative count against mass, both on log10 axes.  *count_out: number of
 *  fragments. */
int post_fragments(const char *run_dir, const char *csv_path, const char *png_path,
                   size_t *count_out, struct spall_error *err);

#endif
