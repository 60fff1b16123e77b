/**
 * @file comm.h
 * @brief The process's rank and size, reductions and error agreement
 *        (issue 20); with decomp.h, the engine's only door to MPI.
 *
 * One binary serves any rank count.  The CLI calls par_world_init(), which
 * initialises MPI only when an MPI launcher started the process (mpirun,
 * srun: its environment says so); a plain `spall run` never touches MPI and
 * runs the serial code unchanged.  Without MPI (build without it, or not
 * launched by mpirun) every function here answers as for one rank: rank 0,
 * size 1, reductions return their input.
 *
 * Error agreement: a failure on one rank must stop every rank with one
 * message, never a hang.  Every place where ranks can fail on their own
 * (set-up, a step, a write) ends in par_agree(), a collective that hands all
 * ranks the error of the lowest failing rank; only rank 0 prints it.
 */
#ifndef SPALL_CORE_PARALLEL_COMM_H
#define SPALL_CORE_PARALLEL_COMM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct spall_error;

/** Initialise MPI when an MPI launcher started the process (CLI only).
 *  Returns 0, or non-zero when the launch was detected but MPI_Init failed. */
int par_world_init(int *argc, char ***argv);
/** Finalise MPI if par_world_init initialised it. */
void par_world_finalize(void);

/** True when MPI is initialised (launched by mpirun) and not finalised. */
bool par_active(void);
/** Rank in MPI_COMM_WORLD (0 without MPI). */
int par_rank(void);
/** Ranks in MPI_COMM_WORLD (1 without MPI). */
int par_size(void);

/** Error agreement (collective under MPI): returns the first non-zero @p rc
 *  of the lowest failing rank on every rank and copies that rank's error
 *  (code, message, key) into @p err on all of them; 0 when all succeeded. */
int par_agree(int rc, struct spall_error *err);

/** Global reductions (collective under MPI); order-independent operations only. */
double par_min_double(double v);
double par_max_double(double v);
uint64_t par_sum_u64(uint64_t v);
int64_t par_min_i64(int64_t v);
/** Element-wise integer sum of @p n values in place. */
void par_sum_u64_array(uint64_t *v, size_t n);

/** Broadcast @p n bytes from @p root. */
void par_bcast(void *buf, size_t n, int root);
void par_barrier(void);
/** Wall clock [s] (MPI_Wtime under MPI, else a monotonic clock). */
double par_wtime(void);

#endif
