#include "core/parallel/h5.h"

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

int parallel_h5_is_mpio(void)
{
#ifdef SPALL_HAVE_MPI
    /* One binary: run without mpirun (MPI never initialised) or on one rank,
     * it keeps the serial file driver, so its files match a serial build. */
    int init = 0, fin = 0, size = 1;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    if (!init || fin)
        return 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size > 1;
#else
    return 0;
#endif
}

hid_t parallel_h5_fapl(void)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    if (fapl < 0)
        return fapl;
#ifdef SPALL_HAVE_MPI
    if (parallel_h5_is_mpio() && H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL) < 0) {
        H5Pclose(fapl);
        return -1;
    }
#endif
    return fapl;
}

hid_t parallel_h5_dxpl(void)
{
    hid_t dxpl = H5Pcreate(H5P_DATASET_XFER);
    if (dxpl < 0)
        return dxpl;
#ifdef SPALL_HAVE_MPI
    if (parallel_h5_is_mpio() && H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE) < 0) {
        H5Pclose(dxpl);
        return -1;
    }
#endif
    return dxpl;
}
