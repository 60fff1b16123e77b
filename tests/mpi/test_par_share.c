/*
 * Rows known to one rank each, to every rank (core/parallel/share.h), under
 * mpirun: a table of 37 rows of 5 doubles whose row k only rank k % size
 * knows (rows listed out of order, values with every bit pattern that must
 * survive: -0.0, a subnormal, infinities, a NaN with a payload) arrives
 * bit for bit on every rank; a row nobody knows keeps the caller's value;
 * a row two ranks claim is refused on every rank alike.
 * Run: mpirun -np N test_par_share (N = 1 is valid: a copy).
 */
#include "core/parallel/comm.h"
#include "core/parallel/share.h"
#include "spall/error.h"
#include "tests/mpi/par_check.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define N_ROWS 37
#define W 5

/* The value of row k, column c (bit patterns a sum or a conversion would
 * change are among them). */
static double value(size_t k, int c)
{
    uint64_t nan_bits = 0x7ff8000000000000ull | (uint64_t)(k + 1);
    double nan_payload;
    memcpy(&nan_payload, &nan_bits, sizeof nan_payload);
    switch ((k + (size_t)c) % 5) {
    case 0:
        return -0.0;
    case 1:
        return 0x1.0p-1070 * (double)(k + 1); /* subnormal */
    case 2:
        return (k % 2 ? 1.0 : -1.0) * INFINITY;
    case 3:
        return nan_payload;
    default:
        return 1.0 / 3.0 + (double)k * 0.1 + (double)c;
    }
}

int main(int argc, char **argv)
{
    if (par_world_init(&argc, &argv))
        return 1;
    const int size = par_size(), rank = par_rank();
    size_t rows[N_ROWS], n_mine = 0;
    double vals[N_ROWS * W], all[N_ROWS * W];
    /* this rank's rows, last first, row N_ROWS - 1 known by nobody */
    for (size_t k = N_ROWS - 1; k-- > 0;)
        if ((int)(k % (size_t)size) == rank) {
            rows[n_mine] = k;
            for (int c = 0; c < W; c++)
                vals[n_mine * W + (size_t)c] = value(k, c);
            n_mine++;
        }
    for (size_t q = 0; q < N_ROWS * W; q++)
        all[q] = 42.0;
    struct spall_error err = {0};
    int rc = par_share_rows(N_ROWS, W, rows, n_mine, vals, all, &err);
    CHECK(rc == SPALL_OK, "share: rc %d, %s", rc, err.msg);
    for (size_t k = 0; k < N_ROWS - 1; k++)
        for (int c = 0; c < W; c++) {
            double want = value(k, c);
            CHECK(memcmp(&all[k * W + (size_t)c], &want, sizeof want) == 0,
                  "row %zu column %d: not the owner's bits", k, c);
        }
    for (int c = 0; c < W; c++)
        CHECK(all[(N_ROWS - 1) * W + (size_t)c] == 42.0, "the row nobody knows was changed");
    if (size > 1) {
        /* every rank claims row 0: refused alike everywhere */
        rows[0] = 0;
        struct spall_error e2 = {0};
        rc = par_share_rows(N_ROWS, W, rows, 1, vals, all, &e2);
        CHECK(rc == SPALL_ERR_INTERNAL && strstr(e2.msg, "known to two ranks"),
              "a row claimed twice: rc %d, '%s'", rc, e2.msg);
    }
    int total = (int)par_sum_u64((uint64_t)failures);
    if (rank == 0)
        printf("test_par_share: %d ranks, %s\n", size, total ? "FAILED" : "ok");
    par_world_finalize();
    return total ? 1 : 0;
}
