/**
 * @file share.c
 * @brief Rows known to one rank each, to every rank (share.h).
 */
#include "core/parallel/share.h"

#include "core/parallel/comm.h"
#include "spall/error.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

/* Copy the rows this rank knows into the table. */
static void copy_mine(size_t n, int w, const size_t *rows, size_t n_mine, const double *vals,
                      double *all)
{
    for (size_t q = 0; q < n_mine; q++)
        if (rows[q] < n)
            memcpy(all + rows[q] * (size_t)w, vals + q * (size_t)w, (size_t)w * sizeof *all);
}

int par_share_rows(size_t n, int w, const size_t *rows, size_t n_mine, const double *vals,
                   double *all, struct spall_error *err)
{
#ifdef SPALL_HAVE_MPI
    const int size = par_size();
    if (size > 1 && par_active()) {
        /* records (row, values); the row index travels as a double, exact
         * below 2^53 */
        const size_t rw = (size_t)w + 1;
        double *sb = malloc((n_mine ? n_mine : 1) * rw * sizeof *sb);
        double *rb = malloc((n ? n : 1) * rw * sizeof *rb);
        int *cnt = malloc(2 * (size_t)size * sizeof *cnt);
        unsigned char *seen = calloc(n ? n : 1, 1);
        int bad = !sb || !rb || !cnt || !seen || n * rw > (size_t)INT_MAX;
        if (par_agree(bad ? spall_error_set(err, SPALL_ERR_NOMEM,
                                            "out of memory sharing %zu rows of %d values", n, w)
                          : SPALL_OK,
                      err)) {
            free(sb);
            free(rb);
            free(cnt);
            free(seen);
            return SPALL_ERR_NOMEM;
        }
        for (size_t q = 0; q < n_mine; q++) {
            sb[q * rw] = (double)rows[q];
            memcpy(sb + q * rw + 1, vals + q * (size_t)w, (size_t)w * sizeof *sb);
        }
        int mine = (int)(n_mine * rw);
        MPI_Allgather(&mine, 1, MPI_INT, cnt, 1, MPI_INT, MPI_COMM_WORLD);
        int at = 0;
        for (int r = 0; r < size; r++) {
            cnt[size + r] = at;
            at += cnt[r];
        }
        /* more records than rows: a row known twice (every rank sees the
         * same counts, so every rank refuses alike) */
        size_t dup = (size_t)at > (n ? n : 1) * rw ? n : SIZE_MAX;
        if (dup == SIZE_MAX) {
            MPI_Allgatherv(sb, mine, MPI_DOUBLE, rb, cnt, cnt + size, MPI_DOUBLE,
                           MPI_COMM_WORLD);
            for (size_t q = 0; q < (size_t)at / rw; q++) {
                const size_t k = (size_t)rb[q * rw];
                if (k >= n)
                    continue;
                if (seen[k]++) /* the same records on every rank: refused alike */
                    dup = k;
                memcpy(all + k * (size_t)w, rb + q * rw + 1, (size_t)w * sizeof *all);
            }
        }
        free(sb);
        free(rb);
        free(cnt);
        free(seen);
        if (dup != SIZE_MAX)
            return spall_error_set(err, SPALL_ERR_INTERNAL,
                                   "sharing %zu rows: row %zu known to two ranks", n, dup);
        return SPALL_OK;
    }
#endif
    (void)err;
    copy_mine(n, w, rows, n_mine, vals, all);
    return SPALL_OK;
}
