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

#endif
