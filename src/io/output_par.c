/**
 * @file output_par.c
 * @brief Collective frame datasets of a distributed run (output_par.h).
 */
#include "io/output_par.h"

#include "core/parallel/decomp.h"
#include "core/parallel/h5.h"
#include "core/particles.h"
#include "core/sim.h"

#include <stdint.h>
#include <stdlib.h>

/* File space of n_global x ncomp with this rank's rows (its owned gids)
 * selected, and the matching memory space. */
static int select_rows(const struct sim *s, int ncomp, hid_t *fspace, hid_t *mspace)
{
    const size_t n = s->p->n_owned, ng = par_n_global(s);
    hsize_t dims[2] = {(hsize_t)ng, (hsize_t)ncomp};
    const int rank = ncomp == 1 ? 1 : 2;
    *fspace = H5Screate_simple(rank, dims, NULL);
    hsize_t mdims[2] = {(hsize_t)n, (hsize_t)ncomp};
    *mspace = H5Screate_simple(rank, mdims, NULL);
    if (*fspace < 0 || *mspace < 0)
        return -1;
    if (n == 0) {
        H5Sselect_none(*fspace);
        H5Sselect_none(*mspace);
        return 0;
    }
    /* owned gids ascend: runs of consecutive gids become one range each */
    size_t runs = 0;
    for (size_t i = 0; i < n; i++)
        runs += i == 0 || s->p->gid[i] != s->p->gid[i - 1] + 1;
    hsize_t *start = malloc(2 * runs * sizeof *start), *count = start ? start + runs : NULL;
    if (!start)
        return -1;
    size_t r = 0;
    for (size_t i = 0; i < n; i++) {
        if (i == 0 || s->p->gid[i] != s->p->gid[i - 1] + 1) {
            start[r] = (hsize_t)s->p->gid[i];
            count[r++] = 0;
        }
        count[r - 1]++;
    }
    hid_t sel = parallel_h5_select_runs(*fspace, runs, start, count);
    free(start);
    if (sel < 0)
        return -1;
    H5Sclose(*fspace);
    *fspace = sel;
    return 0;
}

hid_t output_par_write_rows(hid_t file, const char *name, int ncomp, const struct sim *s,
                            const double *data)
{
    hid_t fspace = -1, mspace = -1, dxpl = parallel_h5_dxpl();
    hid_t ds = -1;
    if (dxpl >= 0 && select_rows(s, ncomp, &fspace, &mspace) == 0) {
        hsize_t dims[2] = {(hsize_t)par_n_global(s), (hsize_t)ncomp};
        hid_t full = H5Screate_simple(ncomp == 1 ? 1 : 2, dims, NULL);
        ds = full < 0 ? -1
                      : H5Dcreate2(file, name, H5T_IEEE_F64LE, full, H5P_DEFAULT, H5P_DEFAULT,
                                   H5P_DEFAULT);
        if (full >= 0)
            H5Sclose(full);
        if (ds >= 0 && H5Dwrite(ds, H5T_NATIVE_DOUBLE, mspace, fspace, dxpl, data) < 0) {
            H5Dclose(ds);
            ds = -1;
        }
    }
    if (fspace >= 0)
        H5Sclose(fspace);
    if (mspace >= 0)
        H5Sclose(mspace);
    if (dxpl >= 0)
        H5Pclose(dxpl);
    return ds;
}

int output_par_write_ids(hid_t file, const char *name, const struct sim *s)
{
    const size_t n = s->p->n_owned;
    int64_t *ids = malloc((n ? n : 1) * sizeof *ids);
    hid_t fspace = -1, mspace = -1, dxpl = parallel_h5_dxpl(), ds = -1;
    int bad = !ids || dxpl < 0 || select_rows(s, 1, &fspace, &mspace) != 0;
    if (!bad) {
        for (size_t i = 0; i < n; i++)
            ids[i] = s->p->gid[i];
        hsize_t dims[1] = {(hsize_t)par_n_global(s)};
        hid_t full = H5Screate_simple(1, dims, NULL);
        ds = full < 0 ? -1
                      : H5Dcreate2(file, name, H5T_STD_I64LE, full, H5P_DEFAULT, H5P_DEFAULT,
                                   H5P_DEFAULT);
        if (full >= 0)
            H5Sclose(full);
        bad = ds < 0 || H5Dwrite(ds, H5T_NATIVE_INT64, mspace, fspace, dxpl, ids) < 0;
    }
    if (ds >= 0)
        H5Dclose(ds);
    if (fspace >= 0)
        H5Sclose(fspace);
    if (mspace >= 0)
        H5Sclose(mspace);
    if (dxpl >= 0)
        H5Pclose(dxpl);
    free(ids);
    return bad ? -1 : 0;
}
