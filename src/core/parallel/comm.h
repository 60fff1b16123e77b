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
 * ranks the error of the lowest failing rank; only rank 0 prints it.  The
 * rule that makes this hold (docs/parallel.md, "Error agreement"): every
 * other collective a rank can reach after it may have failed alone is
 * preceded by a par_agree(), and a rank that fails returns its error to the
 * next par_agree() without entering any other collective.  That agreement
 * then meets the others' next one, wherever each stands; from then on the
 * error is marked agreed (spall_error.agreed) and travels out on every rank
 * without further messages, however many agreement points each way out has.
 *
 * Fault injection (par_fault): SPALL_FAULT=site:rank[,site:rank...] makes
 * that rank fail at that site, for the tests of the agreement
 * (tests/cli/mpi_fault.sh; the sites are listed in docs/parallel.md).
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

/** Fault injection for the agreement's tests: SPALL_FAULT (a comma-separated
 *  list of site:rank) names @p site with this rank: returns SPALL_ERR_IO with
 *  a message naming the site and rank, else SPALL_OK.  Any rank count. */
int par_fault(const char *site, struct spall_error *err);

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
