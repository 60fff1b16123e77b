/**
 * @file par_check.h
 * @brief The check of the MPI unit tests (tests/mpi/test_*.c): a failed
 *        condition prints the rank, file, line and a message and counts in
 *        `failures`, so that every rank goes on to the collective calls
 *        after it (an early return would leave the others waiting); the
 *        test sums `failures` over the ranks at the end.
 */
#ifndef SPALL_TESTS_MPI_PAR_CHECK_H
#define SPALL_TESTS_MPI_PAR_CHECK_H

#include "core/parallel/comm.h"

#include <stdio.h>

static int failures;

#define CHECK(cond, ...)                                                                        \
    do {                                                                                        \
        if (!(cond)) {                                                                          \
            fprintf(stderr, "rank %d: FAIL %s:%d: ", par_rank(), __FILE__, __LINE__);           \
            fprintf(stderr, __VA_ARGS__);                                                       \
            fputc('\n', stderr);                                                                \
            failures++;                                                                         \
        }                                                                                       \
    } while (0)

#endif
