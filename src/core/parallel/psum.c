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
    struct xsum acc[2];
    xsum_init(&acc[0]);
    xsum_init(&acc[1]);
    for (size_t i = 0; i < s->p->n_owned; i++) {
        double e;
        eval(m, s, i, &e, NULL);
        xsum_add(&acc[0], e);
        xsum_add(&acc[1], diss[i]);
    }
    double sum[2];
    par_xsum_finish(s, acc, 2, sum);
    *strain = sum[0];
    *dissipated = sum[1];
}
