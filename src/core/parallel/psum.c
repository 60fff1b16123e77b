/**
 * @file psum.c
 * @brief Exact sums over all ranks (psum.h).
 */
#include "core/parallel/psum.h"

#include "core/exact_sum.h"
#include "core/particles.h"
#include "core/sim.h"

#ifdef SPALL_HAVE_MPI
#include <mpi.h>
#endif

void par_xsum_finish(const struct sim *s, struct xsum *acc, size_t n, double *out)
{
#ifdef SPALL_HAVE_MPI
    if (s->par && n) {
        /* normalised digits are below 2^32 in magnitude: the element-wise
         * sum over fewer than 2^30 ranks cannot overflow an int64 */
        for (size_t k = 0; k < n; k++)
            xsum_normalize(&acc[k]);
        MPI_Allreduce(MPI_IN_PLACE, acc, (int)(n * XSUM_WORDS), MPI_INT64_T, MPI_SUM,
                      MPI_COMM_WORLD);
    }
#else
    (void)s;
#endif
    for (size_t k = 0; k < n; k++)
        out[k] = xsum_round(&acc[k]);
}

void par_bond_energy(const struct model *m, const struct sim *s, par_particle_energy_fn eval,
                     const double *diss, double *strain, double *dissipated)
{
    /* The energy of every history row visits every bond again: on one thread
     * it cost 2.6 times the force loop of a 3D fcc lattice run with a row per
     * step (perf, 59 407 particles).  Exact accumulators make the threads'
     * partial sums independent of how the particles are split, so the
     * threaded sum is bitwise the serial one (eval only reads the model). */
    struct xsum acc[2];
    xsum_init(&acc[0]);
    xsum_init(&acc[1]);
    const size_t n = s->p->n_owned;
#pragma omp parallel if (n > SPALL_OMP_MIN_PARTICLES)
    {
        struct xsum part[2];
        xsum_init(&part[0]);
        xsum_init(&part[1]);
#pragma omp for schedule(static)
        for (size_t i = 0; i < n; i++) {
            double e;
            eval(m, s, i, &e, NULL);
            xsum_add(&part[0], e);
            xsum_add(&part[1], diss[i]);
        }
#pragma omp critical(par_bond_energy_merge)
        {
            xsum_merge(&acc[0], &part[0]);
            xsum_merge(&acc[1], &part[1]);
        }
    }
    double sum[2];
    par_xsum_finish(s, acc, 2, sum);
    *strain = sum[0];
    *dissipated = sum[1];
}
