/* HDF5 property lists for files shared by all ranks (issue 20).
 * Frames and checkpoints open their files through these so the same code
 * writes one file per frame on one process or on many: with MPI initialised
 * and more than one rank the file access list selects MPI-IO and the transfer
 * list collective I/O; otherwise both are plain defaults (serial path unchanged). */
#ifndef SPALL_CORE_PARALLEL_H5_H
#define SPALL_CORE_PARALLEL_H5_H

#include <hdf5.h>

/* New file access property list; the caller closes it with H5Pclose.
 * Returns a negative id on failure. Never sets H5F_CLOSE_STRONG, which
 * MPI-IO does not allow. */
hid_t parallel_h5_fapl(void);

/* New dataset transfer property list (collective under MPI); the caller
 * closes it with H5Pclose. Returns a negative id on failure. */
hid_t parallel_h5_dxpl(void);

/* 1 when the lists above select MPI-IO (MPI built in, initialised, >1 rank). */
int parallel_h5_is_mpio(void);

/* A new dataspace: a copy of @p space (rank 1, or rank 2 with every column)
 * selecting the @p n row ranges [start[k], start[k] + count[k]), which must
 * ascend and not overlap; n = 0 selects nothing.  The caller closes it.
 * Built by halves with H5Scombine_select: adding the ranges one by one
 * with H5S_SELECT_OR costs O(n^2) in HDF5 1.10 (11 000 ranges of a
 * 2 M-row frame: 21 s per dataset), by halves O(n log n) (0.17 s).
 * Returns a negative id on failure. */
hid_t parallel_h5_select_runs(hid_t space, size_t n, const hsize_t *start, const hsize_t *count);

#endif
