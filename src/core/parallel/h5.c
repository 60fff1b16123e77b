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

static hid_t select_range(hid_t space, hsize_t cols, size_t lo, size_t hi,
                          const hsize_t *start, const hsize_t *count)
{
    if (hi - lo == 1) {
        hid_t one = H5Scopy(space);
        /* a rank-1 space reads only the first entry of each */
        hsize_t st[2] = {start[lo], 0}, ct[2] = {count[lo], cols};
        if (one >= 0 && H5Sselect_hyperslab(one, H5S_SELECT_SET, st, NULL, ct, NULL) < 0) {
            H5Sclose(one);
            return -1;
        }
        return one;
    }
    const size_t mid = lo + (hi - lo) / 2;
    hid_t a = select_range(space, cols, lo, mid, start, count);
    hid_t b = a >= 0 ? select_range(space, cols, mid, hi, start, count) : -1;
    hid_t both = b >= 0 ? H5Scombine_select(a, H5S_SELECT_OR, b) : -1;
    if (a >= 0)
        H5Sclose(a);
    if (b >= 0)
        H5Sclose(b);
    return both;
}

hid_t parallel_h5_select_runs(hid_t space, size_t n, const hsize_t *start, const hsize_t *count)
{
    const int rank = H5Sget_simple_extent_ndims(space);
    hsize_t dims[2] = {0, 1};
    if (rank < 1 || rank > 2 || H5Sget_simple_extent_dims(space, dims, NULL) < 0)
        return -1;
    if (n == 0) {
        hid_t none = H5Scopy(space);
        if (none >= 0 && H5Sselect_none(none) < 0) {
            H5Sclose(none);
            return -1;
        }
        return none;
    }
    return select_range(space, rank == 2 ? dims[1] : 1, 0, n, start, count);
}
