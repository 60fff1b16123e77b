/**
 * @file comm.c
 * @brief Rank, size, reductions and error agreement (comm.h).  MPI is called
 *        only here and in the other files of src/core/parallel (decomp.c,
 *        reduce.c, step.c, h5.c); models and the I/O layer never call it.
 */
#include "core/parallel/comm.h"

#include "spall/error.h"

#include <stdlib.h>
#include <string.h>
#include <omp.h>

#ifdef SPALL_HAVE_MPI
#include <mpi.h>

/* Environment variables set by the launchers spall knows: Open MPI's mpirun,
 * PMIx (Slurm srun --mpi=pmix, Open MPI 5) and PMI-1/2 (MPICH, Slurm). */
static bool launched_by_mpi(void)
{
    static const char *const vars[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK",
                                       "PMI_SIZE"};
    for (size_t k = 0; k < sizeof vars / sizeof vars[0]; k++)
        if (getenv(vars[k]))
            return true;
    return false;
}
#endif

int par_world_init(int *argc, char ***argv)
{
#ifdef SPALL_HAVE_MPI
    if (!launched_by_mpi())
        return 0;
    int provided = 0;
    /* OpenMP threads inside a rank; only the master thread calls MPI */
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
        return 1;
    /* errors are agreed and reported by spall (par_agree), not by aborting */
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    return 0;
#else
    (void)argc;
    (void)argv;
    return 0;
#endif
}

void par_world_finalize(void)
{
#ifdef SPALL_HAVE_MPI
    if (par_active())
        MPI_Finalize();
#endif
}

bool par_active(void)
{
#ifdef SPALL_HAVE_MPI
    int init = 0, fin = 0;
    MPI_Initialized(&init);
    MPI_Finalized(&fin);
    return init && !fin;
#else
    return false;
#endif
}

int par_rank(void)
{
#ifdef SPALL_HAVE_MPI
    if (par_active()) {
        int r = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &r);
        return r;
    }
#endif
    return 0;
}

int par_size(void)
{
#ifdef SPALL_HAVE_MPI
    if (par_active()) {
        int n = 1;
        MPI_Comm_size(MPI_COMM_WORLD, &n);
        return n;
    }
#endif
    return 1;
}

int par_agree(int rc, struct spall_error *err)
{
#ifdef SPALL_HAVE_MPI
    if (!par_active() || par_size() == 1)
        return rc;
    /* every rank holds this error already (an earlier agreement) and is on
     * its way out with it: the ranks' ways out need not pass the same number
     * of agreement points (the rank that failed met the others' next one
     * from wherever it failed), so none of them may wait for the others here */
    if (rc && err && err->agreed)
        return rc;
    int size = par_size();
    int mine = rc ? par_rank() : size, first = size;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (first == size) {
        if (err) /* all passed: an error record kept from before is no longer news */
            err->agreed = 0;
        return 0;
    }
    struct spall_error e = {0};
    if (par_rank() == first) {
        if (err)
            e = *err;
        e.code = rc;
    }
    MPI_Bcast(&e, (int)sizeof e, MPI_BYTE, first, MPI_COMM_WORLD);
    e.agreed = 1;
    if (err)
        *err = e;
    return e.code ? e.code : SPALL_ERR_INTERNAL;
#else
    (void)err;
    return rc;
#endif
}

int par_fault(const char *site, struct spall_error *err)
{
    /* one getenv per visit: the sites are set-up steps and file writes,
     * never the step's loops, so the hook costs nothing a run could see */
    const char *spec = getenv("SPALL_FAULT");
    if (!spec || !spec[0])
        return SPALL_OK;
    const size_t n = strlen(site);
    const int rank = par_rank();
    for (const char *p = spec; *p;) {
        const char *comma = strchr(p, ',');
        const size_t len = comma ? (size_t)(comma - p) : strlen(p);
        if (len > n + 1 && strncmp(p, site, n) == 0 && p[n] == ':') {
            char *end = NULL;
            const long r = strtol(p + n + 1, &end, 10);
            if (end == p + len && r == rank)
                return spall_error_set(err, SPALL_ERR_IO,
                                       "fault injected at '%s' on rank %d (SPALL_FAULT=%s)", site,
                                       rank, spec);
        }
        p += len + (comma ? 1 : 0);
    }
    return SPALL_OK;
}

double par_min_double(double v)
{
#ifdef SPALL_HAVE_MPI
    if (par_active() && par_size() > 1) {
        double r = v;
        MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
        return r;
    }
#endif
    return v;
}

double par_max_double(double v)
{
#ifdef SPALL_HAVE_MPI
    if (par_active() && par_size() > 1) {
        double r = v;
        MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        return r;
    }
#endif
    return v;
}

uint64_t par_sum_u64(uint64_t v)
{
    par_sum_u64_array(&v, 1);
    return v;
}

void par_sum_u64_array(uint64_t *v, size_t n)
{
#ifdef SPALL_HAVE_MPI
    if (par_active() && par_size() > 1 && n > 0)
        MPI_Allreduce(MPI_IN_PLACE, v, (int)n, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
#else
    (void)v;
    (void)n;
#endif
}

int64_t par_min_i64(int64_t v)
{
#ifdef SPALL_HAVE_MPI
    if (par_active() && par_size() > 1) {
        int64_t r = v;
        MPI_Allreduce(&v, &r, 1, MPI_INT64_T, MPI_MIN, MPI_COMM_WORLD);
        return r;
    }
#endif
    return v;
}

void par_bcast(void *buf, size_t n, int root)
{
#ifdef SPALL_HAVE_MPI
    if (par_active() && par_size() > 1 && n > 0)
        MPI_Bcast(buf, (int)n, MPI_BYTE, root, MPI_COMM_WORLD);
#else
    (void)buf;
    (void)n;
    (void)root;
#endif
}

void par_barrier(void)
{
#ifdef SPALL_HAVE_MPI
    if (par_active() && par_size() > 1)
        MPI_Barrier(MPI_COMM_WORLD);
#endif
}

double par_wtime(void)
{
#ifdef SPALL_HAVE_MPI
    if (par_active())
        return MPI_Wtime();
#endif
    return omp_get_wtime();
}
