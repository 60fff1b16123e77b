/**
 * @file output_par.h
 * @brief Frames of a distributed run (issue 20): every rank writes the rows
 *        of its owned particles, at their global ids, collectively into the
 *        one HDF5 file of the frame (core/parallel/h5.h), so the file has
 *        the serial layout and order.  Used by io/output_hdf5.c when
 *        sim->par is set.
 */
#ifndef SPALL_IO_OUTPUT_PAR_H
#define SPALL_IO_OUTPUT_PAR_H

#include <hdf5.h>

struct sim;

/** Create dataset @p name of n_global x @p ncomp doubles (1-D when ncomp
 *  is 1) and write this rank's owned rows @p data (n_owned x ncomp) at
 *  their global ids.  Returns the open dataset (caller closes) or < 0. */
hid_t output_par_write_rows(hid_t file, const char *name, int ncomp, const struct sim *s,
                            const double *data);
/** The int64 dataset @p name holding 0..n_global-1 (one vertex per particle). */
int output_par_write_ids(hid_t file, const char *name, const struct sim *s);

#endif
